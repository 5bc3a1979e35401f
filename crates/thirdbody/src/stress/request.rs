//! What a user asks of the stresses below a solved contact (the case file's `[stress]`
//! section, docs/case-file.md), turned into concrete [`Section`]s, and the scalar
//! results read off them: the maximum shear `tau1 = (s1 - s3)/2` in the XZ plane and
//! where it lies (paper Fig. 10), the extremes of the tensile-compressive stress
//! sigma_x on the surface (Fig. 9) and, for a coated body, on both sides of the
//! coating–substrate interface (Fig. 12), where brittle cracks start.
//!
//! Defaults (an empty `[stress]` section): the XZ plane through y = 0 from the surface
//! down to three contact half-lengths in 64 depths, the surface plane, and for a
//! coated body both sides of the interface. The contact half-length is the larger
//! half-extent of the loaded cells along x and y.

use super::{stresses_observed, Section, Side, StressField};
use crate::case::Body;
use crate::error::{Error, Result};
use crate::grid::Grid;

/// Default number of depths of the XZ section and the block.
pub const DEFAULT_DEPTH_POINTS: usize = 64;
/// Default depth of the XZ section and the block, in contact half-lengths.
pub const DEFAULT_DEPTH_IN_HALF_LENGTHS: f64 = 3.0;

/// A kind of section a user can ask for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SectionKind {
    /// The XZ plane y = `StressRequest::y`, at `depth_points` depths.
    Xz,
    /// The surface z = 0 at every cell centre.
    Surface,
    /// Both sides of the coating–substrate interface (coated bodies only).
    Interface,
    /// Every cell centre at `depth_points` depths (a 3-D block).
    Block,
}

impl SectionKind {
    /// The name used in case files.
    pub fn name(self) -> &'static str {
        match self {
            SectionKind::Xz => "xz",
            SectionKind::Surface => "surface",
            SectionKind::Interface => "interface",
            SectionKind::Block => "block",
        }
    }

    /// Parses a case-file name (`"xz"`, `"surface"`, `"interface"`, `"block"`).
    pub fn from_name(name: &str) -> Option<Self> {
        [Self::Xz, Self::Surface, Self::Interface, Self::Block]
            .into_iter()
            .find(|k| k.name() == name)
    }
}

/// The `[stress]` section: which sections, down to which depth, how finely.
#[derive(Debug, Clone, PartialEq)]
pub struct StressRequest {
    /// Sections to compute; `None` for the defaults (XZ, surface, and the interface
    /// of a coated body).
    pub sections: Option<Vec<SectionKind>>,
    /// y of the XZ plane (default 0, the point of initial contact).
    pub y: f64,
    /// Deepest depth of the XZ section and the block; `None` for three contact
    /// half-lengths.
    pub max_depth: Option<f64>,
    /// Depths of the XZ section and the block, evenly spaced from 0 to `max_depth`.
    pub depth_points: usize,
    /// Further planes z = const (each at every cell centre).
    pub planes: Vec<f64>,
}

impl Default for StressRequest {
    fn default() -> Self {
        StressRequest {
            sections: None,
            y: 0.0,
            max_depth: None,
            depth_points: DEFAULT_DEPTH_POINTS,
            planes: Vec::new(),
        }
    }
}

/// Which section of a request a computed field is: its identity, from which its
/// output name follows.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SectionId {
    /// The XZ plane at the request's y.
    Xz,
    /// The surface z = 0.
    Surface,
    /// One side of the coating–substrate interface.
    Interface(Side),
    /// The 3-D block.
    Block,
    /// The request's k-th extra plane (from 1).
    Plane(usize),
}

impl SectionId {
    /// The name its outputs carry: `xz`, `surface`, `interface_coating`,
    /// `interface_substrate`, `block`, `plane_1`, ...
    pub fn name(self) -> String {
        match self {
            SectionId::Xz => "xz".into(),
            SectionId::Surface => "surface".into(),
            SectionId::Interface(Side::Coating) => "interface_coating".into(),
            SectionId::Interface(Side::Substrate) => "interface_substrate".into(),
            SectionId::Block => "block".into(),
            SectionId::Plane(k) => format!("plane_{k}"),
        }
    }
}

/// A section of a request, with its identity.
#[derive(Debug, Clone, PartialEq)]
pub struct NamedSection {
    /// Which section it is.
    pub id: SectionId,
    /// What to compute.
    pub section: Section,
}

impl NamedSection {
    /// The name its outputs carry (see [`SectionId::name`]).
    pub fn name(&self) -> String {
        self.id.name()
    }
}

/// Scalar stress results (magnitudes in the case's stress unit; `None` where the
/// section they come from was not asked for).
#[derive(Debug, Clone, Default, PartialEq, serde::Serialize)]
pub struct StressSummary {
    /// Largest maximum shear `tau1 = (s1 - s3)/2` in the XZ section (>= 0; the paper
    /// prints it negative).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub tau1_max: Option<f64>,
    /// x of that maximum.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub tau1_max_x: Option<f64>,
    /// Depth z of that maximum.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub tau1_max_z: Option<f64>,
    /// Most compressive sigma_x on the surface.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub sigma_x_min: Option<f64>,
    /// Most tensile sigma_x on the surface.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub sigma_x_max: Option<f64>,
    /// Most tensile sigma_x on the coating side of the interface.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub interface_sigma_x_max_coating: Option<f64>,
    /// Most tensile sigma_x on the substrate side of the interface.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub interface_sigma_x_max_substrate: Option<f64>,
}

/// Deepest `stress.max_depth` allowed, in widths of the solved window: far deeper
/// the stresses are zero to double precision and the depths could overflow.
const MAX_DEPTH_IN_WINDOWS: f64 = 100.0;

/// What a stress computation reports while it runs (a front end's progress bar).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum StressProgress<'a> {
    /// Before anything: the number of depth planes (one per depth of each section;
    /// a surface or interface section is one) that will be computed.
    Start {
        /// Depth planes in all.
        planes: usize,
    },
    /// A section starts.
    Section {
        /// Its name, as in the file names (`xz`, `interface_coating`, ...).
        name: &'a str,
        /// Its depth planes.
        planes: usize,
    },
    /// One depth plane is done.
    PlaneDone,
}

/// Computed sections and their summary.
#[derive(Debug, Clone)]
pub struct StressResults {
    /// Each requested section and its field, in request order.
    pub sections: Vec<(NamedSection, StressField)>,
    /// Scalar results.
    pub summary: StressSummary,
}

impl StressRequest {
    /// Checks the request against the body; errors name the `[stress]` key.
    pub fn validate(&self, body: &Body) -> Result<()> {
        if !self.y.is_finite() {
            return Err(Error::invalid("stress.y", self.y, "a finite y"));
        }
        if let Some(z) = self.max_depth {
            if !(z.is_finite() && z > 0.0) {
                return Err(Error::invalid(
                    "stress.max_depth",
                    z,
                    "a finite depth > 0 (z points into the body)",
                ));
            }
        }
        if self.depth_points < 2 {
            return Err(Error::invalid(
                "stress.depth_points",
                self.depth_points,
                "at least 2 depths (from the surface to max_depth)",
            ));
        }
        if self.depth_points > 4096 {
            return Err(Error::invalid(
                "stress.depth_points",
                self.depth_points,
                "at most 4096 depths",
            ));
        }
        for (k, &z) in self.planes.iter().enumerate() {
            if !(z.is_finite() && z >= 0.0) {
                return Err(Error::invalid(
                    &format!("stress.planes[{k}]"),
                    z,
                    "a finite depth >= 0 (z points into the body)",
                ));
            }
        }
        if let Some(kinds) = &self.sections {
            if kinds.is_empty() && self.planes.is_empty() {
                return Err(Error::invalid(
                    "stress.sections",
                    "[]",
                    "at least one of \"xz\", \"surface\", \"interface\", \"block\" \
                     (or some planes)",
                ));
            }
            for (k, kind) in kinds.iter().enumerate() {
                if kinds[..k].contains(kind) {
                    return Err(Error::invalid(
                        "stress.sections",
                        kind.name(),
                        "each section once",
                    ));
                }
                if *kind == SectionKind::Interface && body.model().interface_depths().is_empty() {
                    return Err(Error::invalid(
                        "stress.sections",
                        "interface",
                        "\"interface\" only with a [coating]",
                    ));
                }
            }
        }
        Ok(())
    }

    /// An upper estimate of the memory the request's results take on a grid of
    /// `cells` (nx, ny), in bytes: eleven stored fields (six components, three
    /// principal stresses, tau1, von Mises) of 8 bytes per point, the block's
    /// `depth_points x nx x ny` points dominating (a 128² x 4096 block is 5.9 GB).
    pub fn estimated_bytes(&self, body: &Body, cells: [usize; 2]) -> f64 {
        let (nx, ny) = (cells[0] as f64, cells[1] as f64);
        let depths = self.depth_points as f64;
        let points: f64 = self
            .kinds(body)
            .iter()
            .map(|kind| match kind {
                SectionKind::Xz => nx * depths,
                SectionKind::Surface => nx * ny,
                SectionKind::Interface => 2.0 * nx * ny,
                SectionKind::Block => nx * ny * depths,
            })
            .sum::<f64>()
            + self.planes.len() as f64 * nx * ny;
        points * super::STORED_BYTES_PER_POINT
    }

    /// The section kinds asked for (the defaults filled in for `body`).
    pub fn kinds(&self, body: &Body) -> Vec<SectionKind> {
        match &self.sections {
            Some(k) => k.clone(),
            None => {
                let mut k = vec![SectionKind::Xz, SectionKind::Surface];
                if !body.model().interface_depths().is_empty() {
                    k.push(SectionKind::Interface);
                }
                k
            }
        }
    }

    /// The depths of the XZ section and the block for a solution whose contact
    /// half-length is `half_length`.
    pub fn depths(&self, half_length: f64) -> Vec<f64> {
        let deepest = self
            .max_depth
            .unwrap_or(DEFAULT_DEPTH_IN_HALF_LENGTHS * half_length);
        let n = self.depth_points;
        (0..n)
            .map(|k| deepest * (k as f64 / (n - 1) as f64))
            .collect()
    }

    /// The concrete sections under `pressure` (one value per cell of `grid`) on `body`.
    pub fn sections(
        &self,
        body: &Body,
        grid: &Grid,
        pressure: &[f64],
    ) -> Result<Vec<NamedSection>> {
        self.validate(body)?;
        let [y_lo, y_hi] = [grid.y0, grid.y0 + grid.ny as f64 * grid.cell];
        let wants_xz = self.kinds(body).contains(&SectionKind::Xz);
        if wants_xz && !(y_lo..=y_hi).contains(&self.y) {
            return Err(Error::invalid(
                "stress.y",
                self.y,
                &format!("a y inside the solved window, {y_lo:.4e} <= y <= {y_hi:.4e}"),
            ));
        }
        let window = (grid.nx.max(grid.ny)) as f64 * grid.cell;
        if let Some(z) = self
            .max_depth
            .filter(|&z| z > MAX_DEPTH_IN_WINDOWS * window)
        {
            return Err(Error::invalid(
                "stress.max_depth",
                z,
                &format!(
                    "a depth > 0 of at most {MAX_DEPTH_IN_WINDOWS} window widths, {:.4e} \
                     (the stresses vanish far below the contact)",
                    MAX_DEPTH_IN_WINDOWS * window
                ),
            ));
        }
        let depths = match self.max_depth {
            Some(_) => self.depths(0.0),
            None => self.depths(contact_half_length(grid, pressure)?),
        };
        let mut out = Vec::new();
        let mut push = |id: SectionId, section: Section| out.push(NamedSection { id, section });
        for kind in self.kinds(body) {
            match kind {
                SectionKind::Xz => push(
                    SectionId::Xz,
                    Section::XzPlane {
                        y: self.y,
                        depths: depths.clone(),
                    },
                ),
                SectionKind::Surface => push(SectionId::Surface, Section::Plane { z: 0.0 }),
                SectionKind::Interface => {
                    push(
                        SectionId::Interface(Side::Coating),
                        Section::Interface {
                            side: Side::Coating,
                        },
                    );
                    push(
                        SectionId::Interface(Side::Substrate),
                        Section::Interface {
                            side: Side::Substrate,
                        },
                    );
                }
                SectionKind::Block => push(
                    SectionId::Block,
                    Section::Block {
                        depths: depths.clone(),
                    },
                ),
            }
        }
        for (k, &z) in self.planes.iter().enumerate() {
            push(SectionId::Plane(k + 1), Section::Plane { z });
        }
        Ok(out)
    }

    /// Computes every requested section under `pressure` (one value per cell of
    /// `grid`, e.g. a [`crate::Solution`]'s) on `body` (the case's body), and the
    /// summary.
    pub fn compute(&self, body: &Body, grid: &Grid, pressure: &[f64]) -> Result<StressResults> {
        self.compute_observed(body, grid, pressure, &|_| {})
    }

    /// As [`StressRequest::compute`], reporting to `observer` (from any thread): first
    /// [`StressProgress::Start`] with the number of depth planes in all, then each
    /// section as it starts and each depth plane as it is done.
    pub fn compute_observed(
        &self,
        body: &Body,
        grid: &Grid,
        pressure: &[f64],
        observer: &(dyn Fn(StressProgress<'_>) + Sync),
    ) -> Result<StressResults> {
        let named = self.sections(body, grid, pressure)?;
        observer(StressProgress::Start {
            planes: named.iter().map(|n| n.section.depth_count()).sum(),
        });
        let mut sections = Vec::with_capacity(named.len());
        for n in named {
            let name = n.name();
            observer(StressProgress::Section {
                name: &name,
                planes: n.section.depth_count(),
            });
            let depth_done = || observer(StressProgress::PlaneDone);
            let field = stresses_observed(grid, pressure, body, &n.section, &depth_done)?;
            sections.push((n, field));
        }
        let summary = summarise(&sections);
        Ok(StressResults { sections, summary })
    }
}

/// The larger half-extent of the loaded cells along x and y (cell edges).
fn contact_half_length(grid: &Grid, pressure: &[f64]) -> Result<f64> {
    let (mut xs, mut ys) = ((usize::MAX, 0), (usize::MAX, 0));
    for j in 0..grid.ny {
        for i in 0..grid.nx {
            if pressure.get(grid.index(i, j)).is_some_and(|&p| p > 0.0) {
                xs = (xs.0.min(i), xs.1.max(i));
                ys = (ys.0.min(j), ys.1.max(j));
            }
        }
    }
    let cells = |(lo, hi): (usize, usize)| if lo > hi { 0 } else { hi - lo + 1 };
    let half = 0.5 * grid.cell * cells(xs).max(cells(ys)) as f64;
    if half > 0.0 {
        Ok(half)
    } else {
        Err(Error::invalid(
            "stress.max_depth",
            "three contact half-lengths",
            "an explicit max_depth: the solution has no loaded cell",
        ))
    }
}

/// Reads the summary off computed sections.
pub fn summarise(sections: &[(NamedSection, StressField)]) -> StressSummary {
    let mut s = StressSummary::default();
    let sigma_x_extremes = |f: &StressField| {
        f.components[0]
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| {
                (lo.min(v), hi.max(v))
            })
    };
    for (named, field) in sections {
        match named.id {
            SectionId::Xz => {
                let tau1 = field.tau1();
                if let Some((n, &t)) = tau1.iter().enumerate().max_by(|a, b| a.1.total_cmp(b.1)) {
                    let nx = field.xs.len() * field.ys.len();
                    s.tau1_max = Some(t);
                    s.tau1_max_x = Some(field.xs[n % field.xs.len()]);
                    s.tau1_max_z = Some(field.zs[n / nx]);
                }
            }
            SectionId::Surface => {
                let (lo, hi) = sigma_x_extremes(field);
                s.sigma_x_min = Some(lo);
                s.sigma_x_max = Some(hi);
            }
            SectionId::Interface(Side::Coating) => {
                s.interface_sigma_x_max_coating = Some(sigma_x_extremes(field).1)
            }
            SectionId::Interface(Side::Substrate) => {
                s.interface_sigma_x_max_substrate = Some(sigma_x_extremes(field).1)
            }
            _ => {}
        }
    }
    s
}
