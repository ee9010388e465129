"""Single-asperity adhesive contact: inputs and scales, the LJ 9-3 law, reference solutions,
the paper's closed-form laws, and the axisymmetric FE model (`fem_asperity.solver.solve.solve_curve`,
imported on demand so that the closed forms load without scikit-fem).
"""

from .closed_forms.laws import PAPER_LAWS, AsperityLaws, LawEvents
from .closed_forms.scales import Scales, effective_modulus, tabor_parameter
from .plumbing.errors import DerjaguinWarning, InputError

__all__ = [
    "AsperityLaws",
    "DerjaguinWarning",
    "InputError",
    "LawEvents",
    "PAPER_LAWS",
    "Scales",
    "effective_modulus",
    "tabor_parameter",
]
