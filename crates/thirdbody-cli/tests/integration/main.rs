//! The command-line program's integration tests in one test binary: each module was
//! a file of its own under `tests/`, and each such file is a binary that cargo
//! compiles and links against the program's crates and all their dependencies
//! separately (docs/performance.md, test suite time). A new test file can go here as
//! a module (`mod name;`) or stay a binary of its own under `tests/`
//! (`recorded_results.rs` does, so that `cargo test --test recorded_results` checks
//! the recorded summaries alone).

#[path = "../common/mod.rs"]
mod common;

mod cli;
mod docs_commands;
mod examples;
mod height_map_friction;
mod hostile_cli;
mod provenance;
mod reproduce;
mod sweep;
