"""The state of a 750-672 module, declared once for all the parts of `device.Wago672`.

The module is one class built in layers, each a file by what it does:

    DeviceState (this file)  what the module holds, and the two read-outs every part uses
      <- Drive               output stage, axis hand-over, STOP ramps, scaling, current, errors
      <- Watches             limit switches, software limits, end of motions, flags, source bits
      <- Modes               mode selection, Start, positioning, speed, PreCalc, referencing, jog
      <- MoveCommands        DRIVE_COMMAND and the run programs' move commands
      <- Wago672             power-on, the process image, the tick, read-outs (device.py)

Why a chain and not mixins: the per-cycle parts are compiled with mypyc (compiled_modules.txt),
whose native classes take single inheritance only; in a chain every attribute is a slot of one C
struct, read without a dictionary lookup. A part calls only what its own layer or a lower one
defines: the layers are ordered by who calls whom (Modes starts motions through Drive and asks
Watches about the limits; MoveCommands starts them through Modes). The method resolution order
is the one the mixins had (no method is defined in two parts).

The attributes are declared here, not in each part, so every part sees the same types; they are
set in `Wago672.__init__` and `_power_on` (device.py).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from axisline.devices.wago672.bits import BitTable
from axisline.devices.wago672.config_table import ConfigTable
from axisline.devices.wago672.errors import ErrorMemory
from axisline.devices.wago672.image import MODE_SPEED, OutputImage
from axisline.devices.wago672.referencing import RefRun
from axisline.devices.wago672.signals import Signals
from axisline.devices.wago672.seams import Inputs, MailboxHandler, RunProgram
from axisline.devices.wago672.thermal import CurrentPhase, OvercurrentModel
from axisline.devices.wago672.trajectory import Feed, Ramp
from axisline.devices.wago672.units import Scaling
from axisline.motion.axis import Axis, MotionCommand

if TYPE_CHECKING:
    from axisline.devices.wago672.device import Wago672

__all__ = ["DeviceState", "SPEED_CONTROL_PERIOD"]

SPEED_CONTROL_PERIOD = 100000  # implicit rotary period of speed control [microsteps] (D11)


class DeviceState:
    """What a 750-672 module holds (see the module docstring)."""

    # ---- the module and what is plugged into it (device.py __init__)
    axis: Axis
    inputs: Inputs
    config: ConfigTable
    bits: BitTable
    errors: ErrorMemory
    mailbox: MailboxHandler
    program: RunProgram | None
    position_table: Callable[[int, int], int]
    cam_pattern: Callable[[float], int] | None
    eeprom_writing: bool
    on_warm_start: Callable[[Wago672], None] | None
    tick_hooks: list[Callable[[int], None]]
    extra_variables: dict[int, Callable[[], int]]
    stepping_timeout_ms: int
    reference_on_target: bool
    environment: dict[str, float]
    feed: Feed
    scaling: Scaling
    _k: float  # microsteps per axis unit
    _dir_sign: float  # -1.0: Drive_Direction inverts the motor (D26)
    _sync_cmd: MotionCommand | None  # the axis follows the feed through this command
    # ---- the process image
    _out: OutputImage
    _out_raw: bytes | None
    _control_bits: bytes
    _last_write: int | None
    _cycle: int | None  # the last cycle ticked
    _now: int  # the cycle being ticked
    _in_tick: bool
    _prev: Signals  # the last tick's signals (for edges)
    _sig: Signals  # this tick's
    _status: tuple[int, int, int, int]
    _outputs: tuple[bool, bool]
    _mbx_on: bool
    _mbx_reply: bytes
    _sources_word: int  # the own source bits last written (watches._write_sources); -1: none yet
    # ---- handshakes and flags
    reset_flag: bool
    mode: int
    busy: bool
    on_target: bool
    on_speed: bool
    reference_ok: bool
    precalc_ack: bool
    err_range_pos: bool
    err_range_neg: bool
    _ready: bool
    _stage_on: bool
    _mode_exit: bool
    _stop_n_ack: bool
    _start_ack: bool
    _direction: bool
    _bad_selection: int
    _error_since: int
    # ---- motion
    _sp: tuple[float, float, float, float]  # this cycle's set point (p, v, a, j) [microsteps]
    _motion: str | None  # "position", "speed", "stop", "jog", "reference"
    _stopping: bool  # a STOP ramp runs (Current_Ratio_Stop)
    _target: float | None  # position target [microsteps, unwrapped]
    _last_target: float | None  # MOVE_REL base (D18)
    _v_set: int  # commanded speed [user units] for On_Speed
    _v_set_f: float  # [microsteps/s]
    _pending: Callable[[], None] | None  # deferred set point (D8)
    _cur_up: Ramp
    _cur_down: Ramp
    _precalc: dict[str, Any] | None
    _source: str  # who started the running task: "pi", "mailbox", "program"
    _mailbox_reference: bool
    _brake_auto: bool
    # ---- move settings (SET_ACC_MODE, SET_ACC, ..., SET_VELOCITY)
    acc_mode: int
    acc_up: int
    acc_down: int
    param_up: int
    param_down: int
    velocity: int
    velocity_target: int
    # ---- limits, referencing and jog
    _range_block: int  # a refused reference start at this limit switch (+1/-1)
    _ls_special: int  # +1/-1: on that limit switch after a limit-switch reference run
    _ls_left: int | None
    _ref: RefRun | None
    _ref_pending_shift: float
    _jog_dir: int
    _jog_block: bool
    _jog_started: int
    _jog_ls: int
    _jog_outside: bool
    # ---- motor current
    _overcurrent: OvercurrentModel
    current_phase: CurrentPhase
    phase_current: float
    current_ratio: int
    _ratio_set: dict[CurrentPhase, int]  # SET_CURRENT values (else the configuration's)

    def _c_plan(self) -> int:
        """Cycle of the last set point: a plan starts from it (kernel rule)."""
        if self._in_tick:
            return self._now - 1
        return self._cycle if self._cycle is not None else 0

    def rotary_period(self) -> int:
        """The period the actual value wraps with [microsteps] (0: linear)."""
        p: int = self.config.values["Rotary_Axis_Period"]
        if p == 0 and self.mode == MODE_SPEED:
            return SPEED_CONTROL_PERIOD
        return p
