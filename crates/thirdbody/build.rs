//! Records the git commit the library is built from (`THIRDBODY_GIT_COMMIT`), when the
//! source is a git checkout and git is on the path; nothing otherwise (a crate tarball).

use std::path::{Path, PathBuf};
use std::process::Command;

fn main() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    // In a worktree `.git` is a file: HEAD is in the worktree's own git folder, the
    // branches and packed-refs in the common one; git names both.
    let git_path = |what: &str| {
        Command::new("git")
            .arg("-C")
            .arg(&root)
            .args(["rev-parse", "--path-format=absolute", what])
            .output()
            .ok()
            .filter(|o| o.status.success())
            .and_then(|o| String::from_utf8(o.stdout).ok())
            .map(|s| PathBuf::from(s.trim()))
    };
    let git = git_path("--git-dir").unwrap_or_else(|| root.join(".git"));
    let common = git_path("--git-common-dir").unwrap_or_else(|| git.clone());
    // Rebuild when HEAD moves: a checkout changes HEAD, a commit changes the branch's
    // ref (a loose file, or packed-refs once packed).
    let mut watched = vec![git.join("HEAD"), common.join("packed-refs")];
    if let Ok(head) = std::fs::read_to_string(git.join("HEAD")) {
        if let Some(reference) = head.trim().strip_prefix("ref: ") {
            watched.push(common.join(reference));
        }
    }
    for path in watched.iter().filter(|p| p.exists()) {
        println!("cargo:rerun-if-changed={}", path.display());
    }
    println!("cargo:rerun-if-changed=build.rs");
    let commit = Command::new("git")
        .arg("-C")
        .arg(&root)
        .args(["rev-parse", "HEAD"])
        .output()
        .ok()
        .filter(|o| o.status.success())
        .and_then(|o| String::from_utf8(o.stdout).ok())
        .map(|s| s.trim().to_owned())
        .filter(|s| s.len() == 40 && s.bytes().all(|b| b.is_ascii_hexdigit()));
    if let Some(commit) = commit {
        println!("cargo:rustc-env=THIRDBODY_GIT_COMMIT={commit}");
    }
}
