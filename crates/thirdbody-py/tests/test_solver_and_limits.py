"""A Solver that keeps its kernels, stresses refused before they cannot fit and
computed in parts, numpy integers in cases, the summary's warnings as Python
warnings, and height maps given as numpy arrays."""

import concurrent.futures
import pathlib
import time
import warnings

import numpy as np
import pytest

import thirdbody
from thirdbody import _sweep

ROOT = pathlib.Path(__file__).resolve().parents[3]
COATED = ROOT / "examples" / "paper_fig12a_thin_coating.toml"
HERTZ = ROOT / "examples" / "hertz.toml"


def _available_bytes():
    try:
        with open("/proc/meminfo") as f:
            for line in f:
                if line.startswith("MemAvailable:"):
                    return int(line.split()[1]) * 1024
    except OSError:
        pass
    return None


def _coated(cells=128):
    # A fixed window: every load below is solved on the same cells, so on the same
    # surface kernel (an automatic window follows the load).
    return thirdbody.Case.from_file(COATED).with_(
        {"grid.cells": [cells, cells], "grid.half_width": [0.07, 0.07],
         "grid.centre": [0.02, 0.0]})


# --- memory and Ctrl-C for stresses -------------------------------------------------

@pytest.mark.skipif(_available_bytes() is None, reason="needs /proc/meminfo (Linux)")
def test_a_block_that_cannot_fit_is_refused_before_it_starts():
    solution = thirdbody.solve(thirdbody.Case.from_file(HERTZ).with_(grid__cells=[32, 32]))
    per_depth = 32 * 32 * 11 * 8
    # At least a million depths (90 GB), and at least twice what the machine has.
    n = max(1_000_000, 2 * _available_bytes() // per_depth)
    depths = np.linspace(0.0, 0.05, n)
    start = time.monotonic()
    with pytest.raises(thirdbody.NotEnoughMemoryError) as refused:
        solution.stresses("block", depths=depths)
    assert time.monotonic() - start < 2.0, "the refusal came after the work had started"
    message = str(refused.value)
    assert isinstance(refused.value, MemoryError) and isinstance(refused.value, ValueError)
    assert f'stresses("block") with {n} depth(s) needs about' in message, message
    assert "GiB" in message and "is available" in message, message
    fits = int(message.split("at most ")[1].split(" depths fit")[0])
    assert 0 < fits < n
    # What the message says fits is computed (a few depths of it, here).
    assert solution.stresses("block", depths=depths[:min(fits, 8)])["tau1"].shape[0] == min(fits, 8)


def test_stresses_in_parts_equal_each_depth_pair_alone():
    solution = thirdbody.solve(thirdbody.Case.from_file(HERTZ).with_(grid__cells=[32, 32]))
    depths = np.linspace(0.0, 0.03, 41)
    for section in ("block", "xz"):
        whole = solution.stresses(section, depths=depths)
        assert np.array_equal(whole["z"], depths)
        pairs = [solution.stresses(section, depths=list(depths[k:k + 2]))
                 for k in range(0, 40, 2)] + [solution.stresses(section, depths=depths[39:])]
        for name in ("sigma_x", "tau_xz", "s1", "tau1", "von_mises"):
            stacked = np.concatenate([p[name] for p in pairs[:-1]] + [pairs[-1][name][1:]])
            assert np.array_equal(whole[name], stacked), (section, name)


def test_a_bad_depth_far_in_the_list_names_its_index():
    solution = thirdbody.solve(thirdbody.Case.from_file(HERTZ).with_(grid__cells=[32, 32]))
    depths = list(np.linspace(0.0, 0.03, 100))
    depths[77] = -1.0
    with pytest.raises(ValueError, match=r"stress.depths\[77\] = -1"):
        solution.stresses("block", depths=depths)


# --- a Solver keeps its kernels --------------------------------------------------------

def test_a_solver_builds_a_coated_kernel_once_for_many_loads():
    case = _coated()
    loads = [3e-6, 4e-6, 5e-6, 6e-6]
    solver = thirdbody.Solver()
    assert (solver.kernels_built, solver.kernels_held) == (0, 0)
    kept = [solver.solve(case.with_(loading__normal_load=q), stresses=False) for q in loads]
    assert solver.kernels_built == 1, repr(solver)
    assert solver.kernels_reused == len(loads) - 1
    assert solver.kernels_held == 1
    for q, solution in zip(loads, kept):
        fresh = thirdbody.solve(case.with_(loading__normal_load=q), stresses=False)
        assert np.array_equal(solution.pressure, fresh.pressure)
        assert solution.summary["friction_coefficient"] == fresh.summary["friction_coefficient"]
    # Nothing kept: every solve builds its own.
    forgetful = thirdbody.Solver(capacity=0)
    for q in loads[:2]:
        forgetful.solve(case.with_(loading__normal_load=q), stresses=False)
    assert (forgetful.kernels_built, forgetful.kernels_held) == (2, 0)
    solver.clear()
    assert solver.kernels_held == 0


def test_a_solver_shared_by_two_threads_gives_the_same_results():
    case = _coated()
    solver = thirdbody.Solver()
    loads = [3e-6, 4e-6, 5e-6, 6e-6]
    with concurrent.futures.ThreadPoolExecutor(2) as pool:
        got = list(pool.map(
            lambda q: solver.solve(case.with_(loading__normal_load=q), stresses=False).pressure,
            loads))
    for q, pressure in zip(loads, got):
        want = thirdbody.solve(case.with_(loading__normal_load=q), stresses=False).pressure
        assert np.array_equal(pressure, want)
    assert solver.kernels_built == 1


class _InThisThread(concurrent.futures.Executor):
    """Runs each case when it is submitted, in the calling thread."""

    def submit(self, fn, *args, **kwargs):
        future = concurrent.futures.Future()
        future.set_result(fn(*args, **kwargs))
        return future


def test_a_sweep_worker_keeps_one_solver_for_its_cases():
    _sweep._worker.__dict__.clear()
    # Without the case's [stress] section: the kernels are the point here.
    table = thirdbody.sweep(_coated(64).with_(stress=None), {"loading.normal_load": [3e-6, 4e-6, 5e-6]},
                            executor=_InThisThread())
    assert (table["status"] == "ok").all()
    assert _sweep._solver().kernels_built == 1
    assert _sweep._solver().kernels_reused == 2


# --- numpy integers -------------------------------------------------------------------

def test_numpy_integers_are_integers_in_a_case():
    text = HERTZ.read_text()
    base = thirdbody.Case.from_toml(text).with_(grid__cells=[32, 32])
    from_array = thirdbody.Case.from_toml(text).with_(grid__cells=np.array([32, 32]))
    from_scalars = thirdbody.Case.from_toml(text).with_(
        {"grid.cells": [np.int64(32), np.int32(32)]})
    assert from_array.case_hash == base.case_hash == from_scalars.case_hash
    assert "cells = [32, 32]" in from_array.toml
    assert base.with_(solver__max_iterations=np.int64(500)).toml.count("max_iterations = 500") == 1
    # Floats stay floats, numpy's too: the message names the key.
    with pytest.raises(ValueError, match="grid.cells"):
        base.with_(grid__cells=np.array([32.0, 32.0]))
    assert base.with_(loading__normal_load=np.float64(1e-6)).case_hash == \
        base.with_(loading__normal_load=1e-6).case_hash
    sections = thirdbody.Case(
        slider={"shape": "sphere", "radius": 1.0},
        substrate={"young": 1.0, "poisson": 0.3},
        loading={"normal_load": 5e-6},
        grid={"cells": np.array([32, 32], dtype=np.int64)},
    )
    assert sections.cells == (32, 32)
    table = thirdbody.sweep(base, {"grid.cells": [np.array([16, 16]), np.array([32, 32])]})
    assert list(table["status"]) == ["ok", "ok"]


# --- warnings ---------------------------------------------------------------------------

def test_a_summary_warning_is_a_python_warning_and_stays_in_the_dataset():
    case = thirdbody.Case.from_file(HERTZ).with_(
        {"grid.cells": [32, 32], "loading.normal_load": 3e-3})
    with pytest.warns(thirdbody.ThirdbodyWarning) as caught:
        solution = thirdbody.solve(case)
    said = solution.summary["warnings"]
    assert said and [str(w.message) for w in caught] == said
    assert caught[0].filename == __file__, "the warning should point at the caller's line"
    assert solution.to_xarray().attrs["warnings"] == "\n".join(said)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        quiet = thirdbody.solve(case.with_(loading__normal_load=5e-6))
    assert "warnings" not in quiet.summary
    assert "warnings" not in quiet.to_xarray().attrs


# --- heights as a numpy array --------------------------------------------------------

def _paraboloid():
    # A paraboloid of radius 1 on 201 x 201 nodes 2.5e-4 apart, a little tilted so
    # that a transposed map would differ.
    s = (np.arange(201) - 100) * 2.5e-4
    return (s[None, :] ** 2 + s[:, None] ** 2) / 2.0 + 1e-3 * s[None, :]


def _solve_summary(case):
    summary = thirdbody.solve(case).summary
    summary.pop("solve_seconds")
    return summary


def test_heights_as_an_array_equal_the_same_map_in_an_npy_file(tmp_path):
    heights = _paraboloid()
    np.save(tmp_path / "map.npy", heights)
    text = """[slider]
shape = "height_map"
file = "map.npy"
cell_size = 2.5e-4
[substrate]
young = 1.0
poisson = 0.3
[loading]
normal_load = 5e-6
[grid]
cells = [48, 48]
"""
    from_file = thirdbody.Case.from_toml(text, base_dir=tmp_path)
    from_array = thirdbody.Case(
        slider={"shape": "height_map", "heights": heights, "cell_size": 2.5e-4},
        substrate={"young": 1.0, "poisson": 0.3},
        loading={"normal_load": 5e-6},
        grid={"cells": [48, 48]},
    )
    assert 'file = "<array>"' in from_array.toml
    assert from_array.case_hash == from_file.case_hash
    want = _solve_summary(from_file)
    assert _solve_summary(from_array) == want, "the same map, the same bits"
    # Any 2-D array-like of numbers, and with_ keeps the array (or takes another).
    assert from_array.with_(loading__normal_load=5e-6).case_hash == from_file.case_hash
    as_lists = from_file.with_({"slider.file": None, "slider.heights": heights.tolist()})
    assert as_lists.case_hash == from_file.case_hash
    whole_section = thirdbody.Case.from_file(HERTZ).with_(
        {"slider": {"shape": "height_map", "heights": heights, "cell_size": 2.5e-4},
         "grid.cells": [48, 48], "loading.normal_load": 5e-6})
    assert whole_section.case_hash == from_file.case_hash


def test_heights_as_an_array_are_checked_as_a_file_is(tmp_path):
    heights = _paraboloid()
    slider = {"shape": "height_map", "cell_size": 2.5e-4}
    rest = dict(substrate={"young": 1.0, "poisson": 0.3}, loading={"normal_load": 5e-6},
                grid={"cells": [48, 48]})
    bad = heights.copy()
    bad[3, 7] = np.nan
    np.save(tmp_path / "bad.npy", bad)
    with pytest.raises(ValueError) as from_file:
        thirdbody.Case(slider={**slider, "file": str(tmp_path / "bad.npy")}, **rest)
    with pytest.raises(ValueError) as from_array:
        thirdbody.Case(slider={**slider, "heights": bad}, **rest)
    assert str(from_array.value) == str(from_file.value)
    assert "row 3, column 7" in str(from_array.value)
    # One row of heights is a line contact's profile, not a map: named, with the shape
    # it is for; three dimensions are no slider at all.
    with pytest.raises(ValueError, match=r"slider.file = 1 x 201 samples.*\"profile\""):
        thirdbody.Case(slider={**slider, "heights": heights[0]}, **rest)
    with pytest.raises(ValueError, match=r"slider.heights of shape \(2, 2, 2\)"):
        thirdbody.Case(slider={**slider, "heights": np.zeros((2, 2, 2))}, **rest)
    with pytest.raises(ValueError, match="slider.heights and slider.file"):
        thirdbody.Case(slider={**slider, "heights": heights, "file": "map.npy"}, **rest)
    with pytest.raises(ValueError, match="numpy.save"):
        thirdbody.sweep(thirdbody.Case(slider={**slider, "heights": heights}, **rest),
                        {"loading.normal_load": [1e-6, 2e-6]})


def _penetration(case):
    return thirdbody.solve(case).summary["penetration"]


def test_a_case_with_heights_as_an_array_pickles_and_solves_in_a_process_pool():
    import pickle

    case = thirdbody.Case(
        slider={"shape": "height_map", "heights": _paraboloid(), "cell_size": 2.5e-4},
        substrate={"young": 1.0, "poisson": 0.3},
        loading={"normal_load": 5e-6},
        grid={"cells": [32, 32]},
    )
    again = pickle.loads(pickle.dumps(case))
    assert again.case_hash == case.case_hash and again.toml == case.toml
    variants = [case.with_(loading__normal_load=q) for q in (4e-6, 5e-6)]
    with concurrent.futures.ProcessPoolExecutor(2) as pool:
        got = list(pool.map(_penetration, variants))
    assert got == [_penetration(v) for v in variants]
