"""Single-asperity adhesive contact: inputs and scales, the LJ 9-3 law, reference solutions and
the paper's closed-form laws (the axisymmetric FE model arrives in a later stage).
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
