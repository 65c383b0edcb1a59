"""contopt: elastic contact analysis and contact-pressure optimisation (Páczelt 1994).

Scenes (``Scene``) are read from a file, TOML text, a dict or a bundled name and run with the
GIL released into a ``Report`` with the names and units of ``result.json``; below them a
half-space grid (``HalfSpace``), a rigid indenter from a numpy gap (``Contact``) and every
contact solver (``Solver``). Lengths in mm, moduli and pressures in MPa, forces in N (scene
results name their units: ``p_mpa``, ``dh_um``).
"""

from ._contopt import (
    CaseResult,
    Contact,
    HalfSpace,
    InputError,
    Optimum,
    Progress,
    Report,
    Scene,
    SceneError,
    Solution,
    Solver,
    Termination,
    __version__,
    optimise,
)

__all__ = [
    "CaseResult",
    "Contact",
    "HalfSpace",
    "InputError",
    "Optimum",
    "Progress",
    "Report",
    "Scene",
    "SceneError",
    "Solution",
    "Solver",
    "Termination",
    "__version__",
    "optimise",
]
