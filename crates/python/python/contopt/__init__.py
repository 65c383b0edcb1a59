"""contopt: elastic contact analysis and contact-pressure optimisation (Páczelt 1994).

Scenes (``Scene``) are read from a file, TOML text, a dict or a bundled name and run with the
GIL released into a ``Report`` with the names and units of ``result.json``; below them a
half-space grid (``HalfSpace``) or a body given by its compliance matrix (``DenseBody``), a
rigid indenter from a numpy gap (``Contact``) and every contact solver (``Solver``). Body kinds
of one's own are added to a ``Registry`` that scenes are read with. Lengths in mm, moduli and pressures in MPa, forces in N (scene
results name their units: ``p_mpa``, ``dh_um``).
"""

from ._contopt import (
    CaseResult,
    Contact,
    DenseBody,
    HalfSpace,
    InputError,
    Optimum,
    Progress,
    Registry,
    Report,
    Scene,
    SceneError,
    Solution,
    Solver,
    Termination,
    __version__,
    optimise,
    solve_in_rust,
)

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
