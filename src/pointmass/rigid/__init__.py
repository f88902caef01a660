"""Rigid bodies (issue 13): solver-independent foundations. Not exported from pointmass yet."""
