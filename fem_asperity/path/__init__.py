"""Path following on an elastic surface loaded by LJ springs: the surface problem, continuation,
edge relaxation, landing of jumps, grids that follow the edge, stable paths and the whole curve."""
