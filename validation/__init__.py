"""Verification of the paper against independent references: checks, figures and the report.

Entry point: `python -m validation all --out out/`.
"""
