"""Elastic solids seen from their surface: the FE half-space (scikit-fem, optionally layered)
and the Boussinesq boundary integral, both behind `operator.ElasticSurface`."""
