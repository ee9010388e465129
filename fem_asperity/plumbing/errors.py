"""The package's exceptions and warnings: what a caller may catch at its boundary."""


class InputError(ValueError):
    """An input outside its allowed range; the message names the parameter and the range."""


class DerjaguinWarning(UserWarning):
    """R/ε is small enough that the Derjaguin (μ-only) scaling loses accuracy."""


class ContinuationError(RuntimeError):
    """The continuation could not proceed (Newton failed at the smallest step)."""
