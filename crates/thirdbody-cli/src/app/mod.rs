//! The `thirdbody` command line: argument parsing, the subcommands, exit codes. The
//! binary (`src/main.rs`) and the Python package's `thirdbody` script both call
//! [`main`], so `pip install` and `cargo install` give the same program.
//!
//! `thirdbody solve CASE.toml --out DIR` reads a case file (docs/case-file.md),
//! solves it, computes the stresses its `[stress]` section asks for, writes the
//! outputs into DIR (docs/outputs.md) and prints a short summary.
//! `thirdbody stress DIR` computes stresses for a case already solved into DIR.
//! `thirdbody reproduce --out DIR` recomputes the paper's figures.
//! Exit codes: 0 success; 2 bad input (the case or a height map), with
//! one line `error: <message>` on stderr that names the field and what is
//! allowed; 1 solver failure or I/O error.
//!
//! `thirdbody sweep` and `thirdbody merge` run parameter sweeps (docs/sweeps.md);
//! they live in [`crate::sweep`], with the same exit codes.

mod outputs;
mod progress;
mod report;
mod reproduce;
mod section;
mod stress_command;
mod stress_outputs;

use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

use crate::heightmap;
use crate::sweep::command::{self as sweep, MergeArgs, SweepArgs};
use anyhow::{Context, Result};
use clap::{Args, CommandFactory, FromArgMatches, Parser, Subcommand};
use thirdbody::case_file::{parse_case_file, CaseFile};
use thirdbody::Parallelism;

#[derive(Parser)]
#[command(
    name = "thirdbody",
    about = "Sliding contact through a nonlinear viscoelastic third-body layer"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Solve one case file and write its outputs.
    Solve(SolveArgs),
    /// Compute subsurface stresses for a case already solved into a folder.
    Stress(stress_command::StressArgs),
    /// Recompute every result figure of the paper (Figs. 2-12) with a report.
    Reproduce(reproduce::ReproduceArgs),
    /// Solve a case over the Cartesian product of varied keys (docs/sweeps.md).
    Sweep(SweepArgs),
    /// Join the folders of a sharded sweep (docs/sweeps.md).
    Merge(MergeArgs),
    /// Print the works a case's computation relies on and what each is used for
    /// (without a case: every work thirdbody may rely on, as BibTeX).
    Cite(CiteArgs),
}

#[derive(Args)]
struct CiteArgs {
    /// The case file (TOML, see docs/case-file.md).
    case: Option<PathBuf>,
    /// Print the case's works as BibTeX entries.
    #[arg(long)]
    bibtex: bool,
}

#[derive(Args)]
struct SolveArgs {
    /// The case file (TOML, see docs/case-file.md).
    case: PathBuf,
    /// Output folder; created after a successful solve.
    #[arg(long, value_name = "DIR")]
    out: PathBuf,
    /// Print nothing but errors.
    #[arg(long)]
    quiet: bool,
    /// Threads for the solve's FFTs (default: all cores).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u16).range(1..))]
    threads: Option<u16>,
    /// Data formats to write: a comma-separated list of npy, csv, vtk (default all;
    /// summary.json and the plots are always written).
    #[arg(long, value_name = "LIST", value_parser = outputs::parse_formats)]
    format: Option<outputs::Formats>,
}

/// A bad input found by the command line itself (unreadable case file, bad
/// arguments); exits with code 2 like the library's input errors.
#[derive(Debug)]
pub(crate) struct BadInput(pub(crate) String);

impl std::fmt::Display for BadInput {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for BadInput {}

/// Runs the command line `args` (the program name first, as `std::env::args_os`
/// gives it) and returns the exit code. `--help`, `--version` and argument errors
/// print and exit the process, as clap does.
pub fn main(args: impl IntoIterator<Item = std::ffi::OsString>) -> ExitCode {
    ExitCode::from(run_command_line(args))
}

/// As [`main`], returning the exit code as a number (for the Python script).
pub fn run_command_line(args: impl IntoIterator<Item = std::ffi::OsString>) -> u8 {
    let command = Cli::command().version(version());
    let cli = Cli::from_arg_matches(&command.get_matches_from(args)).unwrap_or_else(|e| e.exit());
    match run(cli) {
        Ok(()) => 0,
        Err(e) => {
            let message = format!("{e:#}").replace('\n', " ");
            eprintln!("error: {message}");
            exit_code(&e)
        }
    }
}

/// What `--version` prints after the program's name: the version and the git commit
/// the library was built from (the `commit` of `summary.json`), "unknown" when it was
/// not built from a git checkout.
fn version() -> &'static str {
    static VERSION: std::sync::OnceLock<String> = std::sync::OnceLock::new();
    VERSION.get_or_init(|| {
        let commit = thirdbody::provenance::commit().unwrap_or("unknown");
        format!("{} (commit {commit})", thirdbody::provenance::VERSION)
    })
}

/// 2 for bad input, 1 for everything else.
fn exit_code(e: &anyhow::Error) -> u8 {
    if sweep::is_bad_input(e) {
        return 2;
    }
    for cause in e.chain() {
        if cause.is::<BadInput>() {
            return 2;
        }
        if let Some(t) = cause.downcast_ref::<thirdbody::Error>() {
            return if t.is_input() { 2 } else { 1 };
        }
    }
    1
}

fn run(cli: Cli) -> Result<()> {
    match cli.command {
        Command::Solve(args) => solve(&args),
        Command::Stress(args) => stress_command::run(&args),
        Command::Reproduce(args) => reproduce::run(&args),
        Command::Sweep(args) => sweep::sweep_command(&args),
        Command::Merge(args) => sweep::merge_command(&args),
        Command::Cite(args) => cite(&args),
    }
}

/// `thirdbody cite`: the works of a case (one per line, or as BibTeX), or every work
/// as BibTeX without a case.
fn cite(args: &CiteArgs) -> Result<()> {
    let Some(path) = &args.case else {
        print!("{}", thirdbody::provenance::REFERENCES);
        return Ok(());
    };
    let (file, _) = read_case(path)?;
    let references = file.references();
    if args.bibtex {
        let entries: Vec<&str> = references.iter().map(|r| r.work.bibtex()).collect();
        print!("{}", entries.join("\n"));
    } else {
        for r in &references {
            println!("{}\n    for {}", r.work.citation, r.used_for);
        }
    }
    Ok(())
}

/// Largest case file read: a case is a few hundred bytes; a table law of a few
/// thousand rows is far below this. Larger input (a 50 MB file, `/dev/zero`) is
/// refused before it is read whole.
const MAX_CASE_FILE_BYTES: u64 = 4 << 20;

/// The text of a case file of at most [`MAX_CASE_FILE_BYTES`].
pub(crate) fn read_case_text(path: &Path) -> Result<String> {
    use std::io::Read;
    let cannot =
        |e: std::io::Error| BadInput(format!("cannot read the case file {}: {e}", path.display()));
    let mut bytes = Vec::new();
    std::fs::File::open(path)
        .map_err(cannot)?
        .take(MAX_CASE_FILE_BYTES + 1)
        .read_to_end(&mut bytes)
        .map_err(cannot)?;
    if bytes.len() as u64 > MAX_CASE_FILE_BYTES {
        return Err(BadInput(format!(
            "the case file {} is larger than {} MiB: a case file is a short TOML text",
            path.display(),
            MAX_CASE_FILE_BYTES >> 20
        ))
        .into());
    }
    String::from_utf8(bytes).map_err(|_| {
        BadInput(format!(
            "the case file {} is not UTF-8 text",
            path.display()
        ))
        .into()
    })
}

/// Reads and validates a case file; height maps are read relative to its folder.
/// Returns the parsed case and its text.
fn read_case(path: &Path) -> Result<(CaseFile, String)> {
    let text = read_case_text(path)?;
    let base = path.parent().unwrap_or(Path::new("."));
    let file = parse_case_file(&text, &mut |file, cell_size| {
        heightmap::load(base, file, cell_size)
    })?;
    Ok((file, text))
}

/// The height-map file of a case (`slider.file`, as written, and where it is read
/// from) when it is a bare file name: `solve` copies it beside `case.toml`, so that
/// `thirdbody stress` can rebuild the case from the output folder alone.
fn height_map_file(case_text: &str, case_path: &Path) -> Option<(String, PathBuf)> {
    let table: toml::Table = case_text.parse().ok()?;
    let name = table.get("slider")?.get("file")?.as_str()?;
    let bare = Path::new(name).file_name()? == std::ffi::OsStr::new(name);
    let reserved = outputs::is_output_name(name);
    (bare && !reserved).then(|| {
        let base = case_path.parent().unwrap_or(Path::new("."));
        (name.to_string(), base.join(name))
    })
}

fn solve(args: &SolveArgs) -> Result<()> {
    let (
        CaseFile {
            case,
            mut solver,
            stress,
        },
        case_text,
    ) = read_case(&args.case)?;
    thirdbody_engine::geometry::check(&case, stress.as_ref()).map_err(BadInput)?;
    crate::memory::check(&case, stress.as_ref(), 1, crate::memory::available_bytes())
        .map_err(BadInput)?;
    if args.out.canonicalize().is_ok_and(|p| p.parent().is_none()) {
        return Err(BadInput(format!(
            "--out {} is a file system's root: give a folder for this case's outputs",
            args.out.display()
        ))
        .into());
    }
    if args.out.exists() && !args.out.is_dir() {
        return Err(BadInput(format!(
            "--out {} exists and is not a folder",
            args.out.display()
        ))
        .into());
    }
    match args.threads {
        Some(1) => solver.parallelism = Parallelism::Sequential,
        Some(n) => rayon::ThreadPoolBuilder::new()
            .num_threads(n.into())
            .build_global()
            .context("cannot start the thread pool")?,
        None => {}
    }

    let mut spinner = progress::Spinner::new(!args.quiet && std::io::stderr().is_terminal());
    let start = Instant::now();
    let mut kernels = thirdbody::KernelCache::new();
    let result = thirdbody::solve_with(&case, &solver, &mut kernels, &mut |p| {
        spinner.observe(p);
        std::ops::ControlFlow::Continue(())
    });
    let solve_seconds = start.elapsed().as_secs_f64();
    spinner.finish();
    let solution = result?;

    let stress = stress
        .map(|request| {
            let bar = progress::StressBar::new(!args.quiet && std::io::stderr().is_terminal());
            let results = solution.stress_results_observed(&request, &|e| bar.observe(e));
            bar.finish();
            results
        })
        .transpose()?;
    let summary = crate::summary::summary_json(&case, &solution, solve_seconds, stress.as_ref())?;
    for warning in thirdbody::report::model_warnings(&case, &solution) {
        eprintln!("warning: {warning}");
    }
    let height_map = height_map_file(&case_text, &args.case);
    outputs::write_all(
        &args.out,
        &outputs::SolveOutputs {
            case_text: &case_text,
            height_map: height_map.as_ref().map(|(n, p)| (n.as_str(), p.as_path())),
            case: &case,
            solution: &solution,
            summary: &summary,
            stress: stress.as_ref(),
            formats: args.format.unwrap_or_default(),
        },
    )?;
    if !args.quiet {
        crate::say!(
            "{}: {}",
            args.case.display(),
            report::human_summary(&case, &solution, solve_seconds)
        );
        if let Some(results) = &stress {
            crate::say!("{}", report::stress_summary(&results.summary));
        }
        crate::say!("outputs in {}", args.out.display());
    }
    Ok(())
}
