//! Results recorded from an earlier build, and their comparison (see
//! `tests/recorded_results.rs` for what is recorded and why).

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use serde_json::{Map, Value};

/// Relative tolerance of a recorded number.
const TOLERANCE: f64 = 1e-12;
/// Keys that measure time or name the build, not results.
const TIMING_KEYS: [&str; 2] = ["solve_seconds", "commit"];

pub fn data_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data")
}

pub fn recording() -> bool {
    std::env::var_os("THIRDBODY_RECORD").is_some()
}

/// Drops timing keys (recursively) so that only results are compared.
pub fn results_only(v: &Value) -> Value {
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
pub fn differences(path: &str, recorded: &Value, now: &Value, out: &mut Vec<String>) {
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

pub fn compare_or_record(file: &str, now: Value) {
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

/// Per numeric column of a CSV: sum, sum of |v|, position-weighted sum, min, max.
pub fn fingerprint(path: &Path) -> Value {
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

/// Compares every CSV that `reproduce --cells 32 --points 3` wrote into `dir` with the
/// recording.
pub fn check_reproduce_data(dir: &Path) {
    let mut csvs: Vec<PathBuf> = std::fs::read_dir(dir)
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
