//! Elastic bodies under the layer, seen through one small interface,
//! [`ElasticBody`]: the influence kernel that maps a pressure uniform over one
//! surface cell to the normal surface displacement at every cell centre (paper eq. 9
//! for a homogeneous half-space, eq. 10 for a coated one, generalised to any stack of
//! layers), the stress kernels at a depth, the depths of material interfaces, and the
//! modulus the automatic window needs. A case's [`Body`] is plain data; [`Body::model`] is the one place that
//! picks the implementation. The solvers never see more than the kernel's DC-FFT
//! spectrum (built through [`crate::KernelCache`]).

pub mod homogeneous;
pub mod layered;
pub(crate) mod quadrature;
pub mod stack;
#[cfg(test)]
pub(crate) mod two_layer_oracle;
pub mod viscoelastic;

use std::sync::Arc;

pub use homogeneous::HomogeneousHalfSpace;
pub use stack::StackBody;

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
use crate::grid::Grid;
use crate::provenance::Reference;
use crate::stress::StressKernels;

/// An elastic body as the solvers and the stress sections see it.
pub trait ElasticBody: std::fmt::Debug + Send + Sync {
    /// The surface influence kernel on square cells of side `cell`, on one quadrant
    /// of offsets: `[dj * nx + di]` is the normal displacement at the centre of the
    /// cell `(di, dj)` cells away from a cell under unit pressure, `0 <= di < nx`,
    /// `0 <= dj < ny` (the kernel is even in both offsets).
    fn surface_kernel_quadrant(&self, cell: f64, nx: usize, ny: usize) -> Result<Vec<f64>>;
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
    /// The smallest plane-strain modulus `E / (1 - nu^2)` of its materials (the
    /// automatic window's Hertz estimate uses it).
    fn softest_modulus(&self) -> f64;
    /// The works its kernels come from, with what each gives.
    fn references(&self) -> Vec<Reference>;
}

impl Body {
    /// The implementation of [`ElasticBody`] for this body: the one place a body's
    /// data meets its model.
    pub fn model(&self) -> Box<dyn ElasticBody> {
        match self {
            Body::Homogeneous(material) => Box::new(HomogeneousHalfSpace {
                material: *material,
            }),
            Body::Layered(stack) => Box::new(StackBody {
                stack: stack.clone(),
            }),
        }
    }
}

/// The surface-displacement kernel of `body` on `grid`'s cells, given by its
/// quadrant only: the spectrum on a padding is built when a product needs it
/// ([`ConvolutionPlan::even_kernel`]).
pub fn surface_kernel(
    body: &Body,
    grid: &Grid,
    plan: &Arc<ConvolutionPlan>,
) -> Result<KernelSpectrum> {
    let quadrant = body
        .model()
        .surface_kernel_quadrant(grid.cell(), grid.nx(), grid.ny())?;
    plan.even_kernel(quadrant)
}
