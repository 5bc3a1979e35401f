//! `results.csv`: one row per finished case in product order, assembled from the case
//! records and written atomically at the end of every run and by `merge`.
//!
//! Columns: `case` (the id), one column per axis (the key's value, or the variant's
//! name), every key of the summary that `thirdbody solve` writes to `summary.json`
//! (alphabetical, as there) except the wall time `solve_seconds`, then `status`
//! (`ok` or `failed`) and `error` (the message of a failed case; its summary cells are
//! empty). Leaving the wall time out makes the file a pure function of the results:
//! a sharded and merged sweep gives the same bytes as an unsharded one. Wall times
//! stay in the records (`cases/<id>.json`). Numbers are in their shortest round-trip
//! form.

use std::path::{Path, PathBuf};

use anyhow::Result;
use serde_json::Value;

use super::folder::{read_record, Record, Status, SweepFile};
use crate::atomic::write_bytes;

/// The results file's name.
pub const RESULTS_FILE: &str = "results.csv";

/// Summary keys left out of `results.csv` because they are wall times.
pub const TIMING_KEYS: [&str; 1] = ["solve_seconds"];

/// The records present in a folder, in product order.
#[derive(Debug, Clone)]
pub struct Collected {
    /// Finished cases.
    pub records: Vec<Record>,
    /// Cases without a record.
    pub missing: usize,
}

impl Collected {
    /// Finished cases that failed.
    pub fn failed(&self) -> usize {
        self.records
            .iter()
            .filter(|r| r.status == Status::Failed)
            .count()
    }
}

/// Reads every case's record from `dir`.
pub fn collect(dir: &Path, file: &SweepFile) -> Collected {
    let mut records = Vec::new();
    let mut missing = 0;
    for entry in &file.cases {
        match read_record(dir, &entry.case) {
            Some(r) => records.push(r),
            None => missing += 1,
        }
    }
    Collected { records, missing }
}

/// Writes `dir/results.csv` from `records` (in product order).
pub fn write_results(dir: &Path, file: &SweepFile, records: &[Record]) -> Result<PathBuf> {
    let path = dir.join(RESULTS_FILE);
    write_bytes(&path, &results_csv(file, records)?)?;
    Ok(path)
}

/// The text of `results.csv`.
pub fn results_csv(file: &SweepFile, records: &[Record]) -> Result<Vec<u8>> {
    let mut keys: Vec<&str> = Vec::new();
    for r in records {
        if let Some(Value::Object(m)) = &r.summary {
            for k in m.keys() {
                if !keys.contains(&k.as_str()) && !TIMING_KEYS.contains(&k.as_str()) {
                    keys.push(k);
                }
            }
        }
    }
    let mut w = csv::Writer::from_writer(Vec::new());
    let mut header = vec!["case"];
    header.extend(file.axes.iter().map(|a| a.name.as_str()));
    header.extend(keys.iter().copied());
    header.extend(["status", "error"]);
    w.write_record(&header)?;
    for r in records {
        let mut row = vec![r.case.clone()];
        match file.cases.get(r.index) {
            Some(entry) if entry.case == r.case => row.extend(file.labels(r.index)),
            _ => row.extend(r.settings.iter().cloned()),
        }
        for k in &keys {
            let cell = match &r.summary {
                Some(Value::Object(m)) => m.get(*k).map(cell).unwrap_or_default(),
                _ => String::new(),
            };
            row.push(cell);
        }
        row.push(r.status.as_str().to_string());
        row.push(r.error.clone().unwrap_or_default().replace('\n', " "));
        w.write_record(&row)?;
    }
    Ok(w.into_inner()?)
}

fn cell(v: &Value) -> String {
    match v {
        Value::Null => String::new(),
        Value::String(s) => s.clone(),
        other => other.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sweep::folder::{AxisEntry, CaseEntry, LevelEntry};
    use serde_json::json;

    #[test]
    fn rows_hold_inputs_summary_and_status_without_wall_times() {
        let level = |label: &str, v: f64| LevelEntry {
            label: label.into(),
            set: vec![("loading.velocity".into(), json!(v))],
        };
        let file = SweepFile {
            format: "f".into(),
            base_case: String::new(),
            axes: vec![AxisEntry {
                name: "loading.velocity".into(),
                log_spaced: true,
                levels: vec![level("0.001", 1e-3), level("0.01", 1e-2)],
            }],
            cases: vec![
                CaseEntry {
                    case: "0000-aa".into(),
                    levels: vec![0],
                },
                CaseEntry {
                    case: "0001-bb".into(),
                    levels: vec![1],
                },
            ],
            plot_scale: Default::default(),
        };
        let records = [
            Record {
                case: "0000-aa".into(),
                index: 0,
                settings: vec!["0.001".into()],
                status: Status::Ok,
                error: None,
                summary: Some(
                    json!({"friction_coefficient": 0.05, "method": "semismooth_newton",
                    "nx": 128, "solve_seconds": 0.3}),
                ),
                solve_seconds: 0.3,
            },
            Record {
                case: "0001-bb".into(),
                index: 1,
                settings: vec!["0.01".into()],
                status: Status::Failed,
                error: Some("no solution, p0 = 1, see README".into()),
                summary: None,
                solve_seconds: 0.1,
            },
        ];
        let text = String::from_utf8(results_csv(&file, &records).unwrap()).unwrap();
        assert_eq!(
            text,
            "case,loading.velocity,friction_coefficient,method,nx,status,error\n\
             0000-aa,0.001,0.05,semismooth_newton,128,ok,\n\
             0001-bb,0.01,,,,failed,\"no solution, p0 = 1, see README\"\n"
        );
    }
}
