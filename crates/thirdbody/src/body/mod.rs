//! Elastic bodies under the layer: the influence kernel that maps a pressure
//! uniform over one surface cell to the normal surface displacement at every cell
//! centre (paper eq. 9 for a homogeneous half-space, eq. 10 for a coated one), and
//! its DC-FFT spectrum, built once per grid and material.

pub mod coated;
mod coated_radial;
pub mod coated_stress;
pub mod homogeneous;
pub(crate) mod quadrature;

use std::sync::Arc;

use crate::case::Body;
use crate::convolution::{ConvolutionPlan, KernelSpectrum};
use crate::error::Result;
use crate::grid::Grid;

/// The surface-displacement kernel spectrum of `body` on `grid`'s cells.
pub fn surface_kernel_spectrum(
    body: &Body,
    grid: &Grid,
    plan: &Arc<ConvolutionPlan>,
) -> Result<KernelSpectrum> {
    match *body {
        Body::Homogeneous(material) => Ok(plan.even_kernel_spectrum(
            &homogeneous::homogeneous_surface_kernel_quadrant(
                material, grid.cell, grid.nx, grid.ny,
            ),
        )),
        Body::Coated {
            coating,
            thickness,
            substrate,
        } => {
            let kernel = coated::coated_surface_kernel_cached(
                coating, thickness, substrate, grid.cell, grid.nx, grid.ny,
            )?;
            Ok(plan.even_kernel_spectrum(&kernel))
        }
    }
}
