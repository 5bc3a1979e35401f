//! Figs. 2-8: the compliance law, the contact pressure (Figs. 3-5) and the friction
//! studies (Figs. 6-8). Each figure takes its cases from [`super::catalogue`], its
//! solutions from [`Solutions`], stages its plots (PNG + SVG) and data (CSV), and
//! returns what the report says of it.

use crate::plot::{self, Series};
use anyhow::Result;
use thirdbody::Case;

use super::catalogue::{self, parameter_line};
use super::render::{
    self, line_figure, max_pressure, mu_curves, number, pressure_row, push_curve_ends, report, L,
};
use super::solutions::Solutions;
use super::{FigureFiles, FigureReport, Resolution};

/// The paper's colours of a friction study, and what we draw dashed.
const RED_BLUE: &str = "the paper draws the linear law red (dashed here) and the sigmoid blue";

pub fn fig2(_: &mut Solutions, _: Resolution, files: &mut FigureFiles) -> Result<FigureReport> {
    let laws = catalogue::fig2();
    let layers: Vec<_> = laws.iter().map(|(l, _)| l.clone()).collect();
    let mut rep = report(
        "Fig. 2",
        "compliance of the layer against pressure (eq. 11)",
        format!(
            "{}; C/C0 drawn, p0' = 0.0025 dashed",
            catalogue::law_line(&layers)
        ),
    );
    let pressures: Vec<f64> = (0..=300).map(|k| 0.03 * k as f64 / 300.0).collect();
    let mut series = Vec::new();
    for (layer, dashed) in &laws {
        let thirdbody::ComplianceLaw::Sigmoid { delta, p0 } = layer.law else {
            continue;
        };
        series.push(Series {
            label: format!("delta = {delta}, p0' = {p0}"),
            x: pressures.clone(),
            y: pressures
                .iter()
                .map(|&p| layer.law_at(p).compliance)
                .collect(),
            dashed: *dashed,
        });
    }
    line_figure(
        files,
        "fig02_compliance",
        &series,
        "Layer compliance, eq. 11",
        [L.pressure, "C / C0"],
        (false, None),
    )?;
    let at_p0 = catalogue::sigmoid(1.0, 1.0, 0.005).law_at(0.005).compliance;
    rep.numbers
        .push(number("C/C0 at p = p0, delta = 1", at_p0, None));
    Ok(rep)
}

pub fn fig3(
    solutions: &mut Solutions,
    r: Resolution,
    files: &mut FigureFiles,
) -> Result<FigureReport> {
    let case = catalogue::fig3(r);
    let mut rep = report(
        "Fig. 3",
        "contact pressure and layer compliance, homogeneous half-space",
        parameter_line([&case], None),
    );
    let s = &solutions.solve_each(std::slice::from_ref(&case))?[0];
    let g = &s.grid;
    let c = s.compliance.clone().unwrap_or_default();
    // The pressure at the cells' centres.
    let centre = s.centre_pressure();
    let p: &[f64] = &centre;
    files.plot("fig03a_pressure", |path| {
        plot::field_map(
            path,
            g,
            p,
            "Contact pressure (Fig. 3a)",
            L.x,
            L.y,
            L.pressure,
            Some(p),
        )
    })?;
    files.plot("fig03b_compliance", |path| {
        plot::field_map(
            path,
            g,
            &c,
            "Layer compliance (Fig. 3b)",
            L.x,
            L.y,
            L.compliance,
            Some(p),
        )
    })?;
    let rows: Vec<Vec<f64>> = (0..g.ny())
        .flat_map(|j| (0..g.nx()).map(move |i| (i, j)))
        .map(|(i, j)| vec![g.x(i), g.y(j), p[g.index(i, j)], c[g.index(i, j)]])
        .collect();
    files.table_csv("fig03.csv", &[L.x, L.y, L.pressure, L.compliance], &rows)?;
    let sum = s.summary();
    let c_min = c.iter().copied().fold(f64::INFINITY, f64::min);
    let c0 = case
        .layer
        .as_ref()
        .map_or(f64::NAN, |l| l.reference_compliance());
    rep.numbers.extend([
        number("max pressure p'", sum.max_pressure, None),
        number("x' of the max pressure", sum.max_pressure_x, None),
        number("contact x' from", sum.contact_x_min, None),
        number("contact x' to", sum.contact_x_max, None),
        number("contact half-width in y'", sum.contact_y_max, None),
        number("friction coefficient mu", sum.friction_coefficient, None),
        number(
            "smallest compliance C/C0 (minimum 1 - delta = 0.5)",
            c_min / c0,
            None,
        ),
    ]);
    rep.notes.push(
        "The contact is close to a half-disc ahead of the initial contact point and the \
         compliance near its centre is close to the minimum C0 (1 - delta), as the paper says."
            .into(),
    );
    Ok(rep)
}

/// Pressure along x for several layers (Figs. 4 and 5).
fn pressure_curves(
    solutions: &mut Solutions,
    files: &mut FigureFiles,
    (stem, title): (&str, &str),
    lines: &[catalogue::Line],
    rep: &mut FigureReport,
) -> Result<()> {
    let cases: Vec<Case> = lines.iter().map(|l| l.case.clone()).collect();
    let solutions = solutions.solve_each(&cases)?;
    let series: Vec<Series> = lines
        .iter()
        .zip(&solutions)
        .map(|(l, s)| pressure_row(s, l.label.clone(), l.dashed))
        .collect();
    for (l, s) in lines.iter().zip(&solutions) {
        rep.numbers.push(number(
            format!("max pressure p', {}", l.label),
            max_pressure(s),
            None,
        ));
    }
    let contact = render::contact_x(&solutions);
    line_figure(
        files,
        stem,
        &series,
        title,
        [L.x, L.pressure],
        (false, contact),
    )
}

pub fn fig4(
    solutions: &mut Solutions,
    r: Resolution,
    files: &mut FigureFiles,
) -> Result<FigureReport> {
    let lines = catalogue::fig4(r);
    let mut rep = report(
        "Fig. 4",
        "contact pressure along x for several p0'",
        format!(
            "{}; the linear layers (dashed) have the largest and the smallest compliance \
             of the sigmoid law; the row of cells nearest y = 0",
            parameter_line(lines.iter().map(|l| &l.case), None)
        ),
    );
    pressure_curves(
        solutions,
        files,
        ("fig04_pressure", "Contact pressure, y = 0 (Fig. 4)"),
        &lines,
        &mut rep,
    )?;
    rep.notes.push(
        "The paper: the nonlinear curves lie between the two linear ones; the smaller p0, \
         the higher the maximum pressure."
            .into(),
    );
    Ok(rep)
}

pub fn fig5(
    solutions: &mut Solutions,
    r: Resolution,
    files: &mut FigureFiles,
) -> Result<FigureReport> {
    let lines = catalogue::fig5(r);
    let mut rep = report(
        "Fig. 5",
        "contact pressure along x for several delta",
        format!(
            "{}; the row of cells nearest y = 0",
            parameter_line(lines.iter().map(|l| &l.case), None)
        ),
    );
    pressure_curves(
        solutions,
        files,
        ("fig05_pressure", "Contact pressure, y = 0 (Fig. 5)"),
        &lines,
        &mut rep,
    )?;
    rep.notes
        .push("The paper: the pressure increases with delta.".into());
    Ok(rep)
}

/// The parameter line of a study, with a figure's reading after it.
fn study_line(study: &catalogue::Study, reading: &str) -> String {
    let cases = study.curves.iter().flat_map(|c| &c.cases);
    format!("{}; {reading}", parameter_line(cases, Some(study.key)))
}

pub fn fig6(
    solutions: &mut Solutions,
    r: Resolution,
    files: &mut FigureFiles,
) -> Result<FigureReport> {
    let study = catalogue::fig6(r);
    let mut rep = report(
        "Fig. 6",
        "friction coefficient against the layer's compliance",
        study_line(
            &study,
            &format!("the range of C' is ours (the caption gives only C' = 0.02), Q' held fixed; {RED_BLUE}"),
        ),
    );
    let series = mu_curves(solutions, &study, &mut rep.notes);
    line_figure(
        files,
        "fig06_mu_vs_compliance",
        &series,
        "Friction against layer compliance (Fig. 6)",
        [study.key, "mu"],
        (true, None),
    )?;
    push_curve_ends(&mut rep, &series, study.key);
    Ok(rep)
}

pub fn fig7(
    solutions: &mut Solutions,
    r: Resolution,
    files: &mut FigureFiles,
) -> Result<FigureReport> {
    let study = catalogue::fig7(r);
    let mut rep = report(
        "Fig. 7",
        "friction coefficient against the thickness of a rigid coating",
        study_line(&study, &format!("C' is not in the caption; {RED_BLUE}")),
    );
    let series = mu_curves(solutions, &study, &mut rep.notes);
    line_figure(
        files,
        "fig07_mu_vs_thickness",
        &series,
        "Friction against coating thickness (Fig. 7)",
        [study.key, "mu"],
        (true, None),
    )?;
    push_curve_ends(&mut rep, &series, study.key);
    rep.notes.push(
        "The paper: mu grows with the thickness of a rigid coating (the body gets stiffer).".into(),
    );
    Ok(rep)
}

pub fn fig8(
    solutions: &mut Solutions,
    r: Resolution,
    files: &mut FigureFiles,
) -> Result<FigureReport> {
    let study = catalogue::fig8(r);
    let mut rep = report(
        "Fig. 8",
        "friction coefficient against sliding velocity, and linear minus nonlinear",
        study_line(&study, "the paper draws the linear law black (dashed here)"),
    );
    let series = mu_curves(solutions, &study, &mut rep.notes);
    line_figure(
        files,
        "fig08a_mu_vs_velocity",
        &series,
        "Friction against velocity (Fig. 8a)",
        [study.key, "mu"],
        (true, None),
    )?;
    // (b): linear minus nonlinear where both were solved.
    let linear_curve = &series[0];
    let differences: Vec<Series> = series[1..]
        .iter()
        .map(|s| {
            let (x, y) =
                s.x.iter()
                    .zip(&s.y)
                    .filter_map(|(v, m)| {
                        let k = linear_curve.x.iter().position(|w| w == v)?;
                        Some((*v, linear_curve.y[k] - m))
                    })
                    .unzip();
            Series {
                label: s.label.clone(),
                x,
                y,
                dashed: false,
            }
        })
        .collect();
    line_figure(
        files,
        "fig08b_mu_difference",
        &differences,
        "Linear minus nonlinear mu (Fig. 8b)",
        [study.key, "mu_linear - mu"],
        (true, None),
    )?;
    push_curve_ends(&mut rep, &series, study.key);
    for d in &differences {
        if let Some((k, m)) = d.y.iter().enumerate().max_by(|a, b| a.1.total_cmp(b.1)) {
            rep.numbers.push(number(
                format!("largest mu_linear - mu, {}", d.label),
                *m,
                None,
            ));
            rep.numbers.push(number(
                format!("V' of that largest difference, {}", d.label),
                d.x[k],
                None,
            ));
        }
    }
    rep.notes.push(
        "The paper: mu decreases with V'; the nonlinear mu lies below the linear one; their \
         difference has a maximum at some V'."
            .into(),
    );
    Ok(rep)
}
