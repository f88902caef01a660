"""Rigid bodies (issue 13). What a script needs is exported from ``pointmass``: the shapes
(``pm.Box``, ``pm.Sphere``, for ``World.add_body``), ``pm.Body``/``pm.Bodies``, the joints
(``pm.BallJoint``, ``pm.HingeJoint``) and the body force generators (``pm.BodySpring``, ...).

quaternion / scalar: rotations on small arrays / on scalars for hot loops; integrate: the
torque-free rotation that keeps L and energy; shapes: sphere, box and their mass properties;
bodies: the struct-of-arrays store and ``Body`` handle; step: the kick and drift kernels;
manifold, narrow_sphere, narrow_box, box_box: narrow-phase kernels; narrow: their Python API;
broadphase: sort and sweep on AABBs; contacts: ``BodyContacts``, the solver's rows; collide:
pairs and planes through the narrow phase. The solver's body stage is the soft step,
``pointmass.solver.body_soft``. forces: body force
generators (springs on both ends, aero on the point velocity, buoyancy, explosion, user
callables) for ``World.add``. islands: union–find over touching bodies and the still-timers;
sleep: what wakes an island and the warm start a sleeping island keeps (``World(sleep=True)``).
joints: ``BallJoint`` (cone and twist limits) and ``HingeJoint`` (angle limits) for
``World.add``; joint_set: the world's ``Joints`` and their warm start (the kernels:
``pointmass.solver.joint_stages`` / ``joint_solver`` / ``joint_soft``); joint_rows: a joint's
angular rows in the current pose (the solver builds on them; rigid never imports solver).
"""
