//! Homogeneous elastic half-space: normal surface displacement under a uniform
//! pressure on a rectangle `|x| <= a, |y| <= b` (Love 1929; Johnson, Contact
//! Mechanics, eq. 3.25; the paper's eq. 9):
//! `w(x, y) = (1 - nu^2) / (pi E) * p * int int_rect dxi deta / sqrt((x - xi)^2 + (y - eta)^2)`.
//! The double integral is written with the primitive
//! `F(u, v) = u asinh(v / |u|) + v asinh(u / |v|)` (its mixed derivative is
//! `1 / sqrt(u^2 + v^2)`), which stays finite on cell edges and corners, unlike
//! the textbook logarithms whose arguments vanish there.

use super::{BodyModel, EdgeProfile, SurfaceKernel};
use crate::case::Elastic;
use crate::error::Result;
use crate::grid::Grid;
use crate::provenance::{self, Reference};
use crate::stress::{HomogeneousStressKernels, Side, StressKernels};
use rayon::prelude::*;

/// A homogeneous elastic half-space.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HomogeneousHalfSpace {
    /// Its material.
    pub material: Elastic,
}

impl BodyModel for HomogeneousHalfSpace {
    fn surface_kernel(
        &self,
        cell: f64,
        nx: usize,
        ny: usize,
        _velocity: f64,
        _lag: bool,
    ) -> Result<SurfaceKernel> {
        Ok(SurfaceKernel::Even {
            quadrant: homogeneous_surface_kernel_quadrant(self.material, cell, nx, ny),
            nx,
        })
    }

    fn line_kernel(
        &self,
        cell: f64,
        nx: usize,
        _velocity: f64,
        reference: f64,
        _lag: bool,
    ) -> Result<SurfaceKernel> {
        let compliance = 1.0 / self.material.plane_strain_modulus();
        Ok(SurfaceKernel::Even {
            quadrant: super::line::homogeneous_line_kernel(compliance, cell, nx, reference),
            nx,
        })
    }

    fn kernel_depends_on_velocity(&self) -> bool {
        false
    }

    fn kernel_is_even(&self, _velocity: f64) -> bool {
        true
    }

    fn dissipated_force(
        &self,
        _grid: &Grid,
        _pressure: &[f64],
        _velocity: f64,
        _edges: EdgeProfile,
    ) -> Result<f64> {
        Ok(0.0)
    }

    fn stress_kernels(&self, _interface_side: Side) -> Box<dyn StressKernels> {
        Box::new(HomogeneousStressKernels {
            material: self.material,
        })
    }

    fn interface_depths(&self) -> Vec<f64> {
        Vec::new()
    }

    fn softest_modulus(&self) -> f64 {
        self.material.plane_strain_modulus()
    }

    fn surface_compliance(
        &self,
        _wavenumber_x: f64,
        _velocity: f64,
    ) -> Option<realfft::num_complex::Complex<f64>> {
        Some((1.0 / self.material.plane_strain_modulus()).into())
    }

    fn references(&self) -> Vec<Reference> {
        vec![Reference::new(
            provenance::LOVE,
            "the homogeneous body's surface and stress kernels (uniform pressure on a rectangle)",
        )]
    }
}

/// `u asinh(v / |u|)`, continued by 0 at u = 0.
pub(super) fn half_primitive(u: f64, v: f64) -> f64 {
    if u == 0.0 {
        0.0
    } else {
        u * (v / u.abs()).asinh()
    }
}

/// `int_{x-a}^{x+a} int_{y-b}^{y+b} dxi deta / sqrt(xi^2 + eta^2)`.
pub fn rectangle_inverse_distance_integral(x: f64, y: f64, a: f64, b: f64) -> f64 {
    let f = |u: f64, v: f64| half_primitive(u, v) + half_primitive(v, u);
    f(x + a, y + b) - f(x + a, y - b) - f(x - a, y + b) + f(x - a, y - b)
}

/// Surface normal displacement at (x, y) per unit pressure on `|x| <= a, |y| <= b`.
pub fn love_rectangle_displacement(material: Elastic, a: f64, b: f64, x: f64, y: f64) -> f64 {
    let nu = material.poisson;
    (1.0 - nu * nu) / (std::f64::consts::PI * material.young)
        * rectangle_inverse_distance_integral(x, y, a, b)
}

/// The influence coefficients between cells `(di, dj)` apart on a grid of square
/// cells of side `cell` (displacement at a cell centre per unit pressure on the other
/// cell) on one quadrant of offsets, `[dj * nx + di]` for `0 <= di < nx`,
/// `0 <= dj < ny` (they are even in both). The primitive F is evaluated once per
/// cell corner of the lattice and shared by the four cells that meet there, a quarter
/// of the work of cell-by-cell evaluation.
pub fn homogeneous_surface_kernel_quadrant(
    material: Elastic,
    cell: f64,
    nx: usize,
    ny: usize,
) -> Vec<f64> {
    let nu = material.poisson;
    let scale = (1.0 - nu * nu) / (std::f64::consts::PI * material.young);
    let f = |u: f64, v: f64| half_primitive(u, v) + half_primitive(v, u);
    // corner[l * (nx + 1) + k] = F((k - 1/2) h, (l - 1/2) h)
    let w = nx + 1;
    let corner: Vec<f64> = (0..(ny + 1) * w)
        .into_par_iter()
        .map(|m| {
            f(
                (m % w) as f64 * cell - 0.5 * cell,
                (m / w) as f64 * cell - 0.5 * cell,
            )
        })
        .collect();
    (0..nx * ny)
        .into_par_iter()
        .map(|m| {
            let (i, j) = (m % nx, m / nx);
            let at = |k: usize, l: usize| corner[l * w + k];
            scale * (at(i + 1, j + 1) - at(i + 1, j) - at(i, j + 1) + at(i, j))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    /// The influence coefficient between cells `(di, dj)` apart, cell by cell: the
    /// quadrant table's oracle.
    fn homogeneous_surface_kernel(material: Elastic, cell: f64) -> impl Fn(i64, i64) -> f64 {
        let a = 0.5 * cell;
        move |di, dj| {
            love_rectangle_displacement(material, a, a, di as f64 * cell, dj as f64 * cell)
        }
    }

    const STEEL: Elastic = Elastic {
        young: 2.0,
        poisson: 0.3,
    };

    #[test]
    fn centre_of_a_square_matches_the_closed_form() {
        // Johnson eq. 3.25 at the centre of a square of side 2a: 8 a ln(1 + sqrt 2).
        let a = 0.37;
        let w = love_rectangle_displacement(STEEL, a, a, 0.0, 0.0);
        let expect = (1.0 - 0.09) / (PI * 2.0) * 8.0 * a * (1.0 + 2f64.sqrt()).ln();
        assert!((w - expect).abs() < 1e-14 * expect);
    }

    #[test]
    fn corner_of_a_square_is_half_the_centre_of_twice_the_square() {
        // Superposition: the corner of a square of side 2a sees a quarter of the
        // centre displacement of a square of side 4a.
        let a = 0.5;
        let corner = love_rectangle_displacement(STEEL, a, a, a, a);
        let big_centre = love_rectangle_displacement(STEEL, 2.0 * a, 2.0 * a, 0.0, 0.0);
        assert!(
            (corner - big_centre / 4.0).abs() < 1e-14 * corner,
            "{corner} {big_centre}"
        );
        assert!(corner.is_finite());
    }

    #[test]
    fn far_field_tends_to_boussinesq() {
        // Point force P = 4ab p at distance r: w = (1 - nu^2) P / (pi E r), Johnson eq. 3.19a.
        let (a, b) = (0.5, 0.25);
        for &r in &[20.0, 200.0, 2000.0] {
            let w = love_rectangle_displacement(STEEL, a, b, r * 0.6, r * 0.8);
            let point = (1.0 - 0.09) * 4.0 * a * b / (PI * 2.0 * r);
            // Next term of the multipole expansion is O((a / r)^2).
            assert!(
                ((w - point) / point).abs() < 0.2 / (r * r),
                "r = {r}: {w} vs {point}"
            );
        }
    }

    #[test]
    fn quadrant_table_equals_cell_by_cell_evaluation() {
        let (nx, ny, h) = (13, 9, 0.37);
        let table = homogeneous_surface_kernel_quadrant(STEEL, h, nx, ny);
        let k = homogeneous_surface_kernel(STEEL, h);
        for j in 0..ny {
            for i in 0..nx {
                let direct = k(i as i64, j as i64);
                assert!(
                    (table[j * nx + i] - direct).abs() <= 1e-13 * direct,
                    "{i} {j}"
                );
            }
        }
    }

    #[test]
    fn integral_against_midpoint_quadrature() {
        // An independent evaluation of the double integral off the rectangle.
        let (a, b, x, y) = (0.3, 0.7, 1.1, -0.4);
        let n = 600;
        let mut s = 0.0;
        for i in 0..n {
            for j in 0..n {
                let xi = -a + (i as f64 + 0.5) * 2.0 * a / n as f64;
                let eta = -b + (j as f64 + 0.5) * 2.0 * b / n as f64;
                s += 1.0 / ((x - xi).powi(2) + (y - eta).powi(2)).sqrt();
            }
        }
        s *= 4.0 * a * b / (n * n) as f64;
        let w = rectangle_inverse_distance_integral(x, y, a, b);
        assert!((w - s).abs() < 1e-6 * s, "{w} vs {s}");
    }
}
