"""Verification of the paper against independent references: checks, figures and the report.

Entry point: `python -m validation all --out out/`.
"""

import fem_asperity  # noqa: F401  first: its import quiets a Ctrl-C while the modules load
