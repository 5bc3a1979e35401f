//! What a user asks of the stresses below a solved contact (the case file's `[stress]`
//! section, docs/case-file.md), turned into concrete [`Section`]s, and the scalar
//! results read off them: the maximum shear `tau1 = (s1 - s3)/2` in the XZ plane and
//! where it lies (paper Fig. 10), the extremes of the tensile-compressive stress
//! sigma_x on the surface (Fig. 9) and, for a layered body, on both sides of every
//! interface (Fig. 12), where brittle cracks start and coatings delaminate, and per
//! layer the largest tau1 and von Mises stress in the XZ section.
//!
//! Defaults (an empty `[stress]` section): the XZ plane through y = 0 from the surface
//! down to three contact half-lengths (no deeper than a rigid base) in 64 depths, the
//! surface plane, and for a layered body both sides of every interface. The contact
//! half-length is the larger half-extent of the loaded cells along x and y.
//!
//! A line contact (plane strain, [`crate::Grid::line`]) has only the XZ section (the
//! same at every y, so `y` stays 0, and no block); its surface, interfaces and
//! planes are rows of it ([`super::line`]).

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
    /// Both sides of every interface of a layered body.
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
    /// One side of an interface (`index`: under layer `index`).
    Interface {
        /// Which interface, from 0 under the top layer.
        index: usize,
        /// Which side.
        side: Side,
    },
    /// The 3-D block.
    Block,
    /// The request's k-th extra plane (from 1).
    Plane(usize),
}

impl SectionId {
    /// The name its outputs carry: `xz`, `surface`, `interface_0_above`,
    /// `interface_0_below`, `block`, `plane_1`, ...
    pub fn name(self) -> String {
        match self {
            SectionId::Xz => "xz".into(),
            SectionId::Surface => "surface".into(),
            SectionId::Interface { index, side } => format!(
                "interface_{index}_{}",
                match side {
                    Side::Above => "above",
                    Side::Below => "below",
                }
            ),
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
    /// Most tensile sigma_x on the upper side of the first interface (a coating's
    /// side of its interface with the substrate; `interfaces[0].above.sigma_x_max`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub interface_sigma_x_max_coating: Option<f64>,
    /// Most tensile sigma_x on the lower side of the first interface (the
    /// substrate's side, for a coating).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub interface_sigma_x_max_substrate: Option<f64>,
    /// Per interface, from the surface down: sigma_x's extremes on each side.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub interfaces: Vec<InterfaceStresses>,
    /// Per layer of a layered body, from the surface down (an elastic base last):
    /// the largest tau1 and von Mises stress in the XZ section.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub layers: Vec<LayerStresses>,
}

/// sigma_x's extremes on the two sides of one interface.
#[derive(Debug, Clone, Default, PartialEq, serde::Serialize)]
pub struct InterfaceStresses {
    /// The interface's index (under layer `index`).
    pub index: usize,
    /// Its depth.
    pub depth: f64,
    /// Most compressive and most tensile sigma_x just above it.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub above: Option<SigmaXRange>,
    /// The same just below it.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub below: Option<SigmaXRange>,
}

/// The most compressive and most tensile sigma_x on a plane.
#[derive(Debug, Clone, Copy, Default, PartialEq, serde::Serialize)]
pub struct SigmaXRange {
    /// Most compressive sigma_x.
    pub sigma_x_min: f64,
    /// Most tensile sigma_x.
    pub sigma_x_max: f64,
}

/// The largest stresses of one layer in the XZ section.
#[derive(Debug, Clone, Copy, Default, PartialEq, serde::Serialize)]
pub struct LayerStresses {
    /// The layer's index (the elastic base: the number of layers).
    pub index: usize,
    /// Whether it is the elastic base (the half-space under the layers).
    pub base: bool,
    /// Largest maximum shear `tau1` at the section's depths in the layer.
    pub tau1_max: f64,
    /// Largest von Mises stress there.
    pub von_mises_max: f64,
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
                        "\"interface\" only for a body with interfaces (a [coating], or \
                         [[body.layers]] on a half-space or two or more on a rigid base)",
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
                SectionKind::Interface => {
                    2.0 * nx * ny * body.model().interface_depths().len() as f64
                }
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
        if grid.is_line() {
            self.check_line()?;
        }
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
        let base = body.model().deepest();
        if let (Some(z), Some(base)) = (self.max_depth, base) {
            if z > base {
                return Err(Error::invalid(
                    "stress.max_depth",
                    z,
                    &format!("a depth of at most the rigid base's, {base:.4e}"),
                ));
            }
        }
        for (k, &z) in self.planes.iter().enumerate() {
            if base.is_some_and(|base| z > base) {
                return Err(Error::invalid(
                    &format!("stress.planes[{k}]"),
                    z,
                    &format!(
                        "a depth of at most the rigid base's, {:.4e}",
                        base.unwrap_or(0.0)
                    ),
                ));
            }
        }
        let depths = match (self.max_depth, base) {
            (Some(_), _) => self.depths(0.0),
            (None, base) => {
                let half = contact_half_length(grid, pressure)?;
                let mut request = self.clone();
                request.max_depth = base
                    .filter(|&b| b < DEFAULT_DEPTH_IN_HALF_LENGTHS * half)
                    .or(Some(DEFAULT_DEPTH_IN_HALF_LENGTHS * half));
                request.depths(0.0)
            }
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
                    for index in 0..body.model().interface_depths().len() {
                        for side in [Side::Above, Side::Below] {
                            push(
                                SectionId::Interface { index, side },
                                Section::Interface { index, side },
                            );
                        }
                    }
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

    /// Checks the request for a line contact (plane strain): its stresses are the XZ
    /// section, the same at every y, so y stays 0 and there is no block; the surface,
    /// the interfaces and the planes are rows of the XZ section.
    fn check_line(&self) -> Result<()> {
        if self.y != 0.0 {
            return Err(Error::invalid(
                "stress.y",
                self.y,
                "no y (0) for a line contact: in plane strain the XZ section is the same \
                 at every y",
            ));
        }
        if self
            .sections
            .as_ref()
            .is_some_and(|k| k.contains(&SectionKind::Block))
        {
            return Err(Error::invalid(
                "stress.sections",
                "block",
                "\"xz\", \"surface\" or \"interface\" for a line contact (plane strain: \
                 its stresses are the XZ section; the surface, the interfaces and the \
                 planes are rows of it)",
            ));
        }
        Ok(())
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
        let summary = summarise(&sections, body);
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

/// Reads the summary off computed sections on `body`.
pub fn summarise(sections: &[(NamedSection, StressField)], body: &Body) -> StressSummary {
    let mut s = StressSummary::default();
    let sigma_x_range = |f: &StressField| {
        let (lo, hi) = f.components[0]
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| {
                (lo.min(v), hi.max(v))
            });
        SigmaXRange {
            sigma_x_min: lo,
            sigma_x_max: hi,
        }
    };
    let interface_depths = body.model().interface_depths();
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
                if let Body::Layered(stack) = body {
                    s.layers = layer_maxima(field, &stack.interface_depths(), &tau1);
                }
            }
            SectionId::Surface => {
                let r = sigma_x_range(field);
                s.sigma_x_min = Some(r.sigma_x_min);
                s.sigma_x_max = Some(r.sigma_x_max);
            }
            SectionId::Interface { index, side } => {
                if s.interfaces.len() <= index {
                    s.interfaces.resize_with(index + 1, Default::default);
                }
                let entry = &mut s.interfaces[index];
                entry.index = index;
                entry.depth = interface_depths.get(index).copied().unwrap_or(f64::NAN);
                let r = sigma_x_range(field);
                match side {
                    Side::Above => entry.above = Some(r),
                    Side::Below => entry.below = Some(r),
                }
                if index == 0 {
                    match side {
                        Side::Above => s.interface_sigma_x_max_coating = Some(r.sigma_x_max),
                        Side::Below => s.interface_sigma_x_max_substrate = Some(r.sigma_x_max),
                    }
                }
            }
            _ => {}
        }
    }
    // Interfaces not asked for keep no entry.
    s.interfaces
        .retain(|i| i.above.is_some() || i.below.is_some());
    s
}

/// Per layer (bottoms at `bottoms`, an elastic base below the last), the largest
/// tau1 and von Mises stress at the section's depths in it (a depth on an interface
/// counts for the layer above, as the section reads it there).
fn layer_maxima(field: &StressField, bottoms: &[f64], tau1: &[f64]) -> Vec<LayerStresses> {
    let von_mises = field.von_mises();
    let per_depth = field.xs.len() * field.ys.len();
    let mut out: Vec<LayerStresses> = Vec::new();
    for (k, &z) in field.zs.iter().enumerate() {
        let layer = bottoms
            .iter()
            .position(|&b| z <= b)
            .unwrap_or(bottoms.len());
        let range = k * per_depth..(k + 1) * per_depth;
        let t = tau1[range.clone()].iter().fold(0.0f64, |m, &v| m.max(v));
        let v = von_mises[range].iter().fold(0.0f64, |m, &v| m.max(v));
        if let Some(e) = out.iter_mut().find(|e| e.index == layer) {
            e.tau1_max = e.tau1_max.max(t);
            e.von_mises_max = e.von_mises_max.max(v);
        } else {
            out.push(LayerStresses {
                index: layer,
                base: layer == bottoms.len(),
                tau1_max: t,
                von_mises_max: v,
            });
        }
    }
    out.sort_by_key(|e| e.index);
    out
}
