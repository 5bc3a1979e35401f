//! Provenance in every result: `summary.json` and every row
//! of `results.csv` carry the thirdbody version, the git commit the program was built
//! from and a hash of the canonical case; `thirdbody cite` prints the references,
//! those of one case with its case file; `--version` names the commit.

use crate::common;

use std::collections::BTreeSet;
use std::process::Command;

fn thirdbody(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_thirdbody"))
        .args(args)
        .output()
        .unwrap()
}

/// `git rev-parse HEAD` of the checkout the tests run in, when there is one.
fn head_commit() -> Option<String> {
    let out = Command::new("git")
        .arg("-C")
        .arg(env!("CARGO_MANIFEST_DIR"))
        .args(["rev-parse", "HEAD"])
        .output()
        .ok()?;
    out.status
        .success()
        .then(|| String::from_utf8(out.stdout).unwrap().trim().to_owned())
}

use common::SPHERE as CASE;

fn summary_of(case: &str) -> serde_json::Value {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("case.toml");
    std::fs::write(&path, case).unwrap();
    let out = dir.path().join("out");
    let run = thirdbody(&[
        "solve",
        path.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--quiet",
        "--format",
        "npy",
    ]);
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap()
}

#[test]
fn the_summary_names_version_commit_and_case() {
    let s = summary_of(CASE);
    assert_eq!(s["thirdbody_version"], env!("CARGO_PKG_VERSION"));
    match head_commit() {
        // The build script read the same checkout: the same commit.
        Some(head) => assert_eq!(s["commit"], head.as_str()),
        None => assert!(s["commit"].is_null()),
    }
    let hash = s["case_hash"].as_str().unwrap();
    assert_eq!(hash.len(), 64);
    // The same case written differently has the same hash; another load another.
    let relaid = format!(
        "# the same case\n{}",
        CASE.replace("radius = 1.0", "radius = 1")
    );
    assert_eq!(summary_of(&relaid)["case_hash"], hash);
    let other = CASE.replace("5e-6", "6e-6");
    assert_ne!(summary_of(&other)["case_hash"], hash);
}

#[test]
fn every_results_row_carries_the_provenance() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("case.toml");
    std::fs::write(&path, CASE).unwrap();
    let out = dir.path().join("sweep");
    let run = thirdbody(&[
        "sweep",
        path.to_str().unwrap(),
        "--vary",
        "loading.normal_load=4e-6,5e-6,6e-6",
        "--out",
        out.to_str().unwrap(),
        "--quiet",
    ]);
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let mut reader = csv::Reader::from_path(out.join("results.csv")).unwrap();
    let header: Vec<String> = reader.headers().unwrap().iter().map(String::from).collect();
    let column = |name: &str| header.iter().position(|h| h == name).unwrap();
    let (v, c, h) = (
        column("thirdbody_version"),
        column("commit"),
        column("case_hash"),
    );
    let mut hashes = BTreeSet::new();
    let rows: Vec<csv::StringRecord> = reader.records().map(|r| r.unwrap()).collect();
    assert_eq!(rows.len(), 3);
    for row in &rows {
        assert_eq!(&row[v], env!("CARGO_PKG_VERSION"));
        if let Some(head) = head_commit() {
            assert_eq!(&row[c], head);
        }
        assert_eq!(row[h].len(), 64);
        hashes.insert(row[h].to_owned());
    }
    // Three loads, three cases; and the middle one is the single solve's case.
    assert_eq!(hashes.len(), 3);
    assert!(hashes.contains(summary_of(CASE)["case_hash"].as_str().unwrap()));
}

#[test]
fn cite_prints_the_references_as_bibtex() {
    let run = thirdbody(&["cite"]);
    assert!(run.status.success());
    let text = String::from_utf8(run.stdout).unwrap();
    assert_eq!(
        text.matches("@article{").count() + text.matches("@book{").count(),
        14
    );
    assert!(text.contains("doi     = {10.3390/lubricants11080333}"));
    for author in [
        "Torskaya",
        "Love",
        "Polonsky",
        "Liu, Shuangbiao",
        "Chen",
        "O'Sullivan",
        "Perriot",
    ] {
        assert!(text.contains(author), "{author} missing");
    }
}

/// `thirdbody cite CASE` with `extra` args, the case written into a fresh folder.
fn cite_case(case: &str, extra: &[&str]) -> String {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("case.toml");
    std::fs::write(&path, case).unwrap();
    let mut args = vec!["cite", path.to_str().unwrap()];
    args.extend_from_slice(extra);
    let run = thirdbody(&args);
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    String::from_utf8(run.stdout).unwrap()
}

#[test]
fn cite_with_a_case_lists_the_works_it_uses() {
    let maxwell = CASE.replace(
        "normal_load = 5e-6\n",
        "normal_load = 5e-6\nvelocity = 0.1\n\n[layer]\ncompliance = 0.02\nrelaxation_time = 1.0\n",
    );
    let text = cite_case(&maxwell, &[]);
    assert!(text.contains("Lubricants 11 (2023) 333"), "{text}");
    assert!(text.contains("Maxwell layer"), "{text}");
    assert!(text.contains("Hintermüller"), "{text}");
    assert!(!text.contains("Polonsky"), "{text}");
    assert!(!text.contains("Perriot"), "{text}");
    // Without creep the same body is solved by conjugate gradients.
    let text = cite_case(CASE, &[]);
    assert!(
        text.contains("Polonsky") && !text.contains("Hintermüller"),
        "{text}"
    );
    let coated = format!("{CASE}\n[coating]\nyoung = 2.0\npoisson = 0.3\nthickness = 0.05\n");
    let bibtex = cite_case(&coated, &["--bibtex"]);
    for key in [
        "perriot2004elastic",
        "osullivan1988sliding",
        "polonsky1999numerical",
    ] {
        assert!(
            bibtex.contains(&format!("{{{key},")),
            "{key} missing: {bibtex}"
        );
    }
    assert!(!bibtex.contains("hintermuller"), "{bibtex}");
}

#[test]
fn version_names_the_commit() {
    let run = thirdbody(&["--version"]);
    assert!(run.status.success());
    let text = String::from_utf8(run.stdout).unwrap();
    let commit = head_commit().unwrap_or_else(|| "unknown".to_owned());
    assert_eq!(
        text.trim(),
        format!("thirdbody {} (commit {commit})", env!("CARGO_PKG_VERSION"))
    );
}
