"""The Python package against the command-line program: the same summaries and
fields for the bundled examples, the same messages for bad input, and solves that run
concurrently in threads (the GIL is released).

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


STRESS_NAMES = ["sigma_x", "sigma_y", "sigma_z", "tau_xy", "tau_xz", "tau_yz", "s1", "s2", "s3",
                "tau1", "von_mises"]


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
    assert set(py_summary) == set(cli_summary)
    close(cli_summary, py_summary)
    if "stress" in cli_summary:
        stresses = solution.case_stresses()
        assert sorted(stresses) == sorted(s["name"] for s in cli_summary["stress"]["sections"])
        for name, got in stresses.items():
            want = np.load(out / f"stress_{name}.npy")
            stacked = np.stack([got[n] for n in STRESS_NAMES])
            assert np.array_equal(stacked, want), name
    else:
        with pytest.raises(ValueError, match=r"no \[stress\] section"):
            solution.case_stresses()
    for name in ["pressure", "gap", "body_displacement", "layer_displacement", "compliance"]:
        path = out / f"{name}.npy"
        array = getattr(solution, name)
        if not path.exists():
            assert array is None, name
            continue
        want = np.load(path)
        assert array.shape == want.shape, name
        assert np.array_equal(array, want), f"{name} differs from the NPY file"


BAD_INPUTS = json.loads(
    (ROOT / "crates" / "thirdbody-cli" / "tests" / "data" / "bad_inputs.json").read_text()
)["cases"]


@pytest.mark.parametrize("entry", BAD_INPUTS, ids=[e["name"] for e in BAD_INPUTS])
def test_the_cli_bad_input_list_raises_the_cli_message(entry, tmp_path):
    text = (ROOT / "examples" / f"{entry['example']}.toml").read_text()
    for old, new in entry["replace"]:
        assert old in text, f"the example no longer has {old!r}"
        text = text.replace(old, new, 1)
    path = tmp_path / "bad.toml"
    path.write_text(text)
    run = cli("solve", path, "--out", tmp_path / "out", "--format", "npy")
    assert run.returncode == entry["exit"], run.stderr
    message = run.stderr.strip()
    assert message.startswith("error: "), message
    kind = ValueError if entry["exit"] == 2 else RuntimeError
    with pytest.raises(kind) as raised:
        thirdbody.solve(thirdbody.Case.from_toml(text))  # with its [stress] section
    if message.startswith("error: not enough memory"):
        kind = thirdbody.NotEnoughMemoryError  # a ValueError too
    assert type(raised.value) is kind
    assert str(raised.value) == message[len("error: "):]
    assert not (tmp_path / "out").exists()


def test_two_solves_in_threads_overlap_in_time():
    # Each solve reports progress from its own thread while it runs; with the GIL
    # held by a solve, the other could not start before it ended, and the two event
    # streams would not interleave.
    case = thirdbody.Case.from_file(ROOT / "examples" / "paper_fig3.toml").with_(
        grid__cells=[256, 256])
    log = []

    def work(name):
        thirdbody.solve(case, progress=lambda e: log.append(name))

    threads = [threading.Thread(target=work, args=(n,)) for n in "ab"]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    first_b, last_a = log.index("b"), len(log) - 1 - log[::-1].index("a")
    first_a, last_b = log.index("a"), len(log) - 1 - log[::-1].index("b")
    assert first_b < last_a and first_a < last_b, "the solves ran one after the other"


def test_fields_are_shared_read_only_arrays_and_stresses_can_wait():
    example = ROOT / "examples" / "paper_fig10a.toml"
    solution = thirdbody.solve(thirdbody.Case.from_file(example), stresses=False)
    assert "stress" not in solution.summary
    with pytest.raises(ValueError, match="stresses=False"):
        solution.case_stresses()
    pressure = solution.pressure
    assert pressure is solution.pressure, "each access must not copy the field"
    assert not pressure.flags.writeable and not solution.x.flags.writeable
    with pytest.raises(ValueError):
        pressure[0, 0] = 1.0


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


def test_stresses_equal_the_cli_stress_files(tmp_path):
    example = ROOT / "examples" / "paper_fig12a_thin_coating.toml"
    out = tmp_path / "out"
    run = cli("solve", example, "--out", out, "--format", "npy,csv")
    assert run.returncode == 0, run.stderr
    solution = thirdbody.solve(thirdbody.Case.from_file(example))
    names = STRESS_NAMES
    xz_csv = np.loadtxt(out / "stress_xz.csv", delimiter=",", skiprows=1)
    depths = sorted(set(xz_csv[:, 2]))
    sections = {
        "stress_surface.npy": solution.stresses("surface"),
        "stress_interface_0_above.npy": solution.stresses("interface", side="coating"),
        "stress_interface_0_below.npy": solution.stresses("interface", interface=0, side="below"),
        "stress_xz.npy": solution.stresses("xz", y=float(xz_csv[0, 1]), depths=depths),
    }
    for name, got in sections.items():
        want = np.load(out / name)
        stacked = np.stack([got[n] for n in names])
        assert stacked.shape == want.shape, name
        assert np.array_equal(stacked, want), name


def test_cases_from_sections_and_variants():
    text = (ROOT / "examples" / "hertz.toml").read_text()
    base = thirdbody.Case.from_toml(text)
    import tomllib  # Python 3.11+: the test machine's; the package itself needs 3.9

    sections = tomllib.loads(text)
    assert thirdbody.Case(**sections).case_hash == base.case_hash
    assert thirdbody.Case(sections).case_hash == base.case_hash
    heavier = base.with_({"loading.normal_load": 2 * sections["loading"]["normal_load"]})
    assert heavier.case_hash != base.case_hash
    assert heavier.with_(loading__normal_load=sections["loading"]["normal_load"]).case_hash == base.case_hash
    with pytest.raises(ValueError, match="loading.normal_load"):
        base.with_({"loading.normal_load": -1.0})
    with pytest.raises(ValueError, match="slider.radius"):
        thirdbody.Case(**{**sections, "slider": {**sections["slider"], "radius": "big"}})


def test_cases_pickle_and_solve_in_a_process_pool():
    import concurrent.futures
    import pickle

    case = thirdbody.Case.from_file(ROOT / "examples" / "hertz.toml")
    assert pickle.loads(pickle.dumps(case)).case_hash == case.case_hash
    variants = [case.with_({"loading.normal_load": q}) for q in (1e-6, 2e-6)]
    with concurrent.futures.ProcessPoolExecutor(2) as pool:
        mus = list(pool.map(_approach, variants))
    assert mus == [_approach(v) for v in variants]


def _approach(case):
    return thirdbody.solve(case).summary["penetration"]


def test_progress_reports_windows_and_iterations_and_its_exceptions_stop_the_solve():
    case = thirdbody.Case.from_file(ROOT / "examples" / "paper_fig3.toml")
    events = []
    solution = thirdbody.solve(case, progress=events.append)
    assert events[0]["event"] == "window" and events[0]["window"] == 1
    iterations = [e for e in events if e["event"] == "iteration"]
    assert iterations and iterations[-1]["residual"] <= 1e-10
    last_window = max(e["window"] for e in events)
    assert solution.summary["windows"] == last_window
    assert iterations[-1]["iteration"] == solution.summary["iterations"]

    def stop_at_three(e):
        if e["event"] == "iteration" and e["iteration"] == 3:
            raise LookupError("stop here")

    with pytest.raises(LookupError, match="stop here"):
        thirdbody.solve(case, progress=stop_at_three)


# A child inherits an ignored SIGINT (a test runner started in the background, under
# nohup or by some CI), and Python then installs no handler of its own: the child
# restores Python's before anything else, as an interactive Python has it.
_PYTHON_SIGINT = "import signal; signal.signal(signal.SIGINT, signal.default_int_handler)\n"


def _interrupted(script, seconds, timeout=60):
    """Runs `script` in a fresh Python with Python's own SIGINT handler, sends SIGINT
    `seconds` after it prints "started", and returns (stderr, seconds from the signal
    to the exit)."""
    import signal
    import sys
    import time

    child = subprocess.Popen([sys.executable, "-c", _PYTHON_SIGINT + script],
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        assert child.stdout.readline().strip() == "started"
        time.sleep(seconds)
        assert child.poll() is None, "the work ended before the interrupt"
        child.send_signal(signal.SIGINT)
        sent = time.monotonic()
        _, err = child.communicate(timeout=timeout)
    finally:
        child.kill()
        child.wait()
    return err, time.monotonic() - sent


def test_ctrl_c_reaches_the_child_when_the_runner_ignores_sigint():
    import signal
    import threading

    if threading.current_thread() is not threading.main_thread():
        pytest.skip("signal dispositions are set from the main thread")
    # As under nohup or a background job: the runner ignores SIGINT, and so would a
    # child started without restoring Python's handler (it would sleep out its 30 s).
    previous = signal.signal(signal.SIGINT, signal.SIG_IGN)
    try:
        err, after = _interrupted('import time\nprint("started", flush=True)\ntime.sleep(30)\n',
                                  0.2, timeout=40)
    finally:
        signal.signal(signal.SIGINT, previous)
    assert "KeyboardInterrupt" in err, err
    assert after < 2.0, f"the child went on {after:.1f} s after Ctrl-C"


def test_ctrl_c_stops_a_long_stress_section():
    # 20,000 depths of an XZ section under the Fig. 3 pressure take tens of seconds;
    # they are computed a few at a time, and Ctrl-C stops them between two.
    script = f"""
import numpy as np
import thirdbody
solution = thirdbody.solve(thirdbody.Case.from_file({str(ROOT / "examples" / "paper_fig3.toml")!r}))
print("started", flush=True)
solution.stresses("xz", depths=np.linspace(0.0, 0.05, 20000))
print("finished", flush=True)
"""
    err, after = _interrupted(script, 1.0)
    assert "KeyboardInterrupt" in err, err
    assert after < 1.5, f"the stresses went on {after:.1f} s after Ctrl-C"


def test_ctrl_c_stops_a_solves_stress_section():
    # The Fig. 3 solve on 256 x 256 takes about a second, its XZ section of 4096
    # depths (the most a [stress] section may ask) several seconds more on 2 cores
    # (on 128 x 128 both ended within 1.5 s on a quiet machine, before the signal).
    script = f"""
import thirdbody
case = thirdbody.Case.from_file({str(ROOT / "examples" / "paper_fig3.toml")!r}).with_(
    {{"grid.cells": [256, 256], "stress.sections": ["xz"], "stress.depth_points": 4096}})
print("started", flush=True)
thirdbody.solve(case)
print("finished", flush=True)
"""
    err, after = _interrupted(script, 1.5)
    assert "KeyboardInterrupt" in err, err
    assert after < 1.5, f"the stresses went on {after:.1f} s after Ctrl-C"


def test_ctrl_c_stops_a_long_solve():
    # Hertz at 1024 x 1024 takes several seconds; Ctrl-C after 1 s stops it at once.
    script = f"""
import thirdbody
case = thirdbody.Case.from_file({str(ROOT / "examples" / "hertz.toml")!r}).with_(grid__cells=[1024, 1024])
print("started", flush=True)
thirdbody.solve(case)
print("finished", flush=True)
"""
    err, after = _interrupted(script, 1.0)
    assert "KeyboardInterrupt" in err, err
    assert after < 2.0, f"the solve went on {after:.1f} s after Ctrl-C"


def test_ctrl_c_stops_a_sweep():
    script = f"""
import thirdbody
case = thirdbody.Case.from_file({str(ROOT / "examples" / "paper_fig3.toml")!r})
print("started", flush=True)
thirdbody.sweep(case, {{"loading.velocity": "1e-4..1e-1:400"}})
print("finished", flush=True)
"""
    err, after = _interrupted(script, 1.5)
    assert "KeyboardInterrupt" in err, err
    assert after < 3.0, f"the sweep went on {after:.1f} s after Ctrl-C"


def _cli_results(tmp_path, case_path, *vary):
    import pandas as pd

    out = tmp_path / "cli_sweep"
    args = ["sweep", case_path, "--out", out, "--quiet"]
    for v in vary:
        args += ["--vary", v]
    run = cli(*args)
    assert run.returncode == 0, run.stderr
    return pd.read_csv(out / "results.csv")


def test_a_sweep_gives_the_rows_of_the_cli_results_csv(tmp_path):
    import pandas as pd

    study = ROOT / "examples" / "sweeps" / "paper_fig8.toml"
    table = thirdbody.sweep(thirdbody.Case.from_file(study))
    pd.testing.assert_frame_equal(table, _cli_results(tmp_path, study), check_exact=True)
    assert len(table) == 32 and (table["status"] == "ok").all()


def test_a_sweep_of_lists_on_a_process_pool_equals_the_cli(tmp_path):
    import concurrent.futures
    import pandas as pd

    example = ROOT / "examples" / "hertz.toml"
    case = thirdbody.Case.from_file(example).with_(grid__cells=[32, 32])
    case_path = tmp_path / "case.toml"
    case_path.write_text(case.toml)
    with concurrent.futures.ProcessPoolExecutor(2) as pool:
        table = thirdbody.sweep(
            case,
            {"loading.normal_load": [1e-6, 5e-6], "substrate.poisson": "0.2,0.3"},
            executor=pool,
        )
    want = _cli_results(tmp_path, case_path, "loading.normal_load=1e-6,5e-6",
                        "substrate.poisson=0.2,0.3")
    pd.testing.assert_frame_equal(table, want, check_exact=True)
    assert list(table.columns[:3]) == ["case", "loading.normal_load", "substrate.poisson"]


def test_a_failed_case_is_a_failed_row_and_a_bad_vary_is_a_value_error(tmp_path):
    case = thirdbody.Case.from_file(ROOT / "examples" / "hertz.toml").with_(grid__cells=[32, 32])
    with pytest.raises(ValueError, match="substrate.poisson"):
        thirdbody.sweep(case, {"substrate.poisson": [0.3, 0.7]})
    with pytest.raises(ValueError, match="velocity"):
        thirdbody.sweep(case, {"loading.velocity": "1e-3..x:3"})
    with pytest.raises(ValueError, match="nothing is varied"):
        thirdbody.sweep(case, {})
    # A fixed window too small for the larger load: that case fails, the other not.
    small = case.with_(grid__half_width=[0.006, 0.006])
    table = thirdbody.sweep(small, {"loading.normal_load": [1e-9, 5e-6]})
    assert list(table["status"]) == ["ok", "failed"]
    assert "edge of the window" in table["error"][1]


def test_a_dask_local_cluster_sweep_equals_the_cli(tmp_path):
    import pandas as pd

    distributed = pytest.importorskip("distributed")
    study = ROOT / "examples" / "sweeps" / "paper_fig8.toml"
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster:
        with distributed.Client(cluster) as client:
            table = thirdbody.sweep(thirdbody.Case.from_file(study),
                                    executor=client.get_executor())
    pd.testing.assert_frame_equal(table, _cli_results(tmp_path, study), check_exact=True)


def test_to_xarray_has_the_case_units_and_attributes_and_round_trips_netcdf(tmp_path):
    xarray = pytest.importorskip("xarray")
    case = thirdbody.Case.from_file(ROOT / "examples" / "ellipsoid_si.toml")
    solution = thirdbody.solve(case)
    data = solution.to_xarray()
    assert np.array_equal(data["pressure"].values, solution.pressure)
    assert np.array_equal(data["x"].values, solution.x)
    assert data["x"].attrs["units"] == "m" and data["pressure"].attrs["units"] == "Pa"
    assert data.attrs["case_hash"] == case.case_hash
    assert data.attrs["friction_coefficient"] == solution.summary["friction_coefficient"]
    assert thirdbody.Case.from_toml(data.attrs["case"]).case_hash == case.case_hash
    path = tmp_path / "solution.nc"
    data.to_netcdf(path)
    back = xarray.load_dataset(path)
    assert np.array_equal(back["pressure"].values, solution.pressure)
    assert back.attrs["case"] == case.toml
    dimensionless = thirdbody.solve(thirdbody.Case.from_file(ROOT / "examples" / "paper_fig3.toml"))
    data = dimensionless.to_xarray()
    assert data["x"].attrs["units"] == "1"
    assert np.array_equal(data["compliance"].values, dimensionless.compliance)


def test_the_thirdbody_command_comes_with_the_package(tmp_path):
    import shutil
    import sys

    script = shutil.which("thirdbody", path=str(pathlib.Path(sys.executable).parent))
    assert script, "pip install put no thirdbody script beside the interpreter"
    ran = subprocess.run([script, "cite"], capture_output=True, text=True)
    assert ran.returncode == 0 and ran.stdout == cli("cite").stdout
    bad = tmp_path / "bad.toml"
    bad.write_text((ROOT / "examples" / "hertz.toml").read_text().replace("radius = 1.0", "radius = 0"))
    ran = subprocess.run([script, "solve", bad, "--out", tmp_path / "out"], capture_output=True,
                         text=True)
    want = cli("solve", bad, "--out", tmp_path / "out2")
    assert (ran.returncode, ran.stderr) == (want.returncode, want.stderr) == (2, want.stderr)
    ran = subprocess.run([script, "solve", ROOT / "examples" / "hertz.toml", "--out",
                          tmp_path / "ok", "--format", "npy"], capture_output=True, text=True)
    assert ran.returncode == 0, ran.stderr
    assert np.array_equal(np.load(tmp_path / "ok" / "pressure.npy"),
                          thirdbody.solve(thirdbody.Case.from_file(ROOT / "examples" / "hertz.toml")).pressure)


def _rss_bytes():
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * os.sysconf("SC_PAGE_SIZE")


@pytest.mark.skipif(not pathlib.Path("/proc/self/statm").exists(), reason="needs Linux /proc")
def test_a_thousand_small_solves_leave_memory_flat():
    case = thirdbody.Case.from_file(ROOT / "examples" / "hertz.toml").with_(grid__cells=[32, 32])
    for _ in range(200):
        thirdbody.solve(case).pressure
    before = _rss_bytes()
    for _ in range(1000):
        solution = thirdbody.solve(case)
        solution.pressure, solution.summary
    grown = _rss_bytes() - before
    # One 32 x 32 solve holds ~100 kB; a leak of it per solve would be ~100 MB.
    assert grown < 8 << 20, f"resident memory grew {grown / 2**20:.1f} MiB over 1000 solves"


def test_a_height_map_case_keeps_its_folder_when_the_working_directory_changes(tmp_path,
                                                                              monkeypatch):
    import pickle

    # A paraboloid of radius 1 on 201 x 201 nodes 2.5e-4 apart (finer than the
    # contact's 0.015 radius; a coarser map's bilinear kinks raise the peak pressure).
    s = (np.arange(201) - 100) * 2.5e-4
    heights = (s[None, :] ** 2 + s[:, None] ** 2) / 2.0
    folder = tmp_path / "study"
    folder.mkdir()
    np.save(folder / "map.npy", heights)
    text = (ROOT / "examples" / "hertz.toml").read_text()
    text = text.replace('shape = "sphere"\nradius = 1.0',
                        'shape = "height_map"\nfile = "map.npy"\ncell_size = 2.5e-4')
    (folder / "case.toml").write_text(text)
    monkeypatch.chdir(folder)
    case = thirdbody.Case.from_file("case.toml")     # relative, as a user types it
    monkeypatch.chdir(tmp_path)                      # a worker started elsewhere
    again = pickle.loads(pickle.dumps(case))
    sphere = thirdbody.solve(thirdbody.Case.from_file(ROOT / "examples" / "hertz.toml"))
    mapped = thirdbody.solve(again).summary
    # The sphere's own solve; Hertz's D = 2.267e-4 (examples/hertz.toml) as well.
    assert math.isclose(mapped["penetration"], sphere.summary["penetration"], rel_tol=1e-3)
    assert math.isclose(mapped["max_pressure"], sphere.summary["max_pressure"], rel_tol=2e-3)


def test_a_stack_from_sections_its_layer_varied_and_its_interfaces():
    # The three-layer example built from Python dicts ([[body.layers]] is a list of
    # dicts), one layer varied by its indexed key, and every interface's stresses by
    # index: sigma_z is continuous across each, sigma_x is not.
    import tomllib

    text = (ROOT / "examples" / "three_layer_coating.toml").read_text()
    text = text.replace("cells = [128, 128]", "cells = [48, 48]")
    sections = tomllib.loads(text)
    assert len(sections["body"]["layers"]) == 3
    case = thirdbody.Case(**sections)
    assert case.case_hash == thirdbody.Case.from_toml(text).case_hash
    thicker = case.with_({"body.layers[1].thickness": 0.004})
    assert thicker.case_hash != case.case_hash
    solution = thirdbody.solve(case)
    stress = solution.summary["stress"]
    assert [i["index"] for i in stress["interfaces"]] == [0, 1, 2]
    assert [l["index"] for l in stress["layers"]] == [0, 1, 2, 3] and stress["layers"][3]["base"]
    for index in range(3):
        above = solution.stresses("interface", interface=index, side="above")
        below = solution.stresses("interface", interface=index, side="below")
        peak = np.abs(above["sigma_z"]).max()
        assert np.abs(above["sigma_z"] - below["sigma_z"]).max() < 1e-8 * peak
        assert np.abs(above["sigma_x"] - below["sigma_x"]).max() > 1e-3 * peak
    with pytest.raises(ValueError, match="stress.interface"):
        solution.stresses("interface", interface=3)
    with pytest.raises(ValueError, match="side"):
        solution.stresses("interface", side="middle")


def test_a_viscoelastic_body_from_sections_varied_solved_and_its_errors():
    # A Zener half-space (no layer) from Python dicts: the body creeps, so the solver
    # is Newton and mu > 0; a slower speed (creep length far below the contact)
    # gives the relaxed body's Hertz approach, and a bad modulus names its key.
    sections = dict(
        slider={"shape": "sphere", "radius": 1.0},
        substrate={"rheology": "zener", "glassy_modulus": 10.0, "relaxed_modulus": 1.0,
                   "relaxation_time": 1.0, "poisson": 0.0},
        loading={"normal_load": 4.0 * 0.05**3 / 3.0, "velocity": 0.005},
        grid={"cells": [48, 48]},
    )
    case = thirdbody.Case(**sections)
    solution = thirdbody.solve(case)
    assert solution.summary["method"] == "semismooth_newton"
    # The standard linear solid's peak, 0.40 a0 / R near V tau / a0 = 0.1 (a0 = 0.05).
    assert 0.35 * 0.05 < solution.summary["friction_coefficient"] < 0.42 * 0.05
    relaxed = thirdbody.solve(case.with_({"loading.velocity": 1e-9})).summary
    assert math.isclose(relaxed["penetration"], 0.05**2, rel_tol=5e-3)   # Hertz, E0* = 1
    assert relaxed["friction_coefficient"] < 1e-3 * solution.summary["friction_coefficient"]
    xz = solution.stresses("xz", depths=[0.01, 0.02, 0.04])
    assert np.isfinite(xz["sigma_z"]).all() and xz["sigma_z"].min() < 0
    with pytest.raises(ValueError, match="substrate.glassy_modulus"):
        case.with_({"substrate.glassy_modulus": 0.5})
