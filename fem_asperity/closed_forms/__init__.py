"""Closed forms, dimensionless: natural scales and the Tabor parameter, the LJ 9-3 law, the
paper's fitted laws, the corrected law (`corrected`) and the classical references (Hertz, JKR,
DMT, Maugis-Dugdale).
Numpy and scipy only: nothing here imports a solid, a path or scikit-fem."""
