//! The surface grid: `nx x ny` square cells of side `h` covering a rectangular window
//! of the slider-fixed frame (docs/architecture.md (numerics)). Cell `(i, j)` has its centre at
//! `x_i = x0 + (i + 1/2) h`, `y_j = y0 + (j + 1/2) h`; fields on the grid are stored
//! row-major with rows along y: value of cell `(i, j)` at index `j * nx + i`.
//! x is the sliding direction (body material flows through the contact in -x).

use crate::error::{Error, Result};

/// Smallest number of cells allowed along either axis.
pub const MIN_CELLS: usize = 8;

/// A window of square cells.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Grid {
    /// Cells along x (columns).
    pub nx: usize,
    /// Cells along y (rows).
    pub ny: usize,
    /// Side of a square cell, `h = 2a` in the paper's notation.
    pub cell: f64,
    /// x of the window's left edge.
    pub x0: f64,
    /// y of the window's lower edge.
    pub y0: f64,
}

impl Grid {
    /// A grid of `nx x ny` cells of side `cell` whose window is centred on `centre`.
    pub fn centred(nx: usize, ny: usize, cell: f64, centre: [f64; 2]) -> Result<Self> {
        for (name, n) in [("grid.cells[0]", nx), ("grid.cells[1]", ny)] {
            if n < MIN_CELLS {
                return Err(Error::invalid(name, n, "at least 8 cells"));
            }
        }
        if !(cell.is_finite() && cell > 0.0) {
            return Err(Error::invalid(
                "grid cell size",
                cell,
                "a finite number > 0",
            ));
        }
        Ok(Grid {
            nx,
            ny,
            cell,
            x0: centre[0] - 0.5 * nx as f64 * cell,
            y0: centre[1] - 0.5 * ny as f64 * cell,
        })
    }

    /// Number of cells.
    pub fn len(&self) -> usize {
        self.nx * self.ny
    }

    /// Always false: a grid has at least 8 x 8 cells.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Area of one cell, `h^2`.
    pub fn cell_area(&self) -> f64 {
        self.cell * self.cell
    }

    /// x of the centre of column `i`.
    pub fn x(&self, i: usize) -> f64 {
        self.x0 + (i as f64 + 0.5) * self.cell
    }

    /// y of the centre of row `j`.
    pub fn y(&self, j: usize) -> f64 {
        self.y0 + (j as f64 + 0.5) * self.cell
    }

    /// Half widths of the window along x and y.
    pub fn half_widths(&self) -> [f64; 2] {
        [
            0.5 * self.nx as f64 * self.cell,
            0.5 * self.ny as f64 * self.cell,
        ]
    }

    /// Centre of the window.
    pub fn centre(&self) -> [f64; 2] {
        let [wx, wy] = self.half_widths();
        [self.x0 + wx, self.y0 + wy]
    }

    /// Index of cell `(i, j)` in a row-major field.
    pub fn index(&self, i: usize, j: usize) -> usize {
        j * self.nx + i
    }

    /// Whether a field is non-zero on the outermost ring of cells.
    pub fn touches_edge(&self, field: &[f64]) -> bool {
        let (nx, ny) = (self.nx, self.ny);
        let row = |j: usize| field[j * nx..(j + 1) * nx].iter().any(|&v| v > 0.0);
        row(0)
            || row(ny - 1)
            || (0..ny).any(|j| field[j * nx] > 0.0 || field[j * nx + nx - 1] > 0.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn centres_are_symmetric_about_the_window_centre() {
        let g = Grid::centred(8, 10, 0.5, [1.0, -2.0]).unwrap();
        assert_eq!(g.x(0) + g.x(7), 2.0);
        assert_eq!(g.y(0) + g.y(9), -4.0);
        assert_eq!(g.centre(), [1.0, -2.0]);
        assert_eq!(g.half_widths(), [2.0, 2.5]);
    }

    #[test]
    fn too_few_cells_is_an_error_naming_the_field() {
        let e = Grid::centred(7, 10, 0.5, [0.0, 0.0]).unwrap_err();
        assert!(e.to_string().contains("grid.cells[0]"), "{e}");
        assert!(e.to_string().contains("at least 8"), "{e}");
    }

    #[test]
    fn edge_detection() {
        let g = Grid::centred(8, 8, 1.0, [0.0, 0.0]).unwrap();
        let mut f = vec![0.0; 64];
        f[g.index(3, 4)] = 1.0;
        assert!(!g.touches_edge(&f));
        f[g.index(7, 4)] = 1.0;
        assert!(g.touches_edge(&f));
    }
}
