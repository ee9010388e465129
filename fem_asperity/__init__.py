"""Single-asperity adhesive contact: inputs and scales, the LJ 9-3 law, reference solutions,
the paper's closed-form laws, and the axisymmetric FE model (`fem_asperity.asperity.solve_curve`,
imported on demand so that the closed forms load without scikit-fem).
"""

from ._checks import DerjaguinWarning, InputError
from .laws import PAPER_LAWS, AsperityLaws, LawEvents
from .scales import Scales, effective_modulus, tabor_parameter

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
