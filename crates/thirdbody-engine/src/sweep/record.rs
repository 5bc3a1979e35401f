//! The record of one solved sweep case: what `thirdbody sweep` writes to
//! `DIR/cases/` and a Python executor's worker returns, the same for both.

use std::panic::{catch_unwind, AssertUnwindSafe};
use std::time::Instant;

use anyhow::Result;
use serde_json::Value;
use thirdbody::{KernelCache, Parallelism};

use super::folder::{Record, Status};
use crate::summary::summary_json;

/// The record of one sweep case: `parse` gives its case file (so that a worker
/// elsewhere, e.g. a Python executor's, can rebuild it from its text), solved with
/// sequential FFTs as one of many; every failure, a panic included, becomes a
/// `failed` record with the message.
pub fn solve_record(
    case: String,
    index: usize,
    settings: Vec<String>,
    parse: impl FnOnce() -> thirdbody::Result<thirdbody::case_file::CaseFile>,
    kernels: &mut KernelCache,
) -> Record {
    let start = Instant::now();
    let outcome = catch_unwind(AssertUnwindSafe(|| -> Result<serde_json::Value> {
        let file = parse()?;
        let mut params = file.solver;
        params.parallelism = Parallelism::Sequential;
        let solve_start = Instant::now();
        let solution = thirdbody::solve_with(&file.case, &params, kernels, &mut |_| {
            std::ops::ControlFlow::Continue(())
        })?;
        let mut summary = summary_json(
            &file.case,
            &solution,
            solve_start.elapsed().as_secs_f64(),
            None,
        )?;
        // A [stress] section in the base case: its scalar results become columns
        // `stress_<key>` (the sections themselves are not kept per case).
        if let Some(request) = &file.stress {
            let stress = solution.stress_results(request)?;
            if let (Value::Object(map), Value::Object(scalars)) =
                (&mut summary, serde_json::to_value(&stress.summary)?)
            {
                for (key, value) in scalars {
                    map.insert(format!("stress_{key}"), value);
                }
            }
        }
        Ok(summary)
    }));
    let (status, summary, error) = match outcome {
        Ok(Ok(summary)) => (Status::Ok, Some(summary), None),
        Ok(Err(e)) => (Status::Failed, None, Some(format!("{e:#}"))),
        Err(panic) => {
            let what = panic
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| panic.downcast_ref::<String>().cloned())
                .unwrap_or_default();
            (
                Status::Failed,
                None,
                Some(format!(
                    "the solver panicked (a bug, please report it): {what}"
                )),
            )
        }
    };
    Record {
        case,
        index,
        settings,
        status,
        error,
        summary,
        solve_seconds: start.elapsed().as_secs_f64(),
    }
}
