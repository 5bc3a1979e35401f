"""Benchmarks of the Python package; prints medians.

    python crates/thirdbody-py/bench/bench_python.py [--repeats N]

1. Overhead: the paper's Fig. 3 case at 128 x 128 solved through ``thirdbody.solve``.
   The wall time of the Python call is set against ``solve_seconds``, the time the
   Rust solve (kernel set-up and solve) took inside that same call, so the ratio is
   what the binding adds: the thread, the pool, the report and the arrays.
2. Dask: the Fig. 8 study (32 cases at 128 x 128) through ``thirdbody.sweep`` on a
   ``distributed.LocalCluster`` with one worker and with two (one thread each): the
   medians and the speed-up of two over one.
3. Kept kernels: 20 solves of the thin-coating case (Fig. 12a) at 256 x 256 on a
   fixed window, each with another load, through one ``thirdbody.Solver`` and through
   ``thirdbody.solve`` (a kernel built per call): the medians of the 20 solves' wall
   time and the ratio.

Run it with nothing else on the machine; it prints the load average with the numbers.
"""

import argparse
import os
import pathlib
import statistics
import time

import thirdbody

ROOT = pathlib.Path(__file__).resolve().parents[3]


def overhead(repeats):
    case = thirdbody.Case.from_file(ROOT / "examples" / "paper_fig3.toml")
    assert case.cells == (128, 128)
    thirdbody.solve(case)  # warm-up: page in the library, first allocations
    walls, inner = [], []
    for _ in range(repeats):
        start = time.perf_counter()
        solution = thirdbody.solve(case)
        walls.append(time.perf_counter() - start)
        inner.append(solution.summary["solve_seconds"])
    wall, rust = statistics.median(walls), statistics.median(inner)
    print(f"Fig. 3, 128 x 128, {repeats} solves: Python call median {wall * 1e3:.1f} ms, "
          f"Rust solve inside it {rust * 1e3:.1f} ms, ratio {wall / rust:.3f}")
    return wall / rust


def dask_speedup(repeats):
    import distributed

    study = thirdbody.Case.from_file(ROOT / "examples" / "sweeps" / "paper_fig8.toml")
    medians = {}
    for workers in (1, 2):
        with distributed.LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                                      dashboard_address="127.0.0.1:0",
                                      scheduler_kwargs={"dashboard": False}) as cluster:
            with distributed.Client(cluster) as client:
                # pure=False: time the solves, not the results Dask keeps for equal tasks.
                executor = client.get_executor(pure=False)
                thirdbody.sweep(study, executor=executor)  # warm-up: import in workers
                times = []
                for _ in range(repeats):
                    start = time.perf_counter()
                    table = thirdbody.sweep(study, executor=executor)
                    times.append(time.perf_counter() - start)
                    assert (table["status"] == "ok").all()
        medians[workers] = statistics.median(times)
        print(f"Fig. 8 study ({len(table)} cases) on a LocalCluster of {workers} worker(s): "
              f"median {medians[workers]:.2f} s over {repeats} runs")
    ratio = medians[1] / medians[2]
    print(f"speed-up of 2 workers over 1: {ratio:.2f}x")
    return ratio


def kept_kernels(repeats):
    case = thirdbody.Case.from_file(ROOT / "examples" / "paper_fig12a_thin_coating.toml").with_(
        {"grid.cells": [256, 256], "grid.half_width": [0.07, 0.07], "grid.centre": [0.02, 0.0]})
    loads = [3e-6 + 2e-7 * k for k in range(20)]
    variants = [case.with_(loading__normal_load=q) for q in loads]

    def fresh():
        for v in variants:
            thirdbody.solve(v, stresses=False)

    def kept():
        solver = thirdbody.Solver()
        for v in variants:
            solver.solve(v, stresses=False)
        assert solver.kernels_built == 1

    medians = {}
    for name, run in (("thirdbody.solve", fresh), ("one Solver", kept)):
        times = []
        for _ in range(repeats):
            start = time.perf_counter()
            run()
            times.append(time.perf_counter() - start)
        medians[name] = statistics.median(times)
        print(f"20 loads, thin coating, 256 x 256, {name}: median {medians[name]:.2f} s "
              f"over {repeats} runs")
    ratio = medians["thirdbody.solve"] / medians["one Solver"]
    print(f"one Solver is {ratio:.2f}x faster")
    return ratio


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=21)
    parser.add_argument("--only", choices=["overhead", "dask", "kernels"],
                        help="run one benchmark only")
    args = parser.parse_args()
    print(f"thirdbody {thirdbody.__version__}, {os.cpu_count()} cores, "
          f"load average {os.getloadavg()[0]:.2f} at the start")
    if args.only in (None, "overhead"):
        overhead(args.repeats)
    if args.only in (None, "dask"):
        dask_speedup(max(3, args.repeats // 4))
    if args.only in (None, "kernels"):
        kept_kernels(max(3, args.repeats // 4))
    print(f"load average {os.getloadavg()[0]:.2f} at the end")


if __name__ == "__main__":
    main()
