"""Tweakable demo parameters: a dataclass whose fields carry a default, a range and a description.

    @dataclass
    class Params:
        stiffness: float = tweak(400.0, 10.0, 2000.0, "Spring constant k [N/m]")
        planks: int = tweak(6, 2, 20, "Number of deck planks", rebuild=True)
        wind: bool = tweak(False, description="Blow wind")
        ammo: str = choice("pistol", ["pistol", "artillery"], "Ammunition")

A *live* parameter is pushed into the running scene by the demo's ``apply``; a *rebuild*
parameter makes the scene be built again. Values outside their range are refused with an error
naming the parameter and its range.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from typing import Any

_META = "pointmass"


@dataclass(frozen=True)
class ParamSpec:
    """One parameter's description, read from its dataclass field."""

    name: str
    default: Any
    kind: type
    low: float | None = None
    high: float | None = None
    description: str = ""
    rebuild: bool = False
    choices: tuple[str, ...] | None = None

    @property
    def range_text(self) -> str:
        if self.choices is not None:
            return "one of " + ", ".join(self.choices)
        if self.kind is bool:
            return "true or false"
        return f"[{self.low:g}, {self.high:g}]"

    def check(self, value: Any) -> Any:
        """``value`` converted to this parameter's type, or a ValueError naming it and its range."""
        if self.kind is bool:
            if isinstance(value, str):
                low = value.strip().lower()
                if low in ("1", "true", "yes", "on"):
                    return True
                if low in ("0", "false", "no", "off"):
                    return False
                raise self._refuse(value)
            return bool(value)
        if self.kind is str:
            if value not in (self.choices or ()):
                raise self._refuse(value)
            return value
        try:
            number = float(value)
        except (TypeError, ValueError):
            raise ValueError(f"parameter {self.name!r} must be a number in {self.range_text}, "
                             f"got {value!r}") from None
        if self.kind is int:
            if not math.isfinite(number) or number != int(number):
                raise ValueError(f"parameter {self.name!r} must be an integer in "
                                 f"{self.range_text}, got {value!r}")
            number = int(number)
        lowest = -math.inf if self.low is None else self.low
        highest = math.inf if self.high is None else self.high
        if not (math.isfinite(number) and lowest <= number <= highest):
            raise ValueError(f"parameter {self.name!r} must be in {self.range_text}, got {value!r}")
        return number

    def _refuse(self, value: Any) -> ValueError:
        return ValueError(f"parameter {self.name!r} must be {self.range_text}, got {value!r}")


def tweak(default: Any, low: float | None = None, high: float | None = None,
          description: str = "", *, rebuild: bool = False) -> Any:
    """A dataclass field for a tweakable number or flag.

    Args:
        default: The default value (float, int or bool).
        low, high: The allowed range (required for numbers, unused for bools).
        description: One line for the panel and ``--help``, with units.
        rebuild: True when a change needs the scene built again (counts, sizes); False when the
            demo's ``apply`` can push it into the running scene.
    """
    kind = type(default)
    if kind not in (float, int, bool):
        raise TypeError(f"tweak default must be float, int or bool, got {default!r}")
    if kind is not bool:
        if low is None or high is None or not low <= default <= high:
            raise ValueError(f"tweak needs low <= default <= high, got {low}, {default}, {high}")
    return dataclasses.field(default=default, metadata={_META: dict(
        kind=kind, low=low, high=high, description=description, rebuild=rebuild)})


def choice(default: str, options, description: str = "", *, rebuild: bool = False) -> Any:
    """A dataclass field for a choice among named options."""
    options = tuple(options)
    if default not in options:
        raise ValueError(f"choice default {default!r} is not one of {options}")
    return dataclasses.field(default=default, metadata={_META: dict(
        kind=str, low=None, high=None, description=description, rebuild=rebuild,
        choices=options)})


def param_specs(params) -> list[ParamSpec]:
    """The specs of a Params dataclass (class or instance), in field order."""
    if params is None:
        return []
    specs = []
    for f in dataclasses.fields(params):
        meta = f.metadata.get(_META)
        if meta is None:
            kind = type(f.default)
            meta = dict(kind=kind, low=None, high=None, description="", rebuild=True)
        specs.append(ParamSpec(name=f.name, default=f.default, **meta))
    return specs


def validate(params) -> None:
    """Check every field of a Params instance against its range."""
    for spec in param_specs(params):
        if spec.low is not None or spec.choices or spec.kind is bool:
            setattr(params, spec.name, spec.check(getattr(params, spec.name)))


def set_param(params, name: str, value: Any) -> ParamSpec:
    """Set one parameter by name after checking it; returns its spec (``.rebuild`` says what to
    do next). Unknown names are refused with the list of known ones."""
    specs = {s.name: s for s in param_specs(params)}
    if name not in specs:
        known = ", ".join(specs) or "none"
        raise ValueError(f"unknown parameter {name!r}; this demo has: {known}")
    setattr(params, name, specs[name].check(value))
    return specs[name]


def apply_overrides(params, assignments: list[str]) -> None:
    """Apply ``name=value`` strings (from ``--set``) to a Params instance. A name given twice
    is refused (``--set push=2 --set push=3`` kept the last silently: a typo or a leftover in
    a script, never what was meant)."""
    given: dict[str, str] = {}
    for text in assignments:
        name, sep, value = text.partition("=")
        if not sep:
            raise ValueError(f"--set expects name=value, got {text!r}")
        name = name.strip()
        if name in given:
            raise ValueError(f"--set {name} is given twice ({given[name]!r} and {text!r}); "
                             "give each parameter once")
        given[name] = text
        set_param(params, name, value.strip())
