//! Subsurface stresses under a computed surface pressure (docs/architecture.md (numerics)): for each
//! depth z, each stress component is the discrete convolution of the pressure with
//! the stresses per unit pressure on one cell (the "stress kernel" of the body),
//! computed by DC-FFT. The homogeneous body uses Love's closed-form stresses under a
//! uniformly loaded rectangle (Love 1929; see [`kernels`]); a coated body will plug
//! its own kernels in through [`StressKernels`].
//!
//! A line contact (plane strain, [`Grid::line`]) has stresses in the XZ plane only:
//! every section is rows of it at y = 0 (the XZ plane's depths, a plane's or an
//! interface's one depth; a block or another y is an error), by a 1-D DC-FFT of the
//! strips' pressure with the body's strip kernels ([`StressKernels::fill_strip`],
//! [`mod@line`]).
//!
//! Conventions: tension positive, z into the body, pressure p >= 0 compressive on
//! z = 0 (so `sigma_z = -p` on the surface under the load). Components are ordered
//! `[sigma_x, sigma_y, sigma_z, tau_xy, tau_xz, tau_yz]`. Surface stresses (z = 0)
//! are evaluated at cell centres (x always; y as asked), where Love's surface
//! formulas are finite; on a row edge they give the mean of both sides.
//!
//! ```
//! use thirdbody::stress::{stresses, Section};
//! use thirdbody::{Body, Elastic, Grid};
//! let grid = Grid::centred(16, 16, 0.1, [0.0, 0.0]).unwrap();
//! let mut p = vec![0.0; grid.len()];
//! p[grid.index(8, 8)] = 1.0;
//! let body = Body::Homogeneous(Elastic { young: 1.0, poisson: 0.3 });
//! let field = stresses(&grid, &p, &body, &Section::Plane { z: 0.0 }).unwrap();
//! // Directly under the loaded cell at the surface, sigma_z = -p.
//! let k = field.index(8, 8, 0);
//! assert!((field.components[2][k] + 1.0).abs() < 1e-12);
//! ```

pub mod derived;
pub mod kernels;
mod layered_kernels;
pub mod line;
mod long_wave;
pub mod request;
mod row_basis;
mod sections;

pub use kernels::{
    love_rectangle_stresses, HomogeneousStressKernels, InfluenceTable, OffsetLattice, PreparedRow,
    RowSource, StressKernels, COMPONENTS,
};
pub use layered_kernels::{LayeredStressKernels, StressMethod};
pub use request::{
    InterfaceStresses, LayerStresses, NamedSection, SectionId, SectionKind, SigmaXRange,
    StressProgress, StressRequest, StressResults, StressSummary,
};

pub use crate::body::Side;
use crate::case::Body;
use crate::error::{Error, Result};
use crate::grid::Grid;
use crate::solution::Solution;
use crate::units::Scales;

/// Where stresses are wanted. x always runs over the grid's cell centres.
#[derive(Debug, Clone, PartialEq)]
pub enum Section {
    /// The plane y = const (e.g. y = 0 through the point of initial contact), at
    /// the given depths: a field of `nx x 1 x depths.len()` points.
    XzPlane {
        /// y of the plane (any finite value; a cell-centre row or not).
        y: f64,
        /// Depths z >= 0.
        depths: Vec<f64>,
    },
    /// One plane z = const (z = 0 is the surface) at every cell centre.
    Plane {
        /// Depth z >= 0.
        z: f64,
    },
    /// A block: every cell centre at each depth.
    Block {
        /// Depths z >= 0.
        depths: Vec<f64>,
    },
    /// An interface between two materials of a layered body, on one side, at every
    /// cell centre (sigma_x, sigma_y and tau_xy jump there). Elsewhere a depth equal
    /// to an interface's is read on the side above it.
    Interface {
        /// Which interface: `index` lies under layer `index` (0: under the top
        /// layer; for a coating, the coating–substrate interface).
        index: usize,
        /// Which side of it.
        side: Side,
    },
}

/// The eleven fields a front end stores for a section, in this order: the six
/// components, the principal stresses s1 >= s2 >= s3, tau1 and von Mises
/// ([`StressField::stored_fields`]).
pub const STORED_FIELD_NAMES: [&str; 11] = [
    "sigma_x",
    "sigma_y",
    "sigma_z",
    "tau_xy",
    "tau_xz",
    "tau_yz",
    "s1",
    "s2",
    "s3",
    "tau1",
    "von_mises",
];

impl StressField {
    /// The fields of [`STORED_FIELD_NAMES`], each with one value per point.
    pub fn stored_fields(&self) -> Vec<Vec<f64>> {
        let mut out: Vec<Vec<f64>> = self.components.to_vec();
        out.extend(self.principal());
        out.push(self.tau1());
        out.push(self.von_mises());
        out
    }
}

/// Bytes a section's results take per point: the eleven stored fields
/// ([`STORED_FIELD_NAMES`]) of 8 bytes.
pub const STORED_BYTES_PER_POINT: f64 = (STORED_FIELD_NAMES.len() * 8) as f64;

impl Section {
    /// The depth planes the section is computed on (one for a plane or interface).
    pub fn depth_count(&self) -> usize {
        match self {
            Section::XzPlane { depths, .. } | Section::Block { depths } => depths.len(),
            Section::Plane { .. } | Section::Interface { .. } => 1,
        }
    }

    /// Checks the section's y and depths (and that an interface section is on a body
    /// with an interface); errors name the `[stress]` key. [`stresses`] checks this
    /// first; a front end that computes a section in parts checks it whole.
    pub fn validate(&self, body: &Body) -> Result<()> {
        match self {
            Section::XzPlane { y, depths } => {
                if !y.is_finite() {
                    return Err(Error::invalid("stress.y", y, "a finite y"));
                }
                check_depths(depths)
            }
            Section::Plane { z } => check_depth("stress.z", *z),
            Section::Block { depths } => check_depths(depths),
            Section::Interface { index, .. } => {
                let count = body.model().interface_depths().len();
                if count == 0 {
                    return Err(Error::invalid(
                        "stress.sections",
                        "interface",
                        "an interface section only for a body with interfaces (a coating or \
                         layers on a half-space, or two or more layers on a rigid base)",
                    ));
                }
                if *index >= count {
                    return Err(Error::invalid(
                        "stress.interface",
                        index,
                        &format!(
                            "an interface index from 0 to {} (interface i lies under layer i)",
                            count - 1
                        ),
                    ));
                }
                Ok(())
            }
        }
    }

    /// The deepest depth the section reads.
    fn deepest(&self) -> f64 {
        match self {
            Section::XzPlane { depths, .. } | Section::Block { depths } => {
                depths.iter().fold(0.0, |m: f64, &z| m.max(z))
            }
            Section::Plane { z } => *z,
            Section::Interface { .. } => 0.0,
        }
    }

    /// The points of the section on a grid of `cells` (nx, ny): `nx` per depth for an
    /// XZ plane, `nx ny` per depth otherwise.
    pub fn point_count(&self, cells: [usize; 2]) -> f64 {
        let [nx, ny] = cells.map(|n| n as f64);
        let per_depth = match self {
            Section::XzPlane { .. } => nx,
            _ => nx * ny,
        };
        per_depth * self.depth_count() as f64
    }

    /// An estimate of the memory the section's results take on a grid of `cells`
    /// (nx, ny), in bytes: [`STORED_BYTES_PER_POINT`] per point (a 32² block of 10⁶
    /// depths is 90 GB), as [`StressRequest::estimated_bytes`] counts them. A front
    /// end compares it with the memory available before asking for the section.
    ///
    /// ```
    /// use thirdbody::stress::Section;
    /// let block = Section::Block { depths: vec![0.0; 1_000_000] };
    /// assert_eq!(block.estimated_bytes([32, 32]), 1e6 * 1024.0 * 88.0);
    /// let xz = Section::XzPlane { y: 0.0, depths: vec![0.0; 10] };
    /// assert_eq!(xz.estimated_bytes([32, 32]), 10.0 * 32.0 * 88.0);
    /// ```
    pub fn estimated_bytes(&self, cells: [usize; 2]) -> f64 {
        self.point_count(cells) * STORED_BYTES_PER_POINT
    }
}

/// Stresses on a section: component `c` at `(xs[i], ys[j], zs[k])` is
/// `components[c][(k * ys.len() + j) * xs.len() + i]` (x fastest, then y, then z).
#[derive(Debug, Clone, PartialEq)]
pub struct StressField {
    /// x of the points (the grid's cell centres).
    pub xs: Vec<f64>,
    /// y of the points.
    pub ys: Vec<f64>,
    /// Depths.
    pub zs: Vec<f64>,
    /// `[sigma_x, sigma_y, sigma_z, tau_xy, tau_xz, tau_yz]`, tension positive.
    pub components: [Vec<f64>; COMPONENTS],
}

impl StressField {
    /// Number of points.
    pub fn len(&self) -> usize {
        self.xs.len() * self.ys.len() * self.zs.len()
    }

    /// Whether the field has no points.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Flat index of point `(xs[i], ys[j], zs[k])`.
    pub fn index(&self, i: usize, j: usize, k: usize) -> usize {
        (k * self.ys.len() + j) * self.xs.len() + i
    }

    /// The six components at flat index `n`.
    pub fn tensor(&self, n: usize) -> [f64; COMPONENTS] {
        std::array::from_fn(|c| self.components[c][n])
    }

    /// Principal stresses `[s1, s2, s3]` (`s1 >= s2 >= s3`) at every point.
    pub fn principal(&self) -> [Vec<f64>; 3] {
        let mut out: [Vec<f64>; 3] = Default::default();
        for n in 0..self.len() {
            let s = derived::principal_stresses(self.tensor(n));
            for (o, v) in out.iter_mut().zip(s) {
                o.push(v);
            }
        }
        out
    }

    /// Maximum shear stress `tau1 = (s1 - s3) / 2` at every point.
    pub fn tau1(&self) -> Vec<f64> {
        (0..self.len())
            .map(|n| derived::max_shear(self.tensor(n)))
            .collect()
    }

    /// Von Mises equivalent stress at every point.
    pub fn von_mises(&self) -> Vec<f64> {
        (0..self.len())
            .map(|n| derived::von_mises(self.tensor(n)))
            .collect()
    }
}

/// The stress kernels of a body: the hook where each body type supplies its own.
/// A depth equal to an interface's is read on `interface_side`.
pub fn stress_kernels(body: &Body, interface_side: Side) -> Result<Box<dyn StressKernels>> {
    body.validate()?;
    Ok(body.model().stress_kernels(interface_side))
}

/// Checks a list of depths: at least one, each finite and >= 0.
fn check_depths(depths: &[f64]) -> Result<()> {
    if depths.is_empty() {
        return Err(Error::invalid(
            "stress.depths",
            "[] (no depths)",
            "at least one depth",
        ));
    }
    for (k, &z) in depths.iter().enumerate() {
        check_depth(&format!("stress.depths[{k}]"), z)?;
    }
    Ok(())
}

fn check_depth(field: &str, z: f64) -> Result<()> {
    if z.is_finite() && z >= 0.0 {
        Ok(())
    } else {
        Err(Error::invalid(
            field,
            z,
            "a finite depth >= 0 (z points into the body)",
        ))
    }
}

/// All six stress components on `section` under `pressure` (one value per cell of
/// `grid`, row-major with rows along y, uniform over each cell) on `body`.
pub fn stresses(
    grid: &Grid,
    pressure: &[f64],
    body: &Body,
    section: &Section,
) -> Result<StressField> {
    stresses_observed(grid, pressure, body, section, &|| {})
}

/// As [`stresses`], calling `depth_done` (from any thread) each time one depth of the
/// section is computed: a front end's progress bar.
pub fn stresses_observed(
    grid: &Grid,
    pressure: &[f64],
    body: &Body,
    section: &Section,
    depth_done: &(dyn Fn() + Sync),
) -> Result<StressField> {
    if pressure.len() != grid.len() {
        return Err(Error::invalid(
            "pressure",
            format!("{} values", pressure.len()),
            &format!(
                "one value per grid cell ({} x {} = {})",
                grid.nx,
                grid.ny,
                grid.len()
            ),
        ));
    }
    if let Some(k) = pressure.iter().position(|p| !p.is_finite()) {
        return Err(Error::invalid(
            &format!("pressure[{k}]"),
            pressure[k],
            "a finite pressure",
        ));
    }
    if grid.is_line() {
        check_line_section(section)?;
    }
    section.validate(body)?;
    if let Some(base) = body.model().deepest() {
        let z = section.deepest();
        if z > base * (1.0 + 1e-12) {
            return Err(Error::invalid(
                "stress.depths",
                z,
                &format!("depths within the layers, at most the rigid base's depth {base:e}"),
            ));
        }
    }
    // In the solver's units (crate::units): the kernels' powers of lengths stay in
    // double precision's range whatever the case's units. Powers of two: exact both
    // ways.
    let scales = Scales::for_stresses(body, grid);
    let lengths = |v: &[f64]| v.iter().map(|&z| scales.length(z)).collect::<Vec<f64>>();
    let scaled_section = match section {
        Section::XzPlane { y, depths } => Section::XzPlane {
            y: scales.length(*y),
            depths: lengths(depths),
        },
        Section::Plane { z } => Section::Plane {
            z: scales.length(*z),
        },
        Section::Block { depths } => Section::Block {
            depths: lengths(depths),
        },
        Section::Interface { index, side } => Section::Interface {
            index: *index,
            side: *side,
        },
    };
    let scaled_pressure: Vec<f64> = pressure.iter().map(|&p| scales.pressure(p)).collect();
    let mut field = stresses_in_units(
        &scales.grid(grid),
        &scaled_pressure,
        &scales.body(body),
        &scaled_section,
        depth_done,
    )?;
    for x in field
        .xs
        .iter_mut()
        .chain(&mut field.ys)
        .chain(&mut field.zs)
    {
        *x *= scales.length;
    }
    for s in field.components.iter_mut().flatten() {
        *s *= scales.modulus;
    }
    Ok(field)
}

/// Checks that `section` exists for a line contact (plane strain): the XZ plane
/// (at y = 0: it is the same at every y), or one of its rows z = const (a plane, the
/// surface, a side of an interface); not a block.
fn check_line_section(section: &Section) -> Result<()> {
    match section {
        Section::XzPlane { y, .. } if *y != 0.0 => Err(Error::invalid(
            "stress.y",
            y,
            "y = 0 for a line contact (plane strain: the XZ section is the same at every y)",
        )),
        Section::Block { .. } => Err(Error::invalid(
            "stress.sections",
            "block",
            "\"xz\", \"surface\", \"interface\" or planes for a line contact (plane \
             strain: its stresses are the XZ section, and a plane z = const is one row of it)",
        )),
        _ => Ok(()),
    }
}

/// [`stresses_observed`] of a checked section, in the units its numbers are in.
fn stresses_in_units(
    grid: &Grid,
    pressure: &[f64],
    body: &Body,
    section: &Section,
    depth_done: &(dyn Fn() + Sync),
) -> Result<StressField> {
    let side = match section {
        Section::Interface { side, .. } => *side,
        _ => Side::Above,
    };
    let kernels = stress_kernels(body, side)?;
    let xs: Vec<f64> = (0..grid.nx).map(|i| grid.x(i)).collect();
    let all_ys = || (0..grid.ny).map(|j| grid.y(j)).collect::<Vec<f64>>();
    if grid.is_line() {
        // Plane strain: every section is rows of the XZ plane, y = 0.
        let depths = match section {
            Section::XzPlane { depths, .. } | Section::Block { depths } => depths.clone(),
            Section::Plane { z } => vec![*z],
            Section::Interface { index, .. } => vec![body.model().interface_depths()[*index]],
        };
        let components = line::section(grid, pressure, kernels.as_ref(), &depths, depth_done)?;
        return Ok(StressField {
            xs,
            ys: vec![0.0],
            zs: depths,
            components,
        });
    }
    let field = match section {
        Section::XzPlane { y, depths } => StressField {
            xs,
            ys: vec![*y],
            zs: depths.clone(),
            components: sections::xz_plane(
                grid,
                pressure,
                kernels.as_ref(),
                *y,
                depths,
                depth_done,
            ),
        },
        Section::Plane { z } => StressField {
            xs,
            ys: all_ys(),
            zs: vec![*z],
            components: sections::planes(grid, pressure, kernels.as_ref(), &[*z], depth_done),
        },
        Section::Block { depths } => StressField {
            xs,
            ys: all_ys(),
            zs: depths.clone(),
            components: sections::planes(grid, pressure, kernels.as_ref(), depths, depth_done),
        },
        Section::Interface { index, .. } => {
            let thickness = body.model().interface_depths()[*index];
            StressField {
                xs,
                ys: all_ys(),
                zs: vec![thickness],
                components: sections::planes(
                    grid,
                    pressure,
                    kernels.as_ref(),
                    &[thickness],
                    depth_done,
                ),
            }
        }
    };
    Ok(field)
}

impl Solution {
    /// Subsurface stresses of this solution's pressure (each cell's mean,
    /// [`Solution::mean_pressure`]) on the body it was solved on.
    pub fn stresses(&self, section: &Section) -> Result<StressField> {
        stresses(&self.grid, &self.mean_pressure(), &self.body, section)
    }

    /// The stresses and their summary that `request` asks for, on the body this
    /// solution was solved on.
    pub fn stress_results(&self, request: &StressRequest) -> Result<StressResults> {
        request.compute(&self.body, &self.grid, &self.mean_pressure())
    }

    /// As [`Solution::stress_results`], reporting to `observer` (from any thread):
    /// see [`StressProgress`].
    pub fn stress_results_observed(
        &self,
        request: &StressRequest,
        observer: &(dyn Fn(StressProgress<'_>) + Sync),
    ) -> Result<StressResults> {
        request.compute_observed(&self.body, &self.grid, &self.mean_pressure(), observer)
    }
}
