"""What one ``World.step`` did: ``StepStats``."""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class StepStats:
    """What one ``World.step`` did.

    Attributes:
        contacts: Contacts generated in the last substep, including speculative ones (a gap
            within the collision margin, negative penetration).
        iterations: Single-contact resolutions the solver performed (all substeps).
        max_penetration: Largest overlap left after resolving [m] (0 when none).
        kinetic_energy: Total kinetic energy after the step [J], summed when first read (a
            property: a step whose energy nobody reads makes no pass over the velocities for
            it). Read it before the world steps again; reading it later raises, as the state
            it described is gone (``World.kinetic_energy()`` gives the current one).
        mode: The solver mode ("sequential" or "worst-first").
        velocity_passes: Velocity passes of the solver (all substeps; see ``pointmass.solver``).
        position_passes: Projection passes (all substeps).
        body_contacts: Rigid-body contact points in the last substep (speculative included),
            particle–body points among them.
        awake_bodies: Movable rigid bodies awake after the step (the rest sleep).
    """

    contacts: int
    iterations: int
    max_penetration: float
    mode: str
    velocity_passes: int = 0
    position_passes: int = 0
    body_contacts: int = 0
    awake_bodies: int = 0

    # The energy is not a field: ``_energy`` holds it once read, or what computes it
    # (``World._energy_after``, set by the step), so ``asdict``, ``==`` and ``repr`` never
    # reach the world behind it.

    @classmethod
    def made(cls, **fields) -> StepStats:
        """A ``StepStats`` of ``fields`` (every field, and ``_energy``), set in one update of
        its ``__dict__``: the frozen dataclass's ``__init__`` sets each field through
        ``object.__setattr__``, ~3 µs of a tiny world's step (``World.step`` makes one every
        step)."""
        stats = cls.__new__(cls)
        stats.__dict__.update(fields)
        return stats

    @property
    def kinetic_energy(self) -> float:
        energy = self.__dict__.get("_energy")
        if energy is None:
            raise RuntimeError("this StepStats was pickled or deep-copied before its kinetic "
                               "energy was read (it is summed when first read, from the world "
                               "that stepped; a copy does not carry the world along)")
        if callable(energy):
            energy = energy()
            object.__setattr__(self, "_energy", energy)  # frozen: cache it once
        return energy

    def __getstate__(self) -> dict:
        state = dict(self.__dict__)
        if callable(state.get("_energy")):
            del state["_energy"]  # a pickle or deep copy does not carry the world along
        return state

    def __setstate__(self, state: dict) -> None:
        for name, value in state.items():
            object.__setattr__(self, name, value)
