//! Helpers shared by the binary's integration tests: run `thirdbody` on a case
//! written into a fresh folder, and read what it wrote.
#![allow(dead_code)]

pub mod recorded;

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The base case of the tests: a layer-free sphere pressed on a homogeneous
/// half-space on a small grid (Hertz: R = 1, E = 1, nu = 0.3, Q = 5e-6, 32 x 32).
pub const SPHERE: &str = r#"
[slider]
shape = "sphere"
radius = 1.0

[substrate]
young = 1.0
poisson = 0.3

[loading]
normal_load = 5e-6

[grid]
cells = [32, 32]
"#;

/// One run of the binary and the folder it wrote into.
pub struct Run {
    pub output: Output,
    pub out_dir: PathBuf,
    pub root: tempfile::TempDir,
}

impl Run {
    pub fn code(&self) -> Option<i32> {
        self.output.status.code()
    }
    pub fn stderr(&self) -> String {
        String::from_utf8_lossy(&self.output.stderr).into_owned()
    }
    pub fn stdout(&self) -> String {
        String::from_utf8_lossy(&self.output.stdout).into_owned()
    }
}

/// Writes `case` (and `files`) into a fresh folder and runs `thirdbody solve`.
pub fn solve(case: &str, files: &[(&str, &str)], extra_args: &[&str]) -> Run {
    let root = tempfile::tempdir().unwrap();
    let case_path = root.path().join("case.toml");
    std::fs::write(&case_path, case).unwrap();
    for (name, text) in files {
        std::fs::write(root.path().join(name), text).unwrap();
    }
    let out_dir = root.path().join("out");
    let output = Command::new(env!("CARGO_BIN_EXE_thirdbody"))
        .arg("solve")
        .arg(&case_path)
        .arg("--out")
        .arg(&out_dir)
        .args(extra_args)
        .output()
        .unwrap();
    Run {
        output,
        out_dir,
        root,
    }
}

/// Runs `thirdbody` with `args`.
pub fn thirdbody(args: &[&std::ffi::OsStr]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_thirdbody"))
        .args(args)
        .output()
        .unwrap()
}

/// Asserts that `dir` is absent or empty.
pub fn assert_no_output(dir: &Path) {
    if dir.exists() {
        let left: Vec<_> = std::fs::read_dir(dir).unwrap().collect();
        assert!(left.is_empty(), "files left in {}: {left:?}", dir.display());
    }
}

/// The summary a run wrote.
pub fn read_summary(dir: &Path) -> serde_json::Map<String, serde_json::Value> {
    let text = std::fs::read_to_string(dir.join("summary.json")).unwrap();
    let value: serde_json::Value = serde_json::from_str(&text).unwrap();
    value.as_object().unwrap().clone()
}
