"""Single-asperity adhesive contact (Song & Komvopoulos): a rigid sphere on an elastic half-space
through Lennard-Jones 9-3 surface springs.

The closed forms and the result types load at once (numpy and scipy only): `Scales`,
`tabor_parameter`, `effective_modulus`, the paper's laws `PAPER_LAWS` / `AsperityLaws`, a solved
path's `Curve` and its `Events` and `Jump`s. The solvers load on first use (scikit-fem and the path
machinery): `solve_curve`, `solve_to_tolerance`, `Solid`, `stored_curve`, `sweep`,
`jump_in_onset`, `refit`, `write_all` (a curve's files). Subpackages, bottom up: `plumbing`
(errors, checks, files, CLI helpers), `closed_forms`, `curves` (what a solve yields), `solids`
(FE and boundary integral), `path` (the surface problem and path following), `solver` (presets,
one curve, its files), `studies` (onset, store, sweeps, refit); see docs/ARCHITECTURE.md.
"""

from importlib import import_module

from .plumbing.interrupt import hold_while_loading

hold_while_loading()  # before numpy and scipy load: the slow part of a command's start

from .closed_forms.laws import PAPER_LAWS, AsperityLaws, LawEvents  # noqa: E402
from .closed_forms.scales import Scales, effective_modulus, tabor_parameter  # noqa: E402
from .curves.curve import Curve  # noqa: E402
from .curves.events import Events, Jump  # noqa: E402
from .plumbing.errors import ContinuationError, DerjaguinWarning, InputError  # noqa: E402
from .plumbing.version import __version__ as __version__  # noqa: E402

#: Names loaded on first use, and the module each comes from.
_LAZY = {
    "solve_curve": "solver.solve",
    "solve_to_tolerance": "solver.solve",
    "CurveResult": "solver.result",
    "write_all": "solver.output",
    "Solid": "solids.fe",
    "stored_curve": "studies.store",
    "jump_in_onset": "studies.onset",
    "sweep": "studies.sweep",
    "refit": "studies.refit",
}


def __getattr__(name):
    if name in _LAZY:
        return getattr(import_module(f".{_LAZY[name]}", __name__), name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


__all__ = [
    "AsperityLaws",
    "ContinuationError",
    "Curve",
    "DerjaguinWarning",
    "Events",
    "InputError",
    "Jump",
    "LawEvents",
    "PAPER_LAWS",
    "Scales",
    "effective_modulus",
    "tabor_parameter",
    *_LAZY,
]
