//! Stress influence kernels: the six stresses at `(x, y, z)` in an elastic half-space
//! per unit pressure uniform on the rectangle `|x| <= a, |y| <= b` of its surface.
//!
//! Homogeneous body: Love's closed form (A. E. H. Love, Phil. Trans. R. Soc. A 228,
//! 377, 1929), obtained from the Boussinesq potentials (Johnson, Contact Mechanics,
//! eq. 3.11-3.12; per unit pressure, `psi = int int 1/rho`, `psi1 = int int
//! ln(rho + z)`, `rho^2 = u^2 + v^2 + z^2`, `u = x - xi`, `v = y - eta`):
//! ```text
//! sigma_x = (1/2pi) [ 2 nu d psi/dz - z d2psi/dx2 - (1 - 2 nu) d2psi1/dx2 ]
//! sigma_y = (1/2pi) [ 2 nu d psi/dz - z d2psi/dy2 - (1 - 2 nu) d2psi1/dy2 ]
//! sigma_z = (1/2pi) [ d psi/dz - z d2psi/dz2 ]
//! tau_xy  = -(1/2pi) [ (1 - 2 nu) d2psi1/dxdy + z d2psi/dxdy ]
//! tau_xz  = -(1/2pi) z d2psi/dxdz,   tau_yz = -(1/2pi) z d2psi/dydz
//! ```
//! Every derivative of the potentials over the rectangle is the four-corner sum
//! `S[G] = G(x+a, y+b) - G(x+a, y-b) - G(x-a, y+b) + G(x-a, y-b)` of a primitive G
//! whose mixed derivative `G_uv` is the point-load integrand. The primitives used
//! (derived here, each checked against quadrature of the point-load stresses in the
//! tests) are
//! ```text
//! d psi/dz    = -S[A],   A  = atan(u v / (z rho))
//! d2psi/dx2   =  S[Cx],  Cx = -u v / ((u^2 + z^2) rho)     (Cy likewise with v)
//! d2psi/dz2   = -S[Cx + Cy]           (psi is harmonic)
//! d2psi/dxdy  =  S[1/rho]
//! d2psi/dxdz  =  S[-z v / ((u^2 + z^2) rho)]             (y, z likewise)
//! d2psi1/dx2  =  S[H1],  H1 = atan(v/u) - atan(z v / (u rho))
//!                            = atan(u v (u^2 + v^2) / ((rho + z)(u^2 rho + z v^2)))
//! d2psi1/dy2  =  S[A - H1]        (psi1 is harmonic: psi1_xx + psi1_yy = -psi_z)
//! d2psi1/dxdy =  S[ln(rho + z)]
//! ```
//! The forms have no subtraction of nearly equal numbers (`rho - z` is written
//! `(u^2 + v^2) / (rho + z)`), take `atan(y / x)` with `x >= 0` continued to `x = 0` so
//! they hold at z = 0 (Love's surface stresses, singular only on cell edges), and
//! the four-corner sums keep ~9 significant digits at 1000 cells from the load.
//!
//! [`StressKernels`] is the hook through which a body supplies its kernels to the
//! DC-FFT sections: a table of the six stresses per unit pressure on one square
//! cell, at a lattice of offsets with the cell's pitch. [`HomogeneousStressKernels`]
//! is Love's; a coated body plugs in its own.

use std::f64::consts::PI;

use crate::case::Elastic;
use crate::error::{Error, Result};

/// Number of stress components, ordered `[sigma_x, sigma_y, sigma_z, tau_xy, tau_xz,
/// tau_yz]` everywhere in this module.
pub const COMPONENTS: usize = 6;

/// The transcendental terms every corner primitive shares (one evaluation serves
/// [`corner_primitives`] and [`corner_primitives_split`]).
struct CornerTerms {
    u2: f64,
    v2: f64,
    z2: f64,
    rho: f64,
    uv: f64,
    a: f64,
    h1: f64,
    l: f64,
}

impl CornerTerms {
    #[inline]
    fn new(u: f64, v: f64, z: f64) -> Self {
        let (u2, v2, z2) = (u * u, v * v, z * z);
        let rho = (u2 + v2 + z2).sqrt();
        let uv = u * v;
        // atan(y / x) with x >= 0, continued by +-pi/2 (or 0) at x = 0: atan2
        // without its quadrant logic, which is slower.
        let half_atan = |y: f64, x: f64| {
            if x > 0.0 {
                (y / x).atan()
            } else if y == 0.0 {
                0.0
            } else {
                0.5 * PI * y.signum()
            }
        };
        CornerTerms {
            u2,
            v2,
            z2,
            rho,
            uv,
            a: half_atan(uv, z * rho),
            h1: half_atan(uv * (u2 + v2), (rho + z) * (u2 * rho + z * v2)),
            l: (rho + z).ln(),
        }
    }
}

/// The six corner primitives `G_c(u, v)` of the stress components (before the
/// factor `1 / (2 pi)`), valid for any signs of `u`, `v` and `z >= 0`.
#[inline]
fn corner_primitives(u: f64, v: f64, z: f64, nu: f64) -> [f64; COMPONENTS] {
    let CornerTerms {
        u2,
        v2,
        z2,
        rho,
        uv,
        a,
        h1,
        l,
    } = CornerTerms::new(u, v, z);
    let m = 1.0 - 2.0 * nu;
    if z2 == 0.0 {
        // The surface: the terms carrying a factor z vanish (no shear traction).
        return [
            -2.0 * nu * a - m * h1,
            -2.0 * nu * a - m * (a - h1),
            -a,
            -m * l,
            0.0,
            0.0,
        ];
    }
    let (uz, vz) = (u2 + z2, v2 + z2);
    let cx = -uv / (uz * rho);
    let cy = -uv / (vz * rho);
    [
        -2.0 * nu * a - z * cx - m * h1,
        -2.0 * nu * a - z * cy - m * (a - h1),
        -a + z * (cx + cy),
        -m * l - z / rho,
        z2 * v / (uz * rho),
        z2 * u / (vz * rho),
    ]
}

/// Parity of each component's primitive under `u -> -u` and `v -> -v`
/// (true = odd).
const ODD_IN_U: [bool; COMPONENTS] = [true, true, true, false, false, true];
pub(crate) const ODD_IN_V: [bool; COMPONENTS] = [true, true, true, false, true, false];

/// The stresses `[sigma_x, sigma_y, sigma_z, tau_xy, tau_xz, tau_yz]` at `(x, y, z)`,
/// `z >= 0`, per unit pressure on `|x| <= a, |y| <= b` (Love 1929), tension positive.
/// At z = 0 the value on a rectangle edge is the mean of both sides; it is infinite
/// only at a corner (tau_xy).
pub fn love_rectangle_stresses(
    material: Elastic,
    a: f64,
    b: f64,
    x: f64,
    y: f64,
    z: f64,
) -> [f64; COMPONENTS] {
    let nu = material.poisson;
    let g = |u, v| corner_primitives(u, v, z, nu);
    let (pp, pm, mp, mm) = (
        g(x + a, y + b),
        g(x + a, y - b),
        g(x - a, y + b),
        g(x - a, y - b),
    );
    let mut out = [0.0; COMPONENTS];
    for c in 0..COMPONENTS {
        out[c] = (pp[c] - pm[c] - mp[c] + mm[c]) / (2.0 * PI);
    }
    out
}

/// Offsets (field point minus loaded cell centre) at which kernels are tabulated,
/// in units of the cell side h: `x = (x_first + k) h` for `k < cols`,
/// `y = (y_first + m) h` for `m < rows`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OffsetLattice {
    /// Cell side h (the loaded cells are squares of side h).
    pub cell: f64,
    /// First x offset, in cells.
    pub x_first: f64,
    /// Number of x offsets.
    pub cols: usize,
    /// First y offset, in cells.
    pub y_first: f64,
    /// Number of y offsets.
    pub rows: usize,
}

/// Six kernels tabulated on an [`OffsetLattice`]: `values[c][m * cols + k]` is
/// component c at offset `((x_first + k) h, (y_first + m) h)`.
#[derive(Debug, Clone, Default)]
pub struct InfluenceTable {
    /// The lattice; `None` before the first fill.
    pub lattice: Option<OffsetLattice>,
    /// Component-major values, rows along y.
    pub values: [Vec<f64>; COMPONENTS],
    /// Work that a body's kernels keep between fills on one lattice (a section's
    /// depths): the table's owner keeps it, one per thread. Not part of the API.
    #[doc(hidden)]
    pub scratch: KernelScratch,
}

/// Work kept between [`StressKernels::fill`]s of one table: for layered bodies,
/// the depth-independent part of the long waves' Hankel transforms.
#[derive(Debug, Clone, Default)]
pub struct KernelScratch {
    pub(super) long_wave: super::long_wave::LongWaveBasis,
    /// Love's kernels for nu = 0 and their derivative in nu, refilled per depth.
    pub(super) love_split: Vec<InfluenceTable>,
}

impl InfluenceTable {
    /// Component `c` at lattice column `k`, row `m`.
    #[inline]
    pub fn get(&self, c: usize, k: usize, m: usize) -> f64 {
        let cols = self.lattice.map_or(0, |l| l.cols);
        self.values[c][m * cols + k]
    }
}

/// A source of subsurface stress kernels for one body: the hook through which each
/// body type (homogeneous, coated) supplies the stresses per unit pressure on one
/// square surface cell.
pub trait StressKernels: Sync {
    /// Fills `table` with the six stresses at depth `z >= 0` per unit pressure on a
    /// cell of side `lattice.cell` centred on the origin, at every offset of
    /// `lattice`. `table` is resized as needed so it can be reused across depths.
    fn fill(&self, z: f64, lattice: &OffsetLattice, table: &mut InfluenceTable);

    /// For each component, whether its kernel is even (`true`) or odd (`false`) in
    /// y, i.e. `K(x, -y) = +-K(x, y)`, to rounding in [`Self::fill`] (Love's kernels
    /// to the last bit, a layered body's to about 1e-16 of the table's peak);
    /// `None` (the default) if no such symmetry may be assumed. Sections use it to
    /// share work between source rows at opposite y offsets: an XZ section then
    /// tabulates the kernels only at offsets `|y|`.
    fn parity_in_y(&self) -> Option<[bool; COMPONENTS]> {
        None
    }

    /// For a section along one row of outputs (`source`, the pressure and the row):
    /// fills `table` as [`Self::fill`] does, or with only a part of the kernels, and
    /// then adds to `row` (`source.nx` values per component) the stresses along the
    /// row due to the rest, summed otherwise (a layered body sums its remainder's
    /// short waves against the pressure's spectrum), except the part that
    /// [`Self::add_prepared_row`] adds. The default puts everything in the table.
    fn fill_row(
        &self,
        z: f64,
        lattice: &OffsetLattice,
        table: &mut InfluenceTable,
        source: &RowSource,
        row: &mut [Vec<f64>; COMPONENTS],
    ) {
        let _ = (source, row);
        self.fill(z, lattice, table);
    }

    /// Work that the rows of a section's `depths` share, built once, while the
    /// depths' [`Self::fill_row`]s run (which must therefore know, from `lattice`,
    /// `source` and the depth alone, what it will hold). It must not depend on which
    /// depths are asked for beyond the set it serves: a depth's stresses are the same
    /// whichever other depths share its section. The default builds nothing.
    fn prepare_row(
        &self,
        lattice: &OffsetLattice,
        source: &RowSource,
        depths: &[f64],
    ) -> Option<PreparedRow> {
        let _ = (lattice, source, depths);
        None
    }

    /// Adds to `row` (after [`Self::fill_row`] and the table's sum) the part of depth
    /// z's stresses along the row that `prepared` ([`Self::prepare_row`]) holds.
    fn add_prepared_row(&self, z: f64, prepared: &PreparedRow, row: &mut [Vec<f64>; COMPONENTS]) {
        let _ = (z, prepared, row);
    }

    /// Plane strain (a line contact): fills `out[c][d + count - 1]`, `-(count - 1)
    /// <= d < count`, with the six stresses at `(d cell, z)` per unit pressure
    /// uniform on the strip `|x| <= cell / 2` of the surface and along all y
    /// ([`super::line`]); `out` is resized as needed. The default is an error: a
    /// body without plane-strain stress kernels.
    fn fill_strip(
        &self,
        z: f64,
        cell: f64,
        count: usize,
        out: &mut [Vec<f64>; COMPONENTS],
    ) -> Result<()> {
        let _ = (z, cell, count, out);
        Err(Error::invalid(
            "slider.shape",
            "a line contact",
            "a point contact: this body has no plane-strain stress kernels",
        ))
    }
}

/// Work a body's [`StressKernels::prepare_row`] builds once for the depths of an XZ
/// section, handed back to its [`StressKernels::add_prepared_row`].
pub type PreparedRow = Box<dyn std::any::Any + Send + Sync>;

/// The pressure on a grid of square cells and one row of outputs along x (at the
/// cell centres, at a y offset `offset` cells from the centre of source row 0), for
/// [`StressKernels::fill_row`]: the section owns it and shares it between the
/// depths; it keeps the pressure's spectra on the periodic boxes the kernels ask for.
pub struct RowSource<'a> {
    pressure: &'a [f64],
    /// Cells along x (outputs and sources).
    pub nx: usize,
    ny: usize,
    /// The row's y offset from source row 0's centre, in cells.
    pub offset: f64,
    spectra: std::sync::Mutex<Vec<std::sync::Arc<PressureSpectrum>>>,
    /// Moments of the pressure against a lattice's interpolation weights, per
    /// lattice and split wavenumber.
    #[allow(clippy::type_complexity)]
    moments: std::sync::Mutex<Vec<(OffsetLattice, f64, std::sync::Arc<Vec<f64>>)>>,
}

impl<'a> RowSource<'a> {
    /// `pressure[l * nx + k]` on source column k, row l; the row of outputs `offset`
    /// cells (along y) from source row 0.
    pub fn new(pressure: &'a [f64], nx: usize, ny: usize, offset: f64) -> Self {
        assert_eq!(pressure.len(), nx * ny, "one pressure per cell");
        RowSource {
            pressure,
            nx,
            ny,
            offset,
            spectra: std::sync::Mutex::new(Vec::new()),
            moments: std::sync::Mutex::new(Vec::new()),
        }
    }

    /// The pressure, `[l * nx + k]`.
    pub(crate) fn pressure(&self) -> &[f64] {
        self.pressure
    }

    /// Source rows (cells along y).
    pub(crate) fn rows(&self) -> usize {
        self.ny
    }

    /// Moments of the pressure for `lattice` and the split `k1` (built by `build` on
    /// first use, then shared between depths and threads).
    pub(crate) fn moments(
        &self,
        lattice: &OffsetLattice,
        k1: f64,
        build: impl FnOnce() -> Vec<f64>,
    ) -> std::sync::Arc<Vec<f64>> {
        let mut moments = self.moments.lock().unwrap_or_else(|e| e.into_inner());
        if let Some((_, _, m)) = moments.iter().find(|(l, k, _)| l == lattice && *k == k1) {
            return m.clone();
        }
        let m = std::sync::Arc::new(build());
        moments.push((*lattice, k1, m.clone()));
        m
    }

    /// The pressure's spectrum on a periodic box of `len` x `len` cells, with the
    /// row's phase for kernels whose y offsets have the fractional part `frac`, at
    /// its first `columns` wavenumbers along x (at most `len / 2 + 1`; computed on
    /// first use, then shared).
    pub(crate) fn spectrum(
        &self,
        len: usize,
        frac: f64,
        columns: usize,
    ) -> std::sync::Arc<PressureSpectrum> {
        let whole = (self.offset - frac).round();
        let columns = columns.min(len / 2 + 1);
        let mut spectra = self.spectra.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(s) = spectra
            .iter()
            .find(|s| s.len == len && s.whole == whole && s.columns >= columns)
        {
            return s.clone();
        }
        let s = std::sync::Arc::new(PressureSpectrum::new(
            self.pressure,
            self.nx,
            self.ny,
            len,
            whole,
            columns,
        ));
        spectra.push(s.clone());
        s
    }
}

/// The DFT of the pressure zero-padded to a periodic box of `len` x `len` cells,
/// `P(jx, jy) = sum_{k,l} p_{k,l} e^{-2 pi i (jx k + jy l) / len}`, times the phase
/// `e^{2 pi i jy f / len}` of the row's whole offset f (in cells) from source row 0,
/// for `jx <= len / 2` (the pressure is real): so that a kernel's box coefficients
/// `K^(j)` give the row's stresses `sum_j K^(j) P(j) e^{2 pi i jx i / len}`.
pub(crate) struct PressureSpectrum {
    len: usize,
    whole: f64,
    /// The wavenumbers along x held, `jx < columns`.
    columns: usize,
    /// `values[jx * len + jy]`.
    values: Vec<realfft::num_complex::Complex<f64>>,
}

impl PressureSpectrum {
    fn new(pressure: &[f64], nx: usize, ny: usize, len: usize, whole: f64, columns: usize) -> Self {
        use rayon::prelude::*;
        use realfft::num_complex::Complex;
        assert!(nx <= len && ny <= len, "the box holds the pressure");
        let half = len / 2 + 1;
        let forward = realfft::RealFftPlanner::<f64>::new().plan_fft_forward(len);
        // Along x, each source row (an unloaded row's spectrum is zero: empty), up to
        // the columns wanted.
        let columns = columns.min(half);
        let rows: Vec<Vec<Complex<f64>>> = (0..ny)
            .into_par_iter()
            .map(|l| {
                let line = &pressure[l * nx..(l + 1) * nx];
                if line.iter().all(|&p| p == 0.0) {
                    return Vec::new();
                }
                let mut real = vec![0.0; len];
                real[..nx].copy_from_slice(line);
                let mut spec = vec![Complex::default(); half];
                forward
                    .process(&mut real, &mut spec)
                    .expect("FFT lengths are fixed by the plan");
                spec.truncate(columns);
                spec
            })
            .collect();
        // Along y, each column, with the row's phase.
        let fft_y = rustfft::FftPlanner::<f64>::new().plan_fft_forward(len);
        let phase: Vec<Complex<f64>> = (0..len)
            .map(|jy| {
                let turns = (jy as i64 * whole as i64).rem_euclid(len as i64);
                Complex::from_polar(1.0, 2.0 * PI * turns as f64 / len as f64)
            })
            .collect();
        let values: Vec<Complex<f64>> = (0..columns)
            .into_par_iter()
            .flat_map_iter(|jx| {
                let mut column = vec![Complex::default(); len];
                for (c, r) in column.iter_mut().zip(&rows) {
                    if let Some(&v) = r.get(jx) {
                        *c = v;
                    }
                }
                fft_y.process(&mut column);
                column.into_iter().zip(&phase).map(|(c, p)| c * p)
            })
            .collect();
        PressureSpectrum {
            len,
            whole,
            columns,
            values,
        }
    }

    /// Column jx (below the columns computed): the values at `jy = 0..len`.
    pub(crate) fn column(&self, jx: usize) -> &[realfft::num_complex::Complex<f64>] {
        &self.values[jx * self.len..(jx + 1) * self.len]
    }
}

/// Love's kernels for a homogeneous half-space.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HomogeneousStressKernels {
    /// The half-space material (only nu enters the stresses).
    pub material: Elastic,
}

/// Corner coordinates `(first - 1/2 + k) h` (k = 0..=n, `first` in cells) as their
/// distinct absolute values and, per corner, the index into them and the sign.
fn folded_corners(first: f64, n: usize, h: f64) -> (Vec<f64>, Vec<(usize, f64)>) {
    let t0 = first - 0.5;
    let corners: Vec<f64> = (0..=n).map(|k| (t0 + k as f64) * h).collect();
    let mut order: Vec<usize> = (0..corners.len()).collect();
    order.sort_by(|&i, &j| corners[i].abs().total_cmp(&corners[j].abs()));
    let mut unique: Vec<f64> = Vec::with_capacity(corners.len());
    let mut map = vec![(0, 1.0); corners.len()];
    for &k in &order {
        let v = corners[k].abs();
        if unique.last() != Some(&v) {
            unique.push(v);
        }
        let sign = if corners[k] < 0.0 { -1.0 } else { 1.0 };
        map[k] = (unique.len() - 1, sign);
    }
    (unique, map)
}

impl StressKernels for HomogeneousStressKernels {
    fn parity_in_y(&self) -> Option<[bool; COMPONENTS]> {
        // A primitive odd in v gives a kernel even in y, and vice versa; the folded
        // evaluation in `fill` makes the symmetry exact.
        Some(ODD_IN_V)
    }

    fn fill(&self, z: f64, lattice: &OffsetLattice, table: &mut InfluenceTable) {
        let nu = self.material.poisson;
        let corners = FoldedCorners::new(lattice);
        let prim = corners.primitives(|u, v| corner_primitives(u, v, z, nu));
        corners.difference(&prim, lattice, table);
    }

    fn fill_strip(
        &self,
        z: f64,
        cell: f64,
        count: usize,
        out: &mut [Vec<f64>; COMPONENTS],
    ) -> Result<()> {
        super::line::homogeneous_strip(self, z, cell, count, out);
        Ok(())
    }
}

/// The distinct corner coordinates `|u| x |v|` of a lattice's cells (each corner is
/// shared by up to four cells, and the primitives have a parity in u and in v).
struct FoldedCorners {
    us: Vec<f64>,
    umap: Vec<(usize, f64)>,
    vs: Vec<f64>,
    vmap: Vec<(usize, f64)>,
}

impl FoldedCorners {
    fn new(lattice: &OffsetLattice) -> Self {
        let (us, umap) = folded_corners(lattice.x_first, lattice.cols, lattice.cell);
        let (vs, vmap) = folded_corners(lattice.y_first, lattice.rows, lattice.cell);
        FoldedCorners { us, umap, vs, vmap }
    }

    /// The primitives `g(u, v)` at the distinct corners, component-major.
    fn primitives(&self, g: impl Fn(f64, f64) -> [f64; COMPONENTS]) -> [Vec<f64>; COMPONENTS] {
        let nu_ = self.us.len();
        let mut prim: [Vec<f64>; COMPONENTS] =
            std::array::from_fn(|_| vec![0.0; nu_ * self.vs.len()]);
        for (q, &v) in self.vs.iter().enumerate() {
            for (p, &u) in self.us.iter().enumerate() {
                for (dst, val) in prim.iter_mut().zip(g(u, v)) {
                    dst[q * nu_ + p] = val;
                }
            }
        }
        prim
    }

    /// The four-corner sums of the primitives `prim` (of [`Self::primitives`]) into
    /// `table`.
    fn difference(
        &self,
        prim: &[Vec<f64>; COMPONENTS],
        lattice: &OffsetLattice,
        table: &mut InfluenceTable,
    ) {
        let (cols, rows) = (lattice.cols, lattice.rows);
        let (us, umap, vmap) = (&self.us, &self.umap, &self.vmap);
        let nu_ = us.len();
        // x offsets symmetric about 0 (the usual case): the kernel row is built for
        // x >= 0 from consecutive folded corners and mirrored with its parity
        // (a primitive odd in u gives a kernel even in x and vice versa).
        let half = cols.div_ceil(2);
        let symmetric_x = cols % 2 == 1 && lattice.x_first == -((half - 1) as f64) && nu_ == half;
        let index: Vec<usize> = umap.iter().map(|&(p, _)| p).collect();
        let sign: Vec<f64> = umap.iter().map(|&(_, s)| s).collect();
        let even = vec![1.0; umap.len()];
        let mut corner = vec![0.0; cols + 1];
        let (mut below, mut above) = (vec![0.0; cols], vec![0.0; cols]);
        let scale = 1.0 / (2.0 * PI);
        table.lattice = Some(*lattice);
        for c in 0..COMPONENTS {
            let out = &mut table.values[c];
            out.clear();
            out.reserve(cols * rows);
            for (r, &(q, sv)) in vmap.iter().enumerate() {
                let sv = scale * if ODD_IN_V[c] { sv } else { 1.0 };
                let src = &prim[c][q * nu_..(q + 1) * nu_];
                // Differences along u of the signed corner values of this corner row.
                if symmetric_x {
                    let mirror = if ODD_IN_U[c] { sv } else { -sv };
                    let centre = if ODD_IN_U[c] { 2.0 * src[0] } else { 0.0 };
                    above[half - 1] = sv * centre;
                    for d in 1..half {
                        let k = src[d] - src[d - 1];
                        above[half - 1 + d] = sv * k;
                        above[half - 1 - d] = mirror * k;
                    }
                } else {
                    let weight = if ODD_IN_U[c] { &sign } else { &even };
                    for ((dst, &p), &w) in corner.iter_mut().zip(&index).zip(weight) {
                        *dst = w * sv * src[p];
                    }
                    for (d, pair) in above.iter_mut().zip(corner.windows(2)) {
                        *d = pair[1] - pair[0];
                    }
                }
                if r > 0 {
                    out.extend(above.iter().zip(&below).map(|(a, b)| a - b));
                }
                std::mem::swap(&mut above, &mut below);
            }
        }
    }
}

impl HomogeneousStressKernels {
    /// Love's kernels are linear in nu: fills `base` with those of nu = 0 and
    /// `slope` with their derivative in nu (the corner primitives are evaluated
    /// once for both).
    pub(crate) fn fill_poisson_split(
        z: f64,
        lattice: &OffsetLattice,
        base: &mut InfluenceTable,
        slope: &mut InfluenceTable,
    ) {
        let corners = FoldedCorners::new(lattice);
        let both = corners.primitives2(|u, v| corner_primitives_split(u, v, z));
        corners.difference(&both.0, lattice, base);
        corners.difference(&both.1, lattice, slope);
    }

    /// The table of `combine(G(0), G')` at depth z, Love's kernels for nu = 0 and
    /// their derivative in nu ([`Self::fill_poisson_split`]) combined by a linear
    /// map, the same at every offset: applied to the corner primitives before their
    /// four-corner sums (which are linear and the same for every component of one
    /// parity), so one table is summed instead of two. `combine` must be linear and
    /// mix only components of the same parity in x and y (`sigma_x`, `sigma_y`,
    /// `sigma_z` together; each shear with itself).
    pub(crate) fn fill_poisson_combined(
        z: f64,
        lattice: &OffsetLattice,
        table: &mut InfluenceTable,
        combine: impl Fn(&[f64; COMPONENTS], &[f64; COMPONENTS]) -> [f64; COMPONENTS],
    ) {
        let corners = FoldedCorners::new(lattice);
        let (zero, slope) = corners.primitives2(|u, v| corner_primitives_split(u, v, z));
        let none = [0.0; COMPONENTS];
        let zero_map = linear_map(|e| combine(e, &none));
        let slope_map = linear_map(|e| combine(&none, e));
        let combined = apply_maps(&[(&zero_map, &zero), (&slope_map, &slope)]);
        corners.difference(&combined, lattice, table);
    }

    /// As [`Self::fill_poisson_combined`] at depth `lambda`, with Love's kernels of
    /// Poisson ratio nu at another depth z added to the combination:
    /// `combine(G_nu(z), G(0)(lambda), G'(lambda))` (linear), one table summed.
    pub(crate) fn fill_love_and_split_combined(
        z: f64,
        nu: f64,
        lambda: f64,
        lattice: &OffsetLattice,
        table: &mut InfluenceTable,
        combine: impl Fn(
            &[f64; COMPONENTS],
            &[f64; COMPONENTS],
            &[f64; COMPONENTS],
        ) -> [f64; COMPONENTS],
    ) {
        let corners = FoldedCorners::new(lattice);
        let own = corners.primitives(|u, v| corner_primitives(u, v, z, nu));
        let (zero, slope) = corners.primitives2(|u, v| corner_primitives_split(u, v, lambda));
        let none = [0.0; COMPONENTS];
        let own_map = linear_map(|e| combine(e, &none, &none));
        let zero_map = linear_map(|e| combine(&none, e, &none));
        let slope_map = linear_map(|e| combine(&none, &none, e));
        let combined = apply_maps(&[(&own_map, &own), (&zero_map, &zero), (&slope_map, &slope)]);
        corners.difference(&combined, lattice, table);
    }
}

/// A linear map of the six components, `m[out][in]`.
type LinearMap = [[f64; COMPONENTS]; COMPONENTS];

/// The matrix of a linear map of the six components, from its images of the unit
/// vectors.
fn linear_map(map: impl Fn(&[f64; COMPONENTS]) -> [f64; COMPONENTS]) -> LinearMap {
    let mut m = [[0.0; COMPONENTS]; COMPONENTS];
    for input in 0..COMPONENTS {
        let mut e = [0.0; COMPONENTS];
        e[input] = 1.0;
        for (out, v) in map(&e).into_iter().enumerate() {
            m[out][input] = v;
        }
    }
    m
}

/// `sum_k m_k v_k` over arrays of corner values, per component: one vectorisable
/// pass per nonzero matrix entry.
fn apply_maps(maps: &[(&LinearMap, &[Vec<f64>; COMPONENTS])]) -> [Vec<f64>; COMPONENTS] {
    let n = maps.first().map_or(0, |(_, v)| v[0].len());
    std::array::from_fn(|out| {
        let mut acc = vec![0.0; n];
        for (m, values) in maps {
            for (input, &weight) in m[out].iter().enumerate() {
                if weight != 0.0 {
                    for (a, &v) in acc.iter_mut().zip(&values[input]) {
                        *a += weight * v;
                    }
                }
            }
        }
        acc
    })
}

impl FoldedCorners {
    /// [`Self::primitives`] of two primitive sets evaluated together.
    #[allow(clippy::type_complexity)]
    fn primitives2(
        &self,
        g: impl Fn(f64, f64) -> ([f64; COMPONENTS], [f64; COMPONENTS]),
    ) -> ([Vec<f64>; COMPONENTS], [Vec<f64>; COMPONENTS]) {
        let nu_ = self.us.len();
        let n = nu_ * self.vs.len();
        let mut a: [Vec<f64>; COMPONENTS] = std::array::from_fn(|_| vec![0.0; n]);
        let mut b: [Vec<f64>; COMPONENTS] = std::array::from_fn(|_| vec![0.0; n]);
        for (q, &v) in self.vs.iter().enumerate() {
            for (p, &u) in self.us.iter().enumerate() {
                let (ga, gb) = g(u, v);
                for c in 0..COMPONENTS {
                    a[c][q * nu_ + p] = ga[c];
                    b[c][q * nu_ + p] = gb[c];
                }
            }
        }
        (a, b)
    }
}

/// [`corner_primitives`] split by its linearity in nu: those of nu = 0 and their
/// derivative in nu, from one evaluation of the transcendental terms.
#[inline]
fn corner_primitives_split(u: f64, v: f64, z: f64) -> ([f64; COMPONENTS], [f64; COMPONENTS]) {
    let CornerTerms {
        u2,
        v2,
        z2,
        rho,
        uv,
        a,
        h1,
        l,
    } = CornerTerms::new(u, v, z);
    let slope = [-2.0 * a + 2.0 * h1, -2.0 * h1, 0.0, 2.0 * l, 0.0, 0.0];
    if z2 == 0.0 {
        return ([-h1, -(a - h1), -a, -l, 0.0, 0.0], slope);
    }
    let (uz, vz) = (u2 + z2, v2 + z2);
    let cx = -uv / (uz * rho);
    let cy = -uv / (vz * rho);
    (
        [
            -z * cx - h1,
            -z * cy - (a - h1),
            -a + z * (cx + cy),
            -l - z / rho,
            z2 * v / (uz * rho),
            z2 * u / (vz * rho),
        ],
        slope,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    const MAT: Elastic = Elastic {
        young: 1.0,
        poisson: 0.3,
    };

    #[test]
    fn table_equals_the_direct_closed_form() {
        // The folded-lattice evaluation is an optimisation of the same formula.
        let kernels = HomogeneousStressKernels { material: MAT };
        let h = 0.7;
        for &(x_first, y_first) in &[(-3.0, -2.0), (-2.0, 0.37)] {
            let lattice = OffsetLattice {
                cell: h,
                x_first,
                cols: 7,
                y_first,
                rows: 5,
            };
            for &z in &[0.0, 0.05, 1.3] {
                let mut table = InfluenceTable::default();
                kernels.fill(z, &lattice, &mut table);
                for m in 0..lattice.rows {
                    for k in 0..lattice.cols {
                        let (x, y) = ((x_first + k as f64) * h, (y_first + m as f64) * h);
                        let direct = love_rectangle_stresses(MAT, h / 2.0, h / 2.0, x, y, z);
                        for (c, d) in direct.iter().enumerate() {
                            let t = table.get(c, k, m);
                            assert!((t - d).abs() < 1e-13, "c {c} z {z} ({x}, {y}): {t} vs {d}");
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn poisson_split_is_love_at_any_nu() {
        let lattice = OffsetLattice {
            cell: 0.7,
            x_first: -3.0,
            cols: 7,
            y_first: 0.5,
            rows: 4,
        };
        for &z in &[0.0, 0.05, 1.3] {
            let (mut base, mut slope) = (InfluenceTable::default(), InfluenceTable::default());
            HomogeneousStressKernels::fill_poisson_split(z, &lattice, &mut base, &mut slope);
            for nu in [0.0, 0.3, 0.5] {
                let mut direct = InfluenceTable::default();
                let material = Elastic { poisson: nu, ..MAT };
                HomogeneousStressKernels { material }.fill(z, &lattice, &mut direct);
                for c in 0..COMPONENTS {
                    for (n, d) in direct.values[c].iter().enumerate() {
                        let split = base.values[c][n] + nu * slope.values[c][n];
                        assert!(
                            (split - d).abs() < 1e-14,
                            "c {c} z {z} nu {nu}: {split} vs {d}"
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn folded_corners_find_the_symmetry() {
        let (u, map) = folded_corners(-2.0, 5, 1.0);
        assert_eq!(u, vec![0.5, 1.5, 2.5]);
        assert_eq!(map[0], (2, -1.0));
        assert_eq!(map[5], (2, 1.0));
    }
}
