#!/usr/bin/env bash
# Every test: the Rust workspace, then the Python package built into a fresh virtual
# environment under target/ (maturin, pytest, numpy and the package's `test` extra:
# pandas, xarray, scipy, matplotlib, dask[distributed], pytest-timeout, all from the
# package index). The Python package is a member of the workspace left out of `cargo
# test` (an extension module does not link against libpython); its build reuses the
# crates the tests compiled (crates/thirdbody-feature-pins, docs/performance.md).
# The Rust test binaries run as many at a time as there are cores
# (tools/run_rust_tests.py); `cargo test --release --workspace --exclude thirdbody-py --exclude thirdbody-bench`
# runs the same tests one binary after another.
set -euo pipefail
cd "$(dirname "$0")"
python3 tools/run_rust_tests.py
venv=target/python-test-venv
rm -rf "$venv"
python3 -m venv "$venv"
"$venv/bin/python" -m pip install --quiet --upgrade pip
# --no-compile: no bytecode for the thousands of modules of scipy, pandas, matplotlib
# and dask the tests never import (15 s of CPU); the imported ones compile on first use.
# --no-build-isolation: maturin is already in the environment (from the venv's bin).
"$venv/bin/python" -m pip install --quiet --no-compile maturin pytest numpy
PATH="$PWD/$venv/bin:$PATH" "$venv/bin/python" -m pip install --quiet --no-compile \
    --no-build-isolation "./crates/thirdbody-py[test]"
THIRDBODY_BIN="$PWD/target/release/thirdbody" "$venv/bin/python" -m pytest -q --timeout 600 \
    --durations=10 crates/thirdbody-py/tests
