//! The shell commands of README.md and docs/*.md run as written: every
//! line of a fenced `sh` block, in a fresh folder that holds a link to the bundled
//! `examples/`, with the built `thirdbody` first on the PATH. `cargo run --release --`
//! is the same program, so it is replaced by that binary (a nested cargo would wait
//! for the build lock of the suite running this test). Lines that are not the
//! program's (`./test.sh`, `pip install`, `cargo bench`, the scaling example) are
//! run by CI itself or are benchmarks, and are listed, not run. Slurm and other
//! commands that need more than this machine are in `bash` blocks, which are not run.

use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// The lines of every ```sh block in `markdown`, continuation lines joined.
fn sh_commands(markdown: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut inside = false;
    let mut pending = String::new();
    for line in markdown.lines() {
        if !inside {
            inside = line.trim_end() == "```sh";
            continue;
        }
        if line.starts_with("```") {
            inside = false;
            continue;
        }
        let line = line.trim_end();
        if let Some(head) = line.strip_suffix('\\') {
            pending.push_str(head);
            continue;
        }
        pending.push_str(line);
        let command = std::mem::take(&mut pending);
        if !command.trim().is_empty() {
            out.push(command.trim().to_string());
        }
    }
    out
}

/// Commands run elsewhere: the test command itself, the package install (test.sh
/// does it), benchmarks.
const NOT_RUN_HERE: [&str; 4] = [
    "./test.sh",
    "pip install",
    "cargo bench",
    "--example scaling",
];

#[test]
fn every_sh_command_of_the_docs_runs_as_written() {
    let root = root();
    let mut files = vec![root.join("README.md")];
    let mut docs: Vec<PathBuf> = std::fs::read_dir(root.join("docs"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "md"))
        .collect();
    docs.sort();
    files.extend(docs);

    let binary = PathBuf::from(env!("CARGO_BIN_EXE_thirdbody"));
    let path = format!(
        "{}:{}",
        binary.parent().unwrap().display(),
        std::env::var("PATH").unwrap_or_default()
    );
    let scratch = tempfile::tempdir().unwrap();
    std::os::unix::fs::symlink(root.join("examples"), scratch.path().join("examples")).unwrap();

    let mut ran = 0;
    for file in &files {
        let text = std::fs::read_to_string(file).unwrap();
        for command in sh_commands(&text) {
            if NOT_RUN_HERE.iter().any(|skip| command.contains(skip)) {
                continue;
            }
            let command = command.replace("cargo run --release --", "thirdbody");
            let run = Command::new("sh")
                .arg("-c")
                .arg(&command)
                .current_dir(scratch.path())
                .env("PATH", &path)
                .output()
                .unwrap();
            assert!(
                run.status.success(),
                "{}: `{command}` failed ({}):\n{}",
                file.display(),
                run.status,
                String::from_utf8_lossy(&run.stderr)
            );
            ran += 1;
        }
    }
    assert!(
        ran >= 10,
        "only {ran} commands found: did the docs lose their examples?"
    );
}

#[test]
fn continuation_lines_are_joined_and_other_blocks_skipped() {
    let md = "text\n```sh\na \\\n  b\n\nc\n```\n```bash\nd\n```\n```sh\ne\n```\n";
    assert_eq!(sh_commands(md), ["a   b", "c", "e"]);
}
