//! A contact case: slider shape, elastic body, third-body layer, loading and grid,
//! in one consistent system of units (dimensionless with R = E2 = T = 1 as in the
//! paper's section 4, or SI). [`Case::validate`] checks every field against its
//! physical range and names the field in the error; the solver assumes a valid case.

use crate::body::layered::{Base, Ply, Stack};
use crate::body::solid::ViscoelasticHalfSpace;
use crate::error::{require_poisson, require_positive, Error, Result};
use crate::layer::Layer;
use crate::provenance::{self, Reference};
use crate::shape::Slider;
use crate::solution::Method;

/// An isotropic linear elastic material.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Elastic {
    /// Young's modulus E.
    pub young: f64,
    /// Poisson's ratio nu, -1 < nu < 0.5.
    pub poisson: f64,
}

impl Elastic {
    /// Plane-strain modulus `E / (1 - nu^2)`.
    pub fn plane_strain_modulus(&self) -> f64 {
        self.young / (1.0 - self.poisson * self.poisson)
    }

    /// The material with its moduli divided by `modulus`.
    pub fn scaled(&self, modulus: f64) -> Elastic {
        Elastic {
            young: self.young / modulus,
            poisson: self.poisson,
        }
    }

    pub(crate) fn validate(&self, section: &str) -> Result<()> {
        require_positive(&format!("{section}.young"), self.young)?;
        require_poisson(&format!("{section}.poisson"), self.poisson)
    }
}

/// The elastic body under the layer (paper Fig. 1). Plain data; [`Body::model`]
/// picks the implementation (`docs/architecture.md`, "Adding an elastic body").
#[derive(Debug, Clone, PartialEq)]
pub enum Body {
    /// A homogeneous half-space (paper eq. 9).
    Homogeneous(Elastic),
    /// Bonded elastic layers on a half-space or a rigid base
    /// ([`crate::body::layered`]); a coating (paper eq. 5 and 10) is a stack of one
    /// layer on a half-space ([`Body::coated`]).
    Layered(Stack),
    /// A linear viscoelastic half-space ([`crate::body::solid`]): in steady
    /// sliding its kernel depends on the speed and is not even in x.
    Viscoelastic(ViscoelasticHalfSpace),
}

impl Body {
    /// A coating of thickness `thickness` perfectly bonded to a substrate half-space
    /// (paper eq. 5 and 10): a stack of one layer.
    pub fn coated(coating: Elastic, thickness: f64, substrate: Elastic) -> Body {
        Body::Layered(Stack {
            layers: vec![Ply {
                material: coating,
                thickness,
            }],
            base: Base::HalfSpace(substrate),
        })
    }

    /// The elastic half-space under everything, if any (E2, nu2 of the paper).
    pub fn half_space(&self) -> Option<Elastic> {
        match self {
            Body::Homogeneous(m) => Some(*m),
            Body::Layered(stack) => match stack.base {
                Base::HalfSpace(m) => Some(m),
                Base::Rigid(_) => None,
            },
            Body::Viscoelastic(_) => None,
        }
    }

    /// The modulus that sets the solver's stress unit: the half-space's Young's
    /// modulus (the paper's E2), on a rigid base the stiffest layer's, and the
    /// relaxed modulus of a viscoelastic body.
    pub fn reference_modulus(&self) -> f64 {
        match self {
            Body::Homogeneous(m) => m.young,
            Body::Layered(stack) => stack.reference_modulus(),
            Body::Viscoelastic(solid) => solid.relaxed_modulus(),
        }
    }

    /// A time that sets the solver's time unit when no layer does: the geometric
    /// mean of a viscoelastic body's retardation times (`None` for elastic bodies).
    pub fn time_scale(&self) -> Option<f64> {
        match self {
            Body::Homogeneous(_) | Body::Layered(_) => None,
            Body::Viscoelastic(solid) => Some(solid.time_scale()),
        }
    }

    /// The same body with lengths divided by `length`, moduli by `modulus` and
    /// times by `time` (the solver's units, `units.rs`).
    pub fn scaled(&self, length: f64, modulus: f64, time: f64) -> Body {
        match self {
            Body::Homogeneous(m) => Body::Homogeneous(m.scaled(modulus)),
            Body::Layered(stack) => Body::Layered(stack.scaled(length, modulus)),
            Body::Viscoelastic(solid) => Body::Viscoelastic(solid.scaled(modulus, time)),
        }
    }

    /// The coating of a one-layer stack on a half-space: `(coating, thickness,
    /// substrate)`; `None` for any other body.
    pub fn as_coating(&self) -> Option<(Elastic, f64, Elastic)> {
        match self {
            Body::Layered(Stack {
                layers,
                base: Base::HalfSpace(substrate),
            }) if layers.len() == 1 => Some((layers[0].material, layers[0].thickness, *substrate)),
            _ => None,
        }
    }

    pub(crate) fn validate(&self) -> Result<()> {
        match self {
            Body::Homogeneous(m) => m.validate("substrate"),
            Body::Layered(stack) if stack.layers.is_empty() => Err(Error::invalid(
                "body.layers",
                "[]",
                "at least one layer (a half-space alone is a [substrate] without layers)",
            )),
            Body::Layered(stack) => stack.validate(),
            Body::Viscoelastic(solid) => solid.validate(),
        }
    }
}

/// Normal load and sliding velocity.
#[derive(Clone, Copy, PartialEq)]
pub struct Loading {
    /// Normal force Q on the slider, > 0.
    pub normal_load: f64,
    /// Sliding velocity V, > 0; may be infinite (no time to creep). Needed only
    /// with a layer.
    pub velocity: Option<f64>,
    /// A line contact's datum: the surface displacement and the approach are
    /// measured against the surface at this distance from the load (in plane strain
    /// they are defined only against a datum, [`crate::body::line`]); default the
    /// slider's radius. Not allowed on a point contact.
    pub reference_distance: Option<f64>,
}

/// Written as derived, leaving out a datum that is not set: a case's hash
/// ([`crate::provenance::case_hash`]) is its debug form, and a point contact's must
/// not change with a key it cannot have.
impl std::fmt::Debug for Loading {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let mut s = f.debug_struct("Loading");
        s.field("normal_load", &self.normal_load)
            .field("velocity", &self.velocity);
        if let Some(d) = &self.reference_distance {
            s.field("reference_distance", d);
        }
        s.finish()
    }
}

/// How the window is chosen.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GridSpec {
    /// Cells along x and y (a line contact: `[nx, 1]`).
    pub cells: [usize; 2],
    /// Fixed window half widths along x and y (centred on the origin unless
    /// `centre` is given); `None` for an automatic window that is enlarged until
    /// it holds the contact.
    pub half_width: Option<[f64; 2]>,
    /// Centre of a fixed window; default the origin.
    pub centre: Option<[f64; 2]>,
}

/// Systems of units a case may be written in; they change only labels.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Units {
    /// The paper's dimensionless variables (lengths / R, stresses / E2, times / T).
    #[default]
    Dimensionless,
    /// Pa, m, s, N.
    Si,
}

/// Everything that defines one contact problem.
#[derive(Debug, Clone, PartialEq)]
pub struct Case {
    /// Slider shape f(x, y).
    pub slider: Slider,
    /// Elastic body.
    pub body: Body,
    /// Third-body layer; `None` for direct contact with the body.
    pub layer: Option<Layer>,
    /// Load and velocity.
    pub loading: Loading,
    /// Grid.
    pub grid: GridSpec,
    /// Units, for labels only.
    pub units: Units,
}

impl Case {
    /// Checks every field; the error names the field and what is allowed.
    pub fn validate(&self) -> Result<()> {
        self.slider.validate()?;
        self.body.validate()?;
        require_positive("loading.normal_load", self.loading.normal_load)?;
        if let Some(layer) = &self.layer {
            layer.validate()?;
            match self.loading.velocity {
                None => {
                    return Err(Error::MissingField {
                        field: "loading.velocity".into(),
                        why: "a case with a [layer] needs the sliding velocity".into(),
                    })
                }
                Some(v) if v.is_nan() || v <= 0.0 => {
                    return Err(Error::invalid(
                        "loading.velocity",
                        v,
                        "a number > 0 (inf for no creep)",
                    ))
                }
                _ => {}
            }
        } else if let Some(v) = self.loading.velocity {
            if v.is_nan() || v < 0.0 {
                return Err(Error::invalid("loading.velocity", v, "a number >= 0"));
            }
        }
        if let Body::Viscoelastic(_) = self.body {
            if self.loading.velocity.is_none() {
                return Err(Error::MissingField {
                    field: "loading.velocity".into(),
                    why: "a viscoelastic body needs the sliding velocity (0 for its relaxed \
                          response, inf for its glassy one)"
                        .into(),
                });
            }
        }
        if self.slider.is_line() {
            return self.validate_line_grid();
        }
        if let Some(d) = self.loading.reference_distance {
            return Err(Error::invalid(
                "loading.reference_distance",
                d,
                "no value on a point contact (it is a line contact's datum)",
            ));
        }
        for (k, &n) in self.grid.cells.iter().enumerate() {
            if n < crate::grid::MIN_CELLS {
                return Err(Error::invalid(
                    &format!("grid.cells[{k}]"),
                    n,
                    "at least 8 cells along each axis",
                ));
            }
            if n > 1 << 14 {
                return Err(Error::invalid(
                    &format!("grid.cells[{k}]"),
                    n,
                    "at most 16384 cells along each axis",
                ));
            }
        }
        if let Some(w) = self.grid.half_width {
            require_positive("grid.half_width[0]", w[0])?;
            require_positive("grid.half_width[1]", w[1])?;
            let hx = 2.0 * w[0] / self.grid.cells[0] as f64;
            let hy = 2.0 * w[1] / self.grid.cells[1] as f64;
            if ((hx - hy) / hx).abs() > 1e-9 {
                return Err(Error::invalid(
                    "grid.half_width",
                    format!("[{}, {}]", w[0], w[1]),
                    "cells must be square: half_width[0] / cells[0] = half_width[1] / cells[1]",
                ));
            }
        }
        if let Some(c) = self.grid.centre {
            if !(c[0].is_finite() && c[1].is_finite()) {
                return Err(Error::invalid(
                    "grid.centre",
                    format!("[{}, {}]", c[0], c[1]),
                    "finite coordinates",
                ));
            }
            if self.grid.half_width.is_none() {
                return Err(Error::MissingField {
                    field: "grid.half_width".into(),
                    why: "grid.centre fixes the window, so its half widths are needed too".into(),
                });
            }
        }
        Ok(())
    }

    /// The grid keys of a line contact: `cells = [nx, 1]`, a half width and centre
    /// along x only (`[w, 0]`, `[c, 0]`), a positive reference distance.
    fn validate_line_grid(&self) -> Result<()> {
        let [nx, ny] = self.grid.cells;
        if ny != 1 {
            return Err(Error::invalid(
                "grid.cells",
                format!("[{nx}, {ny}]"),
                "one number of cells along x for a line contact (slider.shape = \"cylinder\"): \
                 cells = N",
            ));
        }
        if !(crate::grid::MIN_CELLS..=1 << 22).contains(&nx) {
            return Err(Error::invalid(
                "grid.cells",
                nx,
                "8 to 4194304 cells along x for a line contact",
            ));
        }
        if let Some(d) = self.loading.reference_distance {
            require_positive("loading.reference_distance", d)?;
        }
        if let Some(w) = self.grid.half_width {
            require_positive("grid.half_width", w[0])?;
            if w[1] != 0.0 {
                return Err(Error::invalid(
                    "grid.half_width",
                    format!("[{}, {}]", w[0], w[1]),
                    "one half width along x for a line contact: half_width = w",
                ));
            }
        }
        if let Some(c) = self.grid.centre {
            if !c[0].is_finite() || c[1] != 0.0 {
                return Err(Error::invalid(
                    "grid.centre",
                    format!("[{}, {}]", c[0], c[1]),
                    "one finite x for a line contact: centre = x",
                ));
            }
            if self.grid.half_width.is_none() {
                return Err(Error::MissingField {
                    field: "grid.half_width".into(),
                    why: "grid.centre fixes the window, so its half width is needed too".into(),
                });
            }
        }
        Ok(())
    }

    /// The contact's geometry (point, or line with its datum), from the slider.
    pub fn geometry(&self) -> crate::grid::Geometry {
        let datum = self
            .loading
            .reference_distance
            .unwrap_or_else(|| self.slider.equivalent_radius());
        self.slider.geometry(datum)
    }

    /// An upper estimate of the memory a solve of this case takes at its peak, in
    /// bytes (as f64: it may exceed any integer a caller would allocate). Per cell:
    /// the DC-FFT scratch and spectrum of the 2nx x 2ny padded grid (~110 bytes), the
    /// solver's vectors and the solution's fields (~110), and with a layer the Newton
    /// step's GMRES basis on the contact cells (~150); measured peaks at 1024² are
    /// 210 (Hertz) and 315 (the paper's Fig. 3) bytes per cell (docs/performance.md).
    /// A viscoelastic body in steady sliding adds its general spectrum and its build
    /// (measured peaks of the CLI's solve: 550 bytes per cell at 256², 470 at 512²),
    /// and a Newton step that stagnates there lengthens the GMRES basis from 41 to
    /// 121 vectors of the contact cells (about half the window's: 320 bytes per cell
    /// more).
    pub fn estimated_solve_bytes(&self) -> f64 {
        let cells = self.grid.cells[0] as f64 * self.grid.cells[1] as f64;
        // A body whose kernel is not even keeps a general spectrum (four times the
        // even one's 16 bytes per cell) and builds it from the half-plane kernel on
        // the wrap-around grid (8 + 32 bytes per cell while it is built), and is
        // solved by Newton.
        let creeping_body = !self.body.model().kernel_is_even(self.velocity());
        let per_cell = if creeping_body {
            880.0
        } else if self.layer.is_some() {
            370.0
        } else {
            220.0
        };
        cells * per_cell + 16.0 * 1024.0 * 1024.0
    }

    /// The method a solve of this case uses when the `[solver]` asks for
    /// `requested` (`None`: the automatic choice): Polonsky–Keer conjugate gradients
    /// when the problem is symmetric (a body whose kernel is even at the case's
    /// velocity, [`crate::body::BodyModel::kernel_is_even`], and no layer or a layer
    /// that is a linear spring bed at that velocity: [`Layer::is_spring_bed`]),
    /// semi-smooth Newton otherwise ([`crate::solve_problem`]).
    pub fn solver_method(&self, requested: Option<Method>) -> Method {
        let velocity = self.velocity();
        let symmetric_layer = self
            .layer
            .as_ref()
            .is_none_or(|layer| layer.is_spring_bed(velocity));
        let even_body = self.body.model().kernel_is_even(velocity);
        requested.unwrap_or(if symmetric_layer && even_body {
            Method::PolonskyKeer
        } else {
            Method::SemismoothNewton
        })
    }

    /// The published works a solve of this case relies on, each once, with what it
    /// is used for: the paper's model, the layer's rheology and its discretisation,
    /// the body's kernels, DC-FFT, and the solver `requested` would pick
    /// ([`Case::solver_method`]). `thirdbody cite CASE` prints them.
    pub fn references(&self, requested: Option<Method>) -> Vec<Reference> {
        let mut all = vec![Reference::new(
            provenance::PAPER,
            if self.layer.is_some() {
                "the third-body layer model: pressure-dependent compliance, integration \
                 along the sliding direction (eq. 2-8)"
            } else {
                "the contact model solved (eq. 3-6)"
            },
        )];
        if let Some(layer) = &self.layer {
            all.extend(layer.rheology.references());
        }
        all.extend(self.body.model().references());
        all.push(Reference::new(
            provenance::DC_FFT,
            "the body's influence as a discrete convolution by FFT",
        ));
        match self.solver_method(requested) {
            Method::PolonskyKeer => all.push(Reference::new(
                provenance::POLONSKY_KEER,
                "the contact solver (conjugate gradients)",
            )),
            Method::SemismoothNewton => all.push(Reference::new(
                provenance::SEMISMOOTH_NEWTON,
                "the contact solver (semi-smooth Newton on the complementarity conditions)",
            )),
            Method::DenseReference => {}
        }
        provenance::merged(all)
    }

    /// Sliding velocity, infinite when none is given.
    pub fn velocity(&self) -> f64 {
        self.loading.velocity.unwrap_or(f64::INFINITY)
    }
}
