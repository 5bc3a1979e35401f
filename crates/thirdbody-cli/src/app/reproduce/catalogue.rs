//! The paper's cases (section 4, dimensionless: R = E2 = T = 1, nu2 = 0.3), in one
//! place: each figure's cases as a constructor, [`every_case`] listing what a whole
//! run solves (so that [`super::solutions::Solutions`] solves each case once and
//! keeps it only until its last use), and [`parameter_line`], which writes a figure's
//! parameters from its cases' values. Where a caption leaves a value open, the figure
//! states its reading beside the generated line.

use thirdbody::{
    Body, Case, ComplianceLaw, Elastic, GridSpec, Integration, Layer, Loading, Slider, Units,
};

use super::Resolution;

const SUBSTRATE: Elastic = Elastic {
    young: 1.0,
    poisson: 0.3,
};
/// The rigid coating of Figs. 7, 11 and 12 (E1/E2 = 3, nu1 = 0.3).
const COATING: Elastic = Elastic {
    young: 3.0,
    poisson: 0.3,
};
/// Q' of Figs. 3-7 and 9-12.
const LOAD: f64 = 5e-6;
/// Q' of Fig. 8.
const FIG8_LOAD: f64 = 25e-6;
/// V' of Figs. 3-7 and 9-12.
const VELOCITY: f64 = 1e-3;
/// C' of every figure but 6.
const COMPLIANCE: f64 = 0.02;

/// The sigmoid law of eq. 11, T = 1, exact integration.
pub fn sigmoid(compliance: f64, delta: f64, p0: f64) -> Layer {
    Layer::maxwell(
        compliance,
        1.0,
        ComplianceLaw::Sigmoid { delta, p0 },
        Integration::Exact,
    )
}

fn linear(compliance: f64) -> Layer {
    Layer::maxwell(compliance, 1.0, ComplianceLaw::Linear, Integration::Exact)
}

/// A sphere R = 1 over `layer` on `body`, automatic window of `cells` per side.
fn case(r: Resolution, body: Body, layer: Layer, load: f64, velocity: f64) -> Case {
    Case {
        slider: Slider::Sphere { radius: 1.0 },
        body,
        layer: Some(layer),
        loading: Loading {
            normal_load: load,
            velocity: Some(velocity),
            reference_distance: None,
        },
        grid: GridSpec {
            cells: [r.cells, r.cells],
            half_width: None,
            centre: None,
        },
        units: Units::Dimensionless,
    }
}

fn homogeneous(r: Resolution, layer: Layer) -> Case {
    case(r, Body::Homogeneous(SUBSTRATE), layer, LOAD, VELOCITY)
}

fn coated(r: Resolution, thickness: f64, layer: Layer) -> Case {
    let body = Body::coated(COATING, thickness, SUBSTRATE);
    case(r, body, layer, LOAD, VELOCITY)
}

/// A case with its legend entry.
pub struct Line {
    /// Legend label.
    pub label: String,
    /// Drawn dashed.
    pub dashed: bool,
    /// The case.
    pub case: Case,
}

/// A parameter study: one curve per model, one case per value of the varied parameter.
pub struct Study {
    /// Symbol of the varied parameter (C', h1', V').
    pub key: &'static str,
    /// Its values.
    pub values: Vec<f64>,
    /// One per model; `cases[k]` is at `values[k]`.
    pub curves: Vec<StudyCurve>,
}

/// One curve of a [`Study`].
pub struct StudyCurve {
    /// Legend label.
    pub label: &'static str,
    /// Drawn dashed.
    pub dashed: bool,
    /// The case at each value.
    pub cases: Vec<Case>,
}

/// A coated panel of Figs. 11 and 12: the nonlinear and the linear layer on one coating.
pub struct CoatedPanel {
    /// h1'.
    pub thickness: f64,
    /// "a" or "b".
    pub panel: &'static str,
    /// Sigmoid law delta = 0.5, p0' = 0.005.
    pub nonlinear: Case,
    /// Linear law.
    pub linear: Case,
}

/// Fig. 2: the sigmoid laws (C0 = 1) and whether each is drawn dashed.
pub fn fig2() -> Vec<(Layer, bool)> {
    [(0.0025, true), (0.005, false)]
        .into_iter()
        .flat_map(|(p0, dashed)| [0.3, 0.6, 1.0].map(|delta| (sigmoid(1.0, delta, p0), dashed)))
        .collect()
}

/// Fig. 3: one sigmoid layer, p0' = 0.001.
pub fn fig3(r: Resolution) -> Case {
    homogeneous(r, sigmoid(COMPLIANCE, 0.5, 0.001))
}

/// Fig. 4: three p0' and the two linear layers bounding the sigmoid law.
pub fn fig4(r: Resolution) -> Vec<Line> {
    let mut lines: Vec<Line> = [0.0025, 0.005, 0.05]
        .iter()
        .map(|&p0| Line {
            label: format!("p0' = {p0}"),
            dashed: false,
            case: homogeneous(r, sigmoid(COMPLIANCE, 0.5, p0)),
        })
        .collect();
    for c in [0.02, 0.01] {
        lines.push(Line {
            label: format!("linear, C' = {c}"),
            dashed: true,
            case: homogeneous(r, linear(c)),
        });
    }
    lines
}

/// Fig. 5: three delta.
pub fn fig5(r: Resolution) -> Vec<Line> {
    [0.01, 0.5, 1.0]
        .iter()
        .map(|&d| Line {
            label: format!("delta = {d}"),
            dashed: false,
            case: homogeneous(r, sigmoid(COMPLIANCE, d, 0.005)),
        })
        .collect()
}

/// `n` values from `lo` to `hi`, evenly spaced in log.
fn log_space(lo: f64, hi: f64, n: usize) -> Vec<f64> {
    (0..n)
        .map(|k| lo * (hi / lo).powf(k as f64 / (n - 1) as f64))
        .collect()
}

/// A study's model: legend label, dashed, the case at a value.
type Model<'a> = (&'static str, bool, &'a dyn Fn(f64) -> Case);

fn study(key: &'static str, values: Vec<f64>, models: &[Model]) -> Study {
    let curves = models
        .iter()
        .map(|&(label, dashed, case_at)| StudyCurve {
            label,
            dashed,
            cases: values.iter().map(|&v| case_at(v)).collect(),
        })
        .collect();
    Study {
        key,
        values,
        curves,
    }
}

/// Fig. 6: mu against C' (0.002 to 0.2, our range: the caption gives only 0.02).
pub fn fig6(r: Resolution) -> Study {
    study(
        "C'",
        log_space(0.002, 0.2, r.points),
        &[
            ("linear", true, &|c| homogeneous(r, linear(c))),
            ("delta = 0.5, p0' = 0.005", false, &|c| {
                homogeneous(r, sigmoid(c, 0.5, 0.005))
            }),
        ],
    )
}

/// Fig. 7: mu against the thickness of the rigid coating, 0.001 to 0.05.
pub fn fig7(r: Resolution) -> Study {
    study(
        "h1'",
        log_space(0.001, 0.05, r.points),
        &[
            ("linear", true, &|h| coated(r, h, linear(COMPLIANCE))),
            ("delta = 0.5, p0' = 0.005", false, &|h| {
                coated(r, h, sigmoid(COMPLIANCE, 0.5, 0.005))
            }),
        ],
    )
}

/// Fig. 8: mu against V' (1e-4 to 1e-1) at Q' = 25e-6, the linear law first.
pub fn fig8(r: Resolution) -> Study {
    let body = Body::Homogeneous(SUBSTRATE);
    let at = |layer: Layer| {
        let body = body.clone();
        move |v: f64| case(r, body.clone(), layer.clone(), FIG8_LOAD, v)
    };
    study(
        "V'",
        log_space(1e-4, 1e-1, r.points),
        &[
            ("linear", true, &at(linear(COMPLIANCE))),
            ("p0' = 0.0025", false, &at(sigmoid(COMPLIANCE, 0.5, 0.0025))),
            ("p0' = 0.005", false, &at(sigmoid(COMPLIANCE, 0.5, 0.005))),
            ("p0' = 0.0075", false, &at(sigmoid(COMPLIANCE, 0.5, 0.0075))),
        ],
    )
}

/// Figs. 9 and 10: delta = 0.01 and 1 (the extremes of Fig. 5).
pub fn fig9_10(r: Resolution) -> Vec<(f64, Case)> {
    [0.01, 1.0]
        .map(|d| (d, homogeneous(r, sigmoid(COMPLIANCE, d, 0.005))))
        .into()
}

/// Figs. 11 and 12: h1' = 0.001 (thin, a) and 0.02 (thick, b).
pub fn fig11_12(r: Resolution) -> Vec<CoatedPanel> {
    [(0.001, "a"), (0.02, "b")]
        .map(|(h, panel)| CoatedPanel {
            thickness: h,
            panel,
            nonlinear: coated(r, h, sigmoid(COMPLIANCE, 0.5, 0.005)),
            linear: coated(r, h, linear(COMPLIANCE)),
        })
        .into()
}

/// Every case a run solves, one entry per use, in the figures' order.
pub fn every_case(r: Resolution) -> Vec<Case> {
    let mut all = vec![fig3(r)];
    all.extend(fig4(r).into_iter().map(|l| l.case));
    all.extend(fig5(r).into_iter().map(|l| l.case));
    for s in [fig6(r), fig7(r), fig8(r)] {
        all.extend(s.curves.into_iter().flat_map(|c| c.cases));
    }
    for _fig in [9, 10] {
        all.extend(fig9_10(r).into_iter().map(|(_, c)| c));
    }
    for _fig in [11, 12] {
        all.extend(
            fig11_12(r)
                .into_iter()
                .flat_map(|p| [p.nonlinear, p.linear]),
        );
    }
    all
}

/// A value as the report prints it: 6 significant digits at most (log-spaced ends
/// such as 0.10000000000000002 print as 0.1), plain decimals from 0.001 up, `5e-6`
/// below.
fn value(v: f64) -> String {
    let v: f64 = format!("{v:.5e}").parse().unwrap_or(v);
    if v != 0.0 && (v.abs() < 1e-3 || v.abs() >= 1e4) {
        format!("{v:e}")
    } else {
        format!("{v}")
    }
}

/// The distinct values of a parameter over the cases, in order of appearance.
struct Parameter {
    symbol: &'static str,
    values: Vec<f64>,
}

impl Parameter {
    fn of(symbol: &'static str, values: impl IntoIterator<Item = f64>) -> Self {
        let mut distinct: Vec<f64> = Vec::new();
        for v in values {
            if !distinct.contains(&v) {
                distinct.push(v);
            }
        }
        Parameter {
            symbol,
            values: distinct,
        }
    }

    /// `p0' = 0.0025, 0.005`, or `C' from 0.002 to 0.2` for the varied key; empty
    /// when no case has the parameter.
    fn text(&self, varied: Option<&str>) -> Option<String> {
        let (first, last) = (self.values.first()?, self.values.last()?);
        Some(if varied == Some(self.symbol) {
            format!("{} from {} to {}", self.symbol, value(*first), value(*last))
        } else {
            let values: Vec<String> = self.values.iter().map(|&v| value(v)).collect();
            format!("{} = {}", self.symbol, values.join(", "))
        })
    }
}

fn joined(parameters: &[Parameter], varied: Option<&str>) -> String {
    let parts: Vec<String> = parameters.iter().filter_map(|p| p.text(varied)).collect();
    parts.join(", ")
}

/// The sigmoid laws' `delta, p0'` and whether a linear law is among `layers`, as
/// `sigmoid law delta = ..., p0' = ...; linear law`.
fn laws_text<'a>(layers: impl Iterator<Item = &'a Layer> + Clone, varied: Option<&str>) -> String {
    let sigmoid = |f: fn(f64, f64) -> f64| {
        layers.clone().filter_map(move |l| match l.law {
            ComplianceLaw::Sigmoid { delta, p0 } => Some(f(delta, p0)),
            _ => None,
        })
    };
    let shape = [
        Parameter::of("delta", sigmoid(|d, _| d)),
        Parameter::of("p0'", sigmoid(|_, p| p)),
    ];
    let mut parts = Vec::new();
    if !shape[0].values.is_empty() {
        parts.push(format!("sigmoid law (eq. 11) {}", joined(&shape, varied)));
    }
    if layers
        .clone()
        .any(|l| matches!(l.law, ComplianceLaw::Linear))
    {
        parts.push("linear law".to_string());
    }
    parts.join("; ")
}

/// A figure's parameters, generated from its cases: Q', V', nu2, the coating (E1/E2,
/// nu1, h1'), C', then the laws; `varied` (a study's key) is given as a range.
pub fn parameter_line<'a>(
    cases: impl IntoIterator<Item = &'a Case>,
    varied: Option<&str>,
) -> String {
    let cases: Vec<&Case> = cases.into_iter().collect();
    let coatings = || {
        cases.iter().filter_map(|c| {
            let (coating, thickness, substrate) = c.body.as_coating()?;
            Some((coating.young / substrate.young, coating.poisson, thickness))
        })
    };
    let layers = cases.iter().filter_map(|c| c.layer.as_ref());
    let parameters = [
        Parameter::of("Q'", cases.iter().map(|c| c.loading.normal_load)),
        Parameter::of("V'", cases.iter().filter_map(|c| c.loading.velocity)),
        Parameter::of(
            "nu2",
            cases
                .iter()
                .filter_map(|c| c.body.half_space().map(|m| m.poisson)),
        ),
        Parameter::of("E1/E2", coatings().map(|c| c.0)),
        Parameter::of("nu1", coatings().map(|c| c.1)),
        Parameter::of("h1'", coatings().map(|c| c.2)),
        Parameter::of("C'", layers.clone().map(|l| l.reference_compliance())),
    ];
    format!(
        "{}; {}",
        joined(&parameters, varied),
        laws_text(layers, varied)
    )
}

/// The parameters of layers alone (Fig. 2).
pub fn law_line(layers: &[Layer]) -> String {
    laws_text(layers.iter(), None)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn r() -> Resolution {
        Resolution {
            cells: 32,
            points: 4,
        }
    }

    #[test]
    fn parameter_lines_come_from_the_cases() {
        let cases: Vec<Case> = fig11_12(r())
            .into_iter()
            .flat_map(|p| [p.nonlinear, p.linear])
            .collect();
        assert_eq!(
            parameter_line(&cases, None),
            "Q' = 5e-6, V' = 0.001, nu2 = 0.3, E1/E2 = 3, nu1 = 0.3, h1' = 0.001, 0.02, \
             C' = 0.02; sigmoid law (eq. 11) delta = 0.5, p0' = 0.005; linear law"
        );
        let s = fig8(r());
        let cases = s.curves.iter().flat_map(|c| &c.cases);
        assert_eq!(
            parameter_line(cases, Some(s.key)),
            "Q' = 2.5e-5, V' from 1e-4 to 0.1, nu2 = 0.3, C' = 0.02; sigmoid law (eq. 11) \
             delta = 0.5, p0' = 0.0025, 0.005, 0.0075; linear law"
        );
    }

    #[test]
    fn every_case_counts_each_use() {
        let all = every_case(r());
        let fig9 = &fig9_10(r())[0].1;
        // Figs. 5, 9 and 10.
        assert_eq!(all.iter().filter(|c| *c == fig9).count(), 3);
        let thin = &fig11_12(r())[0].nonlinear;
        // Fig. 7's first point, Figs. 11 and 12.
        assert_eq!(all.iter().filter(|c| *c == thin).count(), 3);
    }
}
