//! The bodies under the layer, seen through one small interface, [`BodyModel`]:
//! the influence kernel that maps a pressure uniform over one surface cell to the
//! normal surface displacement at every cell centre (paper eq. 9 for a homogeneous
//! half-space, eq. 10 for a coated one, generalised to any stack of layers, and the
//! steady-sliding kernel of a viscoelastic half-space), whether that kernel is even
//! and whether it depends on the sliding speed, the power the body dissipates, the
//! stress kernels at a depth, the depths of material interfaces, and the modulus the
//! automatic window needs. A case's [`Body`] is plain data; [`Body::model`] is the one place that
//! picks the implementation. The solvers never see more than the kernel's DC-FFT
//! spectrum (built through [`crate::KernelCache`]).

pub mod homogeneous;
pub mod hysteresis;
pub mod layered;
pub mod line;
pub(crate) mod quadrature;
pub mod solid;
pub mod stack;
pub(crate) mod stack_line;
#[cfg(test)]
pub(crate) mod two_layer_oracle;
pub mod viscoelastic;

use std::sync::Arc;

use realfft::num_complex::Complex;

pub use homogeneous::HomogeneousHalfSpace;
pub use hysteresis::EdgeProfile;
pub use solid::{SolidRheology, ViscoelasticHalfSpace};
pub use stack::StackBody;
pub use viscoelastic::ViscoelasticBody;

/// Which side of an interface between two materials a depth equal to the
/// interface's is read on (stresses that jump there: sigma_x, sigma_y, tau_xy).
/// For a coating, `Above` is the coating's side and `Below` the substrate's.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Side {
    /// The layer above the interface.
    Above,
    /// The layer (or half-space) below it.
    Below,
}

use crate::case::Body;
use crate::convolution::{ConvolutionPlan, KernelSpectrum};
use crate::error::Result;
use crate::grid::{Geometry, Grid};
use crate::provenance::Reference;
use crate::stress::StressKernels;

/// The surface influence kernel of a body on square cells: the normal displacement
/// at the centre of the cell `(di, dj)` cells away from a cell under unit pressure
/// (`di`, `dj` the field cell's index minus the loaded cell's), stored by the
/// symmetry it has. Every kernel is even in `dj` (the sliding direction is x).
#[derive(Debug, Clone, PartialEq)]
pub enum SurfaceKernel {
    /// Even in `di` and `dj` (an elastic body, or a viscoelastic one at zero or
    /// infinite speed): `quadrant[dj * nx + di]` for `0 <= di < nx`, `0 <= dj < ny`.
    Even {
        /// The quadrant.
        quadrant: Vec<f64>,
        /// Cells along x.
        nx: usize,
    },
    /// Even in `dj` only (a body that creeps in steady sliding):
    /// `half[dj * (2 nx - 1) + (di + nx - 1)]` for `-nx < di < nx`, `0 <= dj < ny`.
    EvenInY {
        /// The half plane of offsets.
        half: Vec<f64>,
        /// Cells along x.
        nx: usize,
    },
}

impl SurfaceKernel {
    /// The kernel at the offset `(di, dj)`, `|di| < nx`, `|dj| < ny`.
    pub fn at(&self, di: i64, dj: i64) -> f64 {
        let dj = dj.unsigned_abs() as usize;
        match self {
            SurfaceKernel::Even { quadrant, nx } => quadrant[dj * nx + di.unsigned_abs() as usize],
            SurfaceKernel::EvenInY { half, nx } => {
                half[dj * (2 * nx - 1) + (di + *nx as i64 - 1) as usize]
            }
        }
    }

    /// Whether the kernel is even in `di` too (the contact operator is then
    /// symmetric).
    pub fn is_even(&self) -> bool {
        matches!(self, SurfaceKernel::Even { .. })
    }
}

/// A body as the solvers and the stress sections see it.
pub trait BodyModel: std::fmt::Debug + Send + Sync {
    /// The surface influence kernel on `nx x ny` square cells of side `cell` when
    /// the slider moves at `velocity` (`+inf` allowed) in +x. With `lag` the slider
    /// bears on the body directly, and the kernel may leave out a lag of the
    /// displacement that the gap takes instead ([`BodyModel::creep_shift`]);
    /// without, it carries the body's whole response (a layer lies between).
    fn surface_kernel(
        &self,
        cell: f64,
        nx: usize,
        ny: usize,
        velocity: f64,
        lag: bool,
    ) -> Result<SurfaceKernel>;
    /// The plane-strain (line contact) surface kernel on `nx` cells of width `cell`
    /// along x, each loaded uniformly along y, when the slider moves at `velocity`
    /// in +x: `Even { quadrant, nx }` holds `nx` values (offsets `0..nx`),
    /// `EvenInY { half, nx }` holds `2 nx - 1` (offsets `-(nx - 1)..nx`). The
    /// displacement is measured against the surface at distance `reference` from
    /// the load for the body's long-wave (relaxed) compliance ([`mod@line`]); a body on
    /// a rigid base has no long-wave compliance and is measured from the base.
    /// `lag` as for [`BodyModel::surface_kernel`].
    fn line_kernel(
        &self,
        cell: f64,
        nx: usize,
        velocity: f64,
        reference: f64,
        lag: bool,
    ) -> Result<SurfaceKernel>;
    /// Whether the surface kernel depends on the sliding speed (a cache of kernels
    /// keys on the speed then).
    fn kernel_depends_on_velocity(&self) -> bool;
    /// The distance `c` by which the solvers read the slider's height upstream, at
    /// `f - c df/dx`, on cells of side `cell` at `velocity`, for the kernels built
    /// with `lag`: a viscoelastic body's kernel gives its creep shorter than a cell
    /// to the gap as this lag ([`viscoelastic`] module documentation, "creep shorter
    /// than a cell"). 0 (the default) for a body whose kernel carries its whole
    /// response.
    fn creep_shift(&self, cell: f64, velocity: f64) -> f64 {
        let _ = (cell, velocity);
        0.0
    }
    /// Whether the surface kernel at `velocity` is even in x, which makes the
    /// contact operator symmetric (conjugate gradients then apply).
    fn kernel_is_even(&self, velocity: f64) -> bool;
    /// The power dissipated in the body divided by the sliding speed (a force) when
    /// the cells of `grid` carry `pressure` (mean over each cell) sliding at
    /// `velocity`, the pressure falling to zero at the contact's edges as `edges`
    /// says: 0 for an elastic body.
    fn dissipated_force(
        &self,
        grid: &Grid,
        pressure: &[f64],
        velocity: f64,
        edges: EdgeProfile,
    ) -> Result<f64>;
    /// The six stresses at depth per unit pressure on one cell; a depth equal to an
    /// interface's is read on `interface_side`.
    fn stress_kernels(&self, interface_side: Side) -> Box<dyn StressKernels>;
    /// Depths of the interfaces between materials, from the surface down (none for
    /// a homogeneous body); interface `i` lies under layer `i`.
    fn interface_depths(&self) -> Vec<f64>;
    /// The deepest depth with stresses, if the body ends (a rigid base's face).
    fn deepest(&self) -> Option<f64> {
        None
    }
    /// The compliance `J(k_x)` of the surface to a pressure wave
    /// `exp(i (k_x x + k_y y))` (wavenumbers in radians per length) when the slider
    /// moves at `velocity` in +x: the wave's displacement is `(2 / |k|) J(k_x)`
    /// times it. Love's operator for a homogeneous elastic half-space has the
    /// plane-strain compliance `J = (1 - nu^2) / E`; a viscoelastic one in steady
    /// sliding the complex creep compliance at the frequency `V k_x` (the
    /// correspondence principle along the material's path). `None` (the default)
    /// for a body whose surface is not of that form (a layered one): the contact
    /// solver then has no approximate inverse of its operator.
    fn surface_compliance(&self, wavenumber_x: f64, velocity: f64) -> Option<Complex<f64>> {
        let _ = (wavenumber_x, velocity);
        None
    }
    /// The smallest plane-strain modulus `E / (1 - nu^2)` of its materials (the
    /// automatic window's Hertz estimate uses it).
    fn softest_modulus(&self) -> f64;
    /// The works its kernels come from, with what each gives.
    fn references(&self) -> Vec<Reference>;
}

impl Body {
    /// The implementation of [`BodyModel`] for this body: the one place a body's
    /// data meets its model.
    pub fn model(&self) -> Box<dyn BodyModel> {
        match self {
            Body::Homogeneous(material) => Box::new(HomogeneousHalfSpace {
                material: *material,
            }),
            Body::Layered(stack) => Box::new(StackBody {
                stack: stack.clone(),
            }),
            Body::Viscoelastic(solid) => Box::new(solid.model()),
        }
    }
}

/// The surface-displacement kernel of `body` on `grid`'s cells at sliding speed
/// `velocity`: an even kernel is given by its quadrant only (the spectrum on a
/// padding is built when a product needs it, [`ConvolutionPlan::even_kernel`]); a
/// kernel even in y only gets its general spectrum on `plan`'s full padding.
pub fn surface_kernel(
    body: &Body,
    grid: &Grid,
    plan: &Arc<ConvolutionPlan>,
    velocity: f64,
    lag: bool,
) -> Result<KernelSpectrum> {
    let model = body.model();
    let (kernel, shift) = match grid.geometry() {
        Geometry::Point => (
            model.surface_kernel(grid.cell(), grid.nx(), grid.ny(), velocity, lag)?,
            0.0,
        ),
        Geometry::Line { datum } => {
            lowered(model.line_kernel(grid.cell(), grid.nx(), velocity, datum, lag)?)
        }
    };
    let spectrum = match kernel {
        SurfaceKernel::Even { quadrant, .. } => plan.even_kernel(quadrant)?,
        kernel @ SurfaceKernel::EvenInY { .. } => {
            plan.kernel_spectrum(|di, dj| kernel.at(di, dj))?
        }
    };
    Ok(spectrum.with_datum_shift(shift))
}

/// A line kernel moved by a constant so that its values over the window lie between
/// its range `r = peak - lowest` (at the farthest offset) and `2 r` (at its peak),
/// with the constant it was lowered by. In plane strain the kernel is defined up to
/// a constant (its datum), which moves only the approach (the load per unit length
/// is fixed), but the solvers scale their steps by the kernel's self-coefficient
/// and precondition it without its mean: a case's datum near the contact, or a
/// creeping body whose relaxed far field lies far beyond the window, makes the
/// kernel near the load small or negative, and Newton stalls (a Zener body with
/// E_g / E_0 = 10 at V tau / a0 = 100, or with the kernel lowered to 0 at the
/// window's edge at V tau / a0 = 0.1 on 4096 cells). With the datum so placed all
/// of them converge (`docs/architecture.md`, "Line contacts").
fn lowered(kernel: SurfaceKernel) -> (SurfaceKernel, f64) {
    let lower = |values: Vec<f64>| {
        let lowest = values.iter().copied().fold(f64::INFINITY, f64::min);
        let peak = values.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let shift = lowest - (peak - lowest);
        (values.into_iter().map(|v| v - shift).collect(), shift)
    };
    match kernel {
        SurfaceKernel::Even { quadrant, nx } => {
            let (quadrant, shift) = lower(quadrant);
            (SurfaceKernel::Even { quadrant, nx }, shift)
        }
        SurfaceKernel::EvenInY { half, nx } => {
            let (half, shift) = lower(half);
            (SurfaceKernel::EvenInY { half, nx }, shift)
        }
    }
}
