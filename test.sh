#!/usr/bin/env bash
# Every test: the Rust workspace, then the Python package built into a fresh virtual
# environment under target/ (maturin, pytest, numpy and the package's `test` extra:
# pandas, xarray, scipy, matplotlib, dask[distributed], pytest-timeout, all from the
# package index). The Python package is a member of the workspace left out of `cargo
# test` (an extension module does not link against libpython); its build reuses the
# crates the tests compiled (crates/thirdbody-feature-pins, docs/performance.md).
#
# Two things overlap to save wall time on a small machine: the virtual environment
# and the test extra's packages install while the Rust tests compile and run, and the
# Rust test binaries run as many at a time as there are cores
# (tools/run_rust_tests.py; `cargo test --release --workspace --exclude thirdbody-py`
# runs the same tests one binary after another).
set -euo pipefail
cd "$(dirname "$0")"
venv=target/python-test-venv
mkdir -p target
rm -rf "$venv"
(
    python3 -m venv "$venv"
    "$venv/bin/python" -m pip install --quiet --upgrade pip
    # The test extra as pyproject.toml lists it (tomllib: Python 3.11+; on an older
    # Python the package's install below fetches it instead).
    extra=$("$venv/bin/python" -c 'import tomllib
with open("crates/thirdbody-py/pyproject.toml", "rb") as f:
    print("\n".join(tomllib.load(f)["project"]["optional-dependencies"]["test"]))' || true)
    if [ -n "$extra" ]; then mapfile -t extra <<< "$extra"; else extra=(); fi
    "$venv/bin/python" -m pip install --quiet maturin pytest numpy ${extra[@]+"${extra[@]}"}
) > target/python-test-venv.log 2>&1 &
python_env=$!
trap 'kill "$python_env" 2> /dev/null || true' EXIT
python3 tools/run_rust_tests.py
if ! wait "$python_env"; then
    cat target/python-test-venv.log >&2
    exit 1
fi
"$venv/bin/python" -m pip install --quiet "./crates/thirdbody-py[test]"
THIRDBODY_BIN="$PWD/target/release/thirdbody" "$venv/bin/python" -m pytest -q --timeout 600 \
    --durations=10 crates/thirdbody-py/tests
