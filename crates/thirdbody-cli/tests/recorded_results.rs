//! Refactoring guard (issue 10): every bundled example and every case of `thirdbody
//! reproduce` gives the numbers recorded from the code before the change, to 1e-12
//! relative. The records are in `tests/data/`: `recorded_summaries.json` holds each
//! example's `summary.json` (timing keys left out); `recorded_reproduce.json` holds a
//! fingerprint of every CSV that `reproduce --cells 32 --points 3` writes (per column:
//! sum, sum of |v|, a position-weighted sum, min and max), which changes when any
//! value changes by more than rounding. The records were written by an older build
//! (see `docs/validation.md` for which commit and which keys changed on purpose since);
//! `THIRDBODY_RECORD=1` rewrites them and is only for a deliberate change of results.

mod common;

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use serde_json::{Map, Value};

/// Relative tolerance of a recorded number.
const TOLERANCE: f64 = 1e-12;
/// Keys that measure time, not results.
const TIMING_KEYS: [&str; 1] = ["solve_seconds"];

fn data_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data")
}

fn recording() -> bool {
    std::env::var_os("THIRDBODY_RECORD").is_some()
}

/// Drops timing keys (recursively) so that only results are compared.
fn results_only(v: &Value) -> Value {
    match v {
        Value::Object(m) => Value::Object(
            m.iter()
                .filter(|(k, _)| !TIMING_KEYS.contains(&k.as_str()))
                .map(|(k, v)| (k.clone(), results_only(v)))
                .collect(),
        ),
        Value::Array(a) => Value::Array(a.iter().map(results_only).collect()),
        other => other.clone(),
    }
}

/// Every difference between `recorded` and `now` beyond the tolerance, as lines.
fn differences(path: &str, recorded: &Value, now: &Value, out: &mut Vec<String>) {
    match (recorded, now) {
        (Value::Object(a), Value::Object(b)) => {
            for (k, va) in a {
                match b.get(k) {
                    Some(vb) => differences(&format!("{path}.{k}"), va, vb, out),
                    None => out.push(format!("{path}.{k}: missing now")),
                }
            }
            // Keys added since the recording are new results, not changed ones.
            for k in b.keys().filter(|k| !a.contains_key(*k)) {
                eprintln!("{path}.{k}: new key (not recorded)");
            }
        }
        (Value::Array(a), Value::Array(b)) if a.len() == b.len() => {
            for (i, (va, vb)) in a.iter().zip(b).enumerate() {
                differences(&format!("{path}[{i}]"), va, vb, out);
            }
        }
        (Value::Number(a), Value::Number(b)) => {
            let (a, b) = (a.as_f64().unwrap(), b.as_f64().unwrap());
            if (a - b).abs() > TOLERANCE * a.abs().max(b.abs()) {
                out.push(format!(
                    "{path}: recorded {a:e}, now {b:e} (relative {:.1e})",
                    (a - b).abs() / a.abs().max(b.abs())
                ));
            }
        }
        (a, b) if a == b => {}
        (a, b) => out.push(format!("{path}: recorded {a}, now {b}")),
    }
}

fn compare_or_record(file: &str, now: Value) {
    let path = data_dir().join(file);
    if recording() {
        std::fs::create_dir_all(data_dir()).unwrap();
        std::fs::write(&path, serde_json::to_string_pretty(&now).unwrap() + "\n").unwrap();
        return;
    }
    let recorded: Value = serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
    let mut diffs = Vec::new();
    differences("", &recorded, &now, &mut diffs);
    assert!(
        diffs.is_empty(),
        "{} differences from {file}:\n{}",
        diffs.len(),
        diffs.join("\n")
    );
}

#[test]
fn every_bundled_example_gives_the_recorded_summary() {
    let examples = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples");
    let mut paths: Vec<PathBuf> = std::fs::read_dir(&examples)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().and_then(|e| e.to_str()) == Some("toml"))
        .collect();
    paths.sort();
    let root = tempfile::tempdir().unwrap();
    let mut all = Map::new();
    for path in paths {
        let name = path.file_stem().unwrap().to_string_lossy().into_owned();
        let out = root.path().join(&name);
        let run = common::thirdbody(&[
            "solve".as_ref(),
            path.as_os_str(),
            "--out".as_ref(),
            out.as_os_str(),
            "--quiet".as_ref(),
            "--format".as_ref(),
            "npy".as_ref(),
        ]);
        assert_eq!(
            run.status.code(),
            Some(0),
            "{name}: {}",
            String::from_utf8_lossy(&run.stderr)
        );
        let summary: Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap())
                .unwrap();
        all.insert(name, results_only(&summary));
    }
    compare_or_record("recorded_summaries.json", Value::Object(all));
}

/// Per numeric column of a CSV: sum, sum of |v|, position-weighted sum, min, max.
fn fingerprint(path: &Path) -> Value {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let mut columns: BTreeMap<usize, Vec<f64>> = BTreeMap::new();
    for line in lines {
        // Series labels are quoted and may hold commas: number the cells after them.
        let numeric = match line.rfind('"') {
            Some(end) => &line[end + 1..],
            None => line,
        };
        let cells: Vec<&str> = numeric.split(',').filter(|c| !c.is_empty()).collect();
        let offset = header.len() - cells.len();
        for (i, c) in cells.iter().enumerate() {
            let v: f64 = c
                .parse()
                .unwrap_or_else(|_| panic!("{}: {c:?}", path.display()));
            columns.entry(offset + i).or_default().push(v);
        }
    }
    let mut out = Map::new();
    for (i, values) in columns {
        let n = values.len() as f64;
        let sum: f64 = values.iter().sum();
        let abs: f64 = values.iter().map(|v| v.abs()).sum();
        let weighted: f64 = values
            .iter()
            .enumerate()
            .map(|(k, v)| v * (k as f64 + 1.0) / n)
            .sum();
        let min = values.iter().copied().fold(f64::INFINITY, f64::min);
        let max = values.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        out.insert(
            format!("{i}:{}", header[i]),
            serde_json::json!({
                "count": values.len(), "sum": sum, "abs_sum": abs,
                "weighted_sum": weighted, "min": min, "max": max,
            }),
        );
    }
    Value::Object(out)
}

#[test]
fn every_reproduce_case_gives_the_recorded_data() {
    let root = tempfile::tempdir().unwrap();
    let dir = root.path().join("paper");
    let run = common::thirdbody(&[
        "reproduce".as_ref(),
        "--out".as_ref(),
        dir.as_os_str(),
        "--cells".as_ref(),
        "32".as_ref(),
        "--points".as_ref(),
        "3".as_ref(),
        "--quiet".as_ref(),
    ]);
    assert_eq!(
        run.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let mut csvs: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().and_then(|e| e.to_str()) == Some("csv"))
        .collect();
    csvs.sort();
    assert!(csvs.len() >= 11, "{} CSV files", csvs.len());
    let mut all = Map::new();
    for path in csvs {
        all.insert(
            path.file_name().unwrap().to_string_lossy().into_owned(),
            fingerprint(&path),
        );
    }
    compare_or_record("recorded_reproduce.json", Value::Object(all));
}
