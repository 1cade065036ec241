"""The handle of an axis command (`MotionCommand`, the PLCopen function-block outputs) and the
axis' states, buffer modes, directions and error ids (axis.py uses them; they are re-exported
there, where users import them from).
"""

from __future__ import annotations

from enum import Enum, IntEnum

from axisline.motion.profiles import Limits

__all__ = ["AxisState", "BufferMode", "Direction", "ErrorId", "MotionCommand"]


class AxisState(Enum):
    """PLCopen single-axis states."""

    DISABLED = "Disabled"
    STANDSTILL = "Standstill"
    HOMING = "Homing"
    DISCRETE_MOTION = "DiscreteMotion"
    CONTINUOUS_MOTION = "ContinuousMotion"
    SYNCHRONIZED_MOTION = "SynchronizedMotion"
    STOPPING = "Stopping"
    ERROR_STOP = "ErrorStop"


class BufferMode(Enum):
    """ABORTING replans at once from the current set point; BUFFERED waits (FIFO)."""

    ABORTING = "Aborting"
    BUFFERED = "Buffered"


class Direction(Enum):
    """Direction of an absolute move on a modulo axis (ignored on linear axes)."""

    SHORTEST = "Shortest"
    POSITIVE = "Positive"
    NEGATIVE = "Negative"
    CURRENT = "Current"  # the direction the axis moves in now; at rest: shortest


class ErrorId(IntEnum):
    """Error ids of commands and of the axis (PLCopen leaves the numbers to the vendor)."""

    NONE = 0
    AXIS_DISABLED = 0x10  # motion command while DISABLED
    AXIS_ERROR_STOP = 0x11  # motion command while ERROR_STOP
    AXIS_STOPPING = 0x12  # motion command while STOPPING
    AXIS_HOMING = 0x13  # command not allowed while HOMING
    INVALID_STATE = 0x14  # e.g. home while moving, end_sync without sync
    INVALID_PARAMETER = 0x20
    SW_LIMIT_LOW = 0x30
    SW_LIMIT_HIGH = 0x31
    FOLLOWING_ERROR = 0x40
    DRIVE_FAULT = 0x41  # default of Axis.fault()
    HOMING_FAILED = 0x42


# ------------------------------------------------------------------------ command handle

_POSITION_KINDS = ("move_absolute", "move_relative", "move_additive")
_VELOCITY_KINDS = ("move_velocity", "jog")


class MotionCommand:
    """Handle of one command with the PLCopen function-block outputs.

    busy: accepted and not finished; active: has control of the axis; done: finished
    normally; aborted (command_aborted): taken over by another command, a stop, a fault or
    power off; error/error_id/error_text: rejected or failed; in_velocity: a velocity
    command (or jog) runs at its velocity; clamped: a value was clamped to the config.
    """

    __slots__ = (
        "kind", "buffer_mode", "busy", "active", "done", "aborted", "error", "error_id",
        "error_text", "in_velocity", "clamped", "target", "_value", "_direction", "_limits",
        "_shape", "_ending",
    )  # fmt: skip

    def __init__(self, kind: str, buffer_mode: BufferMode = BufferMode.ABORTING) -> None:
        self.kind = kind
        self.buffer_mode = buffer_mode
        self.busy = False
        self.active = False
        self.done = False
        self.aborted = False
        self.error = False
        self.error_id = 0
        self.error_text = ""
        self.in_velocity = False
        self.clamped = False
        self.target: float | None = None  # resolved position target (axis frame) once started
        self._value = 0.0  # position, distance or velocity as commanded
        self._direction = Direction.SHORTEST
        self._limits: Limits | None = None
        self._shape = "trapezoid"
        self._ending = False  # a jog that is braking after jog(0)

    @property
    def command_aborted(self) -> bool:
        return self.aborted

    def _fail(self, error_id: int, text: str) -> MotionCommand:
        self.busy = self.active = self.in_velocity = False
        self.error = True
        self.error_id = int(error_id)
        self.error_text = text
        return self

    def _finish(self) -> None:
        self.busy = self.active = False
        self.done = True

    def _abort(self) -> None:
        if self.busy:
            self.busy = self.active = self.in_velocity = False
            self.aborted = True

    def __repr__(self) -> str:
        flags = [n for n in ("busy", "active", "done", "aborted", "error", "in_velocity") if getattr(self, n)]
        err = f", error_id={self.error_id:#x}, {self.error_text!r}" if self.error else ""
        return f"MotionCommand({self.kind}, {'|'.join(flags) or 'idle'}{err})"


class _Rejected(Exception):
    def __init__(self, error_id: int, text: str) -> None:
        super().__init__(text)
        self.error_id = error_id
        self.text = text


# Compiled, the public names get this source's docstrings and annotations back (help(),
# inspect.signature); in plain Python this does nothing. See axisline/_docs.py.
from axisline._docs import document as _document  # noqa: E402

_document(globals())
