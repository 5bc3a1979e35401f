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
};

/// The labels of `units`.
pub const fn labels(units: Units) -> &'static Labels {
    match units {
        Units::Dimensionless => &DIMENSIONLESS,
        Units::Si => &SI,
    }
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
}
