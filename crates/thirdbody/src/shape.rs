//! Slider shapes: the initial separation f(x, y) between the slider and the flat
//! layer surface, measured from the slider's lowest point (paper eq. 3 with
//! the sign of docs/architecture.md (conventions): the contact condition is `w = D - f`), and its slope
//! df/dx, which gives the hysteresis friction `mu = sum(p df/dx) h^2 / Q`
//! (the general form of paper eq. 12). Shapes are sampled at cell centres.

use crate::convolution::Parallelism;
use crate::error::{require_positive, Error, Result};
use crate::grid::Geometry;
use crate::passes::Passes;

/// A rigid smooth slider.
#[derive(Debug, Clone, PartialEq)]
pub enum Slider {
    /// Paraboloid of radius R: `f = (x^2 + y^2) / (2 R)` (the paper's sphere).
    Sphere {
        /// Radius R.
        radius: f64,
    },
    /// Elliptic paraboloid: `f = x^2 / (2 Rx) + y^2 / (2 Ry)`.
    Ellipsoid {
        /// Radius of curvature in the xz plane.
        radius_x: f64,
        /// Radius of curvature in the yz plane.
        radius_y: f64,
    },
    /// Heights sampled on a grid of square cells, interpolated bilinearly.
    HeightMap(HeightMap),
    /// A cylinder of radius R with its axis along y, a line contact (plane
    /// strain): `f = x^2 / (2 R)`, loads per unit length.
    Cylinder {
        /// Radius R.
        radius: f64,
    },
    /// A profile uniform along y, a line contact (plane strain): heights sampled
    /// along x, interpolated linearly.
    Profile(Profile),
}

/// Heights of a slider uniform along y, sampled along x at spacing `cell_size`,
/// centred on the origin: `heights[i]` at `x = (i + 1/2 - n/2) h`. Heights are
/// shifted so that the lowest is zero.
#[derive(Debug, Clone, PartialEq)]
pub struct Profile {
    /// Spacing of the samples.
    pub cell_size: f64,
    /// Heights.
    pub heights: Vec<f64>,
}

impl Profile {
    /// The profile of a height map with one row (or one column) of samples; a
    /// map of several rows and columns is an error naming `slider.file`.
    pub fn from_map(map: HeightMap) -> Result<Profile> {
        if map.nx != 1 && map.ny != 1 {
            return Err(Error::invalid(
                "slider.file",
                format!("{} x {} samples", map.ny, map.nx),
                "one row (or one column) of heights for a profile (a line contact); a \
                 2-D map is shape = \"height_map\"",
            ));
        }
        Ok(Profile {
            cell_size: map.cell_size,
            heights: map.heights,
        })
    }

    /// Half the extent over which the profile can be interpolated (between the
    /// centres of its outermost samples).
    pub fn half_extent(&self) -> f64 {
        0.5 * (self.heights.len() as f64 - 1.0) * self.cell_size
    }

    fn validate(&self) -> Result<()> {
        require_positive("slider.cell_size", self.cell_size)?;
        if self.heights.len() < 3 {
            return Err(Error::invalid(
                "slider.file",
                format!("{} samples", self.heights.len()),
                "a profile of at least 3 samples",
            ));
        }
        if let Some(k) = self.heights.iter().position(|h| !h.is_finite()) {
            return Err(Error::invalid(
                "slider.file",
                format!("{} at sample {k}", self.heights[k]),
                "finite heights everywhere (no NaN or inf)",
            ));
        }
        Ok(())
    }

    /// Linear interpolation of the height at x; `None` outside.
    fn height(&self, x: f64) -> Option<f64> {
        let n = self.heights.len();
        let u = x / self.cell_size + 0.5 * n as f64 - 0.5;
        if u < -1e-9 || u > (n - 1) as f64 + 1e-9 {
            return None;
        }
        let i = (u.floor().max(0.0) as usize).min(n - 2);
        let s = u - i as f64;
        Some((1.0 - s) * self.heights[i] + s * self.heights[i + 1])
    }

    /// The mean slope of the interpolated profile over `[x - width/2, x + width/2]`
    /// (clamped to the profile), as [`HeightMap`]'s: the exact slope of the
    /// interpolant under each cell; `None` outside.
    fn mean_slope(&self, x: f64, width: f64) -> Option<f64> {
        let e = self.half_extent();
        let (lo, hi) = ((x - 0.5 * width).max(-e), (x + 0.5 * width).min(e));
        if hi <= lo {
            return None;
        }
        Some((self.height(hi)? - self.height(lo)?) / (hi - lo))
    }
}

/// Heights of the slider surface on a regular grid centred on the origin,
/// row-major with rows along y. Heights are shifted so that the lowest is zero.
#[derive(Debug, Clone, PartialEq)]
pub struct HeightMap {
    /// Samples along x.
    pub nx: usize,
    /// Samples along y.
    pub ny: usize,
    /// Spacing of the samples (cell size of the map).
    pub cell_size: f64,
    /// Heights, `heights[j * nx + i]` at `x = (i + 1/2 - nx/2) h`, `y = (j + 1/2 - ny/2) h`.
    pub heights: Vec<f64>,
}

impl HeightMap {
    /// Half extents of the region where the map can be interpolated (between the
    /// centres of its outermost samples).
    pub fn half_extent(&self) -> [f64; 2] {
        [
            0.5 * (self.nx as f64 - 1.0) * self.cell_size,
            0.5 * (self.ny as f64 - 1.0) * self.cell_size,
        ]
    }

    fn validate(&self) -> Result<()> {
        require_positive("slider.cell_size", self.cell_size)?;
        if self.nx < 2 || self.ny < 2 || self.heights.len() != self.nx * self.ny {
            return Err(Error::invalid(
                "slider.file",
                format!("{} x {} samples", self.ny, self.nx),
                "a rectangular map of at least 2 x 2 samples (one row of heights is a \
                 line contact's slider.shape = \"profile\")",
            ));
        }
        if let Some(k) = self.heights.iter().position(|h| !h.is_finite()) {
            return Err(Error::invalid(
                "slider.file",
                format!(
                    "{} at row {}, column {}",
                    self.heights[k],
                    k / self.nx,
                    k % self.nx
                ),
                "finite heights everywhere (no NaN or inf)",
            ));
        }
        Ok(())
    }

    /// The mean x-slope of the interpolated surface over `[x - width/2, x + width/2]`
    /// on the line y (clamped to the map): the difference of the interpolated heights
    /// at the ends over their distance; `None` outside the map.
    ///
    /// The friction sum `sum(p df/dx) h^2` takes, per cell, the slope of the slider
    /// under that cell's pressure. Where the map's nodes fall on the cell centres (a
    /// profilometer map at the solver's spacing) the one-sided slope of the bilinear
    /// interpolant at a node biases mu by hm / (2R); the mean over the cell is the
    /// exact slope of the interpolated surface, the same on either side of a node,
    /// and exact for a paraboloid whose nodes sit on the cell centres or corners.
    fn mean_x_slope(&self, x: f64, y: f64, width: f64) -> Option<f64> {
        let [ex, _] = self.half_extent();
        let lo = (x - 0.5 * width).max(-ex);
        let hi = (x + 0.5 * width).min(ex);
        if hi <= lo {
            return None;
        }
        let f_lo = self.height(lo, y)?;
        let f_hi = self.height(hi, y)?;
        Some((f_hi - f_lo) / (hi - lo))
    }

    /// Bilinear interpolation of the height at (x, y); `None` outside.
    fn height(&self, x: f64, y: f64) -> Option<f64> {
        let h = self.cell_size;
        let u = x / h + 0.5 * self.nx as f64 - 0.5;
        let v = y / h + 0.5 * self.ny as f64 - 0.5;
        let eps = 1e-9;
        if u < -eps || v < -eps || u > (self.nx - 1) as f64 + eps || v > (self.ny - 1) as f64 + eps
        {
            return None;
        }
        let i = (u.floor().max(0.0) as usize).min(self.nx - 2);
        let j = (v.floor().max(0.0) as usize).min(self.ny - 2);
        let (s, t) = (u - i as f64, v - j as f64);
        let at = |i: usize, j: usize| self.heights[j * self.nx + i];
        let (f00, f10, f01, f11) = (at(i, j), at(i + 1, j), at(i, j + 1), at(i + 1, j + 1));
        let f = (1.0 - t) * ((1.0 - s) * f00 + s * f10) + t * ((1.0 - s) * f01 + s * f11);
        Some(f)
    }
}

impl Slider {
    pub(crate) fn validate(&self) -> Result<()> {
        match self {
            Slider::Sphere { radius } => require_positive("slider.radius", *radius),
            Slider::Ellipsoid { radius_x, radius_y } => {
                require_positive("slider.radius_x", *radius_x)?;
                require_positive("slider.radius_y", *radius_y)
            }
            Slider::HeightMap(m) => m.validate(),
            Slider::Cylinder { radius } => require_positive("slider.radius", *radius),
            Slider::Profile(p) => p.validate(),
        }
    }

    /// The contact's geometry: a line contact (plane strain) for a slider uniform
    /// along y, a point contact otherwise. `datum` is a line contact's
    /// [`Geometry::Line`] datum.
    pub fn geometry(&self, datum: f64) -> Geometry {
        match self {
            Slider::Cylinder { .. } | Slider::Profile(_) => Geometry::Line { datum },
            _ => Geometry::Point,
        }
    }

    /// Whether the slider makes a line contact.
    pub fn is_line(&self) -> bool {
        matches!(self.geometry(1.0), Geometry::Line { .. })
    }

    /// Effective radius used by the automatic window and Hertz estimates:
    /// `sqrt(Rx Ry)` for an ellipsoid, the curvature at the lowest point for a map
    /// or a profile.
    pub fn equivalent_radius(&self) -> f64 {
        match self {
            Slider::Profile(p) => {
                let f = &p.heights;
                let k = (0..f.len())
                    .min_by(|&a, &b| f[a].total_cmp(&f[b]))
                    .unwrap_or(0);
                let h = p.cell_size;
                let curvature = if k > 0 && k + 1 < f.len() {
                    (f[k + 1] - 2.0 * f[k] + f[k - 1]) / (h * h)
                } else {
                    0.0
                };
                if curvature > 0.0 {
                    1.0 / curvature
                } else {
                    h * f.len() as f64
                }
            }
            Slider::Sphere { radius } | Slider::Cylinder { radius } => *radius,
            Slider::Ellipsoid { radius_x, radius_y } => (radius_x * radius_y).sqrt(),
            Slider::HeightMap(m) => {
                // Curvature from the second differences around the lowest sample.
                let k = (0..m.heights.len())
                    .min_by(|&a, &b| m.heights[a].total_cmp(&m.heights[b]))
                    .unwrap_or(0);
                let (i, j) = (k % m.nx, k / m.nx);
                let at = |i: usize, j: usize| m.heights[j * m.nx + i];
                let h = m.cell_size;
                let mut curv: f64 = 0.0;
                if i > 0 && i + 1 < m.nx {
                    curv = curv.max((at(i + 1, j) - 2.0 * at(i, j) + at(i - 1, j)) / (h * h));
                }
                if j > 0 && j + 1 < m.ny {
                    curv = curv.max((at(i, j + 1) - 2.0 * at(i, j) + at(i, j - 1)) / (h * h));
                }
                if curv > 0.0 {
                    1.0 / curv
                } else {
                    // A flat bottom: the map's own size is the only length.
                    m.cell_size * (m.nx.max(m.ny) as f64)
                }
            }
        }
    }

    /// Fills `f` and `dfdx` at the centres of `grid`'s cells.
    ///
    /// Fails if the window reaches outside a height map.
    pub fn sample(&self, grid: &crate::grid::Grid, f: &mut [f64], dfdx: &mut [f64]) -> Result<()> {
        self.sample_rows(grid, f, dfdx, Parallelism::Sequential)
    }

    /// [`Self::sample`] with the rows split over the pool when `parallelism` and
    /// the grid's size allow (the solvers' rule, `crate::passes`).
    pub(crate) fn sample_rows(
        &self,
        grid: &crate::grid::Grid,
        f: &mut [f64],
        dfdx: &mut [f64],
        parallelism: Parallelism,
    ) -> Result<()> {
        let min_height = match self {
            Slider::HeightMap(m) => m.heights.iter().copied().fold(f64::INFINITY, f64::min),
            Slider::Profile(p) => p.heights.iter().copied().fold(f64::INFINITY, f64::min),
            _ => 0.0,
        };
        use rayon::prelude::*;
        // Rows in parallel; every value is computed alone, so the bits do not
        // depend on the thread count.
        let rows = f.par_chunks_mut(grid.nx).zip(dfdx.par_chunks_mut(grid.nx));
        let min_rows = Passes::new(grid.len(), parallelism).min_rows(grid.nx);
        rows.enumerate()
            .with_min_len(min_rows)
            .try_for_each(|(j, (frow, drow))| {
                let y = grid.y(j);
                for i in 0..grid.nx {
                    let x = grid.x(i);
                    let (fv, dv) = match self {
                        Slider::Sphere { radius } => ((x * x + y * y) / (2.0 * radius), x / radius),
                        Slider::Cylinder { radius } => (x * x / (2.0 * radius), x / radius),
                        Slider::Profile(p) => match (p.height(x), p.mean_slope(x, grid.cell)) {
                            (Some(fv), Some(dv)) => (fv - min_height, dv),
                            _ => {
                                let e = p.half_extent();
                                let [wx, _] = grid.half_widths();
                                return Err(Error::invalid(
                                    "grid",
                                    format!(
                                        "a window of half width {wx:.4e} centred at {:.4e}",
                                        grid.centre()[0]
                                    ),
                                    &format!(
                                        "a window inside the profile (half extent {e:.4e}); \
                                         give a longer profile or a smaller grid.half_width"
                                    ),
                                ));
                            }
                        },
                        Slider::Ellipsoid { radius_x, radius_y } => (
                            x * x / (2.0 * radius_x) + y * y / (2.0 * radius_y),
                            x / radius_x,
                        ),
                        Slider::HeightMap(m) => {
                            match (m.height(x, y), m.mean_x_slope(x, y, grid.cell)) {
                                (Some(fv), Some(dv)) => (fv - min_height, dv),
                                _ => {
                                    let [ex, ey] = m.half_extent();
                                    let [wx, wy] = grid.half_widths();
                                    let c = grid.centre();
                                    return Err(Error::invalid(
                                        "grid",
                                        format!(
                                    "a window of half widths {wx:.4e} x {wy:.4e} centred at \
                                     ({:.4e}, {:.4e})",
                                    c[0], c[1]
                                ),
                                        &format!(
                                    "a window inside the height map (half extents {ex:.4e} x \
                                     {ey:.4e}); give a larger map or a smaller grid.half_width"
                                ),
                                    ));
                                }
                            }
                        }
                    };
                    frow[i] = fv;
                    drow[i] = dv;
                }
                Ok(())
            })?;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::grid::Grid;

    #[test]
    fn height_map_of_a_paraboloid_reproduces_the_sphere() {
        // A map sampled from the sphere's own formula must interpolate back to it
        // within the bilinear error h^2 / (8 R) per axis.
        let (n, h, r) = (101, 0.02, 1.0);
        let mut heights = vec![0.0; n * n];
        for j in 0..n {
            for i in 0..n {
                let x = (i as f64 + 0.5 - n as f64 / 2.0) * h;
                let y = (j as f64 + 0.5 - n as f64 / 2.0) * h;
                heights[j * n + i] = (x * x + y * y) / (2.0 * r) + 3.0;
            }
        }
        let map = Slider::HeightMap(HeightMap {
            nx: n,
            ny: n,
            cell_size: h,
            heights,
        });
        let sphere = Slider::Sphere { radius: r };
        let g = Grid::centred(16, 16, 0.05, [0.1, -0.05]).unwrap();
        let (mut f1, mut d1, mut f2, mut d2) = (
            vec![0.0; 256],
            vec![0.0; 256],
            vec![0.0; 256],
            vec![0.0; 256],
        );
        map.sample(&g, &mut f1, &mut d1).unwrap();
        sphere.sample(&g, &mut f2, &mut d2).unwrap();
        for k in 0..256 {
            assert!((f1[k] - f2[k]).abs() < h * h / (4.0 * r) + 1e-12, "{k}");
            assert!((d1[k] - d2[k]).abs() < h / r, "{k}");
        }
        assert!((map.equivalent_radius() - r).abs() < 1e-9);
    }

    #[test]
    fn nan_in_a_height_map_is_named() {
        let map = Slider::HeightMap(HeightMap {
            nx: 2,
            ny: 2,
            cell_size: 1.0,
            heights: vec![0.0, f64::NAN, 0.0, 0.0],
        });
        let e = map.validate().unwrap_err().to_string();
        assert!(
            e.contains("slider.file") && e.contains("NaN") && e.contains("row 0, column 1"),
            "{e}"
        );
    }

    #[test]
    fn window_outside_the_map_is_an_error() {
        let map = Slider::HeightMap(HeightMap {
            nx: 4,
            ny: 4,
            cell_size: 1.0,
            heights: vec![0.0; 16],
        });
        let g = Grid::centred(8, 8, 1.0, [0.0, 0.0]).unwrap();
        let e = map.sample(&g, &mut [0.0; 64], &mut [0.0; 64]).unwrap_err();
        assert!(e.to_string().contains("inside the height map"), "{e}");
    }
}
