"""Verification of the paper against independent references: checks, figures and the report.

Entry point: `python -m validation all --out out/`.
"""

from fem_asperity.plumbing.interrupt import quiet_while_loading

quiet_while_loading()  # before numpy and scipy load: the slow part of a command's start
