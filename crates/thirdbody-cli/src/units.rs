//! Every label that depends on a case's [`Units`], in one table (the name
//! `summary.json` gives the system is the library's [`Units::name`]): plot axes and colour bars (the paper's primed
//! dimensionless variables, section 4, or SI with the unit in brackets), the units
//! printed after numbers, and the paper's symbol of each case key (sweep plots).
//! `units = "si"` changes only these labels; the numbers are the case's own.

use thirdbody::Units;

/// The labels of one system of units.
#[derive(Debug)]
pub struct Labels {
    /// Axis label of x.
    pub x: &'static str,
    /// Axis label of y.
    pub y: &'static str,
    /// Axis label of the depth z.
    pub depth: &'static str,
    /// Colour-bar label of the pressure.
    pub pressure: &'static str,
    /// Colour-bar label of the layer's compliance.
    pub compliance: &'static str,
    /// Written after a stress component's name in a label (`sigma_x / E2`).
    pub stress_scale: &'static str,
    /// Printed after a length (with its leading space; empty when dimensionless).
    pub length_unit: &'static str,
    /// Printed after an area.
    pub area_unit: &'static str,
    /// Printed after a force.
    pub force_unit: &'static str,
    /// Printed after a pressure or stress.
    pub stress_unit: &'static str,
    /// Printed after a moment.
    pub moment_unit: &'static str,
    /// Printed after a force per unit length (a line contact's loads and forces).
    pub line_force_unit: &'static str,
    /// Printed after a moment per unit length (a line contact's).
    pub line_moment_unit: &'static str,
}

const DIMENSIONLESS: Labels = Labels {
    x: "x'",
    y: "y'",
    depth: "z' (depth)",
    pressure: "p'",
    compliance: "C'",
    stress_scale: "/ E2",
    length_unit: "",
    area_unit: "",
    force_unit: "",
    stress_unit: "",
    moment_unit: "",
    line_force_unit: " (per unit length)",
    line_moment_unit: " (per unit length)",
};

const SI: Labels = Labels {
    x: "x (m)",
    y: "y (m)",
    depth: "z (m, depth)",
    pressure: "p (Pa)",
    compliance: "C (m/Pa)",
    stress_scale: "(Pa)",
    length_unit: " m",
    area_unit: " m^2",
    force_unit: " N",
    stress_unit: " Pa",
    moment_unit: " N m",
    line_force_unit: " N/m",
    line_moment_unit: " N m/m",
};

/// The labels of `units`.
pub const fn labels(units: Units) -> &'static Labels {
    match units {
        Units::Dimensionless => &DIMENSIONLESS,
        Units::Si => &SI,
    }
}

/// How a case's plots write lengths and stresses: the paper's primed dimensionless
/// variables as they are, or SI values in a decimal multiple of the metre and the
/// pascal chosen for the figure (µm for a contact 300 µm long, MPa for 100 MPa), so that
/// tick labels read as plain numbers. The data files keep the case's own units.
#[derive(Debug, Clone)]
pub struct PlotUnits {
    labels: &'static Labels,
    /// Plotted length = `length.0` times the case's; `length.1` the unit's symbol.
    length: (f64, &'static str),
    /// Plotted stress = `stress.0` times the case's; `stress.1` the unit's symbol.
    stress: (f64, &'static str),
}

impl PlotUnits {
    /// The plot units of a case in `units` whose figures show lengths up to about
    /// `length` and stresses up to about `stress` (magnitudes in the case's units).
    pub fn new(units: Units, length: f64, stress: f64) -> Self {
        let labels = labels(units);
        match units {
            Units::Dimensionless => PlotUnits {
                labels,
                length: (1.0, ""),
                stress: (1.0, ""),
            },
            Units::Si => PlotUnits {
                labels,
                length: prefixed(
                    length,
                    &[(1e-9, "nm"), (1e-6, "\u{b5}m"), (1e-3, "mm"), (1.0, "m")],
                ),
                stress: prefixed(
                    stress,
                    &[(1.0, "Pa"), (1e3, "kPa"), (1e6, "MPa"), (1e9, "GPa")],
                ),
            },
        }
    }

    fn si(&self) -> bool {
        !self.length.1.is_empty()
    }

    /// A length in plot units.
    pub fn length(&self, v: f64) -> f64 {
        v * self.length.0
    }

    /// A stress in plot units.
    pub fn stress(&self, v: f64) -> f64 {
        v * self.stress.0
    }

    /// Axis label of x.
    pub fn x(&self) -> String {
        self.axis(self.labels.x, "x", self.length.1)
    }

    /// Axis label of y.
    pub fn y(&self) -> String {
        self.axis(self.labels.y, "y", self.length.1)
    }

    /// Axis label of the depth.
    pub fn depth(&self) -> String {
        if self.si() {
            format!("z ({}, depth)", self.length.1)
        } else {
            self.labels.depth.to_string()
        }
    }

    /// Label of the pressure.
    pub fn pressure(&self) -> String {
        self.axis(self.labels.pressure, "p", self.stress.1)
    }

    /// Label of a stress component `name` (`sigma_x / E2`, `sigma_x (MPa)`).
    pub fn stress_label(&self, name: &str) -> String {
        if self.si() {
            format!("{name} ({})", self.stress.1)
        } else {
            format!("{name} {}", self.labels.stress_scale)
        }
    }

    /// A length value with its unit, 4 significant digits (`y = -2.703 µm`).
    pub fn length_text(&self, v: f64) -> String {
        let v = self.length(v);
        let text = if v == 0.0 {
            "0".to_string()
        } else if (1e-3..1e4).contains(&v.abs()) {
            let decimals = (3 - v.abs().log10().floor() as i32).clamp(0, 6) as usize;
            format!("{v:.decimals$}")
        } else {
            format!("{v:.3e}")
        };
        if self.si() {
            format!("{text} {}", self.length.1)
        } else {
            text
        }
    }

    fn axis(&self, dimensionless: &str, symbol: &str, unit: &str) -> String {
        if self.si() {
            format!("{symbol} ({unit})")
        } else {
            dimensionless.to_string()
        }
    }
}

/// Of `units` (factor of the base unit, symbol; increasing), the largest whose factor is
/// at most `magnitude` (the first for smaller or no magnitude), as (multiplier of values
/// in the base unit, symbol).
fn prefixed(magnitude: f64, units: &[(f64, &'static str)]) -> (f64, &'static str) {
    let (factor, symbol) = units
        .iter()
        .rev()
        .find(|(f, _)| magnitude.is_finite() && magnitude >= *f)
        .unwrap_or(&units[0]);
    (1.0 / factor, symbol)
}

/// The system whose `summary.json` name is `name`.
pub fn from_name(name: &str) -> Option<Units> {
    [Units::Dimensionless, Units::Si]
        .into_iter()
        .find(|&u| u.name() == name)
}

/// The paper's symbol of a case key (section 4's primed variables when dimensionless,
/// the symbol and its unit in SI); `None` for keys without one.
pub fn key_symbol(key: &str, units: Units) -> Option<&'static str> {
    let (dimensionless, si) = match key {
        "loading.velocity" => ("V'", "V (m/s)"),
        "loading.normal_load" => ("Q'", "Q (N)"),
        "layer.compliance" => ("C'", "C0 (m/Pa)"),
        "layer.p0" => ("p0'", "p0 (Pa)"),
        "layer.delta" => ("delta", "delta"),
        "layer.relaxation_time" => ("T'", "T (s)"),
        "coating.thickness" => ("h1'", "h1 (m)"),
        "coating.young" => ("E1'", "E1 (Pa)"),
        "coating.poisson" => ("nu1", "nu1"),
        "substrate.young" => ("E2'", "E2 (Pa)"),
        "substrate.poisson" => ("nu2", "nu2"),
        _ => return None,
    };
    Some(match units {
        Units::Dimensionless => dimensionless,
        Units::Si => si,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip() {
        for u in [Units::Dimensionless, Units::Si] {
            assert_eq!(from_name(u.name()), Some(u));
        }
        assert_eq!(from_name("imperial"), None);
    }

    #[test]
    fn si_plots_use_a_prefixed_unit_for_the_values_shown() {
        // A contact 300 µm long under 100 MPa: µm and MPa.
        let u = PlotUnits::new(Units::Si, 3e-4, 1e8);
        assert_eq!(
            (u.x(), u.depth(), u.pressure()),
            (
                "x (\u{b5}m)".to_string(),
                "z (\u{b5}m, depth)".to_string(),
                "p (MPa)".to_string()
            )
        );
        assert!((u.length(1.5e-4) - 150.0).abs() < 1e-9);
        assert!((u.stress(2.5e7) - 25.0).abs() < 1e-9);
        assert_eq!(u.stress_label("sigma_x"), "sigma_x (MPa)");
        assert_eq!(u.length_text(-2.703e-6), "-2.703 \u{b5}m");
        assert_eq!(u.length_text(0.0), "0 \u{b5}m");
        let m = PlotUnits::new(Units::Si, 0.004, 2e9);
        assert_eq!(
            (m.x(), m.pressure()),
            ("x (mm)".to_string(), "p (GPa)".to_string())
        );
        // Dimensionless: the paper's labels, values unchanged.
        let d = PlotUnits::new(Units::Dimensionless, 3e-4, 1e8);
        assert_eq!(
            (d.x(), d.pressure(), d.stress_label("tau1")),
            ("x'".to_string(), "p'".to_string(), "tau1 / E2".to_string())
        );
        assert_eq!(d.length(0.25), 0.25);
    }
}
