//! The units a solve runs in. Every solve is done in the paper's dimensionless
//! variables (section 4: lengths by the slider radius R, stresses by the substrate's
//! modulus E2, times by the layer's time T), each scale rounded to the nearest power
//! of two: the case is divided by the scales before it is assembled and the solution
//! multiplied by them afterwards ([`Scales`]). So one dimensionless problem written in
//! any consistent units (metres or nanometres, pascals or gigapascals, 1e-100 or
//! 1e100) is one problem for the solver: its numbers stay near those of the paper's
//! examples, far from double precision's overflow and underflow, and its tolerances
//! and thresholds mean the same. Powers of two make both conversions exact (a scaled
//! number has the same significand), so a case already written with R = E2 = T = 1,
//! like the paper's, is solved bit for bit as before, and converting back adds no
//! rounding. Lengths are R for a sphere, `sqrt(Rx Ry)` for an ellipsoid and the
//! map's extent for a height map; T is the time the layer's rheology states
//! ([`crate::layer::RheologyModel::time_scale`]: the Maxwell T, a retardation time),
//! 1 without a layer.

use crate::case::{Body, Case};
use crate::error::{Error, Result};
use crate::grid::{Geometry, Grid};
use crate::layer::{ComplianceLaw, Layer, SolverUnits};
use crate::shape::{HeightMap, Profile, Slider};
use crate::solution::Solution;

/// The units of a solve: one length, one modulus (pressure) and one time, each a
/// power of two. A quantity in the case's units is the scaled one times its unit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Scales {
    /// Unit of length.
    pub length: f64,
    /// Unit of pressure and modulus.
    pub modulus: f64,
    /// Unit of time.
    pub time: f64,
    /// Whether forces are per unit length (a line contact): their unit is then
    /// modulus times length, else modulus times length squared.
    pub per_length: bool,
}

/// The power of two nearest `x` (on a log scale), kept among the normal numbers;
/// 1 for a value that is not finite and positive (the case's validation reports it).
fn power_of_two_near(x: f64) -> f64 {
    if !(x.is_finite() && x > 0.0) {
        return 1.0;
    }
    let exponent = x.log2().round().clamp(-1022.0, 1023.0) as i32;
    // 2^e built from its bits: exact for every normal exponent.
    f64::from_bits(((exponent + 1023) as u64) << 52)
}

/// `g` with each of its lengths mapped by `f`.
fn grid_lengths(g: &Grid, f: impl Fn(f64) -> f64) -> Grid {
    Grid {
        nx: g.nx,
        ny: g.ny,
        cell: f(g.cell),
        x0: f(g.x0),
        y0: f(g.y0),
        geometry: match g.geometry {
            Geometry::Point => Geometry::Point,
            Geometry::Line { datum } => Geometry::Line { datum: f(datum) },
        },
    }
}

impl Scales {
    /// The scales of `case` (module docs).
    pub fn of(case: &Case) -> Scales {
        let length = match &case.slider {
            Slider::HeightMap(m) => m.cell_size * m.nx.max(m.ny) as f64,
            Slider::Profile(p) => p.cell_size * p.heights.len() as f64,
            other => other.equivalent_radius(),
        };
        let time = match &case.layer {
            Some(layer) => layer.rheology.time_scale(),
            None => case.body.time_scale().unwrap_or(1.0),
        };
        Scales {
            length: power_of_two_near(length),
            modulus: power_of_two_near(case.body.reference_modulus()),
            time: power_of_two_near(time),
            per_length: case.slider.is_line(),
        }
    }

    /// The units of a stress computation on `body` under a pressure on `grid`: the
    /// window's size, the body's reference modulus (no time), as powers of two. Love's
    /// and the coated kernels raise lengths to the fourth power: in 1e-100 units
    /// they would underflow.
    pub fn for_stresses(body: &Body, grid: &Grid) -> Scales {
        Scales {
            length: power_of_two_near(grid.cell * grid.nx.max(grid.ny) as f64),
            modulus: power_of_two_near(body.reference_modulus()),
            time: 1.0,
            per_length: grid.is_line(),
        }
    }

    /// A grid in these units.
    pub fn grid(&self, g: &Grid) -> Grid {
        grid_lengths(g, |x| self.length(x))
    }

    /// Whether the case's units are already the solver's (nothing to convert).
    pub fn are_unity(&self) -> bool {
        self.length == 1.0 && self.modulus == 1.0 && self.time == 1.0
    }

    /// A length in these units.
    pub fn length(&self, x: f64) -> f64 {
        x / self.length
    }

    /// A pressure (or stress, or modulus) in these units.
    pub fn pressure(&self, p: f64) -> f64 {
        p / self.modulus
    }

    /// A compliance (length per pressure).
    fn compliance(&self, c: f64) -> f64 {
        c / self.length * self.modulus
    }

    /// A force (pressure times area), divided one factor at a time so that no
    /// intermediate leaves the range a scaled force can have.
    fn force(&self, q: f64) -> f64 {
        if self.per_length {
            q / self.modulus / self.length
        } else {
            q / self.modulus / self.length / self.length
        }
    }

    /// A force of the solver back in the case's units.
    fn unscaled_force(&self, q: f64) -> f64 {
        if self.per_length {
            q * self.modulus * self.length
        } else {
            q * self.modulus * self.length * self.length
        }
    }

    /// A body in these units.
    pub fn body(&self, body: &Body) -> Body {
        body.scaled(self.length, self.modulus, self.time)
    }

    fn slider(&self, slider: &Slider) -> Slider {
        match slider {
            Slider::Sphere { radius } => Slider::Sphere {
                radius: self.length(*radius),
            },
            Slider::Ellipsoid { radius_x, radius_y } => Slider::Ellipsoid {
                radius_x: self.length(*radius_x),
                radius_y: self.length(*radius_y),
            },
            Slider::HeightMap(m) => Slider::HeightMap(HeightMap {
                nx: m.nx,
                ny: m.ny,
                cell_size: self.length(m.cell_size),
                heights: m.heights.iter().map(|&h| self.length(h)).collect(),
            }),
            Slider::Cylinder { radius } => Slider::Cylinder {
                radius: self.length(*radius),
            },
            Slider::Profile(p) => Slider::Profile(Profile {
                cell_size: self.length(p.cell_size),
                heights: p.heights.iter().map(|&h| self.length(h)).collect(),
            }),
        }
    }

    /// The units a rheology is scaled to.
    fn rheology_units(&self) -> SolverUnits {
        SolverUnits {
            length: self.length,
            stress: self.modulus,
            time: self.time,
        }
    }

    fn layer(&self, layer: &Layer) -> Result<Layer> {
        let law = match &layer.law {
            ComplianceLaw::Linear => ComplianceLaw::Linear,
            ComplianceLaw::Sigmoid { delta, p0 } => ComplianceLaw::Sigmoid {
                delta: *delta,
                p0: self.pressure(*p0),
            },
            ComplianceLaw::Table(t) => ComplianceLaw::Table(crate::layer::law::Table::new(
                t.pressures().iter().map(|&p| self.pressure(p)).collect(),
                t.compliances()
                    .iter()
                    .map(|&c| self.compliance(c))
                    .collect(),
            )?),
        };
        Ok(Layer {
            rheology: layer.rheology.scaled(&self.rheology_units()),
            law,
            integration: layer.integration,
        })
    }

    /// The case in these units. A case whose values are valid but cannot be
    /// written in the paper's variables (a load of 1e300 on a modulus of 1e-300) is
    /// [`Error::OutOfRange`], naming the keys.
    pub fn scaled_case(&self, case: &Case) -> Result<Case> {
        let mut scaled = case.clone();
        scaled.slider = self.slider(&case.slider);
        scaled.body = self.body(&case.body);
        scaled.layer = (case.layer.as_ref().map(|l| self.layer(l)).transpose())
            .map_err(|e| self.out_of_range(e))?;
        scaled.loading.normal_load = self.force(case.loading.normal_load);
        scaled.loading.velocity = case.loading.velocity.map(|v| v / self.length * self.time);
        scaled.loading.reference_distance = case.loading.reference_distance.map(|d| self.length(d));
        scaled.grid.half_width = case.grid.half_width.map(|w| w.map(|x| self.length(x)));
        scaled.grid.centre = case.grid.centre.map(|c| c.map(|x| self.length(x)));
        scaled.validate().map_err(|e| self.out_of_range(e))?;
        Ok(scaled)
    }

    /// A value that was valid in the case's units and is not in the solver's: its
    /// key is named with the scales it was divided by.
    fn out_of_range(&self, e: Error) -> Error {
        match e {
            Error::InvalidValue { field, value, .. } => Error::OutOfRange {
                why: format!(
                    "{field} is {value} in the solver's units (length {:e}, stress {:.3e}, \
                     time {:e}: powers of two near the slider's radius, substrate.young and \
                     the layer's time), so the case's values are too far apart for double \
                     precision; check {field} against the slider radius and substrate.young",
                    self.length, self.modulus, self.time
                ),
            },
            other => other,
        }
    }

    /// A grid of the solver back in the case's units.
    pub fn unscaled_grid(&self, g: &Grid) -> Grid {
        grid_lengths(g, |x| x * self.length)
    }

    /// A solution of the scaled case back in the case's units; `body` is the case's.
    pub fn unscaled_solution(&self, s: Solution, body: Body, normal_load: f64) -> Solution {
        let lengths = |v: Vec<f64>| v.into_iter().map(|x| x * self.length).collect();
        let compliances = |v: Vec<f64>| {
            v.into_iter()
                .map(|c| c * self.length / self.modulus)
                .collect()
        };
        Solution {
            grid: self.unscaled_grid(&s.grid),
            body,
            pressure: s.pressure.into_iter().map(|p| p * self.modulus).collect(),
            contact_edges: s.contact_edges,
            body_displacement: lengths(s.body_displacement),
            layer_displacement: s.layer_displacement.map(lengths),
            compliance: s.compliance.map(compliances),
            gap: lengths(s.gap),
            shape: lengths(s.shape),
            shape_slope: s.shape_slope,
            dissipated_force: self.unscaled_force(s.dissipated_force),
            approach: s.approach * self.length,
            normal_load,
            info: s.info,
        }
    }

    /// An error of the scaled solve, with its lengths back in the case's units.
    pub fn unscaled_error(&self, e: Error) -> Error {
        match e {
            Error::ContactAtWindowEdge {
                half_width_x,
                half_width_y,
            } => Error::ContactAtWindowEdge {
                half_width_x: half_width_x * self.length,
                half_width_y: half_width_y * self.length,
            },
            Error::NoConvergence {
                iterations,
                residual,
                tolerance,
                history,
                hint,
            } if !self.are_unity() => Error::NoConvergence {
                iterations,
                residual,
                tolerance,
                history,
                hint: format!(
                    "{hint} (pressures and lengths in this message are in the solver's units: \
                     multiply pressures by {:e} and lengths by {:e})",
                    self.modulus, self.length
                ),
            },
            other => other,
        }
    }
}
