//! The library's integration tests in one test binary: each module was a file of its
//! own under `tests/`, and each such file is a binary that cargo compiles and links
//! against the library and all its dependencies separately (one link each, most of
//! the test build's time on a 2-core machine: docs/performance.md, test suite time).
//! A new test file can go here as a module (`mod name;`) or stay a binary of its own
//! under `tests/` when it needs a process to itself.

#[path = "../bundled/mod.rs"]
mod bundled;
#[path = "../cases/mod.rs"]
mod cases;

mod fractional_friction;
mod fuzz_cases;
mod hertz_and_limits;
mod hostile_input;
mod no_global_state;
mod paper_fig10;
mod paper_ranges;
mod paper_trends;
mod pk_sparse_updates;
mod rheologies;
mod solver_vs_reference;
mod stiff_coatings;
mod threads;
mod units;
