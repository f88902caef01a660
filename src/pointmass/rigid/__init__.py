"""Rigid bodies (issue 13): solver-independent foundations. Not exported from pointmass yet.

quaternion / scalar: rotations on small arrays / on scalars for hot loops; integrate: the
torque-free rotation that keeps L and energy; shapes: sphere, box and their mass properties;
bodies: the struct-of-arrays store and ``Body`` handle; step: the kick and drift kernels;
manifold, narrow_sphere, narrow_box, box_box: narrow-phase kernels; narrow: their Python API.
"""
