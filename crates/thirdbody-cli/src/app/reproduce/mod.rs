//! `thirdbody reproduce --out DIR`: every result figure of the paper (Lubricants 2023,
//! 11, 333, Figs. 2-12) recomputed with the paper's parameters (section 4,
//! dimensionless: R = E2 = T = 1, nu2 = 0.3), each as PNG and SVG with its data as CSV
//! beside it, and `DIR/report.md` listing each figure, its parameters, the key numbers
//! and, where the paper prints numbers (Fig. 10's tau1 values and their 35% increase,
//! the 12% and 16% pressure increases of Fig. 11's text), ours beside the paper's.
//!
//! The paper's cases are in [`catalogue`] (with the parameter lines generated from
//! them), their solutions in [`solutions`] (each case solved once per run, though
//! several figures use it), the figures in [`figures`] (Figs. 2-8) and
//! [`stress_figures`] (Figs. 9-12) with the rendering they share in [`render`]; this
//! module runs them, stages every file (all or nothing, like `thirdbody solve`) and
//! writes the report. Cases inside a figure are solved in parallel (rayon), each
//! solve on one thread.

mod catalogue;
mod figures;
mod render;
mod solutions;
mod stress_figures;

use std::fmt::Write as _;
use std::fs::File;
use std::io::{BufWriter, IsTerminal, Write};
use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{Context, Result};
use clap::Args;

use crate::app::BadInput;
use crate::atomic::Staging;
use solutions::Solutions;

/// A figure of the paper: takes its cases' solutions from the run's [`Solutions`],
/// stages its files and returns what the report says of it.
type Figure = fn(&mut Solutions, Resolution, &mut FigureFiles) -> Result<FigureReport>;

/// Every figure, in the paper's order.
const ALL: [Figure; 11] = [
    figures::fig2,
    figures::fig3,
    figures::fig4,
    figures::fig5,
    figures::fig6,
    figures::fig7,
    figures::fig8,
    stress_figures::fig9,
    stress_figures::fig10,
    stress_figures::fig11,
    stress_figures::fig12,
];

/// Arguments of `thirdbody reproduce`.
#[derive(Args)]
pub struct ReproduceArgs {
    /// Output folder.
    #[arg(long, value_name = "DIR")]
    out: PathBuf,
    /// Cells along each side of the grid (the paper's figures need about 128; a
    /// smaller value gives a quick, coarse preview).
    #[arg(long, value_name = "N", default_value_t = 128)]
    cells: usize,
    /// Points of each curve of the parameter studies (Figs. 6-8).
    #[arg(long, value_name = "N", default_value_t = 8)]
    points: usize,
    /// Print nothing but errors.
    #[arg(long)]
    quiet: bool,
}

/// Resolution of a reproduction.
#[derive(Debug, Clone, Copy)]
pub struct Resolution {
    /// Cells per side.
    pub cells: usize,
    /// Points per parameter-study curve.
    pub points: usize,
}

/// A number the report prints, with the paper's value where it gives one.
pub struct KeyNumber {
    /// What it is.
    pub name: String,
    /// Ours.
    pub ours: f64,
    /// The paper's printed value.
    pub paper: Option<f64>,
}

/// One reproduced figure: its files are staged by the figure itself.
pub struct FigureReport {
    /// "Fig. 3" etc.
    pub id: String,
    /// What it shows.
    pub title: String,
    /// The parameters, as the paper's caption gives them (and our readings).
    pub parameters: String,
    /// Files written (names in DIR).
    pub files: Vec<String>,
    /// Key numbers.
    pub numbers: Vec<KeyNumber>,
    /// Remarks (readings of the caption, failed points).
    pub notes: Vec<String>,
}

/// Stages the files of a figure and remembers their names.
pub struct FigureFiles<'a> {
    staging: &'a mut Staging,
    names: Vec<String>,
}

impl FigureFiles<'_> {
    /// Stages `name` through `write`.
    pub fn write(&mut self, name: &str, write: impl FnOnce(&Path) -> Result<()>) -> Result<()> {
        self.staging.write(name, write)?;
        self.names.push(name.to_string());
        Ok(())
    }

    /// Stages a plot as `stem.png` and `stem.svg`.
    pub fn plot(&mut self, stem: &str, draw: impl Fn(&Path) -> Result<()>) -> Result<()> {
        self.write(&format!("{stem}.png"), &draw)?;
        self.write(&format!("{stem}.svg"), &draw)
    }

    /// Stages a long-format CSV `series,x,y` of line-plot series.
    pub fn series_csv(
        &mut self,
        name: &str,
        header: [&str; 3],
        series: &[crate::plot::Series],
    ) -> Result<()> {
        self.write(name, |p| {
            let mut w = BufWriter::new(File::create(p)?);
            writeln!(w, "{}", header.join(","))?;
            for s in series {
                for (x, y) in s.x.iter().zip(&s.y) {
                    writeln!(w, "\"{}\",{x},{y}", s.label)?;
                }
            }
            w.flush()?;
            Ok(())
        })
    }

    /// Stages a CSV with the given header and rows.
    pub fn table_csv(&mut self, name: &str, header: &[&str], rows: &[Vec<f64>]) -> Result<()> {
        self.write(name, |p| {
            let mut w = BufWriter::new(File::create(p)?);
            writeln!(w, "{}", header.join(","))?;
            for row in rows {
                let cells: Vec<String> = row.iter().map(|v| v.to_string()).collect();
                writeln!(w, "{}", cells.join(","))?;
            }
            w.flush()?;
            Ok(())
        })
    }
}

/// Runs `thirdbody reproduce`.
pub fn run(args: &ReproduceArgs) -> Result<()> {
    if args.cells < 16 || args.cells > 1024 {
        return Err(BadInput(format!(
            "--cells {} is not allowed: 16 to 1024 cells per side",
            args.cells
        ))
        .into());
    }
    if args.points < 2 || args.points > 64 {
        return Err(BadInput(format!(
            "--points {} is not allowed: 2 to 64 points per curve",
            args.points
        ))
        .into());
    }
    if args.out.exists() && !args.out.is_dir() {
        return Err(BadInput(format!("--out {} is not a folder", args.out.display())).into());
    }
    let resolution = Resolution {
        cells: args.cells,
        points: args.points,
    };
    let start = Instant::now();
    let mut staging = Staging::new(&args.out)?;
    let mut solutions = Solutions::new(catalogue::every_case(resolution));
    let mut reports = Vec::new();
    let bar =
        super::progress::FigureBar::new(!args.quiet && std::io::stderr().is_terminal(), ALL.len());
    for (k, figure) in ALL.iter().enumerate() {
        bar.start(&format!("figure {} of {}", k + 1, ALL.len()));
        let t = Instant::now();
        let mut files = FigureFiles {
            staging: &mut staging,
            names: Vec::new(),
        };
        let mut report = figure(&mut solutions, resolution, &mut files)?;
        report.files = files.names;
        if !args.quiet {
            bar.done(&format!(
                "{}: {} ({:.1} s)",
                report.id,
                report.title,
                t.elapsed().as_secs_f64()
            ));
        }
        reports.push(report);
    }
    bar.finish();
    let seconds = start.elapsed().as_secs_f64();
    let text = report_markdown(&reports, resolution, seconds);
    staging.write("report.md", |p| Ok(std::fs::write(p, &text)?))?;
    staging
        .commit()
        .context("cannot move the reproduced figures into place")?;
    if !args.quiet {
        crate::say!(
            "reproduced {} figures in {seconds:.0} s; see {}",
            reports.len(),
            args.out.join("report.md").display()
        );
    }
    Ok(())
}

/// A number in the report: 4 significant digits.
fn fmt(v: f64) -> String {
    if v == 0.0 || !v.is_finite() {
        return format!("{v}");
    }
    let magnitude = v.abs().log10().floor() as i32;
    if (-4..5).contains(&magnitude) {
        let decimals = (3 - magnitude).max(0) as usize;
        format!("{v:.decimals$}")
    } else {
        format!("{v:.3e}")
    }
}

fn report_markdown(reports: &[FigureReport], r: Resolution, seconds: f64) -> String {
    let mut t = String::new();
    let _ = writeln!(t, "# The paper's figures, reproduced by thirdbody\n");
    let _ = writeln!(
        t,
        "Paper: *Effect of Non-Linear Properties of Intermediate Layer on Sliding Contact \
         of Homogeneous and Coated Elastic Solids*, Lubricants 2023, 11, 333. All \
         quantities are the paper's dimensionless ones (section 4): lengths / R, stresses / \
         E2, V' = V T / R, C' = C0 E2 / R, sphere R = 1, E2 = 1, nu2 = 0.3, T = 1, exact \
         integration of the layer law (docs/architecture.md, conventions). Grid: {} x {} cells, automatic \
         window; {} points per parameter-study curve. Computed in {seconds:.0} s.\n",
        r.cells, r.cells, r.points
    );
    let _ = writeln!(
        t,
        "Conventions: the slider moves in +x; stresses are positive in tension; tau1 = \
         (s1 - s3)/2 >= 0 (the paper prints it with a minus sign); mu = M / (R Q) > 0 when \
         the pressure shifts to the leading edge.\n"
    );
    for f in reports {
        let _ = writeln!(t, "## {}: {}\n", f.id, f.title);
        let _ = writeln!(t, "Parameters: {}\n", f.parameters);
        let _ = writeln!(
            t,
            "Files: {}\n",
            f.files
                .iter()
                .map(|n| format!("`{n}`"))
                .collect::<Vec<_>>()
                .join(", ")
        );
        if !f.numbers.is_empty() {
            let _ = writeln!(t, "| quantity | thirdbody | paper | difference |");
            let _ = writeln!(t, "|---|---|---|---|");
            for n in &f.numbers {
                let (paper, diff) = match n.paper {
                    // A percentage against a percentage: the difference in points.
                    Some(p) if n.name.ends_with("(%)") => {
                        (fmt(p), format!("{:+.1} points", n.ours - p))
                    }
                    Some(p) => (fmt(p), format!("{:+.1}%", 100.0 * (n.ours - p) / p.abs())),
                    None => ("—".into(), "—".into()),
                };
                let _ = writeln!(t, "| {} | {} | {paper} | {diff} |", n.name, fmt(n.ours));
            }
            let _ = writeln!(t);
        }
        for note in &f.notes {
            let _ = writeln!(t, "- {note}");
        }
        if !f.notes.is_empty() {
            let _ = writeln!(t);
        }
    }
    t
}
