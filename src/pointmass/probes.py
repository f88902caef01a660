"""Probes: record chosen quantities every step into numpy arrays, with their times.

    >>> import pointmass as pm
    >>> world = pm.World()
    >>> ball = world.add_particle((0, 10, 0))
    >>> probe = world.add_probe(pm.Probe(y=pm.probes.position(ball, axis=1),
    ...                                  energy=pm.probes.kinetic_energy))
    >>> for _ in range(60):
    ...     _ = world.step(1 / 60)
    >>> probe.t.shape, probe["y"].shape
    ((60,), (60,))

A quantity is any function of the world returning a number or a fixed-size vector; the helpers
below cover positions, velocities, energies, contact counts and link lengths. Export with
``to_npz``/``to_csv`` (and read back with ``Probe.load``), or ``plot()`` with matplotlib (the
``notebook`` extra). The core never imports matplotlib until ``plot`` is called.
"""

from __future__ import annotations

from collections import deque
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

if TYPE_CHECKING:
    from .world import World

#: What a probe samples: a function of the world, returning a number or an array.
Quantity = Callable[["World"], Any]


class Probe:
    """Named quantities sampled after every ``World.step`` (add it with ``world.add_probe``).

    Args:
        max_samples: Keep only the latest this many samples (a window's live plot), or None
            to keep everything (a notebook's run).
        quantities: name = function of the world returning a float or a vector.
    """

    def __init__(self, *, max_samples: int | None = None, **quantities: Quantity) -> None:
        if not quantities:
            raise ValueError("a Probe needs at least one quantity, e.g. Probe(y=position(0, 1))")
        for name, fn in quantities.items():
            if not callable(fn):
                raise TypeError(f"quantity {name!r} must be a function of the world, got {fn!r}")
        if max_samples is not None and not (isinstance(max_samples, int) and max_samples >= 1):
            raise ValueError(f"max_samples must be an integer >= 1 or None, got {max_samples!r}")
        self.quantities = dict(quantities)
        self.max_samples = max_samples
        self._t: deque[float] = deque(maxlen=max_samples)
        self._values: dict[str, deque] = {name: deque(maxlen=max_samples) for name in quantities}

    def record(self, world) -> None:
        """Sample every quantity now (the world calls this after each step)."""
        self._t.append(float(world.time))
        for name, fn in self.quantities.items():
            self._values[name].append(np.array(fn(world), dtype=np.float64))

    def clear(self) -> None:
        self._t.clear()
        for values in self._values.values():
            values.clear()

    def __len__(self) -> int:
        return len(self._t)

    @property
    def t(self) -> np.ndarray:
        """Sample times [s], shape (T,)."""
        return np.array(self._t)

    def __getitem__(self, name: str) -> np.ndarray:
        """The samples of ``name``: shape (T,) for a number, (T, K) for a vector."""
        if name not in self._values:
            raise KeyError(f"this probe has no quantity {name!r}; it has {self.names()}")
        values = self._values[name]
        return np.array(values) if values else np.zeros(0)

    def names(self) -> list[str]:
        return list(self._values)

    # -- export ------------------------------------------------------------------------------
    def to_npz(self, path: str | Path) -> Path:
        """Save times (``t``) and every quantity to a numpy ``.npz``."""
        path = Path(path)
        arrays = {"t": self.t, **{name: self[name] for name in self.names()}}
        np.savez(path, **arrays)  # type: ignore[arg-type]  # (numpy's stub: allow_pickle)
        return path

    def _columns(self) -> tuple[list[str], np.ndarray]:
        header, columns = ["t"], [self.t[:, None]]
        for name in self.names():
            data = self[name].reshape(len(self), -1)
            if data.shape[1] == 1:
                header.append(name)
            else:
                header += [f"{name}[{k}]" for k in range(data.shape[1])]
            columns.append(data)
        return header, np.hstack(columns) if len(self) else np.zeros((0, len(header)))

    def to_csv(self, path: str | Path) -> Path:
        """Save a CSV: a header row (``t``, then each quantity; vectors as ``name[k]``)."""
        path = Path(path)
        header, table = self._columns()
        np.savetxt(path, table, delimiter=",", header=",".join(header), comments="",
                   fmt="%.17g")
        return path

    @staticmethod
    def load(path: str | Path) -> dict[str, np.ndarray]:
        """Read a probe saved by ``to_npz`` or ``to_csv``: ``{"t": ..., name: ...}``."""
        path = Path(path)
        if path.suffix == ".npz":
            with np.load(path) as data:
                return {name: data[name] for name in data.files}
        with path.open() as f:
            header = f.readline().strip().split(",")
        table = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)
        out: dict[str, list] = {}
        for k, column in enumerate(header):
            out.setdefault(column.split("[")[0], []).append(table[:, k])
        return {name: cols[0] if len(cols) == 1 else np.column_stack(cols)
                for name, cols in out.items()}

    def plot(self, *names: str, ax=None):
        """Plot the named quantities (all by default) against time with matplotlib."""
        try:
            import matplotlib.pyplot as plt
        except ImportError:
            raise ImportError('Probe.plot needs matplotlib: pip install "pointmass[notebook]"') \
                from None
        if ax is None:
            ax = plt.figure().add_subplot()
        for name in names or self.names():
            data = self[name].reshape(len(self), -1)
            for k in range(data.shape[1]):
                ax.plot(self.t, data[:, k], label=name if data.shape[1] == 1 else f"{name}[{k}]")
        ax.set_xlabel("t [s]")
        ax.legend()
        return ax


# -- quantities --------------------------------------------------------------------------------
def position(particle: int, axis: int | None = None) -> Quantity:
    """A particle's position [m] (a 3-vector, or one axis)."""
    if axis is None:
        return lambda world: world.particles.position[particle].copy()
    return lambda world: float(world.particles.position[particle, axis])


def velocity(particle: int, axis: int | None = None) -> Quantity:
    """A particle's velocity [m/s] (a 3-vector, or one axis)."""
    if axis is None:
        return lambda world: world.particles.velocity[particle].copy()
    return lambda world: float(world.particles.velocity[particle, axis])


def kinetic_energy(world) -> float:
    """Total kinetic energy [J]."""
    return world.kinetic_energy()


def potential_energy(world) -> float:
    """Gravitational and stored potential energy [J] (``World.potential_energy``)."""
    return world.potential_energy()


def contacts(world) -> float:
    """Contacts found in the last step."""
    return float(world.contacts.count)


def link_length(link, index: int = 0) -> Quantity:
    """The current length [m] of link ``index`` of a Cable/Rod (or spring) generator."""
    def length(world) -> float:
        lengths = (link.current_lengths(world.particles) if hasattr(link, "current_lengths")
                   else link.lengths(world.particles))
        return float(lengths[index])
    return length
