"""Benchmarks of the Python package (issue 12, acceptance 4 and 5); prints medians.

    python crates/thirdbody-py/bench/bench_python.py [--repeats N]

1. Overhead: the paper's Fig. 3 case at 128 x 128 solved through ``thirdbody.solve``.
   The wall time of the Python call is set against ``solve_seconds``, the time the
   Rust solve (kernel set-up and solve) took inside that same call, so the ratio is
   what the binding adds: the thread, the pool, the report and the arrays.
2. Dask: the Fig. 8 study (32 cases at 128 x 128) through ``thirdbody.sweep`` on a
   ``distributed.LocalCluster`` with one worker and with two (one thread each): the
   medians and the speed-up of two over one.

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
                                      dashboard_address=None) as cluster:
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


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=21)
    args = parser.parse_args()
    print(f"thirdbody {thirdbody.__version__}, {os.cpu_count()} cores, "
          f"load average {os.getloadavg()[0]:.2f} at the start")
    overhead(args.repeats)
    dask_speedup(max(3, args.repeats // 4))
    print(f"load average {os.getloadavg()[0]:.2f} at the end")


if __name__ == "__main__":
    main()
