//! Refactoring guard: every bundled example and every case of `thirdbody
//! reproduce` gives the numbers recorded from the code before the change, to 1e-12
//! relative. The records are in `tests/data/`: `recorded_summaries.json` holds each
//! example's `summary.json` (timing keys left out); `recorded_reproduce.json` holds a
//! fingerprint of every CSV that `reproduce --cells 32 --points 3` writes (per column:
//! sum, sum of |v|, a position-weighted sum, min and max), which changes when any
//! value changes by more than rounding. The records were written by an older build
//! (see `docs/validation.md` for which commit and which keys changed on purpose since);
//! `THIRDBODY_RECORD=1` rewrites them and is only for a deliberate change of results.

mod common;

use std::path::{Path, PathBuf};

use common::recorded::{compare_or_record, results_only};
use serde_json::{Map, Value};

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

// The reproduce data are compared in `tests/integration/reproduce.rs`, which runs
// `reproduce` once for its own checks and this one.
