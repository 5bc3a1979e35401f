"""Parameter sweeps from Python: the product of ``thirdbody sweep`` (the same case ids,
labels and validation), solved on any :class:`concurrent.futures.Executor`, gathered
into the rows of ``results.csv`` as a pandas DataFrame.
"""

from __future__ import annotations

import concurrent.futures as cf
import io
import os
import threading
from typing import Any, Callable, Mapping, Optional

from . import _thirdbody

#: Each worker thread's (or process's) own Solver: the cases a worker solves share its
#: kernels (a sweep over loads or velocities on a fixed window builds one), and no
#: two threads share one.
_worker = threading.local()


def _solver() -> "_thirdbody.Solver":
    """The calling thread's Solver, made at its first case."""
    solver = getattr(_worker, "solver", None)
    if solver is None:
        solver = _worker.solver = _thirdbody.Solver()
    return solver


def _solve_job(job):
    """Solves one case of a sweep with the worker's Solver: module-level so that
    process pools and Dask workers can unpickle it by name."""
    return _solver()._solve_record(*job)


def sweep(
    case: "_thirdbody.Case",
    vary: Optional[Mapping[str, Any]] = None,
    executor: Optional[cf.Executor] = None,
    progress: Optional[Callable[[int, int], Any]] = None,
):
    """Solves ``case`` over the Cartesian product of ``vary`` and returns a pandas
    DataFrame with the columns and rows of ``thirdbody sweep``'s ``results.csv``.

    ``vary`` maps dotted case keys to values: a list (``[1e-3, 1e-2]``; ``None``
    removes the key) or a string in the syntax of ``--vary`` (``"1e-3..1e-1:10"``
    for 10 log-spaced values, ``"0..1:5:lin"``). The first key varies slowest. A
    ``[sweep]`` section in the case's text adds its axes and variants, as for the
    CLI (docs/sweeps.md).

    ``executor`` runs the cases: any ``concurrent.futures.Executor`` (a
    ``ProcessPoolExecutor``, a Dask ``distributed`` client's ``get_executor()``);
    by default a thread pool with one thread per core (solves release the GIL). A
    case that fails is a row with ``status`` ``"failed"`` and its ``error``.
    ``progress(done, total)`` is called after each case. Ctrl-C cancels the cases
    not yet started and raises ``KeyboardInterrupt``. Each worker thread keeps one
    :class:`Solver` for the cases it solves (their kernels, up to 256 MiB, live as
    long as the thread).
    """
    try:
        import pandas
    except ImportError as e:  # pragma: no cover - depends on the environment
        raise ImportError("thirdbody.sweep needs pandas: pip install pandas") from e
    plan = _thirdbody.SweepPlan(case, dict(vary or {}))
    total = len(plan)
    own = executor is None
    if own:
        executor = cf.ThreadPoolExecutor(max_workers=os.cpu_count() or 1)
    futures = {}
    try:
        for index in range(total):
            futures[executor.submit(_solve_job, plan.job(index))] = index
        records = [None] * total
        done = 0
        for future in cf.as_completed(futures):
            records[futures[future]] = future.result()
            done += 1
            if progress is not None:
                progress(done, total)
    except BaseException:
        for future in futures:
            future.cancel()
        raise
    finally:
        if own:
            executor.shutdown(wait=False, cancel_futures=True)
    text = plan.results_csv(records)
    return pandas.read_csv(io.BytesIO(text))
