"""Type stubs of the compiled module ``thirdbody._thirdbody`` (crates/thirdbody-py/src/lib.rs)."""

from os import PathLike
from pathlib import Path
from typing import Any, Callable, Dict, List, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

_Path = Union[str, "PathLike[str]"]
_Array = npt.NDArray[np.float64]
_Depths = Union[Sequence[float], npt.NDArray[np.floating[Any]]]

__version__: str

class Case:
    """A contact case, exactly as a case file gives it. Immutable: ``with_`` derives
    variants. Picklable (its text, height-map folder and heights array, if any)."""

    def __new__(cls, sections: Optional[Dict[str, Any]] = None, **kwargs: Any) -> "Case":
        """A case from its sections as one dict and/or keyword arguments, mirroring
        the case file: ``Case(slider={"shape": "sphere", "radius": 1.0}, ...)``.
        Integers may be numpy's (``np.int64``, ``np.array([128, 128])``). A height
        map may be an array instead of a file: ``slider={"shape": "height_map",
        "heights": array, "cell_size": h}`` (shape ``(ny, nx)``, rows along y; the
        text then reads ``file = "<array>"``). Raises ``ValueError`` as the case-file
        parser does."""
    @staticmethod
    def from_toml(text: str, base_dir: Optional[_Path] = None) -> "Case":
        """A case from a case file's text; relative height-map paths are read from
        ``base_dir`` (default: the working directory). A ``[sweep]`` section is set
        aside."""
    @staticmethod
    def from_file(path: _Path) -> "Case":
        """A case from a TOML case file (height maps read beside it)."""
    def with_(self, changes: Optional[Dict[str, Any]] = None, **kwargs: Any) -> "Case":
        """A variant with dotted keys changed (``{"loading.velocity": 1e-2}``, or
        ``loading__velocity=1e-2``); ``None`` removes a key; ``"slider.heights"``
        takes an array of heights."""
    @property
    def toml(self) -> str:
        """The case file's text this case was parsed from."""
    @property
    def cells(self) -> Tuple[int, ...]:
        """The grid's cell counts as the fields' shape: ``(nx, ny)``, or ``(nx,)`` for a
        line contact."""
    @property
    def case_hash(self) -> str:
        """SHA-256 of the canonical case (``case_hash`` of summary.json)."""
    def __reduce__(
        self,
    ) -> Tuple[Callable[..., "Case"], Tuple[str, Path, Optional[_Array]]]: ...
    @staticmethod
    def _rebuild(text: str, base: _Path, heights: Optional[Any]) -> "Case":
        """The case ``__reduce__`` describes: its text, height-map folder and heights
        given as an array, if any."""

class Solution:
    """A solved contact; made by :func:`solve`. Arrays are read-only, shape ``(ny, nx)``,
    or ``(nx,)`` for a line contact (plane strain; its summary has no y keys, its
    loads and forces are per unit length)."""

    @property
    def summary(self) -> Dict[str, Any]:
        """The keys and values of ``summary.json``."""
    @property
    def pressure(self) -> _Array:
        """Contact pressure: each cell's mean (what its load is), as ``pressure.npy``."""
    @property
    def gap(self) -> _Array:
        """Gap between slider and deformed surface."""
    @property
    def body_displacement(self) -> _Array:
        """Elastic body's surface displacement."""
    @property
    def layer_displacement(self) -> Optional[_Array]:
        """Layer's displacement (``None`` without a layer)."""
    @property
    def compliance(self) -> Optional[_Array]:
        """Layer's compliance ``C[p]`` (``None`` without a layer)."""
    @property
    def x(self) -> _Array:
        """x of the cell centres, shape ``(nx,)``."""
    @property
    def y(self) -> Optional[_Array]:
        """y of the cell centres, shape ``(ny,)``; ``None`` for a line contact."""
    @property
    def is_line(self) -> bool:
        """Whether this is a line contact (fields of shape ``(nx,)``)."""
    def stresses(
        self,
        section: str,
        *,
        y: float = 0.0,
        z: float = 0.0,
        depths: Optional[_Depths] = None,
        side: str = "coating",
    ) -> Dict[str, _Array]:
        """Subsurface stresses on one section: ``"xz"`` (plane ``y``, at ``depths``),
        ``"surface"``, ``"plane"`` (depth ``z``), ``"block"`` (at ``depths``) or
        ``"interface"`` (``side`` = ``"coating"`` or ``"substrate"``). Keys ``x``,
        ``y``, ``z`` (1-D) and ``sigma_x, sigma_y, sigma_z, tau_xy, tau_xz, tau_yz,
        s1, s2, s3, tau1, von_mises``, each of shape ``(len(z), len(y), len(x))``.
        ``NotEnoughMemoryError`` before anything starts when the results (88 bytes
        a point) exceed the memory available; Ctrl-C stops it
        (``KeyboardInterrupt``)."""
    def case_stresses(self) -> Dict[str, Dict[str, _Array]]:
        """The sections of the case's ``[stress]`` section, by name (as the CLI's
        file names), each a dict as :meth:`stresses` returns. ``ValueError`` without
        a ``[stress]`` section or after ``solve(..., stresses=False)``."""
    def to_xarray(self) -> Any:
        """The solution as an ``xarray.Dataset`` (needs xarray) on dims ``(y, x)``,
        or ``(x,)`` for a line contact; the summary's scalars and its ``warnings``
        (one string, a line each) are attributes."""

def solve(
    case: Case,
    progress: Optional[Callable[[Dict[str, Any]], object]] = None,
    *,
    stresses: bool = True,
) -> Solution:
    """Solves ``case`` without the GIL. ``progress`` gets dicts with ``event`` =
    ``"window"`` (``window``, ``cells``, ``half_width``) or ``"iteration"``
    (``window``, ``iteration``, ``residual``). Ctrl-C (in the solve or its
    stresses) raises ``KeyboardInterrupt``. With ``stresses``, the case's
    ``[stress]`` section is computed too. The
    summary's ``warnings`` are also given to ``warnings.warn`` as
    :class:`thirdbody.ThirdbodyWarning`. Kernels are built for this call: see
    :class:`Solver`. ``NotEnoughMemoryError`` when the case cannot fit."""

class Solver:
    """A solver that keeps the DC-FFT plans and surface kernels it builds (one per
    body, grid size and cell size; a coated kernel costs 0.1 to 6 s at 256²) for its
    later solves. One solve at a time: another thread's call waits (give each
    thread its own)."""

    def __new__(cls, capacity: int = 8) -> "Solver":
        """An empty solver keeping up to ``capacity`` kernels (and 256 MiB)."""
    def solve(
        self,
        case: Case,
        progress: Optional[Callable[[Dict[str, Any]], object]] = None,
        *,
        stresses: bool = True,
    ) -> Solution:
        """As :func:`solve`, with this solver's kernels."""
    @property
    def kernels_built(self) -> int:
        """Surface kernels built since the solver was made."""
    @property
    def kernels_reused(self) -> int:
        """Surface kernels handed out again without building them."""
    @property
    def kernels_held(self) -> int:
        """Surface kernels held now."""
    def clear(self) -> None:
        """Drops every kernel and plan held."""
    def _solve_record(self, text: str, base: _Path, id: str, index: int,
                      labels: Sequence[str]) -> str:
        """Solves one sweep case on one thread, as ``thirdbody sweep`` does, with this
        solver's kernels; its record as JSON (a failure is a ``failed`` record)."""

def cite() -> str:
    """The works the computations rely on, as BibTeX (``thirdbody cite``)."""

class SweepPlan:
    """The cases of a sweep (the product of ``thirdbody sweep``, with its ids and
    labels) and the assembly of its ``results.csv``; used by ``thirdbody.sweep``."""

    def __new__(cls, case: Case, vary: Dict[str, Any]) -> "SweepPlan":
        """The product of ``vary`` (dotted key -> list of values, or a string in the
        ``--vary`` syntax) over ``case``; every case is checked (``ValueError``)."""
    def __len__(self) -> int: ...
    @property
    def axes(self) -> List[str]:
        """The varied keys, in order."""
    def job(self, index: int) -> Tuple[str, Path, str, int, List[str]]:
        """The arguments of :meth:`Solver._solve_record` for case ``index``: case
        text, height-map folder, id, index, labels."""
    def results_csv(self, records: Sequence[str]) -> bytes:
        """The bytes of ``results.csv`` from the JSON records of
        :meth:`Solver._solve_record`."""

def _command_line(args: Sequence[str]) -> int:
    """Runs the ``thirdbody`` command line (program name first); its exit code."""
