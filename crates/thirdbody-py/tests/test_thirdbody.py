"""The Python package against the command-line program (issue 12, acceptance 2, 3, 6
in part): the same summaries and fields for the bundled examples, the same messages
for bad input, and solves that run concurrently in threads (the GIL is released).

The CLI binary is the one `cargo test --release` (or `cargo build --release`) built:
`target/release/thirdbody`, or the path in THIRDBODY_BIN.
"""

import json
import math
import os
import pathlib
import subprocess
import threading

import numpy as np
import pytest

import thirdbody

ROOT = pathlib.Path(__file__).resolve().parents[3]
EXAMPLES = sorted((ROOT / "examples").glob("*.toml"))
CLI = pathlib.Path(os.environ.get("THIRDBODY_BIN", ROOT / "target" / "release" / "thirdbody"))


def cli(*args):
    assert CLI.exists(), f"build the CLI first (cargo build --release): {CLI} is missing"
    return subprocess.run([str(CLI), *map(str, args)], capture_output=True, text=True)


def close(a, b, path=""):
    """Every number of `a` equals `b`'s to 1e-12 (relative); timing keys skipped."""
    if isinstance(a, dict):
        for k, v in a.items():
            if k == "solve_seconds":
                continue
            assert k in b, f"{path}.{k} missing"
            close(v, b[k], f"{path}.{k}")
    elif isinstance(a, list):
        assert len(a) == len(b), path
        for i, (x, y) in enumerate(zip(a, b)):
            close(x, y, f"{path}[{i}]")
    elif isinstance(a, float) or isinstance(b, float):
        assert math.isclose(a, b, rel_tol=1e-12, abs_tol=0.0) or a == b, f"{path}: {a} vs {b}"
    else:
        assert a == b, f"{path}: {a} vs {b}"


def test_import_gives_the_version_and_the_references():
    assert thirdbody.__version__.count(".") == 2
    assert thirdbody.cite() == cli("cite").stdout


def test_the_summary_carries_the_provenance():
    summary = thirdbody.solve(thirdbody.Case.from_file(ROOT / "examples" / "hertz.toml")).summary
    assert summary["thirdbody_version"] == thirdbody.__version__
    assert len(summary["case_hash"]) == 64
    assert summary["commit"] is None or len(summary["commit"]) == 40


@pytest.mark.parametrize("example", EXAMPLES, ids=[e.stem for e in EXAMPLES])
def test_every_bundled_example_matches_the_cli(example, tmp_path):
    out = tmp_path / "out"
    run = cli("solve", example, "--out", out, "--format", "npy")
    assert run.returncode == 0, run.stderr
    cli_summary = json.loads((out / "summary.json").read_text())
    solution = thirdbody.solve(thirdbody.Case.from_file(example))
    py_summary = solution.summary
    # Python does not compute stresses yet: every other key of summary.json is there.
    cli_summary.pop("stress", None)
    assert set(py_summary) == set(cli_summary)
    close(cli_summary, py_summary)
    for name in ["pressure", "gap", "body_displacement", "layer_displacement", "compliance"]:
        path = out / f"{name}.npy"
        array = getattr(solution, name)
        if not path.exists():
            assert array is None, name
            continue
        want = np.load(path)
        assert array.shape == want.shape, name
        assert np.array_equal(array, want), f"{name} differs from the NPY file"


BAD = {
    "slider.radius": ("radius = 1.0", "radius = -1.0"),
    "substrate.poisson": ("poisson = 0.3", "poisson = 0.7"),
    "grid.cells": ("cells = [128, 128]", "cells = [4, 128]"),
    "loading.normal_load": ("normal_load = 5e-6", "normal_load = nan"),
    "unknown key": ("[loading]", "[loading]\nspeed = 1"),
    "not toml": ("[slider]", "[slider"),
}


@pytest.mark.parametrize("name", sorted(BAD))
def test_bad_input_raises_value_error_with_the_cli_message(name, tmp_path):
    text = (ROOT / "examples" / "paper_fig3.toml").read_text()
    old, new = BAD[name]
    assert old in text, f"the example no longer has {old!r}"
    bad = text.replace(old, new, 1)
    path = tmp_path / "bad.toml"
    path.write_text(bad)
    run = cli("solve", path, "--out", tmp_path / "out")
    assert run.returncode == 2, run.stderr
    message = run.stderr.strip()
    assert message.startswith("error: "), message
    with pytest.raises(ValueError) as raised:
        thirdbody.Case.from_toml(bad)
    assert str(raised.value) == message[len("error: "):]
    assert not (tmp_path / "out").exists()


def test_two_solves_in_threads_equal_sequential_ones():
    case = thirdbody.Case.from_file(ROOT / "examples" / "hertz.toml")
    sequential = [thirdbody.solve(case).pressure for _ in range(2)]
    results = [None, None]

    def work(i):
        results[i] = thirdbody.solve(case).pressure

    threads = [threading.Thread(target=work, args=(i,)) for i in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for got, want in zip(results, sequential):
        assert np.array_equal(got, want)
