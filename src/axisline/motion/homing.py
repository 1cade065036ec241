"""Homing procedures: how an axis finds its reference while in the HOMING state.

`Axis.home(procedure)` puts the axis into HOMING. In every following cycle, *before* the
set point of that cycle is sampled, the axis calls

    procedure.start(axis)        # once, in the first homing cycle
    done = procedure.step(axis)  # every homing cycle (also the first), True when finished

so the procedure sees the set point of the previous cycle (`axis.command_position`) next
to the inputs of this cycle, which the plant produced while following that set point; a
motion it commands starts from that set point and moves the axis from this cycle on.

A procedure talks to the axis only through `HomingAxis` (motions at a velocity, a halt,
shifting the position reference). It raises `HomingError` when homing cannot finish; the
axis then goes to ERROR_STOP with ErrorId.HOMING_FAILED. A procedure returns True only
with the axis at rest (`axis.motion_ended` and zero velocity).

Software limits are not watched while homing: until the reference is known the limits
are not in machine coordinates. Personalities add their own modes (CLM home to marker,
COMPAX homing modes, WAGO reference runs) as further subclasses.
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from collections.abc import Callable
from typing import Protocol

__all__ = ["HomingAxis", "HomingError", "HomingProcedure", "DirectHoming", "SwitchHoming"]


class HomingError(RuntimeError):
    """Homing cannot finish; the message becomes the axis error text."""


class HomingAxis(Protocol):
    """What a homing procedure may do with its axis."""

    @property
    def command_position(self) -> float: ...

    @property
    def command_velocity(self) -> float: ...

    @property
    def motion_ended(self) -> bool:
        """The motion last commanded by the procedure has reached its end (or none runs)."""
        ...

    def homing_move_velocity(self, velocity: float, acceleration: float | None = None) -> None:
        """Run at `velocity` (signed); replans on the fly from the current set point."""
        ...

    def homing_halt(self, deceleration: float | None = None) -> None:
        """Brake to rest."""
        ...

    def homing_set_position(self, position: float, relative: bool = False) -> None:
        """Shift the reference: the set point becomes `position` (or moves by it)."""
        ...


class HomingProcedure(ABC):
    """A homing mode. Instances keep their progress; `start` resets it."""

    @abstractmethod
    def start(self, axis: HomingAxis) -> None:
        """Called once, in the first cycle of HOMING."""

    @abstractmethod
    def step(self, axis: HomingAxis) -> bool:
        """Called every HOMING cycle; True when the reference is set and the axis is at rest."""


class DirectHoming(HomingProcedure):
    """Take the current set point as `position` (PLCopen MC_Home with a direct mode)."""

    def __init__(self, position: float) -> None:
        self.position = float(position)

    def start(self, axis: HomingAxis) -> None:
        axis.homing_set_position(self.position)

    def step(self, axis: HomingAxis) -> bool:
        return True

    def __repr__(self) -> str:
        return f"DirectHoming(position={self.position!r})"


class SwitchHoming(HomingProcedure):
    """Search a reference switch, capture the set point at its rising edge, stop, and
    give the captured point the coordinate `position`.

    switch: returns the switch state of this cycle (True = actuated).
    velocity: search speed (> 0); direction: +1 or -1, the search direction.
    acceleration: of the search and of the stop (None: the axis limits).
    max_distance: give up (HomingError) after this much travel without an edge.

    A switch already actuated at the start is first left in the opposite direction, so
    the edge is always approached from the same side (the reference does not depend on
    where the axis stood). The edge is resolved to the cycle: the captured point is the
    set point of the cycle before the switch was seen, which the plant followed while the
    input was sampled; with a lagging drive the error is the drive lag.
    """

    _LEAVE, _SEARCH, _BRAKE, _DONE = range(4)

    def __init__(
        self,
        switch: Callable[[], bool],
        velocity: float,
        direction: int,
        position: float,
        acceleration: float | None = None,
        max_distance: float | None = None,
    ) -> None:
        if not callable(switch):
            raise ValueError(f"switch must be callable, got {switch!r}")
        if not velocity > 0.0:
            raise ValueError(f"velocity must be > 0, got {velocity!r}")
        if direction not in (1, -1):
            raise ValueError(f"direction must be +1 or -1, got {direction!r}")
        if acceleration is not None and not acceleration > 0.0:
            raise ValueError(f"acceleration must be > 0, got {acceleration!r}")
        if max_distance is not None and not max_distance > 0.0:
            raise ValueError(f"max_distance must be > 0, got {max_distance!r}")
        self.switch = switch
        self.velocity = float(velocity)
        self.direction = direction
        self.position = float(position)
        self.acceleration = acceleration
        self.max_distance = max_distance
        self.captured: float | None = None  # set point at the edge, in the old reference
        self._phase = self._DONE
        self._origin = 0.0

    def start(self, axis: HomingAxis) -> None:
        self.captured = None
        if self.switch():
            self._phase = self._LEAVE
            axis.homing_move_velocity(-self.direction * self.velocity, self.acceleration)
        else:
            self._search(axis)

    def _search(self, axis: HomingAxis) -> None:
        self._phase = self._SEARCH
        self._origin = axis.command_position
        axis.homing_move_velocity(self.direction * self.velocity, self.acceleration)

    def step(self, axis: HomingAxis) -> bool:
        if self._phase == self._LEAVE:
            if not self.switch():
                self._search(axis)
        elif self._phase == self._SEARCH:
            if self.switch():
                self.captured = axis.command_position
                axis.homing_halt(self.acceleration)
                self._phase = self._BRAKE
            elif self.max_distance is not None and abs(axis.command_position - self._origin) > self.max_distance:
                raise HomingError(f"reference switch not found within {self.max_distance:g}")
        elif self._phase == self._BRAKE:
            if axis.motion_ended and self.captured is not None:
                axis.homing_set_position(self.position - self.captured, relative=True)
                self._phase = self._DONE
                return True
        return self._phase == self._DONE

    def __repr__(self) -> str:
        return (
            f"SwitchHoming(velocity={self.velocity!r}, direction={self.direction!r}, "
            f"position={self.position!r})"
        )
