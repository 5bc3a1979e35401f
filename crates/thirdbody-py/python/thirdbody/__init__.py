"""thirdbody: steady sliding contact through a viscoelastic third-body layer.

The same engine as the ``thirdbody`` command-line program (Lubricants 2023, 11, 333)::

    import thirdbody
    case = thirdbody.Case.from_file("examples/paper_fig3.toml")
    solution = thirdbody.solve(case)        # or thirdbody.Solver().solve(case), kernels kept
    solution.summary["friction_coefficient"]
    solution.pressure            # numpy array, shape (ny, nx)
    table = thirdbody.sweep(case, {"loading.velocity": "1e-3..1e-1:5"})

See docs/python.md for the tutorial.
"""

from ._errors import NotEnoughMemoryError, ThirdbodyWarning
from ._thirdbody import Case, Solution, Solver, cite, solve, __version__
from ._sweep import sweep

__all__ = ["Case", "NotEnoughMemoryError", "Solution", "Solver", "ThirdbodyWarning", "cite",
           "solve", "sweep", "__version__"]
