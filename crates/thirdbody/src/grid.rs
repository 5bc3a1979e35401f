//! The surface grid: `nx x ny` square cells of side `h` covering a rectangular window
//! of the slider-fixed frame (docs/architecture.md (numerics)). Cell `(i, j)` has its centre at
//! `x_i = x0 + (i + 1/2) h`, `y_j = y0 + (j + 1/2) h`; fields on the grid are stored
//! row-major with rows along y: value of cell `(i, j)` at index `j * nx + i`.
//! x is the sliding direction (body material flows through the contact in -x).
//! The grid also carries the contact's geometry ([`Geometry`]): a point contact's
//! cells are squares of area `h^2`; a line contact (plane strain, everything
//! constant along y) has one row of strips of width `h` and unit length, so that
//! loads are per unit length. The solvers see only [`Grid::cell_measure`].

use crate::error::{Error, Result};

/// Smallest number of cells allowed along either axis.
pub const MIN_CELLS: usize = 8;

/// The geometry of a contact, a property of its grid.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum Geometry {
    /// A point contact: a 2-D window of square cells (3-D elasticity).
    #[default]
    Point,
    /// A line contact (plane strain): one row of cells along x, the slider and the
    /// load uniform along y, loads and forces per unit length.
    Line {
        /// The datum of the surface displacement, which in plane strain is defined
        /// only against one: the surface at this distance from the load
        /// ([`crate::body::line`]).
        datum: f64,
    },
}

/// A window of square cells. Its fields are read through methods and set only by
/// the checked constructors ([`Grid::new`], [`Grid::centred`]), so that every grid
/// has at least [`MIN_CELLS`] cells along each axis and a finite positive cell.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Grid {
    /// Cells along x (columns).
    pub(crate) nx: usize,
    /// Cells along y (rows).
    pub(crate) ny: usize,
    /// Side of a square cell, `h = 2a` in the paper's notation.
    pub(crate) cell: f64,
    /// x of the window's left edge.
    pub(crate) x0: f64,
    /// y of the window's lower edge.
    pub(crate) y0: f64,
    /// Point or line contact.
    pub(crate) geometry: Geometry,
}

impl Grid {
    /// A grid of `nx x ny` cells of side `cell` whose window's lower left corner is
    /// `corner` (`[x0, y0]`). Too few cells, a cell that is not finite and positive
    /// or a corner that is not finite is an error naming it.
    pub fn new(nx: usize, ny: usize, cell: f64, corner: [f64; 2]) -> Result<Self> {
        let centred = Grid::centred(nx, ny, cell, [0.0, 0.0])?;
        for (name, v) in [("grid x0", corner[0]), ("grid y0", corner[1])] {
            if !v.is_finite() {
                return Err(Error::invalid(name, v, "a finite number"));
            }
        }
        Ok(Grid {
            x0: corner[0],
            y0: corner[1],
            ..centred
        })
    }

    /// Cells along x (columns).
    pub fn nx(&self) -> usize {
        self.nx
    }

    /// Cells along y (rows).
    pub fn ny(&self) -> usize {
        self.ny
    }

    /// Side of a square cell, `h = 2a` in the paper's notation.
    pub fn cell(&self) -> f64 {
        self.cell
    }

    /// x of the window's left edge.
    pub fn x0(&self) -> f64 {
        self.x0
    }

    /// y of the window's lower edge.
    pub fn y0(&self) -> f64 {
        self.y0
    }

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
            geometry: Geometry::Point,
        })
    }

    /// A line-contact grid: `nx` strips of width `cell` along x whose window is
    /// centred on `centre_x` (one row, `ny = 1`, centred on y = 0), its displacements
    /// measured against the surface at distance `datum` from the load. Too few
    /// cells, a cell, centre or datum that is not finite (and positive) is an error
    /// naming it.
    pub fn line(nx: usize, cell: f64, centre_x: f64, datum: f64) -> Result<Self> {
        let square = Grid::centred(nx, MIN_CELLS, cell, [centre_x, 0.0])?;
        if !centre_x.is_finite() {
            return Err(Error::invalid("grid centre", centre_x, "a finite number"));
        }
        if !(datum.is_finite() && datum > 0.0) {
            return Err(Error::invalid(
                "loading.reference_distance",
                datum,
                "a finite number > 0",
            ));
        }
        Ok(Grid {
            ny: 1,
            y0: -0.5 * cell,
            geometry: Geometry::Line { datum },
            ..square
        })
    }

    /// Point or line contact.
    pub fn geometry(&self) -> Geometry {
        self.geometry
    }

    /// Whether this is a line contact's grid.
    pub fn is_line(&self) -> bool {
        matches!(self.geometry, Geometry::Line { .. })
    }

    /// The measure of one cell in the load and force sums: its area `h^2` for a
    /// point contact, its width `h` for a line contact (forces per unit length).
    pub fn cell_measure(&self) -> f64 {
        match self.geometry {
            Geometry::Point => self.cell * self.cell,
            Geometry::Line { .. } => self.cell,
        }
    }

    /// The same window with `nx` cells along x (and, for a point contact, `ny`
    /// along y) of side `cell`, centred on `centre`: the line or point grid of
    /// this grid's geometry.
    pub fn resized(&self, nx: usize, ny: usize, cell: f64, centre: [f64; 2]) -> Result<Self> {
        match self.geometry {
            Geometry::Point => Grid::centred(nx, ny, cell, centre),
            Geometry::Line { datum } => Grid::line(nx, cell, centre[0], datum),
        }
    }

    /// Number of cells.
    pub fn len(&self) -> usize {
        self.nx * self.ny
    }

    /// Always false: a grid has at least 8 x 8 cells.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// x of the centre of column `i`.
    pub fn x(&self, i: usize) -> f64 {
        self.x0 + (i as f64 + 0.5) * self.cell
    }

    /// y of the centre of row `j`.
    pub fn y(&self, j: usize) -> f64 {
        self.y0 + (j as f64 + 0.5) * self.cell
    }

    /// Half widths of the window along x and y (a line contact's: `[w, 0]`).
    pub fn half_widths(&self) -> [f64; 2] {
        let wy = match self.geometry {
            Geometry::Point => 0.5 * self.ny as f64 * self.cell,
            Geometry::Line { .. } => 0.0,
        };
        [0.5 * self.nx as f64 * self.cell, wy]
    }

    /// Centre of the window.
    pub fn centre(&self) -> [f64; 2] {
        let [wx, _] = self.half_widths();
        let cy = match self.geometry {
            Geometry::Point => self.y0 + 0.5 * self.ny as f64 * self.cell,
            Geometry::Line { .. } => 0.0,
        };
        [self.x0 + wx, cy]
    }

    /// Index of cell `(i, j)` in a row-major field.
    pub fn index(&self, i: usize, j: usize) -> usize {
        j * self.nx + i
    }

    /// Whether a field is non-zero on the outermost ring of cells (a line
    /// contact's: its first and last cell).
    pub fn touches_edge(&self, field: &[f64]) -> bool {
        let (nx, ny) = (self.nx, self.ny);
        if self.is_line() {
            return field[0] > 0.0 || field[nx - 1] > 0.0;
        }
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
    fn an_invalid_grid_cannot_be_built() {
        let message = |r: Result<Grid>| r.unwrap_err().to_string();
        let e = message(Grid::new(8, 3, 0.5, [0.0, 0.0]));
        assert!(
            e.contains("grid.cells[1]") && e.contains("at least 8"),
            "{e}"
        );
        let e = message(Grid::new(8, 8, 0.0, [0.0, 0.0]));
        assert!(e.contains("grid cell size") && e.contains("> 0"), "{e}");
        let e = message(Grid::centred(8, 8, f64::NAN, [0.0, 0.0]));
        assert!(e.contains("grid cell size"), "{e}");
        let e = message(Grid::new(8, 8, 1.0, [0.0, f64::INFINITY]));
        assert!(e.contains("grid y0") && e.contains("finite"), "{e}");
        let g = Grid::new(9, 8, 0.5, [-1.0, 2.0]).unwrap();
        assert_eq!(
            (g.nx(), g.ny(), g.cell(), g.x0(), g.y0()),
            (9, 8, 0.5, -1.0, 2.0)
        );
    }

    #[test]
    fn a_line_grid_is_one_row_of_strips_of_unit_length() {
        let g = Grid::line(10, 0.5, 1.0, 3.0).unwrap();
        assert_eq!((g.nx(), g.ny(), g.len()), (10, 1, 10));
        assert!(g.is_line());
        assert_eq!(g.cell_measure(), 0.5);
        assert_eq!(g.x(0) + g.x(9), 2.0);
        assert_eq!(g.y(0), 0.0);
        assert_eq!(g.centre(), [1.0, 0.0]);
        assert_eq!(g.half_widths(), [2.5, 0.0]);
        let mut f = vec![0.0; 10];
        f[4] = 1.0;
        assert!(!g.touches_edge(&f));
        f[9] = 1.0;
        assert!(g.touches_edge(&f));
        let point = Grid::centred(8, 8, 0.5, [0.0, 0.0]).unwrap();
        assert_eq!(point.cell_measure(), 0.25);
        assert_eq!(g.resized(16, 16, 0.25, [0.0, 3.0]).unwrap().ny(), 1);
        let e = Grid::line(7, 0.5, 0.0, 1.0).unwrap_err().to_string();
        assert!(
            e.contains("grid.cells[0]") && e.contains("at least 8"),
            "{e}"
        );
        let e = Grid::line(8, 0.5, f64::NAN, 1.0).unwrap_err().to_string();
        assert!(e.contains("grid centre"), "{e}");
        let e = Grid::line(8, 0.5, 0.0, 0.0).unwrap_err().to_string();
        assert!(e.contains("loading.reference_distance"), "{e}");
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
