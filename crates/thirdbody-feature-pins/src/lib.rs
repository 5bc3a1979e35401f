//! No code. Depending on this crate switches on, in a few shared crates, the features
//! that the tests' dev-dependencies and the Python package's proc macros switch on,
//! so that `./test.sh` compiles the library, the front ends and their dependencies
//! once for both (the crate's Cargo.toml lists the features and why).
