"""Types of contopt's extension module. Lengths in mm, moduli and pressures in MPa, forces in
N; a scene's results name their units (``p_mpa``, ``dh_um``, ``approach_um``)."""

from collections.abc import Callable, Mapping
from os import PathLike
from typing import Any, Literal, Optional, Union

from typing_extensions import final

import numpy as np
import numpy.typing as npt

__version__: str
__all__ = [
    "CaseResult",
    "Contact",
    "DenseBody",
    "HalfSpace",
    "InputError",
    "Optimum",
    "Progress",
    "Registry",
    "Report",
    "Scene",
    "SceneError",
    "Solution",
    "Solver",
    "Termination",
    "__version__",
    "optimise",
    "solve_in_rust",
]

_FloatArray = npt.NDArray[np.float64]
_ArrayLike = npt.ArrayLike
_Path = Union[str, PathLike[str]]

class SceneError(ValueError):
    """A scene that cannot be read, checked or run, with its place."""

    file: str
    line: Optional[int]
    column: Optional[int]
    case: Optional[str]
    key: str
    value: Optional[str]
    allowed: str
    message: str

class InputError(ValueError):
    """Bad input to the library: the argument or field, its value, what it must be."""

    key: Optional[str]
    value: Optional[str]
    allowed: str

@final
class Termination:
    """How a method ended: ``kind`` as in result.json's ``termination``."""

    @property
    def kind(self) -> str: ...
    @property
    def converged(self) -> bool: ...
    @property
    def details(self) -> dict[str, Any]: ...
    @property
    def message(self) -> str: ...
    def __eq__(self, value: object, /) -> bool: ...

@final
class Progress:
    """What a progress callback is given."""

    @property
    def cases_done(self) -> int: ...
    @property
    def cases(self) -> int: ...
    @property
    def method(self) -> Optional[str]: ...
    @property
    def level(self) -> int: ...
    @property
    def iteration(self) -> int: ...

@final
class HalfSpace:
    """An elastic half-space under nx × ny cells of dx × dy mm; arrays have shape (ny, nx)."""

    def __new__(
        cls,
        *,
        nx: int,
        ny: int,
        dx_mm: float,
        dy_mm: float,
        e_mpa: float,
        nu: float,
        origin_mm: Optional[tuple[float, float]] = None,
        periodic: bool = False,
    ) -> HalfSpace: ...
    @property
    def shape(self) -> tuple[int, int]: ...
    @property
    def x_mm(self) -> _FloatArray: ...
    @property
    def y_mm(self) -> _FloatArray: ...
    @property
    def cell_mm(self) -> tuple[float, float]: ...
    @property
    def origin_mm(self) -> tuple[float, float]: ...
    @property
    def cell_area_mm2(self) -> float: ...
    @property
    def e_mpa(self) -> float: ...
    @property
    def nu(self) -> float: ...
    @property
    def periodic(self) -> bool: ...

@final
class DenseBody:
    """A body under nx × ny cells whose compliance [mm/N] is a symmetric positive definite
    (nx·ny) × (nx·ny) matrix: entry [i, j] the displacement at cell i (C order of the (ny, nx)
    arrays) under a unit compressive force on cell j."""

    def __new__(
        cls,
        compliance_mm_per_n: _ArrayLike,
        *,
        nx: int,
        ny: int,
        dx_mm: float,
        dy_mm: float,
        origin_mm: Optional[tuple[float, float]] = None,
    ) -> DenseBody: ...
    @property
    def shape(self) -> tuple[int, int]: ...
    @property
    def cell_area_mm2(self) -> float: ...

_Factory = Callable[[dict[str, Any], _FloatArray, _FloatArray], _ArrayLike]

@final
class Registry:
    """The kinds a scene may name: the library's, and body kinds added from Python."""

    @staticmethod
    def standard() -> Registry: ...
    def kinds(self) -> dict[str, list[str]]: ...
    def add_body(self, name: str, factory: _Factory) -> None: ...

@final
class Contact:
    """A rigid indenter on a half-space grid or a dense body, its shape the gap h [mm], shape
    (ny, nx)."""

    def __new__(
        cls,
        body: Union[HalfSpace, DenseBody],
        gap_mm: _ArrayLike,
        *,
        force_n: Optional[float] = None,
        approach_mm: Optional[float] = None,
        indenter_ends: Optional[Literal["x", "y", "xy"]] = None,
    ) -> Contact: ...
    @property
    def shape(self) -> tuple[int, int]: ...

def solve_in_rust(solver: Solver, contact: Contact) -> float:
    """The same solve as ``solver.solve(contact)``, on this thread, nothing converted: its
    time in Rust [s] (what the binding adds is the difference)."""

@final
class Solution:
    """A solve's answer; arrays of shape (ny, nx)."""

    @property
    def pressure_mpa(self) -> _FloatArray: ...
    @property
    def gap_mm(self) -> _FloatArray: ...
    @property
    def contact(self) -> npt.NDArray[np.bool_]: ...
    @property
    def approach_mm(self) -> Optional[float]: ...
    @property
    def force_n(self) -> float: ...
    @property
    def contact_area_mm2(self) -> float: ...
    @property
    def p_max_mpa(self) -> float: ...
    @property
    def termination(self) -> Termination: ...
    @property
    def converged(self) -> bool: ...
    @property
    def seconds(self) -> float: ...
    @property
    def iterations(self) -> int: ...
    @property
    def method(self) -> str: ...
    @property
    def warnings(self) -> list[str]: ...
    @property
    def residuals(self) -> dict[str, float]: ...

@final
class Solver:
    """A contact solver and its settings (defaults: ``Solver.defaults(kind)``)."""

    def __new__(cls, kind: str = "auto", **settings: Any) -> Solver: ...
    @staticmethod
    def kinds() -> list[str]: ...
    @staticmethod
    def defaults(kind: str) -> dict[str, Any]: ...
    @property
    def kind(self) -> str: ...
    @property
    def settings(self) -> dict[str, Any]: ...
    def solve(self, contact: Contact, *, start_mpa: Optional[_ArrayLike] = None) -> Solution: ...

@final
class CaseResult:
    """One case of result.json; interface fields of shape (n,), points (n, 3)."""

    @property
    def label(self) -> str: ...
    @property
    def solved(self) -> bool: ...
    @property
    def termination(self) -> Termination: ...
    @property
    def x_mm(self) -> _FloatArray: ...
    @property
    def p_mpa(self) -> _FloatArray: ...
    @property
    def d_um(self) -> _FloatArray: ...
    @property
    def dh_um(self) -> _FloatArray: ...
    @property
    def h_um(self) -> _FloatArray: ...
    def to_dict(self) -> dict[str, Any]: ...
    def __getattr__(self, name: str) -> Any: ...

@final
class Report:
    """result.json's report; ``to_json()`` is ``contopt run --json``'s output."""

    @property
    def scene(self) -> str: ...
    @property
    def description(self) -> str: ...
    @property
    def schema_version(self) -> int: ...
    @property
    def cases(self) -> list[CaseResult]: ...
    @property
    def solved(self) -> bool: ...
    def to_json(self) -> str: ...
    def to_dict(self) -> dict[str, Any]: ...
    def write(self, out: _Path = "results") -> str: ...
    def __len__(self) -> int: ...

@final
class Scene:
    """A scene, its cases read and checked."""

    @staticmethod
    def from_file(path: _Path, *, registry: Optional[Registry] = None) -> Scene: ...
    @staticmethod
    def from_toml(
        text: str,
        *,
        edits: Optional[Mapping[str, Any]] = None,
        file: _Path = "scene.toml",
        registry: Optional[Registry] = None,
    ) -> Scene: ...
    @staticmethod
    def from_dict(
        data: Mapping[str, Any], *, file: _Path = "<dict>", registry: Optional[Registry] = None
    ) -> Scene: ...
    @staticmethod
    def bundled(name: str, *, edits: Optional[Mapping[str, Any]] = None) -> Scene: ...
    @staticmethod
    def bundled_names() -> list[str]: ...
    @staticmethod
    def bundled_text(name: str) -> str: ...
    @property
    def name(self) -> str: ...
    @property
    def description(self) -> str: ...
    @property
    def file(self) -> str: ...
    @property
    def cases(self) -> list[str]: ...
    def check(self) -> list[dict[str, Any]]: ...
    def run(
        self, *, threads: int = 1, progress: Optional[Callable[[Progress], object]] = None
    ) -> Report: ...

@final
class Optimum:
    """An optimisation's answer; arrays of shape (ny, nx), ``dh_mm`` per design node."""

    @property
    def p_max_mpa(self) -> float: ...
    @property
    def dh_mm(self) -> _FloatArray: ...
    @property
    def dh_max_mm(self) -> float: ...
    @property
    def gap_change_mm(self) -> _FloatArray: ...
    @property
    def pressure_mpa(self) -> _FloatArray: ...
    @property
    def gap_mm(self) -> _FloatArray: ...
    @property
    def passes(self) -> int: ...
    @property
    def method(self) -> str: ...
    @property
    def termination(self) -> Termination: ...
    @property
    def converged(self) -> bool: ...
    @property
    def warnings(self) -> list[str]: ...
    @staticmethod
    def defaults(kind: str) -> dict[str, Any]: ...

def optimise(
    contact: Contact,
    v: _ArrayLike,
    *,
    method: str = "load_split",
    solver: Optional[Solver] = None,
    gap_shape: Union[None, str, _ArrayLike] = None,
    omega_v: Optional[_ArrayLike] = None,
    omega_opt: Optional[_ArrayLike] = None,
    **settings: Any,
) -> Optimum:
    """The optimum initial gap of ``contact`` under the controller's values ``v`` (ny, nx)."""
