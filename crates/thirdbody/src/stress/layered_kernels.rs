//! Stress kernels of a layered body (bonded layers on a half-space or a rigid base,
//! [`crate::body::layered`]; the paper's coating, eq. 5, is one layer of thickness
//! h1 on a substrate): the six stresses at depth z per unit pressure on one square
//! surface cell, for the DC-FFT sections of [`super`]. Below, "the coating" is the top
//! layer (thickness h1) and "the substrate" any depth below it, read in its own
//! layer's material.
//!
//! In Fourier space the stresses at depth z are `T(k, z) p^(k)` with the transfer
//! functions `T` of [`crate::body::layered::LayeredSolver::plane_response`]; the
//! kernel of a cell of side h is
//! `S(X) = (1 / 4 pi^2) int T(k) P(k) e^{i k.X} dk`, `P = h^2 sinc(kx h/2) sinc(ky h/2)`.
//! `T` does not decay at large k near the surface, and in the coating it does not
//! vanish at k -> 0, so `S` is split into three parts, each computed where it is
//! well behaved:
//!
//! 1. Love's closed-form rectangle stresses of a homogeneous half-space with the
//!    Poisson ratio of the side (z's layer), exact. Its transfer is Boussinesq's
//!    `T_xixi = -(1 - kz) e^{-kz}`, `T_etaeta = -2 nu e^{-kz}`, `T_zz = -(1 + kz)
//!    e^{-kz}`, `T_xiz = i kz e^{-kz}`.
//! 2. Two carriers of the difference `T - T_Love` at small k, both Love kernels
//!    at the depth `lambda` (`2 h1 - z` in the coating, `z` in the substrate), so
//!    they decay at large k as fast as the difference does. (a) In the coating the
//!    difference does not vanish as k -> 0: the coating takes the substrate's
//!    surface strains, so `Delta T(0+) = (d_xi, d_eta)` in the wave-frame in-plane
//!    components, carried by `e^{-k lambda}`: the derivative of Love's stresses
//!    with respect to nu has the transfer `-2 e^{-k l} (s^2, c^2, -c s)` in
//!    (xx, yy, xy), `(c, s) = k / |k|`. (b) The slope `r1` of the difference at
//!    k = 0 (both sides), carried by `k e^{-k lambda}`: Love's nu = 0 stresses give
//!    `k l e^{-k l}` times `(c^2, s^2, c s)` with (a) added, times 1 in sigma_z and
//!    times `i (c, s)` in the shears.
//! 3. The remainder, O(k^2) at k -> 0 and decaying at large k like `e^{-k lambda}`
//!    (the reflection from the interface), split by the smooth share `chi(k) = e^{-q}
//!    sum_{j<8} q^j / j!`, `q = (k / k1)^2` ([`super::long_wave`]):
//!    (a) its short waves `(1 - chi) T` are summed on a periodic lattice of the cell
//!    pitch: base wavenumbers `2 pi j / (M h)` plus their aliases `2 pi m / h` until
//!    `e^{-k lambda}` is negligible, then one inverse 2-D FFT. The four wave-frame
//!    functions of |k| are tabulated once per depth on Chebyshev panels, graded
//!    towards k = 0 (each thread of the tabulation reuses one
//!    [`LayeredSolver`]). On one box `REACH / k1` wide (thousands of cells for a
//!    large window) the cost per depth grows like `(h / lambda)^2`: the aliases
//!    resolve the sub-cell structure, so the box's wavenumbers up to `ALIAS_DECAY /
//!    lambda` all take a transfer. Where that needs aliases (`ALIAS_DECAY h /
//!    lambda >= pi`, lambda below 10 cells) on a box wider than the offsets, the
//!    short waves are instead split in bands as the sub-cell split's below (exact
//!    alias sums, no taper): the top band on a box of a few cells, each lower band
//!    on a box only as wide as its reach (docs/performance.md);
//!    (b) its long waves `chi T` in free space, by Hankel transforms
//!    ([`super::long_wave`]). Their k and r nodes, the angular modes of the four
//!    unit wave-frame transfers (the modes are linear in the transfer), the Bessel
//!    functions and the interpolation axes depend on the lattice only: the caller's
//!    [`InfluenceTable`] keeps them (`KernelScratch`) for all the depths of a
//!    section, so a depth pays only for its transfer at the k nodes and the sums.
//!
//!    For an XZ section ([`StressKernels::fill_row`]: one row of outputs) neither
//!    part goes through the kernel table: (a) is summed on the same box directly
//!    against the pressure's DFT on that box (`remainder_on_row`: per wavenumber the
//!    alias-summed spectrum times the pressure's, summed over ky with the row's
//!    phase, one inverse FFT along x; the same periodic convolution as the table's,
//!    so the same images, none within reach), and (b) against the pressure's moments
//!    of the long waves' tensor interpolant (`long_wave::long_wave_on_row`), which
//!    the section keeps for all depths. Only Love's kernels and the carriers are
//!    tabulated; banded, sub-cell, thin-film and thick-coating depths keep the table.
//!
//!    Love's kernels are linear in nu, so the carriers' pair (nu = 0 and its
//!    derivative) comes from one evaluation of the corner primitives, and below
//!    the top layer, where lambda = z, it gives the depth's own Love kernels too.
//!    For a coating thinner than a cell ([`StressMethod::SubCell`]) the split is
//!    moved to `k1 = 4 / h`: the short waves' kernel then lies within five cells, so
//!    a 16 x 16 box holds it, and its alias sum is capped at 128 orders per axis
//!    and tapered by a smooth step in the wavenumber over the upper half (a
//!    low-pass filter whose real-space kernel has all moments zero: it changes the
//!    kernel only where that varies on the scale `h / 128`, i.e. nowhere but on the
//!    loaded cell's own edges). The long waves `chi(k / k1) T` are split again into
//!    bands `chi(k / k_hi) - chi(k / k_lo)`, `k_lo = k_hi / 4` (`/ 2` for decay
//!    lengths under 1.5 cells; the ladder passes through the XZ rows' split `kx h =
//!    3/8`, and no band is narrower than a ratio 1.5), down to the full
//!    expansion's `k0 ~ 4 / span`: each band's kernel falls off within `REACH /
//!    k_lo` (as the short waves' within `REACH / k1`), so it is summed on a box that
//!    much wider than the offsets it reaches, with the few aliases its band edge
//!    `8 k_hi` needs; below k0, Hankel transforms as in (b). A stiff coating's
//!    membrane length (thousands of cells at E1/E2 = 1e4) then never meets a box's
//!    images, and the cost depends neither on `h / h1` nor on E1/E2: a band
//!    evaluates the transfer at about `16 (k_hi h L)^2 / pi` wavenumbers on a box of
//!    L cells, `L ~ REACH / (k_lo h)`, some 2e5 per band.
//!
//! Why the split. A lattice sum is the kernel plus its periodic
//! images. The remainder's wave-frame functions are analytic in |k|, so in (kx, ky)
//! its non-analytic terms (`|k|^3, |k|^5, ...` in the normal stresses, `|k|^2, ...`
//! in the shears) give real-space tails `r^-5` and `r^-4`; worse, for a stiff
//! coating the Taylor series in k converges only for `k < 1 / l`, with the coating's
//! membrane length `l ~ 2 (E1/E2) h1`, so the kernel reaches out to ~l before that
//! tail starts. Summed on a box of a few windows, the images put a window-dependent
//! offset on every coefficient (+8 % on the surface sigma_x of E1/E2 = 30, h1 = 0.002
//! on its automatic window). The short waves' kernel is the remainder minus a
//! Gaussian smoothing of width `1 / k1` whose moments vanish up to order 15, so it
//! falls off like `(k1 r)^-16` times the remainder's 16th derivative and a box
//! `REACH / k1` wider than the offsets holds it without images; the long waves are
//! band-limited to `8 k1`, so their Hankel transforms and the tensor interpolation
//! to the offsets are cheap when `k1 ~ 4 / span`. Measured: one cell's coefficients
//! agree between windows of 65, 129 and 257 cells to 5e-10 of the peak for E1/E2 from
//! 1/10 to 100 and h1 from a/10 to 2a (`tests/coated_stress_window.rs`), and the
//! sections of the stiff case agree with a brute-force Fourier quadrature to 2.4e-7
//! of the peak (`tests/coated_stress_brute_force.rs`).
//!
//! With all materials equal the remainder and the carrier vanish (to rounding), and
//! the kernels are Love's. At an interface each side uses its own transfer and its
//! own nu: sigma_z, tau_xz and tau_yz are continuous (Love's are independent of nu),
//! sigma_x, sigma_y and tau_xy jump as continuity of the in-plane strains demands.

use std::f64::consts::PI;

use rayon::prelude::*;
use realfft::num_complex::Complex;
use realfft::RealFftPlanner;
use rustfft::FftPlanner;

use super::kernels::{
    HomogeneousStressKernels, InfluenceTable, OffsetLattice, PreparedRow, RowSource, StressKernels,
    COMPONENTS,
};
use super::long_wave::{
    long_wave_kernels, long_wave_on_row, long_wave_share, short_wave_share, Radial, BAND_EDGE,
};
use super::row_basis::{finish_rows, LongWaveRow, Share, ShortWaveRow};
use crate::body::layered::{Base, LayeredSolver, Stack};
use crate::body::quadrature::GaussLegendre;
use crate::body::quadrature::{ChebyshevPanels, InterleavedPanels};
use crate::body::Side;
use crate::case::Elastic;
use crate::error::Result;

/// How a layered body's stress kernels are computed ([`LayeredStressKernels`] picks
/// one per lattice and depth; tests compare them on both sides of each switch). `h1`
/// is the top layer's thickness, `d` the stack's.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StressMethod {
    /// Love's kernels, two carriers and the remainder (lattice sum and Hankel
    /// transforms): exact, at a cost that grows like `(cell / h1)^2` for thin top
    /// layers.
    Full,
    /// A top layer thinner than the cell: as `Full`, but the remainder is split at
    /// `k1 = 4 / cell`: its short waves (a kernel within five cells of the loaded
    /// one) on a small periodic box whose alias sum is capped and smoothly tapered,
    /// its long waves in bands of wavenumbers a factor 4 apart, each on a box wider
    /// than its kernel's reach, and below `~4 / span` by Hankel transforms. The
    /// cost grows neither with `cell / h1` nor with the modulus ratios.
    SubCell,
    /// A stack much thinner than the cell: Love's kernels and the two carriers (the
    /// long-wave limit and its O(k d) slope), without the O((k l)^2) remainder.
    ThinFilm,
    /// A top layer much thicker than the window: Love's kernels of the depth's
    /// material plus the constant the far interfaces add.
    ThickCoating,
}

/// Relative size of the last alias term kept: `e^{-k lambda}` below `e^{-ALIAS_DECAY}`.
const ALIAS_DECAY: f64 = 32.0;
/// The short-wave part's kernel is negligible beyond `REACH / k1` from the loaded
/// cell; the periodic box leaves that much room between an offset and the nearest
/// image of the loaded cell. Measured on the window test (E1/E2 = 100, h1 = 2a, the
/// worst case): 16 leaves 6e-9 of the peak, 20 leaves 5e-10.
const REACH: f64 = 20.0;
/// The split wavenumber `k1 = REACH / (SPLIT_SPANS * span)` (at most 1 / h): the box
/// is then `1 + SPLIT_SPANS` spans of the offsets, as large as the former lattice
/// sum's (whose cost it keeps), and the long waves are band-limited to `8 k1 = 32 /
/// span`.
const SPLIT_SPANS: f64 = 5.0;
/// The split wavenumber of [`StressMethod::SubCell`], times the cell: the short
/// waves' kernel then reaches `REACH / SUB_CELL_SPLIT = 5` cells and the long waves
/// are band-limited to `BAND_EDGE * SUB_CELL_SPLIT = 32` over the cell.
const SUB_CELL_SPLIT: f64 = 4.0;
/// Alias orders of the [`StressMethod::SubCell`] short waves, per axis: beyond half
/// of them the alias terms are tapered smoothly to zero. For offsets on cell
/// centres the alias series along an axis alternates in sign (`sinc` at `theta + 2
/// pi m`) with a smooth amplitude, and a smooth taper over many orders sums such a
/// series to far below rounding.
const SUB_CELL_ALIASES: i64 = 128;
/// Alias orders of the [`StressMethod::SubCell`] short waves along an axis whose
/// offsets are not whole cells (an XZ section on a row edge): offsets on the loaded
/// cell's edge see its sub-cell structure (the kernel varies there on the scale
/// lambda), so the sum is exact (untapered) down to `lambda ~ cell / 100`, tapered
/// below. With 128 tapered orders the edge was off by 3e-5 of the peak at E1/E2 =
/// 1e4, h1 = cell / 30 and by 0.2 at E1/E2 = 300, h1 = cell / 100, at z = h1.
const SUB_CELL_EDGE_ALIASES: i64 = 512;
/// The ratio of the split wavenumbers that bound one band of the
/// [`StressMethod::SubCell`] long waves: a band's lattice sum evaluates the
/// transfer at about `16 (k_hi h L)^2 / pi` wavenumbers on a box of L cells, `L ~
/// REACH / (k_lo h)` (or the offsets' span), so about `16 (REACH BAND_RATIO)^2 / pi`
/// per band. The sum's terms within each band's decay cut grow like the ratio
/// squared and the number of bands falls only like its logarithm, but each band has
/// its fixed costs (its box's transforms, its radial values): for decay lengths under
/// `FINE_BANDS_BELOW` cells, whose bands reach far in wavenumber, bands half as wide
/// (`BAND_RATIO / 2`) are cheaper (a section through a 0.64-cell layer on a rigid
/// base, every depth banded: 494 -> 383 ms); for longer ones they cost more (a
/// 6.4-cell layer: 212 -> 218 ms). The bands telescope for any ratios.
const BAND_RATIO: f64 = 4.0;
const FINE_BANDS_BELOW: f64 = 1.5;
/// Alias orders of the [`StressMethod::Full`] short waves, per axis: their sum is
/// exact (no taper) up to `e^{-k lambda} = e^{-ALIAS_DECAY}`, which needs about
/// `5 cell / lambda` orders. Only coatings at least a cell thick use `Full` in a
/// solve (at most 6 orders); thinner ones use it in tests, as the reference of
/// [`StressMethod::SubCell`], down to `lambda ~ cell / 200`. (It was 64, which
/// truncated the sum below `lambda ~ cell / 12`: 2e-3 of the peak at E1/E2 = 1e4,
/// h1 = cell / 30.)
const FULL_ALIASES: i64 = 1024;
/// Chebyshev panel degree of the tabulated remainder.
const PANEL_DEGREE: usize = 20;
/// The coating's half-space (plus a constant) is used where the lattice's diagonal
/// is below this fraction of h1, as for the surface kernel (`THICK_COATING_S` in
/// `body/coated.rs`).
pub const THICK_COATING: f64 = 1e-4;
/// The thin film (no remainder) is used where the remainder's largest wave-frame
/// transfer at the wavenumbers `1 / cell` and `pi / cell` is below this. That
/// transfer falls like `h1^2` and the thin film's error like `h1` (measured on one
/// cell's coefficients, lattice of 9 x 9: about `0.2 sqrt(transfer)` of the peak for
/// E1/E2 = 0.3 and 3, `0.03 sqrt(transfer)` for 30), so the error at the switch is
/// below 1e-3 of the peak (`tests/coated_stress_limits.rs`, docs/validation.md).
pub const THIN_FILM: f64 = 2.5e-5;

/// Stress kernels of a layered body.
#[derive(Debug, Clone, PartialEq)]
pub struct LayeredStressKernels {
    /// The stack (validated, at least one layer).
    pub stack: Stack,
    /// The side read at a depth equal to an interface's.
    pub interface_side: Side,
}

impl LayeredStressKernels {
    /// The top layer's thickness h1.
    fn top_thickness(&self) -> f64 {
        self.stack.layers[0].thickness
    }

    /// The index of the layer that holds depth z (`layers.len()`: the half-space
    /// base); at an interface, the side `interface_side` picks. A depth below a
    /// rigid base (refused by the stress requests) is read in the last layer.
    pub(super) fn layer(&self, z: f64) -> usize {
        let n = self.stack.layers.len();
        let mut bottom = 0.0;
        for (i, ply) in self.stack.layers.iter().enumerate() {
            bottom += ply.thickness;
            if z < bottom {
                return i;
            }
            if z == bottom {
                let below = i + 1 < n || matches!(self.stack.base, Base::HalfSpace(_));
                return if self.interface_side == Side::Below && below {
                    i + 1
                } else {
                    i
                };
            }
        }
        match self.stack.base {
            Base::HalfSpace(_) => n,
            Base::Rigid(_) => n - 1,
        }
    }

    /// The material of layer `layer` (`layers.len()`: the base half-space).
    pub(super) fn material(&self, layer: usize) -> Elastic {
        match (self.stack.layers.get(layer), self.stack.base) {
            (Some(ply), _) => ply.material,
            (None, Base::HalfSpace(m)) => m,
            (None, Base::Rigid(_)) => unreachable!("no material below a rigid base"),
        }
    }

    /// The wave-frame transfer `[xixi, etaeta, zz, xiz / i]` at wavenumber k >= 0 and
    /// depth z in `layer` (`crate::body::layered`); at k = 0 its long-wave limit.
    pub(super) fn transfer(
        &self,
        solver: &mut LayeredSolver,
        k: f64,
        layer: usize,
        z: f64,
    ) -> [f64; 4] {
        if k == 0.0 {
            return self.long_wave_transfer(solver, layer, z);
        }
        solver.plane_response(k, layer, z).stress
    }

    /// A solver of the stack, for [`Self::transfer`].
    pub(super) fn solver(&self) -> LayeredSolver {
        LayeredSolver::new(&self.stack).expect("a validated stack")
    }

    /// The transfer's limit at k -> 0: Richardson's extrapolation `2 T(e) - T(2 e)`
    /// from a wavenumber far below every length of the stack, its membrane lengths
    /// (a stiff layer's `(E / E_min) h`) included: the error is `O((e L)^2)`, about
    /// 1e-12.
    fn long_wave_transfer(&self, solver: &mut LayeredSolver, layer: usize, z: f64) -> [f64; 4] {
        let e = 1e-6 / self.longest_length(z);
        let a = solver.plane_response(e, layer, z).stress;
        let b = solver.plane_response(2.0 * e, layer, z).stress;
        std::array::from_fn(|q| 2.0 * a[q] - b[q])
    }

    /// The longest length in the transfer at depth z: z plus every layer's thickness,
    /// a stiff layer's stretched to its membrane length `(E / E_min) h`.
    fn longest_length(&self, z: f64) -> f64 {
        let softest = self
            .stack
            .layers
            .iter()
            .map(|p| p.material.young)
            .chain(match self.stack.base {
                Base::HalfSpace(m) => Some(m.young),
                Base::Rigid(_) => None,
            })
            .fold(f64::INFINITY, f64::min);
        let length: f64 = z + self
            .stack
            .layers
            .iter()
            .map(|p| p.thickness * (p.material.young / softest).max(1.0))
            .sum::<f64>();
        length
    }

    /// The long-wave in-plane stresses of the layer minus Love's, `(d_xi, d_eta)`:
    /// zero in the half-space base.
    fn long_wave_difference(&self, solver: &mut LayeredSolver, layer: usize, z: f64) -> (f64, f64) {
        if layer == self.stack.layers.len() {
            return (0.0, 0.0);
        }
        let t = self.transfer(solver, 0.0, layer, z);
        let nu = self.material(layer).poisson;
        (t[0] + 1.0, t[1] + 2.0 * nu)
    }

    /// The decay length of the difference from Love's at large k: the reflection
    /// from the top layer's bottom (`2 h1 - z`) in the top layer, the depth below it.
    pub(super) fn decay_length(&self, layer: usize, z: f64) -> f64 {
        if layer == 0 {
            2.0 * self.top_thickness() - z
        } else {
            z
        }
    }

    /// The wave-frame transfer `[xixi, etaeta, zz, xiz / i]` at k minus Love's and
    /// the long-wave carrier `(d_xi, d_eta) e^{-k lambda}`.
    fn difference(
        &self,
        solver: &mut LayeredSolver,
        layer: usize,
        z: f64,
        carrier: (f64, f64, f64),
        k: f64,
    ) -> [f64; 4] {
        let t = self.transfer(solver, k, layer, z);
        self.difference_from(t, layer, z, carrier, k)
    }

    /// [`Self::difference`] of the transfer `t` at k.
    fn difference_from(
        &self,
        t: [f64; 4],
        layer: usize,
        z: f64,
        carrier: (f64, f64, f64),
        k: f64,
    ) -> [f64; 4] {
        let nu = self.material(layer).poisson;
        let kz = k * z;
        let e = (-kz).exp();
        let love = [-(1.0 - kz) * e, -2.0 * nu * e, -(1.0 + kz) * e, kz * e];
        let (d_xi, d_eta, lambda) = carrier;
        let ec = (-k * lambda).exp();
        [
            t[0] - love[0] - d_xi * ec,
            t[1] - love[1] - d_eta * ec,
            t[2] - love[2],
            t[3] - love[3],
        ]
    }
}

/// The largest distance from the loaded cell's centre to a corner of an offset's cell.
fn diagonal(lattice: &OffsetLattice) -> f64 {
    let h = lattice.cell;
    let extent = |first: f64, count: usize| {
        let (a, b) = (first.abs(), (first + count as f64 - 1.0).abs());
        (a.max(b) + 0.5) * h
    };
    extent(lattice.x_first, lattice.cols).hypot(extent(lattice.y_first, lattice.rows))
}

/// `d/dk` at k = 0 of a function analytic in k (Richardson on two small steps).
fn slope_at_zero(mut f: impl FnMut(f64) -> [f64; 4], step: f64) -> [f64; 4] {
    let (a, b) = (f(step), f(2.0 * step));
    std::array::from_fn(|q| 2.0 * a[q] / step - b[q] / (2.0 * step))
}

impl LayeredStressKernels {
    /// The method [`StressKernels::fill`] uses on `lattice`: the top layer's
    /// half-space when the lattice's diagonal is below `THICK_COATING` h1, the thin
    /// film when the stack is thinner than a cell and the remainder is below
    /// `THIN_FILM` at the grid's wavenumbers, the sub-cell split for other top layers
    /// thinner than a cell, else the full expansion.
    pub fn method(&self, lattice: &OffsetLattice) -> StressMethod {
        let diagonal = diagonal(lattice);
        if diagonal < THICK_COATING * self.top_thickness() {
            StressMethod::ThickCoating
        } else if self.stack.thickness() < lattice.cell
            && self.remainder_at_grid_scale(lattice.cell) < THIN_FILM
        {
            StressMethod::ThinFilm
        } else if self.top_thickness() < lattice.cell {
            StressMethod::SubCell
        } else {
            StressMethod::Full
        }
    }

    /// The method [`StressKernels::fill`] uses at depth z: [`Self::method`], except
    /// that the sub-cell split is kept to depths whose remainder decays within half a
    /// cell (`lambda` = `2 h1 - z` in the coating, z in the substrate), where the
    /// full expansion's cost, growing like `(h / lambda)^2`, is more than 4 times
    /// that of `lambda = h`. Deeper, the full expansion needs at most 10 aliases per
    /// axis and is cheap and exact. (The first sub-cell split summed its long waves
    /// on one box twice the offsets' span: deep kernels as wide as the window met
    /// its images, 3.4e-5 of the peak and 1 % of the local stress at the window's
    /// edge 1.6 windows deep in the paper's Fig. 11a on 32².)
    pub fn method_at(&self, z: f64, lattice: &OffsetLattice) -> StressMethod {
        let method = self.method(lattice);
        let lambda = self.decay_length(self.layer(z), z);
        if method == StressMethod::SubCell && lambda >= 0.5 * lattice.cell {
            StressMethod::Full
        } else {
            method
        }
    }

    /// [`StressKernels::fill`] with a given method (the others are kept for tests
    /// that measure the error of the switch). Not part of the API: public only for
    /// `tests/coated_tables` and the limits of `tests/coated_stress_limits.rs`.
    #[doc(hidden)]
    pub fn fill_with(
        &self,
        z: f64,
        lattice: &OffsetLattice,
        table: &mut InfluenceTable,
        method: StressMethod,
    ) {
        self.fill_parts(z, lattice, table, method, None);
    }

    /// [`Self::fill_with`]; with `row`, the full expansion's short waves on one box
    /// (no bands) are summed against the pressure along the row
    /// (`remainder_on_row`) and added to the row's stresses instead of the table.
    fn fill_parts(
        &self,
        z: f64,
        lattice: &OffsetLattice,
        table: &mut InfluenceTable,
        method: StressMethod,
        row: Option<(&RowSource, &mut [Vec<f64>; COMPONENTS])>,
    ) {
        if method == StressMethod::ThickCoating {
            self.fill_thick(z, lattice, table);
            return;
        }
        let layer = self.layer(z);
        let material = self.material(layer);
        // 1. Love's kernels of the depth's material (filled with the carriers' below).
        // 2. Carriers of the difference's long-wave limit and of its slope at k = 0,
        // with transfers `e^{-k lambda}` and `k mu e^{-k mu}`. The slope's depth mu is
        // lambda, except in the sub-cell split, where it is at least a cell: the
        // slope of a stiff coating is large (~ its membrane length), and a carrier as
        // sharp as lambda puts a large term on the loaded cell's edges that the
        // remainder must cancel with wavenumbers up to ~1 / lambda, more than its
        // capped alias sum holds (any depth takes up the slope exactly).
        let (carrier, r1) = self.carriers(layer, z);
        let (d_xi, d_eta, lambda) = carrier;
        let mu = if method == StressMethod::SubCell {
            lambda.max(lattice.cell)
        } else {
            lambda
        };
        let [al, be, ga, ep] = r1.map(|r| r / mu);
        // Love's kernels for nu = 0 and their derivative in nu at a depth (they are
        // linear in nu: `G(1/2) - G(0)` is half the derivative).
        if lambda == z && mu == lambda {
            // Below the top layer the carriers' depth is z: Love's kernels of the
            // depth's material are `G(0) + nu G'`, and the carriers combine the same
            // two tables, so all is one combination of their corner primitives.
            let nu = material.poisson;
            HomogeneousStressKernels::fill_poisson_combined(z, lattice, table, |g0, g1| {
                let c = carrier_terms(g0, g1, (d_xi, d_eta), [al, be, ga, ep]);
                std::array::from_fn(|q| g0[q] + nu * g1[q] + c[q])
            });
        } else if mu == lambda {
            // In the top layer: Love's kernels at z and the carriers at lambda, one
            // combination of their corner primitives.
            let nu = material.poisson;
            HomogeneousStressKernels::fill_love_and_split_combined(
                z,
                nu,
                lambda,
                lattice,
                table,
                |g, g0, g1| {
                    let c = carrier_terms(g0, g1, (d_xi, d_eta), [al, be, ga, ep]);
                    std::array::from_fn(|q| g[q] + c[q])
                },
            );
        } else {
            self.fill_love_and_carriers(z, lattice, table, material, (carrier, r1), mu);
        }
        if method == StressMethod::ThinFilm {
            return;
        }
        // 3. The remainder, O(k^2) at k = 0: its short waves by a periodic lattice
        // sum, its long waves by Hankel transforms.
        let eval = |solver: &mut LayeredSolver, k: f64| {
            self.remainder(solver, layer, z, carrier, r1, mu, k)
        };
        let remainder = Radial {
            stack: &self.stack,
            eval: &eval,
        };
        let k1 = split_wavenumber(lattice);
        let sub_cell = method == StressMethod::SubCell;
        // In an XZ section, whether the rows built once for the section
        // ([`StressKernels::prepare_row`]) hold this depth's remainder (below the
        // band split kx, for a depth summed in bands); they are added to the row
        // afterwards ([`StressKernels::add_prepared_row`]).
        let rows_plan = row
            .as_ref()
            .filter(|(source, _)| row_lattice(lattice, source))
            .and_then(|_| self.row_plan(lattice, z));
        if sub_cell || needs_bands(lattice, lambda) {
            // The short waves need aliases on a box of `REACH / k1` cells: in bands.
            // The sub-cell split caps and tapers the top band's aliases.
            let top = Pass::Short {
                taper: sub_cell,
                edge: sub_cell && z > 0.0,
            };
            match rows_plan.and_then(|plan| plan.band_split) {
                // Bands down to kx on small boxes, in the table; below kx from the rows.
                Some(kxh) => {
                    self.add_bands(lattice, lambda, top, &remainder, table, kxh / lattice.cell)
                }
                None => self.add_banded_remainder(lattice, lambda, top, &remainder, table),
            }
            return;
        }
        if rows_plan.is_some() {
            return;
        }
        let short_waves = Pass::Short {
            taper: false,
            edge: false,
        };
        let thickness = self.stack.thickness();
        match row {
            Some((source, row)) if row_lattice(lattice, source) => {
                // A depth the rows do not serve (deeper than they are graded for, or a
                // decay length within 0.1 % of the alias threshold): per depth.
                remainder_on_row(
                    lattice,
                    lambda,
                    thickness,
                    k1,
                    &remainder,
                    short_waves,
                    source,
                    row,
                );
                // The long waves' moments take every source row at its signed offset
                // (the section's lattice may hold only the offsets |y|).
                let basis = &mut table.scratch.long_wave;
                let signed = OffsetLattice {
                    y_first: source.offset - (source.rows() as f64 - 1.0),
                    rows: source.rows(),
                    ..*lattice
                };
                long_wave_on_row(&signed, k1, &remainder, basis, source, row);
            }
            _ => {
                let long = long_wave_kernels(lattice, k1, &remainder, &mut table.scratch.long_wave);
                let short = remainder_on_lattice(
                    lattice,
                    lambda,
                    thickness,
                    k1,
                    &remainder,
                    short_waves,
                    None,
                );
                for ((t, s), l) in table.values.iter_mut().zip(short).zip(long) {
                    for ((v, a), b) in t.iter_mut().zip(s).zip(l) {
                        *v += a + b;
                    }
                }
            }
        }
    }

    /// The remainder in bands, added to `table`: split at `k1 = SUB_CELL_SPLIT /
    /// cell`, its short waves (pass `top`) on the offsets within their reach
    /// (`REACH / SUB_CELL_SPLIT` cells) of the loaded cell, on a small box: for
    /// [`StressMethod::SubCell`] with a capped and tapered alias sum, for
    /// [`StressMethod::Full`] with the exact one; its long waves split again into
    /// bands `chi(k / k_hi) - chi(k / k_lo)`, `k_lo = k_hi / BAND_RATIO`, down to the
    /// full expansion's split `k0 ~ 4 / span`, each band on the offsets within its
    /// reach `REACH / k_lo` by a lattice sum with the few aliases its band edge `8
    /// k_hi` needs; below `k0` by Hankel transforms in free space, as the full
    /// expansion. No band's kernel reaches its box's images, however long the
    /// coating's membrane length, and the cost depends neither on `cell / h1` nor on
    /// `E1 / E2`. The bands telescope: `(1 - chi(k / k1)) + sum (chi(k / k_hi) -
    /// chi(k / k_lo)) = 1 - chi(k / k0)`, the full expansion's short waves, which its
    /// one box of `REACH / k0` cells would sum at `(cell / lambda)^2` times more
    /// wavenumbers (a second per depth at `lambda ~ 3` cells on a window of 256).
    fn add_banded_remainder(
        &self,
        lattice: &OffsetLattice,
        lambda: f64,
        top: Pass,
        remainder: &Radial,
        table: &mut InfluenceTable,
    ) {
        let h = lattice.cell;
        let k0 = split_wavenumber(lattice).min(SUB_CELL_SPLIT / h);
        self.add_bands(lattice, lambda, top, remainder, table, k0);
        let long = long_wave_kernels(lattice, k0, remainder, &mut table.scratch.long_wave);
        for (t, l) in table.values.iter_mut().zip(long) {
            for (v, a) in t.iter_mut().zip(l) {
                *v += a;
            }
        }
    }

    /// Love's kernels of the depth's material at z plus the two carriers at lambda
    /// (the slope's at `mu`), into `table`.
    fn fill_love_and_carriers(
        &self,
        z: f64,
        lattice: &OffsetLattice,
        table: &mut InfluenceTable,
        material: Elastic,
        (carrier, r1): ((f64, f64, f64), [f64; 4]),
        mu: f64,
    ) {
        let (d_xi, d_eta, lambda) = carrier;
        let [al, be, ga, ep] = r1.map(|r| r / mu);
        let love_split = |depth: f64, zero: &mut InfluenceTable, slope: &mut InfluenceTable| {
            HomogeneousStressKernels::fill_poisson_split(depth, lattice, zero, slope);
        };
        // The split tables are kept between depths (the table's scratch, one per
        // thread): allocating them per depth cost page faults.
        let mut split = std::mem::take(&mut table.scratch.love_split);
        split.resize_with(2, InfluenceTable::default);
        let (zero, dnu) = split.split_at_mut(1);
        love_split(lambda, &mut zero[0], &mut dnu[0]);
        let slope_pair = (mu != lambda).then(|| {
            let (mut zero, mut slope) = (InfluenceTable::default(), InfluenceTable::default());
            love_split(mu, &mut zero, &mut slope);
            (zero, slope)
        });
        let (zero, dnu) = (&split[0], &split[1]);
        let (zero_s, dnu_s) = slope_pair.as_ref().map_or((zero, dnu), |(z, h)| (z, h));
        if lambda == z {
            // Below the top layer the carriers' depth is z: Love's kernels of the
            // depth's material are `G(0) + nu G'`.
            let nu = material.poisson;
            table.lattice = Some(*lattice);
            for ((t, g0), g1) in table.values.iter_mut().zip(&zero.values).zip(&dnu.values) {
                t.clear();
                t.extend(g0.iter().zip(g1).map(|(a, b)| a + nu * b));
            }
        } else {
            HomogeneousStressKernels { material }.fill(z, lattice, table);
        }
        // The carriers: A at lambda, B and the shears at the slope's depth mu.
        let at = |t: &InfluenceTable, n: usize| std::array::from_fn(|c| t.values[c][n]);
        for n in 0..lattice.cols * lattice.rows {
            let terms = carrier_terms_at(
                &at(dnu, n),
                &at(zero_s, n),
                &at(dnu_s, n),
                (d_xi, d_eta),
                [al, be, ga, ep],
            );
            for (v, t) in table.values.iter_mut().zip(terms) {
                v[n] += t;
            }
        }
        drop(slope_pair);
        table.scratch.love_split = split;
    }

    /// The short waves above `k1 = SUB_CELL_SPLIT / cell` (pass `top`) and the bands
    /// below it down to `k_stop` ([`Self::add_banded_remainder`]), added to `table`.
    fn add_bands(
        &self,
        lattice: &OffsetLattice,
        lambda: f64,
        top: Pass,
        remainder: &Radial,
        table: &mut InfluenceTable,
        k_stop: f64,
    ) {
        let h = lattice.cell;
        let k1 = SUB_CELL_SPLIT / h;
        let k_stop = k_stop.min(k1);
        // One radial table for every pass of the depth: graded down to the lowest
        // band's hundredth, up to the decay's cut (no pass reads beyond it).
        let theta_top = (ALIAS_DECAY * h / lambda.max(1e-300))
            .min(PI * (2 * FULL_ALIASES + 1) as f64 * 2f64.sqrt());
        let shared = std::sync::Arc::new(RadialTable::new(
            theta_top,
            h,
            2.0 * (lambda + self.stack.thickness()),
            0.01 * k_stop * h,
            remainder,
        ));
        let mut add = |reach: f64, k_hi: f64, pass: Pass| {
            self.add_near(
                lattice, reach, lambda, k_hi, remainder, pass, table, &shared,
            );
        };
        add(REACH / (k1 * h), k1, top);
        let ratio = if lambda < FINE_BANDS_BELOW * h {
            0.5 * BAND_RATIO
        } else {
            BAND_RATIO
        };
        // The ladder passes through the XZ rows' band split kx, whichever route sums
        // this depth: the bands above kx are then the same on both routes (an XZ
        // section takes the part below kx from its rows, a table goes on down to k0).
        let rung = self
            .row_parameters(lattice)
            .kxh
            .map(|kxh| kxh / h)
            .filter(|&kx| kx > k_stop && kx < k1);
        let mut k_hi = k1;
        while k_hi > k_stop {
            let target = rung.filter(|&kx| k_hi > kx).unwrap_or(k_stop);
            // No band narrower than a ratio 1.5: the last one above a rung takes the
            // rest.
            let k_lo = if k_hi / ratio < 1.5 * target {
                target
            } else {
                k_hi / ratio
            };
            add(REACH / (k_lo * h), k_hi, Pass::Band { low: k_lo * h });
            k_hi = k_lo;
        }
    }

    /// A pass of the remainder (`remainder_on_lattice`) on the offsets of `lattice`
    /// within `reach` cells (plus one) of the loaded cell along both axes, added to
    /// `table`: beyond them the pass's kernel is negligible.
    #[allow(clippy::too_many_arguments)]
    fn add_near(
        &self,
        lattice: &OffsetLattice,
        reach: f64,
        lambda: f64,
        k_hi: f64,
        remainder: &Radial,
        pass: Pass,
        table: &mut InfluenceTable,
        shared: &std::sync::Arc<RadialTable>,
    ) {
        let reach = reach.ceil() + 1.0;
        let clip = |first: f64, count: usize| {
            let lo = ((-reach - first).ceil()).max(0.0) as usize;
            let hi = ((reach - first).floor()).min(count as f64 - 1.0);
            (hi >= lo as f64).then(|| (lo, hi as usize - lo + 1))
        };
        let (Some((x0, cols)), Some((y0, rows))) = (
            clip(lattice.x_first, lattice.cols),
            clip(lattice.y_first, lattice.rows),
        ) else {
            return;
        };
        let near = OffsetLattice {
            cell: lattice.cell,
            x_first: lattice.x_first + x0 as f64,
            cols,
            y_first: lattice.y_first + y0 as f64,
            rows,
        };
        let part = remainder_on_lattice(
            &near,
            lambda,
            self.stack.thickness(),
            k_hi,
            remainder,
            pass,
            Some(shared),
        );
        for (t, s) in table.values.iter_mut().zip(part) {
            for r in 0..rows {
                for c in 0..cols {
                    t[(y0 + r) * lattice.cols + x0 + c] += s[r * cols + c];
                }
            }
        }
    }
}

impl LayeredStressKernels {
    /// The long-wave carrier `(d_xi, d_eta, lambda)` at depth z on `side` (lambda: the
    /// decay length of the difference from Love's at large k) and the slope `r1` of
    /// the difference at k = 0.
    fn carriers(&self, layer: usize, z: f64) -> ((f64, f64, f64), [f64; 4]) {
        let mut solver = self.solver();
        let lambda = self.decay_length(layer, z);
        let (d_xi, d_eta) = self.long_wave_difference(&mut solver, layer, z);
        let carrier = (d_xi, d_eta, lambda);
        let r1 = slope_at_zero(
            |k| self.difference(&mut solver, layer, z, carrier, k),
            1e-4 / (self.stack.thickness() + z),
        );
        (carrier, r1)
    }

    /// The remainder's wave-frame transfer at k: the difference from Love's minus
    /// both carriers (the slope's at depth `mu`), O(k^2) at k = 0.
    #[allow(clippy::too_many_arguments)]
    fn remainder(
        &self,
        solver: &mut LayeredSolver,
        layer: usize,
        z: f64,
        carrier: (f64, f64, f64),
        r1: [f64; 4],
        mu: f64,
        k: f64,
    ) -> [f64; 4] {
        let t = self.transfer(solver, k, layer, z);
        self.remainder_from(t, layer, z, carrier, r1, mu, k)
    }

    /// [`Self::remainder`] of the transfer `t` at k (an XZ section's rows read `t` from
    /// a solver solved once per node, [`RowWork`]).
    #[allow(clippy::too_many_arguments)]
    fn remainder_from(
        &self,
        t: [f64; 4],
        layer: usize,
        z: f64,
        carrier: (f64, f64, f64),
        r1: [f64; 4],
        mu: f64,
        k: f64,
    ) -> [f64; 4] {
        let d = self.difference_from(t, layer, z, carrier, k);
        let e = k * (-k * mu).exp();
        std::array::from_fn(|q| d[q] - r1[q] * e)
    }

    /// The largest wave-frame remainder at the wavenumbers `1 / cell` and `pi / cell`
    /// at the surface and on both sides of the interface (per unit pressure): about
    /// `(k l)^2` while the coating's length l (h1, or its membrane length when stiff)
    /// is short against the cell. Not part of the API: public only for the report of
    /// `tests/coated_stress_limits.rs`.
    #[doc(hidden)]
    pub fn remainder_at_grid_scale(&self, cell: f64) -> f64 {
        let n = self.stack.layers.len();
        let elastic_base = matches!(self.stack.base, Base::HalfSpace(_));
        let mut points = vec![(0.0, 0)];
        for (i, z) in self.stack.interface_depths().into_iter().enumerate() {
            points.push((z, i));
            if i + 1 < n || elastic_base {
                points.push((z, i + 1));
            }
        }
        let mut largest = 0.0f64;
        let mut solver = self.solver();
        for (z, layer) in points {
            let (carrier, r1) = self.carriers(layer, z);
            for k in [1.0 / cell, PI / cell] {
                for v in self.remainder(&mut solver, layer, z, carrier, r1, carrier.2, k) {
                    largest = largest.max(v.abs());
                }
            }
        }
        // NaN (an overflow) counts as large.
        if largest.is_nan() {
            f64::INFINITY
        } else {
            largest
        }
    }

    /// The coating's half-space: Love's kernels of the side's material plus, on
    /// every offset, the constant the far interface adds, `cell^2 / (2 pi) int_0^inf
    /// D(k) k dk` with D the angular mean of the difference of the transfers from
    /// Love's (sigma_x, sigma_y: `(xixi + etaeta) / 2`; sigma_z: `zz`; the others
    /// have no mean). The difference varies on the scale h1 in real space, so over a
    /// window of diagonal W it is that constant to O((W / h1)^2). At depths beyond
    /// h1 / 2 (far below the window) the whole kernel is the constant of the full
    /// transfer (to O((W / z)^2)); Love's corner sums would lose every digit there.
    fn fill_thick(&self, z: f64, lattice: &OffsetLattice, table: &mut InfluenceTable) {
        let layer = self.layer(z);
        let material = self.material(layer);
        let nu = material.poisson;
        let h1 = self.top_thickness();
        let deep = z >= 0.5 * h1;
        if deep {
            table.lattice = Some(*lattice);
            for v in table.values.iter_mut() {
                v.clear();
                v.resize(lattice.cols * lattice.rows, 0.0);
            }
        } else {
            HomogeneousStressKernels { material }.fill(z, lattice, table);
        }
        // In t = k scale the integrands decay at least like t^3 e^{-t} (deep: e^{-k z};
        // the difference: e^{-k (2 h1 - z)}, 2 h1 - z > 1.5 h1): panels of 0.25 to
        // t = 80 leave below 1e-28.
        let scale = if deep { z } else { h1 };
        let rule = GaussLegendre::new(8);
        let mut sums = [0.0; 2];
        let mut solver = self.solver();
        for panel in 0..320 {
            let lo = 0.25 * panel as f64;
            for (q, sum) in sums.iter_mut().enumerate() {
                *sum += rule.integrate(lo, lo + 0.25, |t| {
                    self.thick_mean(&mut solver, layer, z, nu, deep, t / scale)[q] * t
                });
            }
        }
        let factor = lattice.cell * lattice.cell / (2.0 * PI * scale * scale);
        let (in_plane, normal) = (sums[0] * factor, sums[1] * factor);
        for (c, add) in [(0, in_plane), (1, in_plane), (2, normal)] {
            for v in table.values[c].iter_mut() {
                *v += add;
            }
        }
    }

    /// The angular means `[(xixi + etaeta) / 2, zz]` of the transfer at k (deep), or of
    /// its difference from Love's.
    fn thick_mean(
        &self,
        solver: &mut LayeredSolver,
        layer: usize,
        z: f64,
        nu: f64,
        deep: bool,
        k: f64,
    ) -> [f64; 2] {
        let t = self.transfer(solver, k, layer, z);
        let (love_in_plane, love_zz) = if deep {
            (0.0, 0.0)
        } else {
            let kz = k * z;
            let e = (-kz).exp();
            (0.5 * (-(1.0 - kz) * e - 2.0 * nu * e), -(1.0 + kz) * e)
        };
        [0.5 * (t[0] + t[1]) - love_in_plane, t[2] - love_zz]
    }
}

impl StressKernels for LayeredStressKernels {
    /// A stack of isotropic layers is symmetric about every vertical plane: its
    /// kernels have Love's parity in y. Love's part and the carriers are evaluated
    /// folded (exactly symmetric); the remainder's lattice sums are symmetric to
    /// rounding.
    fn parity_in_y(&self) -> Option<[bool; COMPONENTS]> {
        Some(super::kernels::ODD_IN_V)
    }

    fn fill(&self, z: f64, lattice: &OffsetLattice, table: &mut InfluenceTable) {
        self.fill_with(z, lattice, table, self.method_at(z, lattice));
    }

    fn fill_row(
        &self,
        z: f64,
        lattice: &OffsetLattice,
        table: &mut InfluenceTable,
        source: &RowSource,
        row: &mut [Vec<f64>; COMPONENTS],
    ) {
        let method = self.method_at(z, lattice);
        self.fill_parts(z, lattice, table, method, Some((source, row)));
    }

    /// The remainder of every depth of the section that takes it from rows built once
    /// (`row_basis`: short waves on two periodic boxes, long waves at polar nodes),
    /// kept in `source` for [`StressKernels::fill_row`].
    fn prepare_row(
        &self,
        lattice: &OffsetLattice,
        source: &RowSource,
        depths: &[f64],
    ) -> Option<PreparedRow> {
        if !row_lattice(lattice, source) {
            return None;
        }
        let h = lattice.cell;
        let RowParameters {
            k1h,
            kxh,
            theta_top,
            deepest,
        } = self.row_parameters(lattice);
        // The short waves `1 - chi(k / k1)` in two families: above `k2` (`1 - chi(k /
        // k2)`, and a banded depth's `chi(k / kx) - chi(k / k2)`) on a box only
        // `REACH / k2` wider than the offsets, and the band `chi(k / k2) - chi(k /
        // k1)` (up to `BAND_EDGE k2`) on the box `REACH / k1` wider: the rows' cost
        // grows like the box's wavenumbers below each family's top.
        let span = span_in_cells(lattice);
        let len_low = box_cells(span, k1h);
        let k2h = row_split(span, k1h, theta_top, len_low, kxh);
        let len_high = box_cells(span, k2h);
        let frac_y = lattice.y_first - lattice.y_first.floor();
        let above = |theta: f64, kh: f64| {
            if theta > BAND_EDGE * kh {
                1.0
            } else {
                short_wave_share(theta, kh)
            }
        };
        let high_share = |theta: f64| above(theta, k2h);
        let band_share = |theta: f64| above(theta, k2h) - above(theta, kxh.unwrap_or(k2h));
        let low_share = |theta: f64| above(theta, k1h) - above(theta, k2h);
        let low_top = (BAND_EDGE * k2h).min(theta_top);
        let columns = |len: usize, top: f64| (top * len as f64 / (2.0 * PI)).floor() as usize + 1;
        let high = ShortWaveRow::new(
            &source.spectrum(len_high, frac_y, columns(len_high, theta_top)),
            len_high,
            frac_y,
            source.nx,
            0.1 * k2h,
            Share {
                share: &high_share,
                top: theta_top,
            },
            kxh.map(|kxh| Share {
                share: &band_share,
                top: BAND_EDGE * kxh,
            }),
        );
        let low = ShortWaveRow::new(
            &source.spectrum(len_low, frac_y, columns(len_low, low_top)),
            len_low,
            frac_y,
            source.nx,
            0.1 * k1h,
            Share {
                share: &low_share,
                top: low_top,
            },
            None,
        );
        let long = LongWaveRow::new(
            source.pressure(),
            source.nx,
            source.rows(),
            source.offset,
            k1h,
            offset_reach(lattice),
            self.longest_length(deepest) / h,
        );
        let solved = |thetas: &[f64]| -> Vec<LayeredSolver> {
            thetas
                .par_iter()
                .map(|&theta| {
                    let mut solver = self.solver();
                    solver.solve(theta / h);
                    solver
                })
                .collect()
        };
        let (high_solved, low_solved, long_solved) = (
            solved(high.nodes()),
            solved(low.nodes()),
            solved(long.nodes()),
        );
        // Per depth that sums its remainder on the rows: whether it is banded, and
        // the remainder's transfer at the nodes it takes (each node's stack solved
        // once above).
        let mut zs: Vec<f64> = depths.to_vec();
        zs.sort_by(f64::total_cmp);
        zs.dedup();
        let plans: Vec<DepthRows> = zs
            .par_iter()
            .filter_map(|&z| {
                let RowPlan {
                    band_split,
                    theta_cut,
                    mu,
                } = self.row_plan(lattice, z)?;
                let banded = band_split.is_some();
                let layer = self.layer(z);
                let (carrier, r1) = self.carriers(layer, z);
                let values = |thetas: &[f64], solved: &[LayeredSolver]| -> Vec<[f64; 4]> {
                    thetas
                        .iter()
                        .zip(solved)
                        .map(|(&theta, solved)| {
                            let t = solved.solved_response(layer, z).stress;
                            self.remainder_from(t, layer, z, carrier, r1, mu, theta / h)
                        })
                        .collect()
                };
                let (n_high, n_low) = (high.used(theta_cut, banded), low.used(theta_cut, false));
                Some(DepthRows {
                    z,
                    banded,
                    high: values(&high.nodes()[..n_high], &high_solved),
                    low: values(&low.nodes()[..n_low], &low_solved),
                    long: values(long.nodes(), &long_solved),
                })
            })
            .collect();
        let mut remainders: Vec<[Vec<f64>; COMPONENTS]> = plans
            .iter()
            .map(|_| std::array::from_fn(|_| vec![0.0; source.nx]))
            .collect();
        let jobs: Vec<(bool, &[[f64; 4]])> = plans
            .iter()
            .map(|p| (p.banded, p.high.as_slice()))
            .collect();
        high.add_many(&jobs, &mut remainders);
        let jobs: Vec<(bool, &[[f64; 4]])> =
            plans.iter().map(|p| (false, p.low.as_slice())).collect();
        low.add_many(&jobs, &mut remainders);
        let jobs: Vec<&[[f64; 4]]> = plans.iter().map(|p| p.long.as_slice()).collect();
        long.add_many(&jobs, &mut remainders);
        remainders.iter_mut().for_each(finish_rows);
        Some(Box::new(RowWork {
            depths: plans.iter().map(|p| p.z).collect(),
            remainders,
        }))
    }

    fn add_prepared_row(&self, z: f64, prepared: &PreparedRow, row: &mut [Vec<f64>; COMPONENTS]) {
        if let Some(rows) = prepared
            .downcast_ref::<RowWork>()
            .and_then(|work| work.remainder_at(z))
        {
            add_to_row(row, rows);
        }
    }

    fn fill_strip(
        &self,
        z: f64,
        cell: f64,
        count: usize,
        out: &mut [Vec<f64>; COMPONENTS],
    ) -> Result<()> {
        super::line::layered_strip(self, z, cell, count, out);
        Ok(())
    }
}

/// One axis of the periodic lattice: box length `m` cells, the integer part of the
/// first offset and its fraction (in cells), and the alias orders kept.
struct Axis {
    len: usize,
    first: i64,
    frac: f64,
    aliases: i64,
    tapered: bool,
}

impl Axis {
    /// `len`: the box, in cells; `(aliases, tapered)`: the alias orders kept and
    /// whether the upper half of their wavenumbers is tapered.
    fn new(first: f64, (aliases, tapered): (i64, bool), len: usize) -> Self {
        let whole = first.floor();
        let frac = first - whole;
        Axis {
            len,
            first: whole as i64,
            frac,
            aliases,
            tapered,
        }
    }

    /// Base wavenumber index j (0..len) as a signed frequency, times 2 pi / len.
    fn base(&self, j: usize) -> f64 {
        let j = if j <= self.len / 2 {
            j as f64
        } else {
            j as f64 - self.len as f64
        };
        2.0 * PI * j / self.len as f64
    }
}

/// The smallest even `2^a 3^b 5^c >= n` (sizes rustfft transforms fastest).
fn fft_friendly(n: usize) -> usize {
    (n.max(2)..)
        .find(|&m| {
            let mut r = m;
            for f in [2, 3, 5] {
                while r % f == 0 {
                    r /= f;
                }
            }
            r == 1 && m % 2 == 0
        })
        .unwrap_or(n)
}

/// `sin(t) / t`.
fn sinc(t: f64) -> f64 {
    if t.abs() < 1e-8 {
        1.0 - t * t / 6.0
    } else {
        t.sin() / t
    }
}

/// The largest distance of an offset from the loaded cell along either axis, in cells.
fn span_in_cells(lattice: &OffsetLattice) -> usize {
    let span = |first: f64, count: usize| {
        let whole = first.floor();
        whole.abs().max((whole + count as f64).abs()) as usize + 1
    };
    span(lattice.x_first, lattice.cols).max(span(lattice.y_first, lattice.rows))
}

/// The wavenumber `k1` splitting the remainder into its long waves (free space) and
/// its short waves (lattice).
fn split_wavenumber(lattice: &OffsetLattice) -> f64 {
    let h = lattice.cell;
    (REACH / (SPLIT_SPANS * span_in_cells(lattice) as f64 * h)).min(1.0 / h)
}

/// Which part of the remainder a lattice sum takes.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Pass {
    /// The short waves `(1 - chi) T`, on a box `REACH / k1` wider than the offsets,
    /// aliases until `e^{-k lambda}` is negligible: at most `FULL_ALIASES` per axis
    /// (`Full`), or at most `SUB_CELL_ALIASES` (`SUB_CELL_EDGE_ALIASES` along an
    /// axis of fractional offsets) with the upper half of their wavenumbers
    /// tapered (`SubCell`).
    /// `edge`: more orders along an axis of fractional offsets (below the surface).
    Short { taper: bool, edge: bool },
    /// A band `(chi(k / k1) - chi(k / k_lo)) T`, `low = k_lo h`: band-limited to
    /// `BAND_EDGE k1`, so a few aliases; its kernel falls off within `REACH / k_lo`,
    /// and the box is that much wider than the offsets' span.
    Band { low: f64 },
}

/// A smooth step from 1 (t <= 0) to 0 (t >= 1), infinitely differentiable.
fn taper(t: f64) -> f64 {
    let bump = |u: f64| if u > 0.0 { (-1.0 / u).exp() } else { 0.0 };
    let (a, b) = (bump(1.0 - t), bump(t));
    if a + b == 0.0 {
        0.0
    } else {
        a / (a + b)
    }
}

/// A part (`pass`) of the remainder kernel on `lattice`: the short waves `(1 -
/// chi(k)) T(k)` or the long waves `chi(k) T(k)`,
/// `[sigma_x, ..., tau_yz]` per offset, from its wave-frame transfer `radial(k) =
/// [xixi, etaeta, zz, xiz / i]` (k in 1/length), which decays at least like
/// `e^{-k lambda}`. Its kernel falls off within `REACH / k1`, so a periodic box that
/// much wider than the offsets' span sums it without images.
fn remainder_on_lattice(
    lattice: &OffsetLattice,
    lambda: f64,
    thickness: f64,
    k1: f64,
    radial: &Radial,
    pass: Pass,
    shared: Option<&std::sync::Arc<RadialTable>>,
) -> [Vec<f64>; COMPONENTS] {
    let spectrum = BoxSpectrum::new(lattice, lambda, thickness, k1, radial, pass, shared);
    let (ax, ay) = (&spectrum.ax, &spectrum.ay);
    let half_x = ax.len / 2 + 1;

    // Output rows of the periodic lattice that the table needs.
    let rows: Vec<usize> = (0..lattice.rows)
        .map(|m| (ay.first + m as i64).rem_euclid(ay.len as i64) as usize)
        .collect();
    let fft_y = FftPlanner::<f64>::new().plan_fft_inverse(ay.len);
    // Column by column (jx = 0..=len/2 of the half plane): the spectrum over all jy,
    // its inverse transform along y, and only the needed output rows kept:
    // `columns[jx][c][r]` for output row `rows[r]`.
    // Each thread reuses its spectrum and FFT scratch buffers (allocating them per
    // column cost as much as the transforms, in page faults).
    let columns: Vec<Option<[Vec<Complex<f64>>; COMPONENTS]>> = (0..half_x)
        .into_par_iter()
        .map_init(
            || {
                let spectrum: [Vec<Complex<f64>>; COMPONENTS] =
                    std::array::from_fn(|_| vec![Complex::default(); ay.len]);
                let scratch = vec![Complex::default(); fft_y.get_inplace_scratch_len()];
                (spectrum, scratch)
            },
            |(column, scratch), jx| {
                if !spectrum.column_reached(jx) {
                    return None;
                }
                for jy in 0..=ay.len / 2 {
                    let (at, partner) = spectrum.at_pair(jx, jy);
                    for (dst, a) in column.iter_mut().zip(at) {
                        dst[jy] = a;
                    }
                    for (dst, a) in column.iter_mut().zip(partner.into_iter().flatten()) {
                        dst[ay.len - jy] = a;
                    }
                }
                Some(std::array::from_fn(|c| {
                    let column = &mut column[c];
                    fft_y.process_with_scratch(column, scratch);
                    rows.iter().map(|&r| column[r]).collect()
                }))
            },
        )
        .collect();

    // Along x: one real inverse transform per output row and component.
    let fft_x = RealFftPlanner::<f64>::new().plan_fft_inverse(ax.len);
    let per_component: Vec<Vec<f64>> = (0..COMPONENTS)
        .into_par_iter()
        .map(|c| {
            let mut spec = vec![Complex::default(); half_x];
            let mut line = vec![0.0; ax.len];
            let mut values = Vec::with_capacity(lattice.cols * lattice.rows);
            for r in 0..rows.len() {
                for (jx, dst) in spec.iter_mut().enumerate() {
                    *dst = columns[jx]
                        .as_ref()
                        .map_or(Complex::default(), |col| col[c][r]);
                }
                // The alias sums are periodic in the base wavenumber only up to the
                // truncation: the zero and Nyquist columns are real to that precision.
                spec[0].im = 0.0;
                spec[half_x - 1].im = 0.0;
                fft_x
                    .process(&mut spec, &mut line)
                    .expect("FFT lengths are fixed by the plan");
                for k in 0..lattice.cols {
                    let nx = (ax.first + k as i64).rem_euclid(ax.len as i64) as usize;
                    values.push(line[nx]);
                }
            }
            values
        })
        .collect();
    let mut it = per_component.into_iter();
    std::array::from_fn(|_| it.next().unwrap_or_default())
}

/// The same part of the remainder as [`remainder_on_lattice`] on the same periodic
/// box, but summed directly against the pressure's spectrum on that box for the one
/// row of outputs of `source`: `sigma_c(x_i) = sum_j K^_c(j) P(j) e^{2 pi i (j_x i +
/// j_y f) / L}` (`K^` the kernel's alias-summed spectrum, `P` the pressure's DFT on
/// the box, f the whole part of the row's offset from source row 0), i.e. the
/// periodic convolution of the pressure with the part's kernel, which the box's
/// width keeps free of images exactly as the table's. No 2-D inverse transform, no
/// kernel table: per depth, the spectrum at the wavenumbers its decay reaches and one
/// real inverse FFT per component. `lattice` is the section's (its offsets span the
/// row's to the sources). Adds `sigma_c(x_i)`, `i < source.nx`, to `row`.
#[allow(clippy::too_many_arguments)]
fn remainder_on_row(
    lattice: &OffsetLattice,
    lambda: f64,
    thickness: f64,
    k1: f64,
    radial: &Radial,
    pass: Pass,
    source: &RowSource,
    row: &mut [Vec<f64>; COMPONENTS],
) {
    let spectrum = BoxSpectrum::new(lattice, lambda, thickness, k1, radial, pass, None);
    let (ax, ay) = (&spectrum.ax, &spectrum.ay);
    assert_eq!(ax.len, ay.len, "a square box");
    assert_eq!(ax.frac, 0.0, "outputs at cell centres along x");
    let pressure = source.spectrum(ax.len, ay.frac, ax.len / 2 + 1);
    let half_x = ax.len / 2 + 1;
    let sums: Vec<[Complex<f64>; COMPONENTS]> = (0..half_x)
        .into_par_iter()
        .map(|jx| {
            let mut sum = [Complex::default(); COMPONENTS];
            if !spectrum.column_reached(jx) {
                return sum;
            }
            let column = pressure.column(jx);
            let len = column.len();
            for jy in 0..=len / 2 {
                let (at, partner) = spectrum.at_pair(jx, jy);
                for (s, a) in sum.iter_mut().zip(at) {
                    *s += a * column[jy];
                }
                for (s, a) in sum.iter_mut().zip(partner.into_iter().flatten()) {
                    *s += a * column[len - jy];
                }
            }
            sum
        })
        .collect();
    let fft_x = RealFftPlanner::<f64>::new().plan_fft_inverse(ax.len);
    let mut spec = vec![Complex::default(); half_x];
    let mut line = vec![0.0; ax.len];
    for (c, out) in row.iter_mut().enumerate() {
        for (dst, s) in spec.iter_mut().zip(&sums) {
            *dst = s[c];
        }
        // Real to the truncation of the alias sums, as in `remainder_on_lattice`.
        spec[0].im = 0.0;
        spec[half_x - 1].im = 0.0;
        fft_x
            .process(&mut spec, &mut line)
            .expect("FFT lengths are fixed by the plan");
        for (o, v) in out.iter_mut().zip(&line[..source.nx]) {
            *o += v;
        }
    }
}

/// The largest `|k| h` of the XZ rows' short waves, just below pi: a depth whose
/// remainder reaches beyond (a decay length within 0.1 % of the alias threshold)
/// sums its short waves per depth.
const ROW_TOP: f64 = 0.999 * PI;

/// The XZ rows serve depths down to this many times the largest offset of the
/// section's lattice (deeper ones sum their remainder per depth).
const ROW_DEPTHS: f64 = 2.0;

/// The band edge (`BAND_EDGE kx h`) of the part of a banded depth's short waves that
/// an XZ section takes from its rows: below pi, so that no aliases are needed, and
/// the rows' panels resolve `chi(k / kx)` (in the rows' weights, exact). The higher
/// kx, the narrower the box of the lowest band a depth sums itself (`REACH / kx`
/// wide): it was 2 (kx h = 1/4, on the bands' ladder), and 3 cut the section through
/// a 1.9-cell layer on a rigid base from 346 to 256 ms.
const ROW_BAND_TOP: f64 = 3.0;

/// What an XZ section's depths share ([`StressKernels::prepare_row`]): the short and
/// long waves' rows per node and, per node, the stack solved at its wavenumber (a
/// depth then reads its transfer without solving the stack again).
struct RowWork {
    /// The depths whose remainder the rows hold (ascending).
    depths: Vec<f64>,
    /// Per depth, the remainder's short waves (or the band family's share, for a
    /// depth summed in bands) and long waves along the row.
    remainders: Vec<[Vec<f64>; COMPONENTS]>,
}

impl RowWork {
    /// The remainder's rows at depth z, if they hold it.
    fn remainder_at(&self, z: f64) -> Option<&[Vec<f64>; COMPONENTS]> {
        let i = self.depths.binary_search_by(|d| d.total_cmp(&z)).ok()?;
        Some(&self.remainders[i])
    }
}

/// The two carriers from Love's kernels for nu = 0 and their derivative in nu at
/// the carriers' depth, `g0` and `g1` (one offset, or one corner's primitives):
/// `A = -(G(1/2) - G(0))` has the transfer `e^{-k l} (s^2, c^2, -c s)` in (xx, yy,
/// xy), `B` the transfer `k l e^{-k l} (c^2, s^2, c s)`, and `G(0)`'s shears `i k l
/// e^{-k l} (c, s)`; the long-wave carrier takes `(d_xi, d_eta)` of A, the slope's
/// `[alpha, beta, gamma, epsilon]` of B and the shears.
fn carrier_terms(
    g0: &[f64; COMPONENTS],
    g1: &[f64; COMPONENTS],
    long_wave: (f64, f64),
    slope: [f64; 4],
) -> [f64; COMPONENTS] {
    carrier_terms_at(g1, g0, g1, long_wave, slope)
}

/// [`carrier_terms`] with the long-wave carrier's `G'` (`g1_long`) at one depth and
/// the slope's `G(0)`, `G'` at another (the sub-cell split's).
fn carrier_terms_at(
    g1_long: &[f64; COMPONENTS],
    g0: &[f64; COMPONENTS],
    g1: &[f64; COMPONENTS],
    (d_xi, d_eta): (f64, f64),
    [al, be, ga, ep]: [f64; 4],
) -> [f64; COMPONENTS] {
    let (axx, ayy, axy) = (-0.5 * g1_long[0], -0.5 * g1_long[1], -0.5 * g1_long[3]);
    let (sxx, syy, sxy) = (-0.5 * g1[0], -0.5 * g1[1], -0.5 * g1[3]);
    let (bxx, byy, bxy) = (g0[0] + syy, g0[1] + sxx, g0[3] - sxy);
    [
        d_xi * ayy + d_eta * axx + al * bxx + be * byy,
        d_xi * axx + d_eta * ayy + al * byy + be * bxx,
        ga * (bxx + byy),
        -(d_xi - d_eta) * axy + (al - be) * bxy,
        ep * g0[4],
        ep * g0[5],
    ]
}

/// What an XZ section's rows ([`StressKernels::prepare_row`]) cover. It depends on
/// the lattice and the stack only, not on the depths asked for: a depth's stresses
/// are the same whichever other depths share its section (the Python package
/// computes a section a few depths at a time).
struct RowParameters {
    /// The split `k1 h` between the long and the short waves.
    k1h: f64,
    /// The band family's split `kx h`, below which a depth summed in bands takes its
    /// remainder from the rows (when some depth can be banded: a top layer thinner
    /// than the alias threshold).
    kxh: Option<f64>,
    /// The largest `|k| h` of the short-wave rows. The decay length is at least the
    /// top layer's thickness (`2 h1 - z` in it, z below it), so the rows reach
    /// `ALIAS_DECAY / h1` (below pi: deeper depths with shorter decay lengths are
    /// summed in bands), and at least the band family's edge.
    theta_top: f64,
    /// The deepest depth the rows serve: `ROW_DEPTHS` times the offsets' reach (the
    /// long waves' panels are graded to the longest length there).
    deepest: f64,
}

/// How one depth takes its remainder from an XZ section's rows.
struct RowPlan {
    /// For a depth summed in bands, the band split `kx h`: the rows hold the part
    /// below kx (the band family's share), small boxes the bands above it.
    band_split: Option<f64>,
    /// The `|k| h` beyond which the depth's remainder is negligible (or, banded, kx's
    /// band edge).
    theta_cut: f64,
    /// The depth of the slope carrier the remainder is taken against.
    mu: f64,
}

impl LayeredStressKernels {
    fn row_parameters(&self, lattice: &OffsetLattice) -> RowParameters {
        let h = lattice.cell;
        let k1h = split_wavenumber(lattice) * h;
        let h1 = self.top_thickness();
        let kxh = needs_bands(lattice, h1)
            .then_some(ROW_BAND_TOP / BAND_EDGE)
            .filter(|&kxh| kxh > k1h);
        let mut theta_top = (ALIAS_DECAY * h / h1).min(ROW_TOP);
        if let Some(kxh) = kxh {
            theta_top = theta_top.max(BAND_EDGE * kxh);
        }
        RowParameters {
            k1h,
            kxh,
            theta_top,
            deepest: ROW_DEPTHS * offset_reach(lattice) * h,
        }
    }

    /// Whether and how depth z of an XZ section on `lattice` takes its remainder from
    /// the rows: depths of the full expansion and of the sub-cell split down to the
    /// deepest the rows serve, whose remainder is within the rows' reach or summed in
    /// bands. `prepare_row` builds the rows of exactly these depths and `fill_parts`
    /// leaves them out of the table.
    fn row_plan(&self, lattice: &OffsetLattice, z: f64) -> Option<RowPlan> {
        let RowParameters {
            kxh,
            theta_top,
            deepest,
            ..
        } = self.row_parameters(lattice);
        let method = self.method_at(z, lattice);
        let sub_cell = method == StressMethod::SubCell;
        if !(sub_cell || method == StressMethod::Full) || z > deepest {
            return None;
        }
        let h = lattice.cell;
        let lambda = self.decay_length(self.layer(z), z);
        let banded = sub_cell || needs_bands(lattice, lambda);
        let mut theta_cut = ALIAS_DECAY * h / lambda;
        let band_split = if banded {
            let kxh = kxh?;
            theta_cut = theta_cut.min(BAND_EDGE * kxh);
            Some(kxh)
        } else if theta_cut > theta_top {
            return None;
        } else {
            None
        };
        Some(RowPlan {
            band_split,
            theta_cut,
            // The sub-cell split's slope carrier is at least a cell deep (as in
            // `fill_parts`), and so is its remainder.
            mu: if sub_cell { lambda.max(h) } else { lambda },
        })
    }
}

/// One depth of an XZ section that takes its remainder from the rows: whether it is
/// summed in bands (and so takes the band family's share), and its remainder's
/// wave-frame transfer at the short and long waves' nodes.
struct DepthRows {
    z: f64,
    banded: bool,
    high: Vec<[f64; 4]>,
    low: Vec<[f64; 4]>,
    long: Vec<[f64; 4]>,
}

/// The split `k2 h` between an XZ section's two families of short-wave rows
/// ([`StressKernels::prepare_row`]): the one of a few candidates between `2 k1 h`
/// and the band split `kx h` that minimises the wavenumbers both boxes sum below
/// their tops (`(span + REACH / k2h)^2 top^2` above `k2`, `len_low^2 (BAND_EDGE
/// k2h)^2` below).
fn row_split(span: usize, k1h: f64, top: f64, len_low: usize, kxh: Option<f64>) -> f64 {
    let cost = |k2h: f64| {
        let high = (span as f64 + REACH / k2h) * top;
        let low = len_low as f64 * BAND_EDGE * k2h.min(top / BAND_EDGE);
        high * high + low * low
    };
    let ceiling = kxh.unwrap_or(f64::INFINITY).min(top);
    (0..16)
        .map(|i| 2.0 * k1h * 2f64.powf(0.5 * i as f64))
        .filter(|&k2h| k2h <= ceiling)
        .min_by(|&a, &b| cost(a).total_cmp(&cost(b)))
        .unwrap_or(k1h)
}

/// `row += rows`.
fn add_to_row(row: &mut [Vec<f64>; COMPONENTS], rows: &[Vec<f64>; COMPONENTS]) {
    for (o, r) in row.iter_mut().zip(rows) {
        for (a, b) in o.iter_mut().zip(r) {
            *a += b;
        }
    }
}

/// Whether the full expansion's short waves at decay length `lambda` need aliases on
/// a box of `REACH / k1` cells, and so are summed in bands.
fn needs_bands(lattice: &OffsetLattice, lambda: f64) -> bool {
    let h = lattice.cell;
    ALIAS_DECAY * h / lambda >= PI && split_wavenumber(lattice) * h < 1.0
}

/// Whether an XZ section's `lattice` (all columns of the row's sources) sums the
/// short waves against the pressure's spectrum, on a box of at most `ROW_BOX_LIMIT`.
fn row_lattice(lattice: &OffsetLattice, source: &RowSource) -> bool {
    lattice.x_first == -(source.nx as f64 - 1.0)
        && lattice.cols == 2 * source.nx - 1
        && box_cells(
            span_in_cells(lattice),
            split_wavenumber(lattice) * lattice.cell,
        ) <= ROW_BOX_LIMIT
}

/// The largest distance (in cells) from the loaded cell's centre to an offset of
/// `lattice`, as the long waves' Hankel transforms take it.
fn offset_reach(lattice: &OffsetLattice) -> f64 {
    let extent = |first: f64, count: usize| first.abs().max((first + count as f64 - 1.0).abs());
    extent(lattice.x_first, lattice.cols)
        .hypot(extent(lattice.y_first, lattice.rows))
        .max(1.0)
}

/// The periodic box (cells per side) of a pass whose lowest wavenumber is `low` (times
/// the cell) for offsets `span` cells from the loaded cell: its kernel reaches `REACH /
/// low` cells, so no image of the loaded cell comes that near an offset.
fn box_cells(span: usize, low: f64) -> usize {
    let reach = (REACH / low).ceil() as usize;
    fft_friendly((span + reach).max(2 * span + 2)).max(16)
}

/// The largest periodic box (cells per side) on which an XZ section sums the short
/// waves against the pressure's spectrum, which it keeps (`len^2 / 2` complex
/// values, 134 MB at this size); a larger box (a window of over ~680 cells) keeps the
/// kernel table, whose lattice sum keeps one column at a time.
const ROW_BOX_LIMIT: usize = 4096;

/// The alias-summed spectrum of a part of the remainder on its periodic box (see
/// [`remainder_on_lattice`]): `at(jx, jy)` is the box's Fourier coefficient of the
/// six components (normalised for an inverse FFT), with the fractional offsets'
/// phases; zero beyond the wavenumbers the decay `e^{-k lambda}` reaches.
struct BoxSpectrum {
    ax: Axis,
    ay: Axis,
    tx: Vec<AxisTerms>,
    ty: Vec<AxisTerms>,
    radial_table: std::sync::Arc<RadialTable>,
    pass: Pass,
    k1h: f64,
    theta_cut: f64,
    norm: f64,
    /// The radial functions times the pass's share at every squared integer radius
    /// `n = ix^2 + iy^2` the sum meets (`theta = 2 pi sqrt(n) / len`), up to the cut:
    /// the box's wavenumbers and their aliases take only `n` integers, so each
    /// distinct one is evaluated once (far fewer than the terms of the sum: sums of two
    /// squares are sparse). `None` for a table too large to keep.
    squares: Option<Vec<[f64; 4]>>,
    /// The sub-cell split's top band where `squares` is too large, summed once for
    /// every base pair ([`BoxSpectrum::by_radius`]); `at_pair` reads it.
    half_plane: Option<Vec<[Complex<f64>; COMPONENTS]>>,
}

/// The largest squared radius [`BoxSpectrum`] tabulates (16 MB of values).
const SQUARES_LIMIT: f64 = 5e5;

/// Per base index of an axis and alias order: theta = k h and the weight (`sinc`,
/// taper and the phase of the fractional offset).
struct AxisTerms {
    theta: Vec<f64>,
    weight: Vec<Complex<f64>>,
    /// `theta len / (2 pi)`: the wavenumber as a signed integer.
    index: Vec<i64>,
}

impl BoxSpectrum {
    fn new(
        lattice: &OffsetLattice,
        lambda: f64,
        thickness: f64,
        k1: f64,
        radial: &Radial,
        pass: Pass,
        shared: Option<&std::sync::Arc<RadialTable>>,
    ) -> Self {
        let h = lattice.cell;
        let k1h = k1 * h;
        // Aliases: |k| up to where e^{-k lambda} is negligible (in cells: k h = theta),
        // or up to the long waves' band edge.
        let mut theta_max = ALIAS_DECAY * h / lambda.max(1e-300);
        if let Pass::Band { .. } = pass {
            theta_max = theta_max.min(BAND_EDGE * k1h);
        }
        // Alias m covers theta in [2 pi m - pi, 2 pi m + pi].
        let needed = ((theta_max + PI) / (2.0 * PI)).floor().min(1e9) as i64;
        // Per axis: the alias orders kept and whether they are tapered. Offsets that
        // are not whole cells along an axis (an XZ section on a row edge) put some of
        // them on the loaded cell's edge, where the kernel varies on the scale lambda:
        // below the surface that axis keeps up to `SUB_CELL_EDGE_ALIASES`. (At the
        // surface the edge values with 128 and 2048 tapered orders agreed to 1e-11 of
        // the peak, h1 = cell / 100 ... cell / 1e4, E1/E2 = 0.01, 3, 300, measured with
        // the slope carrier at lambda; with 128 against the full expansion at h1 =
        // cell / 60: `tests/coated_stress_sub_cell.rs`.)
        let orders = |first: f64| -> (i64, bool) {
            let edge = matches!(pass, Pass::Short { edge: true, .. });
            let cap = if first == first.floor() || !edge {
                SUB_CELL_ALIASES
            } else {
                SUB_CELL_EDGE_ALIASES
            };
            match pass {
                Pass::Short { taper: true, .. } if needed > cap => (cap, true),
                Pass::Short { taper: true, .. } => (needed.max(0), false),
                Pass::Short { taper: false, .. } => (needed.clamp(0, FULL_ALIASES), false),
                Pass::Band { .. } => (needed.max(0), false),
            }
        };
        // A square box, so that the images are equally far in both directions.
        let span = span_in_cells(lattice);
        // The lowest wavenumber of the pass: its kernel reaches `REACH` over it.
        let low = match pass {
            Pass::Short { .. } => k1h,
            Pass::Band { low } => low,
        };
        let len = box_cells(span, low);
        let ax = Axis::new(lattice.x_first, orders(lattice.x_first), len);
        let ay = Axis::new(lattice.y_first, orders(lattice.y_first), len);
        let aliases = ax.aliases.max(ay.aliases);
        // The taper's weight at theta along an axis: 1 up to half the wavenumbers the
        // aliases cover, then a smooth step to 0 at their edge `(2 aliases + 1) pi`. As a
        // smooth function of the wavenumber (not of the alias order) it is a low-pass
        // filter whose real-space kernel has all moments zero, so it changes the kernel
        // only where that varies on the scale `cell / aliases`.
        let taper_weight = |a: &Axis, t: f64| {
            if a.tapered {
                let half = 0.5 * PI * (2 * a.aliases + 1) as f64;
                taper((t.abs() - half) / half)
            } else {
                1.0
            }
        };
        // Theta = k h of the table: up to the largest alias, capped by the decay (the
        // sum below reads no theta beyond `theta_max`). Capping at `theta_max` rather
        // than a period beyond it keeps the table at most 64 panels of the transfer's
        // scale `h / (2 (lambda + h1))` (lambda >= h1), however thick the coating.
        let theta_top = (PI * (2 * aliases + 1) as f64 * 2f64.sqrt()).min(theta_max);
        // The longest length in the transfer's exponentials is about z + 2 h1 <= 2 lambda + 2 h1.
        // Below k1 / 100 the high-pass factor is below 1e-16.
        let radial_table = match shared {
            Some(table) => table.clone(),
            None => std::sync::Arc::new(RadialTable::new(
                theta_top,
                h,
                2.0 * (lambda + thickness),
                0.01 * low,
                radial,
            )),
        };

        // Per axis: for each base index and alias order, theta = k h, sinc and the phase
        // of the fractional offset.
        let terms = |a: &Axis| -> Vec<AxisTerms> {
            let n_alias = (2 * a.aliases + 1) as usize;
            (0..a.len)
                .map(|j| {
                    let mut theta = Vec::with_capacity(n_alias);
                    let mut weight = Vec::with_capacity(n_alias);
                    let mut index = Vec::with_capacity(n_alias);
                    let signed = if j <= a.len / 2 {
                        j as i64
                    } else {
                        j as i64 - a.len as i64
                    };
                    for m in -a.aliases..=a.aliases {
                        let t = a.base(j) + 2.0 * PI * m as f64;
                        theta.push(t);
                        weight.push(Complex::from_polar(
                            sinc(t / 2.0) * taper_weight(a, t),
                            t * a.frac,
                        ));
                        index.push(signed + m * a.len as i64);
                    }
                    AxisTerms {
                        theta,
                        weight,
                        index,
                    }
                })
                .collect()
        };
        let (tx, ty) = (terms(&ax), terms(&ay));
        let norm = 1.0 / (ax.len * ay.len) as f64;
        let mut spectrum = BoxSpectrum {
            ax,
            ay,
            tx,
            ty,
            radial_table,
            pass,
            k1h,
            // Beyond theta_max the remainder is below e^{-ALIAS_DECAY} of its scale.
            theta_cut: theta_max,
            norm,
            squares: None,
            half_plane: None,
        };
        spectrum.squares = spectrum.tabulate_squares();
        // The sub-cell split's top band beyond the squared-radii table (a decay length
        // under about a tenth of a cell): once per |k| for every base pair. (Within the
        // table, per base pair was 8 % faster: a section through a 0.19-cell layer.)
        if spectrum.squares.is_none()
            && matches!(pass, Pass::Short { taper: true, .. })
            && spectrum.ax.len == spectrum.ay.len
        {
            spectrum.half_plane = Some(spectrum.by_radius());
        }
        spectrum
    }

    /// The half plane's coefficients (`jx <= len / 2`, every `jy`; index `jx len +
    /// jy`) of a square box, visiting each |k| once: a wavenumber `(ix, iy)` of the
    /// lattice with `0 <= iy <= ix` stands for up to eight, `(+-ix, +-iy)` and `(+-iy,
    /// +-ix)`, which share |k| and so one radial evaluation; each is added to its base
    /// pair `(ix mod len, iy mod len)` with its weights along x and y (those of
    /// [`AxisTerms`]). The same terms as [`Self::at_pair`]'s, summed in another order,
    /// at a quarter of its radial evaluations (it sums the half plane): the sub-cell
    /// split's top band has about `pi (32 len h / (2 pi lambda))^2 / 2` terms per depth
    /// (millions for a decay length under a tenth of a cell). Measured: a section
    /// through a 0.064-cell layer on a rigid base, 4.0 -> 2.4 s.
    fn by_radius(&self) -> Vec<[Complex<f64>; COMPONENTS]> {
        let len = self.ax.len;
        // Per axis and signed index: the weight and the base index (`jx` only on the
        // half plane), zero weight where the axis has no term.
        struct Lookup {
            lowest: i64,
            weight: Vec<Complex<f64>>,
            base: Vec<usize>,
            kept: Vec<bool>,
        }
        let lookup = |terms: &[AxisTerms], half_plane: bool| -> Lookup {
            let (lowest, highest) = terms
                .iter()
                .flat_map(|t| &t.index)
                .fold((i64::MAX, i64::MIN), |(lo, hi), &i| (lo.min(i), hi.max(i)));
            let size = (highest - lowest + 1) as usize;
            let mut table = Lookup {
                lowest,
                weight: vec![Complex::default(); size],
                base: vec![0; size],
                kept: vec![false; size],
            };
            for (j, t) in terms.iter().enumerate() {
                for (&i, &w) in t.index.iter().zip(&t.weight) {
                    let k = (i - lowest) as usize;
                    table.weight[k] = w;
                    table.base[k] = j;
                    table.kept[k] = !half_plane || j <= len / 2;
                }
            }
            table
        };
        let (lx, ly) = (lookup(&self.tx, true), lookup(&self.ty, false));
        let slot = |l: &Lookup, i: i64| -> Option<usize> {
            let k = usize::try_from(i - l.lowest).ok()?;
            l.kept.get(k).copied().unwrap_or(false).then_some(k)
        };
        let n_max = (self.theta_cut * len as f64 / (2.0 * PI)).powi(2).floor() as i64;
        let reach = ((n_max as f64).sqrt().floor() as i64).max(0);
        // A wedge point has an image among the axes' terms only if its larger index is
        // within the wider axis's extent and its smaller within the narrower's (the
        // alias orders are capped, the decay's cut may reach far beyond them).
        let extent = |l: &Lookup| l.lowest.abs().max(l.lowest + l.weight.len() as i64 - 1);
        let (narrow, wide) = (extent(&lx).min(extent(&ly)), extent(&lx).max(extent(&ly)));
        let mut spectrum = vec![[Complex::<f64>::default(); COMPONENTS]; (len / 2 + 1) * len];
        let i = Complex::new(0.0, 1.0);
        let mut add = |radial: [f64; 4], ix: i64, iy: i64, n: i64| {
            // The distinct images (a, b) of (ix, iy).
            let (sx, sy) = (if ix == 0 { 1 } else { 2 }, if iy == 0 { 1 } else { 2 });
            let mut images = [(0i64, 0i64); 8];
            let mut count = 0;
            for k in 0..sx * sy {
                let a = if k % 2 == 0 { ix } else { -ix };
                let b = if k / 2 == 0 { iy } else { -iy };
                images[count] = (a, b);
                count += 1;
                if ix != iy {
                    images[count] = (b, a);
                    count += 1;
                }
            }
            let inverse = if n > 0 { 1.0 / (n as f64).sqrt() } else { 0.0 };
            for &(a, b) in &images[..count] {
                let (Some(kx), Some(ky)) = (slot(&lx, a), slot(&ly, b)) else {
                    continue;
                };
                let (c, s) = if n > 0 {
                    (a as f64 * inverse, b as f64 * inverse)
                } else {
                    (1.0, 0.0)
                };
                let f = wave_frame_factors(radial, c, s);
                let w = lx.weight[kx] * ly.weight[ky];
                let cell = &mut spectrum[lx.base[kx] * len + ly.base[ky]];
                for q in 0..4 {
                    cell[q] += w * f[q];
                }
                cell[4] += i * w * f[4];
                cell[5] += i * w * f[5];
            }
        };
        // The wedge's points four at a time (their radial values together).
        let mut batch: Vec<(i64, i64, i64, f64)> = Vec::with_capacity(4);
        let mut flush = |batch: &mut Vec<(i64, i64, i64, f64)>| {
            let mut thetas = [0.0; 4];
            for (t, p) in thetas.iter_mut().zip(batch.iter()) {
                *t = p.3;
            }
            let radial = self.radial_table.eval_four(thetas);
            for (&(ix, iy, n, theta), r) in batch.iter().zip(radial) {
                let share = self.high_pass(theta);
                add(r.map(|v| v * share), ix, iy, n);
            }
            batch.clear();
        };
        for ix in 0..=reach.min(wide) {
            for iy in 0..=ix.min(narrow) {
                let n = ix * ix + iy * iy;
                if n > n_max {
                    break;
                }
                let theta = 2.0 * PI * (n as f64).sqrt() / len as f64;
                batch.push((ix, iy, n, theta));
                if batch.len() == 4 {
                    flush(&mut batch);
                }
            }
        }
        if !batch.is_empty() {
            flush(&mut batch);
        }
        let norm = self.norm;
        for cell in &mut spectrum {
            for v in cell.iter_mut() {
                *v *= norm;
            }
        }
        spectrum
    }

    /// The table of [`BoxSpectrum::squares`], if it is small enough.
    fn tabulate_squares(&self) -> Option<Vec<[f64; 4]>> {
        let len = self.ax.len;
        let n_max = (self.theta_cut * len as f64 / (2.0 * PI)).powi(2).floor();
        if self.ay.len != len || n_max.is_nan() || n_max >= SQUARES_LIMIT {
            return None;
        }
        let n_max = n_max as i64;
        let mut needed = vec![false; n_max as usize + 1];
        for x in &self.tx[..=len / 2] {
            for &ix in &x.index {
                let a = ix * ix;
                if a > n_max {
                    continue;
                }
                for y in &self.ty {
                    for &iy in &y.index {
                        let n = a + iy * iy;
                        if n <= n_max {
                            needed[n as usize] = true;
                        }
                    }
                }
            }
        }
        let ns: Vec<usize> = (0..needed.len()).filter(|&n| needed[n]).collect();
        let values: Vec<[f64; 4]> = ns
            .par_chunks(256)
            .flat_map_iter(|ns| {
                let thetas: Vec<f64> = ns
                    .iter()
                    .map(|&n| 2.0 * PI * (n as f64).sqrt() / len as f64)
                    .collect();
                let radial = self.radial_table.eval_many(&thetas);
                thetas
                    .into_iter()
                    .zip(radial)
                    .map(|(theta, r)| {
                        let share = self.high_pass(theta);
                        r.map(|v| v * share)
                    })
                    .collect::<Vec<_>>()
            })
            .collect();
        let mut table = vec![[0.0; 4]; needed.len()];
        for (n, v) in ns.into_iter().zip(values) {
            table[n] = v;
        }
        Some(table)
    }

    /// `1 - chi(k)`, which is 1 to double precision beyond BAND_EDGE k1, or the band
    /// `chi(k / k1) - chi(k / k_lo) = (1 - chi(k / k_lo)) - (1 - chi(k / k1))`
    /// (accurate where both shares are near 1).
    fn high_pass(&self, theta: f64) -> f64 {
        let k1h = self.k1h;
        match self.pass {
            Pass::Short { .. } if theta > BAND_EDGE * k1h => 1.0,
            Pass::Short { .. } => short_wave_share(theta, k1h),
            Pass::Band { low } if theta > BAND_EDGE * low => long_wave_share(theta, k1h),
            Pass::Band { low } => short_wave_share(theta, low) - short_wave_share(theta, k1h),
        }
    }

    /// Whether any wavenumber of column jx is within the decay's reach.
    fn column_reached(&self, jx: usize) -> bool {
        self.tx[jx].theta.iter().any(|t| t.abs() <= self.theta_cut)
    }

    /// The six components' coefficients at base wavenumbers `(jx, jy)` and `(jx, len -
    /// jy)` (the second is `None` where it is the first: `jy` 0 or `len / 2`). The two
    /// rows' alias terms are at `(kx, ky)` and `(kx, -ky)`: the same |k| (one radial
    /// evaluation for both), the same `c`, the opposite `s`, and conjugate phases
    /// along y. The terms of one alias order along y are summed first with their
    /// weights along x (`row`), then the row is weighted along y for both: the partner
    /// takes the same row sums with the conjugate weight and the signs of the
    /// components odd in `s` flipped.
    fn at_pair(
        &self,
        jx: usize,
        jy: usize,
    ) -> (
        [Complex<f64>; COMPONENTS],
        Option<[Complex<f64>; COMPONENTS]>,
    ) {
        let paired = jy != 0 && 2 * jy != self.ay.len;
        if let Some(half_plane) = &self.half_plane {
            let len = self.ay.len;
            return (
                half_plane[jx * len + jy],
                paired.then(|| half_plane[jx * len + len - jy]),
            );
        }
        let (x, y) = (&self.tx[jx], &self.ty[jy]);
        let mut acc = [Complex::<f64>::default(); COMPONENTS];
        let mut partner = [Complex::<f64>::default(); COMPONENTS];
        // One alias order along y: `sum_x wx f` of each term's six factors
        // (`wave_frame_factors`; the shears times i), added with wy to the row and
        // with its conjugate to the partner (s -> -s flips the fourth and sixth).
        let add_term = |row: &mut [Complex<f64>; COMPONENTS],
                        radial: [f64; 4],
                        c: f64,
                        s: f64,
                        wx: Complex<f64>| {
            let f = wave_frame_factors(radial, c, s);
            for (r, v) in row.iter_mut().zip(f) {
                *r += wx * v;
            }
        };
        let mut add_row = |row: [Complex<f64>; COMPONENTS], wy: Complex<f64>| {
            let i = Complex::new(0.0, 1.0);
            for q in 0..4 {
                acc[q] += wy * row[q];
            }
            acc[4] += i * wy * row[4];
            acc[5] += i * wy * row[5];
            if paired {
                let wy = wy.conj();
                for q in 0..3 {
                    partner[q] += wy * row[q];
                }
                partner[3] -= wy * row[3];
                partner[4] += i * wy * row[4];
                partner[5] -= i * wy * row[5];
            }
        };
        if let Some(squares) = &self.squares {
            let n_max = squares.len() as i64 - 1;
            for (&iy, &wy) in y.index.iter().zip(&y.weight) {
                let b = iy * iy;
                if b > n_max {
                    continue;
                }
                let mut row = [Complex::<f64>::default(); COMPONENTS];
                for (&ix, &wx) in x.index.iter().zip(&x.weight) {
                    let n = ix * ix + b;
                    if n > n_max {
                        continue;
                    }
                    let (c, s) = if n > 0 {
                        let radius = (n as f64).sqrt();
                        (ix as f64 / radius, iy as f64 / radius)
                    } else {
                        (1.0, 0.0)
                    };
                    add_term(&mut row, squares[n as usize], c, s, wx);
                }
                add_row(row, wy);
            }
        } else {
            let theta_cut = self.theta_cut;
            for (&ty_, &wy) in y.theta.iter().zip(&y.weight) {
                if ty_.abs() > theta_cut {
                    continue;
                }
                let mut row = [Complex::<f64>::default(); COMPONENTS];
                // Four alias terms at a time (their radial values evaluated together
                // where all four are within the cut), added in order.
                for (txs, wxs) in x.theta.chunks(4).zip(x.weight.chunks(4)) {
                    // |k| h; the wave numbers are bounded (a few times 2 pi),
                    // so hypot's overflow guard is not needed.
                    let mut thetas = [f64::INFINITY; 4];
                    for (t, &tx_) in thetas.iter_mut().zip(txs) {
                        *t = (tx_ * tx_ + ty_ * ty_).sqrt();
                    }
                    let radial = if thetas.iter().all(|&t| t <= theta_cut) {
                        self.radial_table.eval_four(thetas)
                    } else {
                        thetas.map(|t| {
                            if t <= theta_cut {
                                self.radial_table.eval(t)
                            } else {
                                [0.0; 4]
                            }
                        })
                    };
                    for ((&tx_, &wx), (&theta, r)) in
                        txs.iter().zip(wxs).zip(thetas.iter().zip(radial))
                    {
                        if theta > theta_cut {
                            continue;
                        }
                        let high_pass = self.high_pass(theta);
                        let r = r.map(|v| v * high_pass);
                        let (c, s) = if theta > 0.0 {
                            (tx_ / theta, ty_ / theta)
                        } else {
                            (1.0, 0.0)
                        };
                        add_term(&mut row, r, c, s, wx);
                    }
                }
                add_row(row, wy);
            }
        }
        let norm = self.norm;
        (
            acc.map(|a| a * norm),
            paired.then(|| partner.map(|a| a * norm)),
        )
    }
}

/// The six stress components' real factors of one wavenumber from the four wave-frame
/// functions `[xixi, etaeta, zz, xiz]` at its direction `(c, s) = k / |k|`:
/// `xixi c^2 + etaeta s^2`, `xixi s^2 + etaeta c^2`, `zz`, `(xixi - etaeta) c s`, `xiz
/// c`, `xiz s` (sigma_x, sigma_y, sigma_z, tau_xy, and tau_xz, tau_yz, which take a
/// factor i).
#[inline]
fn wave_frame_factors([xixi, etaeta, zz, xiz]: [f64; 4], c: f64, s: f64) -> [f64; COMPONENTS] {
    [
        xixi * c * c + etaeta * s * s,
        xixi * s * s + etaeta * c * c,
        zz,
        (xixi - etaeta) * c * s,
        xiz * c,
        xiz * s,
    ]
}

/// The four wave-frame functions of `theta = k h` on Chebyshev panels, evaluated
/// together (the lattice sum spends most of its time here). Panels double in width
/// from `theta_graded` up to the width `2 h / length` of the transfer's exponentials
/// (near k = 0 a stiff coating's transfer varies on the scale of its membrane length,
/// far below that width), keep that width up to four times it, then grow by
/// `GEOMETRIC_RATIO`: on `[a, 1.25 a]` the interpolant of any `e^{-theta L}` is within
/// `(0.25 a L / 4)^20 / 20! e^{-a L}`, at most 1e-26 of its value at 0 (the same
/// bound as the XZ rows' panels, `super::row_basis`), so the wide tables of thin
/// layers (wavenumbers up to `32 h / lambda`, hundreds of the width) take tens of
/// panels instead of hundreds.
struct RadialTable {
    graded: Vec<InterleavedPanels<4>>,
    theta_graded: f64,
    uniform_from: f64,
    uniform: Option<InterleavedPanels<4>>,
    geometric_from: f64,
    /// The geometric panels' lower ends and interpolants.
    geometric: Vec<(f64, InterleavedPanels<4>)>,
}

/// The growth of the radial table's panels beyond four times the uniform width.
const GEOMETRIC_RATIO: f64 = 1.25;

impl RadialTable {
    /// Tabulates `radial(theta / h)` on `[0, theta_top]`: graded panels from
    /// `theta_graded`, then panels no wider than the scale `h / length` of its
    /// exponentials, then geometric ones.
    fn new(theta_top: f64, h: f64, length: f64, theta_graded: f64, radial: &Radial) -> Self {
        let width = (2.0 * h / length.max(1e-300)).min(PI);
        // The panels first, then one parallel evaluation of the transfer at all points.
        let mut spans: Vec<(f64, f64, usize)> = vec![(0.0, theta_graded, 1)];
        let mut lo = theta_graded;
        while lo < width && lo < theta_top {
            spans.push((lo, 2.0 * lo, 1));
            lo *= 2.0;
        }
        let graded_count = spans.len();
        let uniform_from = lo;
        let geometric_from = (4.0 * width).max(lo).min(theta_top.max(lo));
        if lo < geometric_from {
            let panels = (((geometric_from - lo) / width).ceil() as usize).max(1);
            spans.push((lo, lo + panels as f64 * width, panels));
            lo += panels as f64 * width;
        }
        let uniform_count = spans.len() - graded_count;
        let geometric_from = lo;
        while lo < theta_top {
            let hi = lo * GEOMETRIC_RATIO;
            spans.push((lo, hi, 1));
            lo = hi;
        }
        let points: Vec<f64> = spans
            .iter()
            .flat_map(|&(lo, hi, n)| ChebyshevPanels::points(lo, hi, n, PANEL_DEGREE))
            .collect();
        let ks: Vec<f64> = points.iter().map(|&t| t / h).collect();
        let values = radial.eval_all(&ks);
        let cosines = ChebyshevPanels::dct_cosines(PANEL_DEGREE);
        let mut offset = 0;
        let mut tables = spans.iter().map(|&(lo, hi, n)| {
            let v = &values[offset..offset + n * PANEL_DEGREE];
            offset += n * PANEL_DEGREE;
            (
                lo,
                InterleavedPanels::new(std::array::from_fn(|q| {
                    let column: Vec<f64> = v.iter().map(|r| r[q]).collect();
                    ChebyshevPanels::from_values_with(lo, hi, n, &cosines, &column)
                })),
            )
        });
        let graded: Vec<InterleavedPanels<4>> =
            tables.by_ref().take(graded_count).map(|(_, t)| t).collect();
        let uniform = (uniform_count > 0)
            .then(|| tables.next().map(|(_, t)| t))
            .flatten();
        let geometric: Vec<(f64, InterleavedPanels<4>)> = tables.collect();
        RadialTable {
            graded,
            theta_graded,
            uniform_from,
            uniform,
            geometric_from,
            geometric,
        }
    }

    fn eval(&self, theta: f64) -> [f64; 4] {
        self.interpolant(theta).eval(theta)
    }

    /// The interpolant that holds theta.
    fn interpolant(&self, theta: f64) -> &InterleavedPanels<4> {
        if theta >= self.geometric_from && !self.geometric.is_empty() {
            let i = self
                .geometric
                .partition_point(|&(lo, _)| lo <= theta)
                .saturating_sub(1);
            return &self.geometric[i].1;
        }
        if theta >= self.uniform_from {
            if let Some(u) = &self.uniform {
                return u;
            }
        }
        let i = if theta < self.theta_graded {
            0
        } else {
            1 + (theta / self.theta_graded).log2().floor() as usize
        };
        &self.graded[i.min(self.graded.len() - 1)]
    }

    /// [`Self::eval`] at four thetas, bitwise the same: together where they share an
    /// interpolant (neighbouring thetas mostly do), so that their recurrences overlap.
    fn eval_four(&self, four: [f64; 4]) -> [[f64; 4]; 4] {
        let first = self.interpolant(four[0]);
        if four
            .iter()
            .all(|&t| std::ptr::eq(self.interpolant(t), first))
        {
            first.eval_batch(four)
        } else {
            four.map(|t| self.eval(t))
        }
    }

    /// [`Self::eval`] at every theta of `thetas`, bitwise the same, four at a time
    /// ([`Self::eval_four`]).
    fn eval_many(&self, thetas: &[f64]) -> Vec<[f64; 4]> {
        let mut out = Vec::with_capacity(thetas.len());
        let mut chunks = thetas.chunks_exact(4);
        for chunk in &mut chunks {
            out.extend(self.eval_four([chunk[0], chunk[1], chunk[2], chunk[3]]));
        }
        out.extend(chunks.remainder().iter().map(|&t| self.eval(t)));
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::body::layered::Ply;

    /// The sub-cell split's top band summed once per |k| (`BoxSpectrum::by_radius`)
    /// against the same box's sum per base pair (`at_pair`'s own alias loop), for a
    /// synthetic transfer decaying over 0.035 cell: offsets on whole cells and on half
    /// cells along y (the edge axis, untapered), and along x 128 tapered alias orders.
    #[test]
    fn the_top_band_by_radius_is_the_sum_per_base_pair() {
        let material = Elastic {
            young: 1.0,
            poisson: 0.3,
        };
        let stack = Stack {
            layers: vec![Ply {
                material,
                thickness: 0.02,
            }],
            base: Base::HalfSpace(material),
        };
        let lambda = 0.035;
        let eval = |_: &mut LayeredSolver, k: f64| {
            let t = k * lambda;
            let e = (-t).exp();
            [
                e * (1.0 + 0.3 * t),
                -0.4 * e,
                e * (1.0 - 0.2 * t * t),
                0.6 * t * e,
            ]
        };
        let radial = Radial {
            stack: &stack,
            eval: &eval,
        };
        let pass = Pass::Short {
            taper: true,
            edge: true,
        };
        for y_first in [-6.0, -5.5] {
            let lattice = OffsetLattice {
                cell: 1.0,
                x_first: -6.0,
                cols: 13,
                y_first,
                rows: 12,
            };
            let spectrum = |by_radius: bool| {
                let mut s =
                    BoxSpectrum::new(&lattice, lambda, 0.02, SUB_CELL_SPLIT, &radial, pass, None);
                if !by_radius {
                    s.half_plane = None;
                }
                s
            };
            let (fast, slow) = (spectrum(true), spectrum(false));
            assert!(fast.half_plane.is_some() && slow.squares.is_none());
            assert!(fast.ax.tapered && fast.ax.aliases == SUB_CELL_ALIASES);
            let len = fast.ay.len;
            let mut pairs = Vec::new();
            for jx in 0..=len / 2 {
                for jy in 0..=len / 2 {
                    pairs.push((jx, jy, fast.at_pair(jx, jy), slow.at_pair(jx, jy)));
                }
            }
            let peak = pairs
                .iter()
                .flat_map(|(_, _, _, (a, _))| a.iter().map(|v| v.norm()))
                .fold(0.0, f64::max);
            assert!(peak > 0.0);
            let mut worst = 0.0f64;
            for (jx, jy, (a, pa), (b, pb)) in pairs {
                let both = a
                    .iter()
                    .zip(&b)
                    .chain(pa.iter().flatten().zip(pb.iter().flatten()));
                for (u, v) in both {
                    worst = worst.max((u - v).norm() / peak);
                    assert!(
                        (u - v).norm() < 1e-13 * peak,
                        "y_first {y_first}, ({jx}, {jy}): {u} against {v}"
                    );
                }
                assert_eq!(pa.is_some(), pb.is_some());
            }
            println!("y_first {y_first}: {worst:.1e} of the peak");
        }
    }
}
