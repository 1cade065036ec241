"""What the kernel needs from the plant: the protocols drives and position sources satisfy.

They live in a module of their own, interpreted, because the plant modules that implement
them may be compiled (mypyc: see compiled_modules.txt), and a compiled module cannot define a
runtime-checkable Protocol. `kinematics` and `drives` re-export them.
"""

from __future__ import annotations

from typing import Protocol, runtime_checkable

__all__ = ["Crossing", "Drive", "PositionSource", "TracedSource"]

Crossing = tuple[float, int]
"""(fraction of the cycle in [0, 1], direction +1 rising / -1 falling)."""


@runtime_checkable
class PositionSource(Protocol):
    """Anything with a position in user units (a drive, a material line, a wheel)."""

    @property
    def position(self) -> float: ...


@runtime_checkable
class TracedSource(PositionSource, Protocol):
    """A position source that knows its exact motion during the last plant step."""

    def crossings(self, x: float) -> tuple[Crossing, ...]: ...

    def position_bounds(self) -> tuple[float, float]: ...


@runtime_checkable
class Drive(Protocol):
    """What the kernel needs from any drive: enable it, advance it, read its motion."""

    @property
    def enabled(self) -> bool: ...

    @property
    def position(self) -> float:
        """Actual position in user units."""
        ...

    @property
    def velocity(self) -> float:
        """Actual velocity in user units/s."""
        ...

    @property
    def acceleration(self) -> float:
        """Actual acceleration in user units/s^2."""
        ...

    def enable(self, on: bool) -> None: ...

    def step(self, dt: float) -> None:
        """Advance the drive by one cycle of ``dt`` seconds with the command held."""
        ...
