//! Empty: a build script only so that the `[build-dependencies]` pin of `syn`'s
//! features takes part in the build (Cargo.toml).
fn main() {}
