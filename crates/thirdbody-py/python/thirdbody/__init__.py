"""thirdbody: steady sliding contact through a viscoelastic third-body layer.

The same engine as the ``thirdbody`` command-line program (Lubricants 2023, 11, 333)::

    import thirdbody
    case = thirdbody.Case.from_file("examples/paper_fig3.toml")
    solution = thirdbody.solve(case)
    solution.summary["friction_coefficient"]
    solution.pressure            # numpy array, shape (ny, nx)
"""

from ._thirdbody import Case, Solution, cite, solve, __version__

__all__ = ["Case", "Solution", "cite", "solve", "__version__"]
