"""One name per thing, everything a script needs at the top level of ``pointmass``."""

from __future__ import annotations

import pointmass as pm
from pointmass.rigid import forces, joints, shapes


def test_the_rigid_names_are_the_rigid_classes():
    """pm.Box and pm.Sphere are the rigid shapes, the joints and body force generators are
    pointmass.rigid's; the particle container is pm.BoxContainer, a contact generator."""
    assert (pm.Box, pm.Sphere) == (shapes.Box, shapes.Sphere)
    assert (pm.BallJoint, pm.HingeJoint, pm.Joint) == (joints.BallJoint, joints.HingeJoint,
                                                       joints.Joint)
    for name in ("BodyForceGenerator", "BodySpring", "AnchoredBodySpring", "Aero", "AeroControl",
                 "BodyBuoyancy", "Explosion", "BodyForce"):
        assert getattr(pm, name) is getattr(forces, name)
    assert issubclass(pm.BoxContainer, pm.ContactGenerator)
    assert not issubclass(pm.Box, pm.ContactGenerator)


def test_every_exported_name_exists_once():
    """``__all__`` names real attributes, each once."""
    assert len(set(pm.__all__)) == len(pm.__all__)
    for name in pm.__all__:
        assert hasattr(pm, name), name
