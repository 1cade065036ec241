"""The WAGO 750-672 stepper controller module as a personality on the motion kernel.

    dev = Wago672(axis, inputs={"Input1": True, "Input5": lambda: x > 100.0})
    each 1 ms cycle:  dev.write_outputs(plc_bytes)   # 12 bytes from the PLC (any time)
                      dev.tick(cycle)                # BEFORE axis.update_setpoint(cycle)
                      axis.update_setpoint(cycle); axis.position_loop(...)
                      plc_bytes_in = dev.read_inputs()

The module never integrates physics: it plans its motion profiles in microsteps with the
kernel's profile generator (trajectory.py) and hands them to the axis as the axis' sync source
(`Axis.start_sync`), so the axis' position loop, following-error watch and traces stay the
kernel's. At rest the sync is ended and the axis shows STANDSTILL; Enable off, an error and
STOP_NO_RAMP switch the axis' power off (the output stage coasts). The axis' counts are
microsteps: `axis.scale.counts_per_unit` is the number of microsteps per axis unit. The
750-672 has no encoder: its "actual position" is its pulse counter, the axis' set point.

Inputs: `inputs` maps "Input1" .. "Input6" (DI1 .. DI6; ints 1 .. 6 work too) to booleans or
to callables returning booleans (the machine wires switches as functions of the position). By
default DI1 is Stop1_N, DI2 the reference switch, DI3/DI4 Jog_Pos/Jog_Neg, DI5/DI6 the
positive/negative limit switch; every consumed signal is read through the bit table
(bits.py), so a relinking in the configuration table moves it.

Handshakes (manual §3.11.1, §3.7.2; wago.md §7):
* Enable -> Ready (no error). Stop2_N and Stop1_N -> Stop_N_ACK; either to 0 brakes with
  Acceleration_Stop_Fast (Stop_N_ACK stays 1 while braking), the mode ends at standstill.
  Enable 0 (or an error): output stage off at once, no ramp, mode ACK cleared at once.
* a mode is selected with its Command bit when Ready, Stop_N_ACK, not Start, not Start_ACK;
  acknowledged by its Command_ACK bit; clearing the bit brakes with Acceleration_Stop_Fast and
  clears the ACK at standstill. Another mode bit while a mode is active has no function.
* Start 0->1 starts the mode's task; Start_ACK follows until Start is 0 again.

Seams for the second engineer (mailbox, tables, run programs, camshaft, bit linking, Modbus):
* `mailbox`: handler called every tick while C0.5 is set with MB0..MB5 of the PLC, returns
  the 6 reply bytes (default `NoMailbox`: toggle handshake, every opcode but IDLE is 0x13).
* `drive_command(opcode, data)`: the move commands of §3.9 (DRIVE_COMMAND, run programs).
* `program`: run-program hook (start(address), stop(), tick(cycle), running, counter).
* `position_table(index, src) -> position`: MOVE_TABLE* lookup; `cam_pattern(position) -> int`:
  CAM1..8 bit sample of the camshaft table at a position (microsteps).
* `bits` (BitTable): the bit field, updated each tick; `config` (ConfigTable).
* `state_variable(n)`: DIAG_RD_VAR; `errors`: the error memory (DIAG_RD_ERROR/DIAG_QUIT_ERROR
  -> `quit_errors()`); `warm_start()`.
* `tick_hooks` (called each tick after the source bits are written), `extra_variables` (more
  state variables), `stopping`, and a program with `autostarted` set runs in Idle mode
  (Program_Autostart). `mailbox.attach(dev)` plugs all of these in (mailbox.py, tables.py,
  program.py, filters.py, recorder.py).

Decisions ([AMBIGUOUS]/[CONFLICT]/[RECONSTRUCTED] points of wago.md; the manual wins):
* D1 Speed control selection (wago.md §3.3 [CONFLICT/AMBIGUOUS]): the manual selects it with
  "Command[]=3" (§3.7.2 C1 table, §3.11.1.11: "selected by selecting the Command[]=3 operating
  image"), i.e. C1.3 and C1.4 together; Command_Ack reports 3 (S1.3 + S1.4). The spec's
  Application_Selector variant is not documented for the 672 (addr 3 allows only 1). Any other
  combination of mode bits at selection is 1354 OPC_MULTIMODE_1.
* D2 Start in JogMode (wago.md §2.5 [CONFLICT], spec line "Start bit in JogMode: [CONFLICT] C1/Start
  description ... Recommendation: JogMode runs without Start"): JogMode runs without Start; a
  Start edge is ignored - no Start_ACK ("Start_ACK: No effect. Handshake not performed", S1 in
  §3.11.1.6.1) and no error (an error would switch the output stage off under a PLC that
  follows the sequence diagram Fig. 3.11.1-15). Test: test_jog::test_start_in_jog_mode_is_ignored.
* D3 Jog control (wago.md §2.5 [CONFLICT]): positive while Jog_Pos (Input3) or Direction_Pos,
  negative while Jog_Neg (Input4) or Direction_Neg; both -> the drive brakes (Acceleration_
  Stop_Fast) and waits for both to be released. Release ramps down with SetupAcceleration.
  Jog and reference runs use constant acceleration (SetupAcceleration is "the acceleration").
* D4 SteppingMode timeout (wago.md §2.5 [AMBIGUOUS], no process-image location): the attribute
  `stepping_timeout_ms` (0 = unlimited JogMode); a jog press ends after it, a new press is needed.
* D5 On_Target in referencing (wago.md §2.4 [CONFLICT]): set when a reference run started from the
  process image has set the reference point (S2 table §3.11.1.5.1, bit table); not set after
  START_REFERENCING (§4.3.4.1.13). Reference_OK and Busy = 0 mark the end in both.
* D6 Reference_Mode bits (wago.md §2.4 [CONFLICT]): bit 0 switch/limit switch, bit 1 edge (§4.6);
  START_REFERENCING's DIR is read when SWT = 0 (the §3.11.1.5.3 tables), not SWT = 1.
* D7 Reference run motion: see referencing.py ([RECONSTRUCTED], as wago.md §2.4 proposes). Both
  Direction bits set: the drive "is deactivated" - no run, no error, Start_ACK given. No direction
  bit: 1431 PROT_REF_DIR.
* D8 On-the-fly with linear/sin^2 ramps (wago.md §2.3 [RECONSTRUCTED], manual note §3.11.1.4): a new
  set point that arrives while the acceleration is not 0 in a linear/sin^2 phase, or that needs a
  ramp time/path plan (which starts from a = 0, docs/decisions.md K3), waits until v = const
  (a = 0: a cruise or the end of the move), then the move is replanned. Busy is 1 and On_Target 0
  from the Start edge on. With constant acceleration the new set point is taken at once.
* D9 Software limits (wago.md §2.13 [AMBIGUOUS]/[RECONSTRUCTED]): watched in single positioning,
  speed control, run program and mailbox moves, never in referencing; jog as the manual says. A
  move may be started toward a target beyond a limit; crossing the limit brakes with
  Acceleration_Stop_Fast and sets Err_Range_Pos/_Neg (manual §3.11.3.2: brought to standstill
  after the violation, no error code named). Outside the range a start that would go further out
  is refused: no motion, no error, Err_Range stays set, Start_ACK is given, Busy 0, On_Target 0.
  The Err_Range bits clear when the position is back inside the range (and, for a reference
  start refused at a limit switch, when the switch is left). Drive_Range_* and Reference_Offset
  are position units (user); Rotary_Axis_Period and CAM9 are microsteps (wago.md §6.2).
* D10 Hardware limit switches: a switch in the direction of travel brakes with
  Acceleration_Stop_Fast. A start in positioning, speed, program or mailbox mode while a limit
  switch is active is 1931 PARTMODL_LIMITSWITCH, except after a reference run to that limit switch
  (special mode, moving away).
* D11 Rotary axis (wago.md §2.6 [AMBIGUOUS]): actual value in [0, P); absolute targets in [0, P)
  else 1123; from standstill the shorter way (half a turn: positive); when moving, the first
  equivalent target ahead of the stopping point (no reversal). Speed control wraps with
  Rotary_Axis_Period, or 100000 microsteps when it is 0 (wago.md §2.6 reading of "a value of
  100000 is assumed").
* D12 On_Target in speed control (§4.6 TargetWindowSpeed vs. S2 table "no function" [CONFLICT]):
  set when the commanded speed has been reached (as TargetWindowSpeed and SPEED describe); Busy
  is 1 until then. On_Speed/On_Target compare |v - v_set| <= TargetWindowSpeed.
* D13 StandStill = the frequency output is 0 (bit table §4.5). Direction is 1 while moving positive
  and reads 0 at standstill ("valid only when StandStill is 0"; wago.md §9.12 shows S2 = 0x05 at target).
* D14 Start with an error pending is simply refused by Ready = 0; Start while Error_Quit is set is
  1361; Start without a mode is 1351; Start while a mode is being left is ignored.
* D15 Freq_Range_Sel/Acc_Range_Sel and the scaling factors are latched while Enable = 0 (§3.7.2:
  "accepted only when Enable is set to 0"); a configuration change takes effect at the next
  Enable. Freq_Range_Sel value = C2 & 3 with C2.0 as LSB (wago.md §3.4 [AMBIGUOUS], §3.7.2 reading).
* D16 Acknowledging a 2xxx error (Error_Quit edge or DIAG_QUIT_ERROR) performs the warm start
  (volatile state lost, Reset bit set; the `on_warm_start` hook lets the table manager reload the
  saved configuration and tables); 3xxx errors stay until power-off.
* D17 MOVE/MOVE_REL/SPEED (non-immediate) are accepted when no process is running (Busy = 0),
  also after a stop left On_Target at 0 - a literal "On_Target has been set" would lock MOVE out
  after every STOP until MOVE_IMMEDIATE. While a process runs they return 0x12.
* D18 MOVE_REL is relative to the last accepted target while one is valid; a stop, STOP_NO_RAMP,
  Enable loss, a reference run or a set position invalidate it (wago.md §2.2 [RECONSTRUCTED]).
* D19 STOP ramps (Stop1_N/Stop2_N, mode exit, limit switches, STOP_FAST) use constant deceleration
  Acceleration_Stop_Fast; 0 uses the deceleration of the running motion. STOP_NO_RAMP holds the
  set point where it is (frequency 0 at once) with the output stage on.
* D20 Speed_Limit: a commanded velocity above it is error 1212 CTRLOUT_F_FREF (the drive is turned
  off) [RECONSTRUCTED code]. Velocity 0/over 25000/negative in positioning: 1117; acceleration
  0/negative: 1121 [RECONSTRUCTED codes, wago.md §3.6.1].
* D21 Ready does not wait for Reset_Quit (wago.md §10.3 item 28).
* D22 Overcurrent shutdown 1413 can be acknowledged once the thermal model has cooled back to 0
  ("a phase with reduced current must follow, in order for the module's thermal model to return
  to its original state", §4.1.4.3). Output-stage temperature and DC-link voltage are simulated
  values (`environment`); above Warn_Treshold_Temperature it is 1894 (ErrorNotificationMode
  bit 1, default) or warning 5893 (WarningNotificationMode bit 1); DC link outside
  DC_Link_Umin/Umax is 1816/1815.
* D23 The brake bit (Break, bit 24) is set when a motion starts; if it was not set, the motion
  starts Braketime_Turn_On ms later; it drops Braketime_Turn_Off ms before a position move ends
  (at standstill otherwise). §3.11.4 naming (wago.md §2.11 [CONFLICT]).
* D24 Positions: user -> microsteps and microsteps -> user truncate toward zero; the set point is
  reported as its nearest microstep (units.py).
* D25 Current_Ratio_Stop applies while a STOP ramp brakes; at standstill (also with Stop2_N = 0) the
  standstill ratio holds the motor - 150 % at rest would trip the 10 s overcurrent model.
* D26 Drive_Direction (HwSwConfig bit 2) inverts the sign of the set point handed to the axis only;
  logical positions, limit switches and software limits keep their directions (wago.md §4.3).

Tests (tests/devices/wago672): D1 test_speed.py; D2-D4 test_jog.py (test_start_in_jog_mode_is_ignored,
test_jog_by_direction_bits_and_both_directions_turn_the_drive_off, test_stepping_mode_timeout_ends_the_run);
D5-D7 test_referencing.py, test_drive_command.py::test_start_referencing_does_not_set_on_target; D8
test_positioning.py::test_on_the_fly_with_linear_ramps_waits_for_constant_speed; D9-D11, D26
test_limits_and_rotary.py; D12 test_speed.py; D13 test_positioning.py::test_exchange_of_wago_md_9_12;
D14, D16, D22 test_errors.py; D15 test_enable_chain.py; D17, D18 test_drive_command.py::test_speed_and_stop_fast;
D20 test_positioning.py::test_velocity_above_speed_limit_turns_the_drive_off; D23
test_positioning.py::test_brake_released_before_the_move_and_applied_before_the_target.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from typing import Any, Protocol

from axisline.devices.wago672.bits import Bit, BitTable
from axisline.devices.wago672.config_table import CONF_VERSION, ConfigTable, ConfigValueError
from axisline.devices.wago672.errors import ErrorClass, ErrorMemory, WagoError, blink_signal, err_flag, error_class
from axisline.devices.wago672.image import (
    C0,
    MODE_IDLE,
    MODE_JOG,
    MODE_MAILBOX,
    MODE_POSITIONING,
    MODE_PROGRAM,
    MODE_REFERENCING,
    MODE_SPEED,
    InputImage,
    OutputImage,
    PositioningActuals,
    PositioningSetpoints,
    ProgramActuals,
    ProgramSetpoints,
    S0,
    SpeedSetpoints,
)
from axisline.devices.wago672.referencing import RefPhase, RefRun
from axisline.devices.wago672.thermal import CurrentPhase, OvercurrentModel, phase_current
from axisline.devices.wago672.trajectory import (
    ACC_INTERNAL_MAX,
    Feed,
    Ramp,
    needs_constant_speed,
    plan_move,
    plan_speed,
    plan_stop,
    ramp_from_mode,
)
from axisline.devices.wago672.units import Scaling, acc_multiplier, freq_prescaler
from axisline.motion.axis import Axis, AxisState, ErrorId
from axisline.motion.profiles import Limits, State, plan_velocity

__all__ = ["Wago672", "NoMailbox", "MailboxHandler", "RunProgram", "Opcode", "RC"]

TICK = 0.001  # the module's scan interval: one TICK = 1 ms (§3.10.6.1.1)
SPEED_CONTROL_PERIOD = 100000  # implicit rotary period of speed control [microsteps] (D11)
_MODE_BITS = {MODE_POSITIONING: 1, MODE_PROGRAM: 2, MODE_SPEED: 3, MODE_REFERENCING: 4, MODE_JOG: 8, MODE_MAILBOX: 16}


class Opcode:
    """Move-mode commands of DRIVE_COMMAND and run programs (manual §4.3, wago.md §3.9)."""

    PROG_END = 0x00
    MOVE = 0x02
    MOVE_IMMEDIATE = 0x03
    MOVE_TABLE = 0x04
    MOVE_TABLE_IMMEDIATE = 0x05
    MOVE_REL = 0x06
    MOVE_TABLE_REL = 0x08
    SPEED = 0x10
    SPEED_IMMEDIATE = 0x11
    STOP_FAST = 0x18
    STOP_NO_RAMP = 0x19
    TORQ = 0x1C
    TORQ_IMM = 0x1D
    START_REFERENCING = 0x20
    SET_ACC_MODE = 0x21
    SET_ACC = 0x22
    SET_ACC_PARAM_UP = 0x23
    SET_ACC_PARAM_DOWN = 0x24
    SET_VELOCITY = 0x25
    SET_VELOCITY_TARGET = 0x2B
    SET_ACTUALPOSITION = 0x2E
    SET_ACTUALPOSITION_ZERO = 0x2F
    SET_CURRENT = 0x39


class RC:
    """Mailbox return codes (Status_Mbx bits 0..6, wago.md §3.7)."""

    OK = 0x00
    GENERAL_ERROR = 0x01
    STILL_EXECUTING = 0x11
    NOT_ACCEPTED = 0x12
    UNKNOWN_COMMAND = 0x13
    ACCESS_DENIED = 0x23


class MailboxHandler(Protocol):
    """The mailbox engine: called every tick while the mailbox is on (C0.5) with MB0..MB5 of
    the PLC; returns MB0..MB5 of the reply (6 bytes)."""

    def exchange(self, request: bytes, device: Wago672) -> bytes: ...


class NoMailbox:
    """Placeholder mailbox: the toggle handshake of §3.7.4 with return code 0x13 (unknown
    command) for every opcode except IDLE (0x00 OK) - "mailbox not available" until the
    mailbox engine is plugged in."""

    def __init__(self) -> None:
        self._reply = bytes(6)
        self._last: tuple[int, int] | None = None

    def exchange(self, request: bytes, device: Wago672) -> bytes:
        opcode, toggle = request[0], request[1] & 0x80
        if self._last is None or (opcode, toggle) != self._last:
            self._last = (opcode, toggle)
            rc = RC.OK if opcode == 0x00 else RC.UNKNOWN_COMMAND
            self._reply = bytes([opcode, toggle | rc, 0, 0, 0, 0])
        return self._reply


class RunProgram(Protocol):
    """Run-program interpreter hook (table manager engineer)."""

    running: bool
    counter: int

    def start(self, address: int, device: Wago672) -> None: ...  # raises WagoError (e.g. 1352)
    def stop(self, device: Wago672) -> None: ...
    def tick(self, cycle: int, device: Wago672) -> None: ...


def _no_position_table(index: int, src: int) -> int:
    raise WagoError(1333, f"position table entry {index} (SRC {src}): no position table is active")


class _Inputs:
    """DI1 .. DI6 from a mapping of booleans or callables ("Input1".."Input6" or 1..6)."""

    def __init__(self, inputs: Mapping[Any, Any] | None) -> None:
        self.source = inputs if inputs is not None else {}

    def read(self, n: int) -> bool:
        src = self.source
        v = src.get(f"Input{n}", src.get(n, False)) if hasattr(src, "get") else False
        if callable(v):
            v = v()
        return bool(v)


class Wago672:
    """The 750-672 module on one stepper axis. See the module docstring."""

    def __init__(
        self,
        axis: Axis,
        inputs: Mapping[Any, Any] | None = None,
        config: ConfigTable | None = None,
        *,
        mailbox: MailboxHandler | None = None,
        program: RunProgram | None = None,
    ) -> None:
        if not math.isclose(axis.period, TICK, rel_tol=1e-9):
            raise ValueError(f"the 750-672 runs a 1 ms TICK; axis {axis.name} has a cycle of {axis.period * 1000:g} ms")
        self.axis = axis
        self.inputs = _Inputs(inputs)
        self.config = config if config is not None else ConfigTable()
        try:
            self.config.validate()
        except ConfigValueError as e:
            raise ValueError(f"configuration table not usable: {e}") from None
        self.bits = BitTable(self.config)
        self.errors = ErrorMemory()
        self.mailbox: MailboxHandler = mailbox if mailbox is not None else NoMailbox()
        self.program: RunProgram | None = program
        self.position_table: Callable[[int, int], int] = _no_position_table
        self.cam_pattern: Callable[[float], int] | None = None
        self.eeprom_writing = False  # set by the table manager: LED A flashes at 10 Hz
        self.on_warm_start: Callable[[Wago672], None] | None = None  # table manager: reload EEPROM data
        # second engineer's parts (mailbox.attach): called each tick after the source bits are
        # written (filters, data recorder, autostart, EEPROM jobs), and extra state variables
        self.tick_hooks: list[Callable[[int], None]] = []
        self.extra_variables: dict[int, Callable[[], int]] = {}
        self.stepping_timeout_ms = 0  # SteppingMode (D4): 0 = JogMode without time limit
        self.reference_on_target = True  # D5: On_Target after a PI reference run
        # simulated environment of the output stage (D22): temperature [degC], DC link [V]
        self.environment: dict[str, float] = {"stage_temperature": 40.0, "dc_link_voltage": 55.0}
        self._k = axis.scale.counts_per_unit  # microsteps per axis unit
        self.feed = Feed(self._k, axis.period)
        self._sync_cmd = None
        self._out = OutputImage()
        self._last_write: int | None = None
        self._cycle: int | None = None
        self._in_tick = False
        self._power_on()

    # ================================================================== power-on / warm start

    def _power_on(self) -> None:
        """State after power-on or a warm start (wago.md §7.1)."""
        self.errors.clear()
        self.bits.reset()
        self.reset_flag = True  # Reset (S3.7) until Reset_Quit
        self.mode = MODE_IDLE  # acknowledged mode (Command_Ack)
        self._mode_exit = False
        self._ready = False
        self._stage_on = False
        self._stop_n_ack = False
        self._start_ack = False
        self.on_target = False
        self.busy = False
        self.on_speed = False
        self.reference_ok = False
        self.precalc_ack = False
        self._direction = False
        self._motion: str | None = None  # "position", "speed", "stop", "jog", "reference"
        self._stopping = False  # a STOP ramp runs (Current_Ratio_Stop)
        self._target: float | None = None  # position target [microsteps, unwrapped]
        self._last_target: float | None = None  # MOVE_REL base (D18)
        self._v_set = 0.0  # commanded speed [user units] for On_Speed
        self._v_set_f = 0.0  # [microsteps/s]
        self._pending: Callable[[], None] | None = None  # deferred set point (D8)
        self._cur_up = self._cur_down = Ramp("trapezoid", 1.0)
        self._precalc: dict | None = None
        self._source = "pi"  # who started the running task: "pi", "mailbox", "program"
        self._mailbox_reference = False
        self.err_range_pos = False
        self.err_range_neg = False
        self._range_block = 0  # a refused reference start at this limit switch (+1/-1)
        self._ls_special = 0  # +1/-1: on that limit switch after a limit-switch reference run
        self._ls_left: int | None = None
        self._jog_dir = 0
        self._jog_block = False
        self._jog_started = 0
        self._jog_ls = 0
        self._jog_outside = False
        self._ref: RefRun | None = None
        self._ref_pending_shift = 0.0
        self._brake_auto = False
        self._overcurrent = OvercurrentModel()
        self.current_phase = CurrentPhase.OFF
        self.phase_current = 0.0
        self.current_ratio = 0
        self._ratio_set: dict[CurrentPhase, int] = {}  # SET_CURRENT values (else the configuration's)
        self._error_since = 0
        self._bad_selection = 0
        self._prev: dict[str, bool] = {}
        self._sig: dict[str, bool] = {}
        self._sp = (0.0, 0.0, 0.0, 0.0)
        self._mbx_on = False
        self._mbx_reply = bytes(6)
        self._status = (0, 0, 0, 0)
        self._outputs = (False, False)
        self._move_settings_from_config()
        self._latch_scaling()
        if self._sync_cmd is not None or self.axis.powered:
            self._axis_power(False)
        p = self._axis_steps()
        self.feed.hold(p)
        self._sp = (p, 0.0, 0.0, 0.0)

    def _move_settings_from_config(self) -> None:
        """Defaults of the move commands (SET_ACC_MODE, SET_ACC, ..., SET_VELOCITY)."""
        c = self.config
        self.acc_mode = c["Acceleration_Modes"]
        self.acc_up = c["Acceleration_RampUp"]
        self.acc_down = c["Acceleration_RampDown"]
        self.param_up = c["Acceleration_RampUp_Param"]
        self.param_down = c["Acceleration_RampDown_Param"]
        self.velocity = c["Speed"]
        self.velocity_target = 0

    def warm_start(self) -> None:
        """Warm start: volatile state lost, Reset bit set (also after acknowledging a 2xxx error)."""
        if self.on_warm_start is not None:
            self.on_warm_start(self)
        self._power_on()

    # ================================================================== PLC side

    def write_outputs(self, data: bytes | bytearray | OutputImage) -> None:
        """The 12 output bytes of the PLC (C0, res, D0..D6, C3, C2, C1); taken at the next tick."""
        self._out = data if isinstance(data, OutputImage) else OutputImage.from_bytes(data)
        self._last_write = self._cycle if self._cycle is not None else 0

    def read_inputs(self) -> bytes:
        """The 12 input bytes for the PLC as of the last tick."""
        return self.input_image().to_bytes()

    def input_image(self) -> InputImage:
        s0, s1, s2, s3 = self._status
        if self._mbx_on:
            data = self._mbx_reply + b"\x00"
        else:
            pos, vel = self._reported()
            if self.mode == MODE_PROGRAM:
                counter = self.program.counter if self.program is not None else 0
                data = ProgramActuals(vel, counter & 0xFFFF, pos).encode()
            else:
                data = PositioningActuals(vel, pos).encode()
        return InputImage(s0, s1, s2, s3, data)

    # ================================================================== read-outs

    @property
    def ready(self) -> bool:
        return self._ready

    @property
    def stop_n_ack(self) -> bool:
        return self._stop_n_ack

    @property
    def start_ack(self) -> bool:
        return self._start_ack

    @property
    def position_steps(self) -> float:
        """Set point of the last tick [microsteps, unwrapped, axis frame]."""
        return self._sp[0]

    @property
    def velocity_steps(self) -> float:
        return self._sp[1]

    @property
    def outputs(self) -> tuple[bool, bool]:
        """DO1, DO2 (OUT1, OUT2: On_Target and Error by default)."""
        return self._outputs

    @property
    def standstill(self) -> bool:
        return self._sp[1] == 0.0

    @property
    def brake(self) -> bool:
        """The Break bit: 1 brake vented (released)."""
        return self._brake_auto or self._sig.get("brake_manual", False)

    def rotary_period(self) -> int:
        """The period the actual value wraps with [microsteps] (0: linear)."""
        p = self.config["Rotary_Axis_Period"]
        if p == 0 and self.mode == MODE_SPEED:
            return SPEED_CONTROL_PERIOD
        return p

    def _reported(self) -> tuple[int, int]:
        """Actual position and velocity in user units for the process image."""
        p = self._sp[0] + self._ref_pending_shift
        steps = int(math.copysign(math.floor(abs(p) + 0.5), p))
        period = self.rotary_period()
        if period:
            steps %= period
        try:
            pos = self.scaling.position(steps)
        except WagoError:
            pos = max(-8388608, min(8388607, int(steps * self.scaling.pos_div / self.scaling.pos_mult)))
        try:
            vel = self.scaling.velocity(self._sp[1])
        except WagoError:
            vel = 32767 if self._sp[1] > 0 else -32768
        return pos, vel

    @property
    def actual_position(self) -> int:
        """Actual position [position units], as reported in D4..D6."""
        return self._reported()[0]

    @property
    def actual_velocity(self) -> int:
        return self._reported()[1]

    def leds(self) -> dict[str, bool]:
        """LED states (§3.3; A..F through the linkable LED bits of §4.5, G..N the I/O)."""
        b = self.bits
        cyc = self._cycle or 0
        led_a = b.read(Bit.LED_A)
        if self.eeprom_writing:
            led_a = (cyc // 50) % 2 == 0  # 10 Hz while the EEPROM is written
        leds = {
            "A": led_a,
            "B": b.read(Bit.LED_B) and self.mode != MODE_SPEED,
            "C": b.read(Bit.LED_C),
            "D": b.read(Bit.LED_D),
            "E": b.read(Bit.LED_E),
            "F": b.read(Bit.LED_F),
            "G": self._outputs[0],
            "H": self._outputs[1],
        }
        for i, name in enumerate("IJKLMN"):
            leds[name] = b.read(Bit.Input1 + i)
        return leds

    def state_variable(self, index: int) -> int:
        """Internal state variable `index` (DIAG_RD_VAR, manual §4.7; 0x1000 + n: bit n)."""
        extra = self.extra_variables.get(index)
        if extra is not None:
            return int(extra())
        if 0x1000 <= index <= 0x10FF:
            return int(self.bits.read(index - 0x1000))
        pos, vel = self._reported()
        cyc = self._cycle or 0
        values = {
            0: cyc,
            1: pos,
            2: vel,
            9: 8,  # hardware version: 8 = 750-672
            15: CONF_VERSION,
            16: self.config["ConfVersion"],
            20: self.scaling.prescaler,
            21: self._overcurrent.state_variable,
            24: int(round(self._sp[0])),
            25: int(round(self._sp[1])),
            30: int(round(self._target)) if self._target is not None else int(round(self._v_set_f)),
            31: self.scaling.multiplier,
            41: self.program.counter if self.program is not None else 0,
            43: int(round(self._v_set_f)),
            55: self.scaling.prescaler,
            56: self.current_ratio,
            1024: cyc,
            1025: pos,
            1026: vel,
            1046: int(round(self.environment["stage_temperature"] * 10)),
            1048: int(round(self.environment["dc_link_voltage"] * 10)),
        }
        return values.get(index, 0)

    # ================================================================== the tick

    def tick(self, cycle: int) -> None:
        """Process one 1 ms cycle; call before `axis.update_setpoint(cycle)`."""
        self._in_tick = True
        self._now = cycle
        try:
            self._tick(cycle)
        finally:
            self._in_tick = False
            self._cycle = cycle

    def _c_plan(self) -> int:
        """Cycle of the last set point: a plan starts from it (kernel rule)."""
        if self._in_tick:
            return self._now - 1
        return self._cycle if self._cycle is not None else 0

    def _tick(self, cycle: int) -> None:
        c = self.config
        b = self.bits
        out = self._out
        # ---- 1 sources: inputs and control bytes
        for i in range(6):
            b.put(Bit.Input1 + i, self.inputs.read(i + 1))
        b.set_byte(Bit.KBUS_CTRL1_0, out.c1)
        b.set_byte(Bit.KBUS_CTRL2_0, out.c2)
        b.set_byte(Bit.KBUS_CTRL3_0, out.c3)
        b.put(Bit.KBUS_Active, self._last_write is not None and cycle - self._last_write <= 100)
        # ---- 2 the signals this module consumes, through their links
        try:
            s = self._read_signals()
        except WagoError as e:
            self._raise(e.code, e.text)
            s = self._sig or {k: False for k in _SIGNALS}
        self._sig = s
        prev = self._prev
        edge = {k: s[k] and not prev.get(k, False) for k in s}
        # ---- 3 reset handshake and latched scaling
        if s["reset_quit"]:
            self.reset_flag = False
        if not s["enable"]:
            self._latch_scaling()
        # ---- 4 error sources and Error_Quit
        self._watch_environment(s)
        if edge["error_quit"]:
            self.quit_errors()
        # ---- 5 Ready and the output stage
        ready = s["enable"] and not self.errors.error
        if self._ready and not ready:
            self._lose_ready()
        self._ready = ready
        self._stage_on = ready and s["enable_drive"]
        if not self._stage_on and self._motion is not None:
            self._no_ramp(stopped=True)
        self._axis_power(self._stage_on)
        if not self._stage_on:
            self.feed.hold(self._axis_steps())
        # ---- 6 the stop chain (Stop2_N, Stop1_N)
        stop_ok = s["stop2_n"] and s["stop1_n"]
        if ready and not stop_ok:
            self._pending = None
            if self._ref is not None and self._ref.active:
                self._ref = None
            self._jog_dir = 0
            if not self._at_rest() and not self._stopping:
                self._stop_fast()
            if self.program is not None and self.program.running:
                self.program.stop(self)
        self._stop_n_ack = ready and (stop_ok or not self._at_rest())
        # ---- 7 modes
        self._select_mode(s)
        # ---- 8 Start, PreCalc, SetActual_Pos
        if edge["start"]:
            self._on_start(s)
        elif not s["start"]:
            self._start_ack = False
        if self.mode in (MODE_POSITIONING, MODE_SPEED):
            self._precalc_step(s, edge)
        elif self._precalc is not None or self.precalc_ack:
            self._precalc, self.precalc_ack = None, False
        if edge["set_actual"] and self._stage_on and self._at_rest() and self._motion is None:
            try:
                self._set_actual(self.scaling.steps(c["Reference_Offset"], "Reference_Offset"))
            except WagoError as e:
                self._raise(e.code, e.text)
        # ---- 9 mode work: referencing, jog, program, mailbox, deferred set points
        if self._ref is not None and self._ref.active and self._stage_on:
            self._ref.step(s["set_reference"], s["ls_pos"], s["ls_neg"])
        if self.mode == MODE_JOG and not self._mode_exit and self._stage_on and stop_ok:
            self._jog_step(s, cycle)
        if self.program is not None and (self.mode == MODE_PROGRAM or self._autostarted()) and self._ready:
            self.program.tick(cycle, self)
        self._mbx_on = bool(out.c0 & C0.MBX)
        if self._mbx_on:
            self._mbx_reply = bytes(self.mailbox.exchange(out.mailbox_request, self))[:6].ljust(6, b"\x00")
        if self._pending is not None and self._stage_on:
            st = self._state()
            if st.a == 0.0:
                pending, self._pending = self._pending, None
                self._guard(pending)
        # ---- 10 watches: limit switches, software limits, speed limit
        if self._stage_on:
            self._watch_limits(s, cycle)
        # ---- 11 this cycle's set point and the states it implies
        self._sp = self.feed.state(cycle)
        self._finish_motions(cycle, stop_ok)
        self._update_flags(s)
        self._current_and_brake(cycle)
        # ---- 12 sources out, axis sync, status bytes
        self._write_sources(s, cycle)
        for hook in self.tick_hooks:
            hook(cycle)
        self._sync_axis(cycle)
        self._status = (self._s0(s), b.byte(Bit.KBUS_ST1_0), b.byte(Bit.KBUS_ST2_0), b.byte(Bit.KBUS_ST3_0))
        self._outputs = (b.read(Bit.OUT1), b.read(Bit.OUT2))
        self._prev = s

    def _read_signals(self) -> dict[str, bool]:
        r = self.bits._resolve  # the bit numbers are known to be valid
        return {name: r(bit, 0) for name, bit in _SIGNAL_ITEMS}

    # ================================================================== errors

    def _raise(self, code: int, text: str = "", cause: Callable[[], bool] | None = None) -> None:
        """Raise a device error or warning. An error switches the output stage off at once."""
        if not self.errors.raise_code(code, text, cause=cause):
            return
        if error_class(code) is ErrorClass.WARNING:
            return
        self._error_since = self._cycle or 0
        if self._ready:
            self._lose_ready()
        self._ready = False
        self._stage_on = False
        self._axis_power(False)
        self.current_phase = CurrentPhase.OFF  # the output stage is off: no current from now on
        self.phase_current = 0.0
        self.current_ratio = 0

    def raise_error(self, code: int, text: str = "", cause: Callable[[], bool] | None = None) -> None:
        """For the second engineer's parts (tables, programs, bit linking): report a device error."""
        self._raise(code, text, cause)

    def quit_errors(self) -> None:
        """Error_Quit rising edge or DIAG_QUIT_ERROR: acknowledge errors and warnings (D16)."""
        if self.errors.acknowledge():
            self.warm_start()
            return
        if self.axis.state is AxisState.ERROR_STOP and not self.errors.error:
            self.axis.reset()

    def _watch_environment(self, s: dict[str, bool]) -> None:
        c = self.config
        if s["error_set"]:
            self._raise(1358, "Error_Set is 1", cause=lambda: self._sig.get("error_set", False))
        temp = self.environment["stage_temperature"]
        if temp * 10.0 > c["Warn_Treshold_Temperature"]:
            over = lambda: self.environment["stage_temperature"] * 10.0 > self.config["Warn_Treshold_Temperature"]  # noqa: E731
            text = f"output stage {temp:g} degC above Warn_Treshold_Temperature {c['Warn_Treshold_Temperature'] / 10:g} degC"
            if c["ErrorNotificationMode"] & 2:
                self._raise(1894, text, cause=over)
            elif c["WarningNotificationMode"] & 2:
                self._raise(5893, text, cause=over)
        u = self.environment["dc_link_voltage"] * 10.0
        if u > c["DC_Link_Umax"]:
            self._raise(1815, f"DC link {u / 10:g} V above DC_Link_Umax {c['DC_Link_Umax'] / 10:g} V",
                        cause=lambda: self.environment["dc_link_voltage"] * 10.0 > self.config["DC_Link_Umax"])
        elif u < c["DC_Link_Umin"]:
            self._raise(1816, f"DC link {u / 10:g} V below DC_Link_Umin {c['DC_Link_Umin'] / 10:g} V",
                        cause=lambda: self.environment["dc_link_voltage"] * 10.0 < self.config["DC_Link_Umin"])
        if self.axis.state is AxisState.ERROR_STOP:
            code = 1892 if self.axis.error_id == ErrorId.FOLLOWING_ERROR else 1811
            self._raise(code, f"axis {self.axis.name}: {self.axis.error_text}")

    # ================================================================== ready, power, axis sync

    def _lose_ready(self) -> None:
        """Ready 1 -> 0: speed 0 at once, mode ACK cleared at once (§3.11.1.2)."""
        self._no_ramp(stopped=True)
        self.mode = MODE_IDLE
        self._mode_exit = False
        self._stop_n_ack = False
        self._start_ack = False
        self.busy = False
        self.on_speed = False
        self._ref = None
        self._jog_dir = 0
        self._precalc, self.precalc_ack = None, False
        if self.program is not None and self.program.running:
            self.program.stop(self)

    def _axis_steps(self) -> float:
        return self.axis.command_position * self._k * self._dir_sign

    def _axis_power(self, on: bool) -> None:
        ax = self.axis
        if on and not ax.powered:
            if ax.state is AxisState.ERROR_STOP:
                ax.reset()
            ax.power(True)
            self.feed.hold(self._axis_steps())
            self._sync_cmd = None
        elif not on and ax.powered:
            ax.power(False)
            self._sync_cmd = None

    def _engaged(self) -> bool:
        cmd = self._sync_cmd
        return cmd is not None and cmd.active and self.axis.state is AxisState.SYNCHRONIZED_MOTION

    def _sync_axis(self, cycle: int) -> None:
        """Hand the feed to the axis while it moves; release it (STANDSTILL) at rest."""
        if not self._stage_on or not self.axis.powered:
            return
        ax = self.axis
        moving = not (
            self.feed.ended(cycle - 1)
            and self.feed.state(cycle - 1)[1] == 0.0
            and self._sp[1] == 0.0
            and ax.command_velocity == 0.0
            and ax.command_acceleration == 0.0
        )
        engaged = self._engaged()
        if moving and not engaged:
            if self.axis.state in (AxisState.STANDSTILL, AxisState.DISCRETE_MOTION, AxisState.CONTINUOUS_MOTION):
                cmd = self.axis.start_sync(self.feed)
                self._sync_cmd = cmd if not cmd.error else None
                if cmd.error:
                    self._raise(1811, f"axis {self.axis.name} refused the set point: {cmd.error_text}")
        elif not moving and engaged:
            self.axis.end_sync()
            self._sync_cmd = None

    def _state(self) -> State:
        """The set point a plan starts from (the last cycle's)."""
        p, v, a, _ = self.feed.state(self._c_plan())
        return State(p, v, a)

    def _at_rest(self) -> bool:
        c = self._c_plan()
        return self.feed.ended(c) and self.feed.state(c)[1] == 0.0

    def _run(self, profile, kind: str, up: Ramp | None = None, down: Ramp | None = None) -> None:
        """Start `profile` from the last set point (brake delay D23 when starting from rest)."""
        c0 = self._c_plan()
        delay = 0
        if not self._brake_auto and self._at_rest():
            delay = self.config["Braketime_Turn_On"]
        self._brake_auto = True
        self.feed.run(profile, c0 + delay)
        self._motion = kind
        self._stopping = kind == "stop"
        self._cur_up = up or Ramp("trapezoid", 1.0)
        self._cur_down = down or self._cur_up

    def _stop_fast(self, kind: str = "stop") -> None:
        """STOP_FAST: brake with Acceleration_Stop_Fast (0: the running deceleration) (D19)."""
        self._pending = None
        st = self._state()
        if st.v == 0.0 and self.feed.ended(self._c_plan()):
            return
        value = self.config["Acceleration_Stop_Fast"]
        try:
            decel = self.scaling.accel(value, "Acceleration_Stop_Fast") if value else self._cur_down.accel
        except WagoError as e:
            self._raise(e.code, e.text)
            return
        keep = self._motion if kind == "keep" else kind
        self._run(plan_stop(st, decel), keep or "stop", Ramp("trapezoid", decel))
        self._stopping = True
        self._last_target = None

    def _no_ramp(self, stopped: bool = False) -> None:
        """STOP_NO_RAMP: frequency 0 at once; the set point stays where it is."""
        self.feed.hold(self._state().p if self._stage_on or stopped else self._axis_steps())
        self._pending = None
        self._motion = None
        self._stopping = False
        self._last_target = None
        self._brake_auto = False

    def _set_actual(self, steps: float) -> None:
        """ActualPosition := steps at standstill (the logical zero is moved)."""
        if self._engaged():
            self.axis.end_sync()
            self._sync_cmd = None
        p = self._state().p
        delta = steps - p
        self.axis.set_position(delta / self._k * self._dir_sign, relative=True)
        self.feed.hold(steps)
        self._sp = (steps, 0.0, 0.0, 0.0)
        self._last_target = None
        self._target = None

    # ================================================================== scaling and ramps

    def _latch_scaling(self) -> None:
        """Prescaler, acceleration factor and scaling factors, taken while Enable = 0 (D15)."""
        c = self.config
        out = self._out
        sig = self._sig
        if sig:
            fsel = int(sig["freq_sel_0"]) | int(sig["freq_sel_1"]) << 1
            asel = int(sig["acc_sel_0"]) | int(sig["acc_sel_1"]) << 1
        else:
            fsel, asel = out.c2 & 3, (out.c2 >> 2) & 3
        try:
            self.scaling = Scaling(
                prescaler=freq_prescaler(fsel, c["Freq_Div"]),
                multiplier=acc_multiplier(asel, c["Acc_Fact"]),
                pos_mult=c["Pos_Mult"], pos_div=c["Pos_Div"],
                speed_mult=c["Speed_Mult"], speed_div=c["Speed_Div"],
                acc_mult=c["Acc_Mult"], acc_div=c["Acc_Div"],
            )
        except WagoError as e:
            self._raise(e.code, e.text)
        self._dir_sign = -1.0 if c["HwSwConfig"] & 0x04 else 1.0
        self.feed.steps_per_unit = self._k * self._dir_sign

    def _ramps(self, acc_up: int, acc_down: int, v_f: float) -> tuple[Ramp, Ramp]:
        """Ramp laws of a positioning or speed command from the acceleration settings."""
        sc = self.scaling
        m = self.acc_mode
        a_up = sc.accel(acc_up, "Acceleration (ramp-up)")
        a_dn = sc.accel(acc_down, "Acceleration (ramp-down)")
        ramps = []
        for phase, typ, par, a, raw in (("Acc", m & 3, (m >> 2) & 3, a_up, self.param_up), ("Dec", (m >> 4) & 3, (m >> 6) & 3, a_dn, self.param_down)):
            steps = abs(sc.distance(raw)) if par == 2 else None
            r = ramp_from_mode(typ, par, a, raw, steps, phase)
            # a ramp time/path that needs more acceleration than the module can make
            peak = None
            if r.time is not None:
                peak = 2.0 * abs(v_f) / r.time
            elif r.path is not None:
                peak = v_f * v_f / r.path
            if peak is not None and peak > ACC_INTERNAL_MAX:
                code = 1556 if r.path is not None else (1554 if phase == "Acc" else 1555)
                raise WagoError(code, f"{phase} ramp {'path' if r.path is not None else 'time'} {raw}: {peak:.0f} microsteps/s^2 exceeds {ACC_INTERNAL_MAX:.0f}")
            ramps.append(r)
        return ramps[0], ramps[1]

    def _defer(self, new_needs_rest: bool) -> bool:
        """Must a new set point wait for v = const? (D8)"""
        st = self._state()
        if st.a == 0.0:
            return False
        if new_needs_rest:
            return True
        accelerating = st.a * st.v > 0.0 or st.v == 0.0
        return (self._cur_up if accelerating else self._cur_down).smooth

    # ================================================================== mode selection

    def _select_mode(self, s: dict[str, bool]) -> None:
        requested = int(s["cmd1"]) | int(s["cmd2"]) << 1 | int(s["cmd3"]) << 2 | int(s["cmd4"]) << 3 | int(s["cmd5"]) << 4
        if self.mode != MODE_IDLE:
            bits = _MODE_BITS[self.mode]
            still = (requested & bits) == bits
            if not still or not self._stop_n_ack:
                if not self._mode_exit:
                    self._leave_mode()
                if self._at_rest():
                    self.mode = MODE_IDLE
                    self._mode_exit = False
                    self._motion = None
            return
        if requested == 0:
            self._bad_selection = 0
            return
        if not (self._ready and self._stop_n_ack and not self._start_ack and not s["start"]):
            return  # selection waits until the module is ready for it (§3.11.1.1)
        if requested not in _MODE_BITS:
            if requested != self._bad_selection:
                self._bad_selection = requested
                self._raise(1354, f"mode bits C1 = {requested << 3:#04x} select more than one mode")
            return
        self.mode = requested
        self._bad_selection = 0
        self.on_target = False
        self.busy = False
        self.on_speed = False
        self._start_ack = False
        self._source = "pi"
        self._jog_dir = 0
        self._jog_block = False
        self._last_target = None

    def _leave_mode(self) -> None:
        """Mode bit cleared (or Stop_N_ACK lost): brake, end the mode's task."""
        self._mode_exit = True
        self._pending = None
        self._ref = None
        self._jog_dir = 0
        if self.program is not None and self.program.running:
            self.program.stop(self)
        if not self._at_rest() and not self._stopping:
            self._stop_fast()
        self.on_target = False
        self.busy = False

    # ================================================================== Start

    def _on_start(self, s: dict[str, bool]) -> None:
        if s["error_quit"]:
            self._raise(1361, "Start while Error_Quit is set")
            return
        if not self._ready:
            return
        if self.mode == MODE_IDLE:
            if self._bad_selection == 0:
                self._raise(1351, "Start without an active mode")
            return
        if self._mode_exit:
            return  # D14
        mode = self.mode
        if mode in (MODE_JOG, MODE_MAILBOX):
            return  # D2: no handshake, no error
        if not s["stop2_n"] or not s["stop1_n"]:
            return
        self._source = "pi"
        ok = True
        try:
            if mode == MODE_POSITIONING:
                if s["precalc"] and self._precalc is not None:
                    ok = self._start_precalc()
                else:
                    sp = PositioningSetpoints.decode(self._out.data)
                    ok = self._pi_position(sp.velocity, sp.acceleration, sp.target)
            elif mode == MODE_SPEED:
                if s["precalc"] and self._precalc is not None:
                    ok = self._start_precalc()
                else:
                    sp = SpeedSetpoints.decode(self._out.data)
                    ok = self._pi_speed(sp.velocity, sp.acceleration)
            elif mode == MODE_REFERENCING:
                ok = self._pi_reference(s)
            elif mode == MODE_PROGRAM:
                if self.program is None:
                    raise WagoError(1352, "no run program is available (no table manager)")
                self._pending = None
                if not self._at_rest():
                    self._stop_fast()
                self.program.start(ProgramSetpoints.decode(self._out.data).start_counter, self)
                self._source = "program"
        except WagoError as e:
            self._raise(e.code, e.text)
            return
        self._start_ack = self._ready and ok is not None

    # ---- single positioning
    def _pi_position(self, velocity: int, acceleration: int, target: int) -> bool:
        if not 1 <= velocity <= 25000:
            raise WagoError(1117, f"Velocity = {velocity} is outside 1 .. 25000")
        if not 1 <= acceleration <= 32767:
            raise WagoError(1121, f"Acceleration = {acceleration} is outside 1 .. 32767")
        return self._move(self._absolute_target(target), velocity, acceleration, acceleration)

    def _absolute_target(self, position: int) -> float:
        """User target -> unwrapped microsteps (rotary: [0, P) and the direction rule, D11)."""
        steps = self.scaling.steps(position, "Target position")
        period = self.config["Rotary_Axis_Period"]
        if not period:
            return float(steps)
        if not 0 <= steps < period:
            raise WagoError(1123, f"Target position {position} ({steps} microsteps) is outside the rotary axis range 0 .. {period - 1}")
        st = self._state()
        base = math.floor(st.p / period) * period
        cur = st.p - base
        if st.v == 0.0:
            diff = steps - cur
            if diff > period / 2.0:
                diff -= period
            elif diff <= -period / 2.0:
                diff += period
            return st.p + diff
        # moving: the first equivalent target at or beyond the stopping point (no reversal)
        a = self._cur_down.accel if self._cur_down.accel > 1.0 else 1.0
        stop_at = st.p + math.copysign(st.v * st.v / (2.0 * a), st.v)
        k = math.ceil((stop_at - steps - base) / period) if st.v > 0 else math.floor((stop_at - steps - base) / period)
        return base + steps + k * period

    def _move(self, target: float, velocity: int, acc_up: int, acc_down: int, v_end: int = 0) -> bool:
        """Start (or retarget) a positioning move [target microsteps]; False if refused (D9)."""
        c = self.config
        if velocity > c["Speed_Limit"]:
            raise WagoError(1212, f"Velocity = {velocity} is above Speed_Limit = {c['Speed_Limit']}")
        if self._sig.get("setup_active", False):
            velocity = min(velocity, max(c["SetupSpeed"], 1))
        f = self.scaling.frequency(velocity)
        st = self._state()
        direction = 1 if target > st.p else -1 if target < st.p else 0
        self._check_limit_switch(direction)
        if self._refused_by_range(direction):
            self.busy = False
            self.on_target = False
            return False
        up, down = self._ramps(acc_up, acc_down, f)
        f_end = math.copysign(self.scaling.frequency(v_end), direction) if v_end else 0.0
        self._target = target
        self._last_target = target
        self._v_set = velocity
        self._v_set_f = f
        self.on_target = False
        self.busy = True

        def go() -> None:
            self._run(plan_move(self._state(), target, f, up, down, f_end), "position", up, down)

        if self._defer(needs_constant_speed(up, down)):
            self._pending = go
        else:
            self._pending = None
            go()
        return True

    # ---- speed control
    def _pi_speed(self, velocity: int, acceleration: int) -> bool:
        if not -25000 <= velocity <= 25000:
            raise WagoError(1117, f"Velocity = {velocity} is outside -25000 .. 25000")
        if not 1 <= acceleration <= 32767:
            raise WagoError(1121, f"Acceleration = {acceleration} is outside 1 .. 32767")
        return self._speed(velocity, acceleration, acceleration)

    def _speed(self, velocity: int, acc_up: int, acc_down: int) -> bool:
        c = self.config
        if abs(velocity) > c["Speed_Limit"]:
            raise WagoError(1212, f"Velocity = {velocity} is above Speed_Limit = {c['Speed_Limit']}")
        f = self.scaling.frequency(velocity)
        direction = 1 if f > 0 else -1 if f < 0 else 0
        self._check_limit_switch(direction)
        if self._refused_by_range(direction):
            self.busy = False
            self.on_target = False
            return False
        up, down = self._ramps(acc_up, acc_down, f)
        self._target = None
        self._last_target = None
        self._v_set = velocity
        self._v_set_f = f
        self.on_target = False
        self.busy = True

        def go() -> None:
            self._run(plan_speed(self._state(), f, up, down), "speed", up, down)

        if self._defer(needs_constant_speed(up, down)):
            self._pending = go
        else:
            self._pending = None
            go()
        return True

    def _guard(self, action: Callable[[], None]) -> None:
        try:
            action()
        except WagoError as e:
            self._raise(e.code, e.text)

    # ---- PreCalc (§3.7.2 C2.6)
    def _precalc_step(self, s: dict[str, bool], edge: dict[str, bool]) -> None:
        if not s["precalc"]:
            self._precalc, self.precalc_ack = None, False
            return
        if not edge["precalc"]:
            return
        data = self._out.data
        if self.mode == MODE_POSITIONING:
            sp = PositioningSetpoints.decode(data)
            self._precalc = {"kind": "position", "v": sp.velocity, "a": sp.acceleration, "target": sp.target}
        else:
            sp2 = SpeedSetpoints.decode(data)
            self._precalc = {"kind": "speed", "v": sp2.velocity, "a": sp2.acceleration}
        # "If the starting speed is zero, a movement sequence will be calculated in advance"
        if self._at_rest():
            try:
                self._validate_precalc()
                self.precalc_ack = True
            except WagoError as e:
                self._precalc = None
                self._raise(e.code, e.text)
        else:
            self.precalc_ack = False

    def _validate_precalc(self) -> None:
        pc = self._precalc
        assert pc is not None
        if pc["kind"] == "position":
            if not 1 <= pc["v"] <= 25000:
                raise WagoError(1117, f"Velocity = {pc['v']} is outside 1 .. 25000")
            if not 1 <= pc["a"] <= 32767:
                raise WagoError(1121, f"Acceleration = {pc['a']} is outside 1 .. 32767")
            pc["steps"] = self._absolute_target(pc["target"])
            f = self.scaling.frequency(pc["v"])
            up, down = self._ramps(pc["a"], pc["a"], f)
            pc["profile"] = plan_move(self._state(), pc["steps"], f, up, down)
            pc["from"] = self._state().p
            pc["ramps"] = (up, down)

    def _start_precalc(self) -> bool:
        """Start with PreCalc_ACK: the latched set points (the precalculated profile if the
        drive is still where it was calculated)."""
        pc = self._precalc
        assert pc is not None
        if pc["kind"] == "speed":
            return self._pi_speed(pc["v"], pc["a"])
        st = self._state()
        if "profile" in pc and st.v == 0.0 and pc["from"] == st.p and self._at_rest():
            direction = 1 if pc["steps"] > st.p else -1 if pc["steps"] < st.p else 0
            self._check_limit_switch(direction)
            if self._refused_by_range(direction):
                return False
            self._target = self._last_target = pc["steps"]
            self._v_set = pc["v"]
            self._v_set_f = self.scaling.frequency(pc["v"])
            self.on_target = False
            self.busy = True
            up, down = pc["ramps"]
            self._run(pc["profile"], "position", up, down)
            return True
        return self._pi_position(pc["v"], pc["a"], pc["target"])

    # ---- referencing
    def _pi_reference(self, s: dict[str, bool]) -> bool:
        pos, neg = s["dir_pos"], s["dir_neg"]
        if pos and neg:
            # "The drive is deactivated when the bit Direction_Neg is set at the same time" (D7)
            self._ref = None
            if not self._at_rest():
                self._stop_fast()
            self.busy = False
            return True
        if not pos and not neg:
            raise WagoError(1431, "reference run without direction: set Direction_Pos or Direction_Neg")
        mode = self.config["Reference_Mode"]
        self._mailbox_reference = False
        return self._start_reference(1 if pos else -1, bool(mode & 1), 1 if mode & 2 else -1, s)

    def _start_reference(self, direction: int, to_limit: bool, edge: int, s: dict[str, bool]) -> bool:
        """Begin a reference run; False if it cannot start at a limit switch."""
        c = self.config
        if c["SetupSpeed"] == 0:
            raise WagoError(1453, "SetupSpeed = 0: a reference run needs a speed")
        f = abs(self.scaling.frequency(c["SetupSpeed"], "SetupSpeed"))
        if c["SetupAcceleration"] == 0:
            raise WagoError(1121, "SetupAcceleration = 0: a reference run needs an acceleration")
        a = self.scaling.accel(c["SetupAcceleration"], "SetupAcceleration")
        self._pending = None
        self.reference_ok = False
        self.on_target = False
        self._target = None
        self._last_target = None
        self._ref_pending_shift = 0.0
        run = RefRun(self, direction, to_limit, edge, f, a)
        self._ref = run
        if not run.start(s["set_reference"], s["ls_pos"], s["ls_neg"]):
            if run.phase is RefPhase.BLOCKED:
                # at the limit switch of the start direction: no motion, Err_Range (no error)
                self._range_block = direction
                if direction > 0:
                    self.err_range_pos = True
                else:
                    self.err_range_neg = True
            self._ref = None
            self.busy = False
            return False
        self.busy = True
        self._v_set = c["SetupSpeed"]
        self._v_set_f = f
        return True

    # RefDrive protocol (referencing.py)
    def ref_velocity(self, velocity: float, acceleration: float) -> None:
        st = self._state()
        lim = Limits(v=max(abs(velocity), abs(st.v), 1.0), a=acceleration, d=acceleration)
        r = Ramp("trapezoid", acceleration)
        self._run(plan_velocity("trapezoid", st, velocity, lim), "reference", r, r)
        self._stopping = False

    def ref_stop_fast(self) -> None:
        self._stop_fast("reference")

    def ref_state(self) -> State:
        return self._state()

    def ref_at_rest(self) -> bool:
        return self._at_rest()

    def ref_edge(self, edge_position: float) -> None:
        """The reference edge: the reported position is the reference value from now on."""
        try:
            ref = self.scaling.steps(self.config["Reference_Offset"], "Reference_Offset")
        except WagoError:
            return
        self._ref_pending_shift = ref - edge_position

    def ref_finish(self, edge_position: float, on_limit_switch: int) -> None:
        """At rest after the edge: ActualPosition = Reference_Offset + braking distance."""
        try:
            ref = self.scaling.steps(self.config["Reference_Offset"], "Reference_Offset")
        except WagoError as e:
            self._raise(e.code, e.text)
            return
        p = self._state().p
        self._set_actual(ref + (p - edge_position))
        self._ref_pending_shift = 0.0
        self.reference_ok = True
        self.busy = False
        self._motion = None
        self.on_target = self.reference_on_target and not self._mailbox_reference
        if on_limit_switch:
            self._ls_special = on_limit_switch
            self._ls_left = None
        self._ref = None

    def ref_fail(self, code: int, text: str) -> None:
        self._ref = None
        self.busy = False
        self._raise(code, text)

    # ================================================================== jog

    def _jog_step(self, s: dict[str, bool], cycle: int) -> None:
        pos = s["jog_pos"] or s["dir_pos"]
        neg = s["jog_neg"] or s["dir_neg"]
        c = self.config
        want = 0 if pos == neg else (1 if pos else -1)
        if pos and neg:
            if self._jog_dir != 0 or not self._at_rest():
                self._stop_fast("jog")
            self._jog_dir = 0
            self._jog_block = True  # "the drive is turned off" until both are released
            return
        if want == 0:
            self._jog_block = False
            if self._jog_dir != 0:
                self._jog_dir = 0
                self._jog_velocity(0.0)
            return
        if self._jog_block:
            return
        if self._jog_dir == want:
            if self.stepping_timeout_ms and cycle - self._jog_started >= self.stepping_timeout_ms:
                self._jog_dir = 0
                self._jog_block = True
                self._jog_velocity(0.0)
            return
        # a new press: not toward an active limit switch
        if (want > 0 and s["ls_pos"]) or (want < 0 and s["ls_neg"]):
            return
        u = self._user_position()
        self._jog_outside = u is not None and not (c["Drive_Range_Neg"] <= u <= c["Drive_Range_Pos"])
        self._jog_ls = 1 if s["ls_pos"] else -1 if s["ls_neg"] else 0
        self._jog_dir = want
        self._jog_started = cycle
        speed = max(c["SetupSpeed"], 1)  # "If the setup speed is parameterized as zero ... speed 1"
        try:
            self._jog_velocity(want * abs(self.scaling.frequency(speed, "SetupSpeed")))
        except WagoError as e:
            self._raise(e.code, e.text)
            return
        self._v_set = speed
        self.busy = True

    def _jog_velocity(self, velocity: float) -> None:
        c = self.config
        if c["SetupAcceleration"] == 0:
            self._raise(1121, "SetupAcceleration = 0: jog needs an acceleration")
            return
        a = self.scaling.accel(c["SetupAcceleration"], "SetupAcceleration")
        st = self._state()
        lim = Limits(v=max(abs(velocity), abs(st.v), 1.0), a=a, d=a)
        r = Ramp("trapezoid", a)
        self._run(plan_velocity("trapezoid", st, velocity, lim), "jog", r, r)
        self._stopping = False

    # ================================================================== watches

    def _user_position(self) -> float | None:
        """Position in user units for the software limits (None: limits not in force)."""
        p = self._state().p
        period = self.rotary_period()
        if period:
            c = self.config
            if not (c["Drive_Range_Neg"] >= 0 or c["Drive_Range_Pos"] < self.scaling.position_float(period)):
                return None  # rotary axis: "otherwise unrestricted"
            p = p % period
        return self.scaling.position_float(p)

    def _check_limit_switch(self, direction: int) -> None:
        """1931 for a start while a limit switch is active, except leaving it in special mode (D10)."""
        s = self._sig
        for active, side in ((s.get("ls_pos", False), 1), (s.get("ls_neg", False), -1)):
            if active and not (self._ls_special == side and direction == -side):
                raise WagoError(1931, f"{'LimitSwitch_Pos' if side > 0 else 'LimitSwitch_Neg'} is active")

    def _refused_by_range(self, direction: int) -> bool:
        """Outside the software limits only moves back into the range are accepted (D9)."""
        u = self._user_position()
        if u is None or direction == 0:
            return False
        c = self.config
        if u > c["Drive_Range_Pos"] and direction > 0:
            self.err_range_pos = True
            return True
        if u < c["Drive_Range_Neg"] and direction < 0:
            self.err_range_neg = True
            return True
        return False

    def _watch_limits(self, s: dict[str, bool], cycle: int) -> None:
        st = self._state()
        v = st.v
        # special mode after a reference run to a limit switch ends 100 ms after leaving it
        if self._ls_special:
            on = s["ls_pos"] if self._ls_special > 0 else s["ls_neg"]
            if on:
                self._ls_left = None
            elif self._ls_left is None:
                self._ls_left = cycle
            elif cycle - self._ls_left >= 100:
                self._ls_special = 0
        if self._range_block and not (s["ls_pos"] if self._range_block > 0 else s["ls_neg"]):
            self._range_block = 0
        if self._motion == "reference" or (self._ref is not None and self._ref.active):
            return  # the reference run handles limit switches; software limits are off
        jog = self.mode == MODE_JOG and self._motion == "jog"
        # hardware limit switches: brake when moving toward an active one
        if (v > 0.0 and s["ls_pos"]) or (v < 0.0 and s["ls_neg"]):
            if not self._stopping:
                self._stop_fast("jog" if jog else "stop")
                if jog:
                    self._jog_dir = 0
                    self._jog_block = True
            return
        if jog and self._jog_ls and not self._stopping:
            # JogMode: leaving the limit switch the drive started on brakes again (§3.11.3.1)
            if not (s["ls_pos"] if self._jog_ls > 0 else s["ls_neg"]):
                self._jog_ls = 0
                self._stop_fast("jog")
                self._jog_dir = 0
                self._jog_block = True
                return
        # software limits
        u = self._user_position()
        if u is None:
            return
        c = self.config
        out_pos = u > c["Drive_Range_Pos"]
        out_neg = u < c["Drive_Range_Neg"]
        if not (out_pos and v > 0.0) and not (out_neg and v < 0.0):
            if jog and not (out_pos or out_neg):
                self._jog_outside = False  # back inside: the limits are in force again
            return
        if jog and self._jog_outside:
            return  # jogging outside the range after a repeated JOG command
        if out_pos:
            self.err_range_pos = True
        else:
            self.err_range_neg = True
        if not self._stopping:
            self._stop_fast("jog" if jog else "stop")
            if jog:
                self._jog_dir = 0
                self._jog_block = True

    # ================================================================== end of motions, flags

    def _finish_motions(self, cycle: int, stop_ok: bool) -> None:
        kind = self._motion
        ended = self.feed.ended(cycle)
        v = self._sp[1]
        if kind == "position" and ended and self._pending is None:
            window = self.scaling.distance(self.config["TargetWindowPosition"]) if self.config["TargetWindowPosition"] else 0
            self.on_target = self._target is not None and abs(self._sp[0] - self._target) <= abs(window) + 1e-6
            self.busy = False
            self._motion = None
            self.velocity_target = 0  # SET_VELOCITY_TARGET is for the next positioning only
        elif kind == "speed" and ended and self._pending is None:
            self.busy = False
            self.on_target = True  # D12
            if v == 0.0:
                self._motion = None
        elif kind in ("stop", "jog") and ended and v == 0.0:
            self._motion = None
            self._stopping = False
            if self._ref is None or not self._ref.active:
                self.busy = False if kind == "stop" or self.mode == MODE_JOG else self.busy
        elif kind == "reference" and ended and v == 0.0 and (self._ref is None or not self._ref.active):
            self._motion = None
            self._stopping = False
        if self._motion is None and self._stopping:
            self._stopping = False
        if self._mode_exit and self.feed.ended(cycle) and v == 0.0:
            self.mode = MODE_IDLE
            self._mode_exit = False
            self._motion = None
        if self._stop_n_ack and not stop_ok and ended and v == 0.0:
            self._stop_n_ack = False
            if self.mode != MODE_IDLE:
                self.mode = MODE_IDLE
                self._mode_exit = False
                self.busy = False
        if self._ready and not stop_ok and not self._stop_n_ack and self.mode != MODE_IDLE:
            self.mode = MODE_IDLE
            self._mode_exit = False

    def _update_flags(self, s: dict[str, bool]) -> None:
        p, v, a, _ = self._sp
        self._direction = v > 0.0  # D13: 1 moving positive; 0 otherwise (valid when moving)
        window = self.config["TargetWindowSpeed"]
        if self._motion in ("position", "speed", "jog", "reference") and self._pending is None:
            actual = self.scaling.velocity_float(v)
            if self._motion != "speed":
                actual = abs(actual)  # positioning, jog, referencing: the speed, either direction
            self.on_speed = abs(actual - self._v_set) <= window and (v != 0.0 or self._v_set == 0)
        else:
            self.on_speed = False
        if self.mode == MODE_JOG:
            self.busy = self._motion == "jog" and v != 0.0
            self.on_target = False
        u = self._user_position()
        c = self.config
        if u is None or c["Drive_Range_Neg"] <= u:
            if self._range_block >= 0:
                self.err_range_neg = False
        if u is None or u <= c["Drive_Range_Pos"]:
            if self._range_block <= 0:
                self.err_range_pos = False
        if self._range_block > 0:
            self.err_range_pos = True
        elif self._range_block < 0:
            self.err_range_neg = True

    def _current_and_brake(self, cycle: int) -> None:
        p, v, a, _ = self._sp
        c = self.config
        if not self._stage_on:
            phase = CurrentPhase.OFF
        elif self._stopping and v != 0.0:
            phase = CurrentPhase.STOP
        elif v == 0.0:
            phase = CurrentPhase.STANDSTILL
        elif a * v > 0.0:
            phase = CurrentPhase.RAMP_UP
        elif a * v < 0.0:
            phase = CurrentPhase.RAMP_DOWN
        else:
            phase = CurrentPhase.DRIVE
        self.current_phase = phase
        if phase is CurrentPhase.OFF:
            ratio = 0
        elif phase is CurrentPhase.STOP:
            ratio = c["Current_Ratio_Stop"]
        else:
            ratio = self._ratio_set.get(phase)
            if ratio is None:
                ratio = c[_RATIO_NAMES[phase]]
        self.current_ratio = ratio
        self.phase_current = phase_current(c["Current"], ratio)
        if self._overcurrent.step(self.phase_current, TICK):
            self._raise(1413, f"overcurrent {self.phase_current:g} A for too long (thermal model)",
                        cause=lambda: self._overcurrent.load > 0.0)
        # automatic brake bit (D23)
        if self._brake_auto:
            if self.feed.ended(cycle) and v == 0.0:
                self._brake_auto = False
            elif self._motion == "position" and self.feed.profile is not None and self._pending is None:
                remaining = self.feed.profile.duration - self.feed.t(cycle)
                if remaining * 1000.0 <= c["Braketime_Turn_Off"] and remaining < self.feed.profile.duration:
                    self._brake_auto = False

    # ================================================================== bits out, S0

    def _write_sources(self, s: dict[str, bool], cycle: int) -> None:
        b = self.bits
        p, v, a, _ = self._sp
        mode = self.mode
        put = b.put
        put(Bit.Reset, self.reset_flag)
        put(Bit.Warning, bool(self.errors.warning))
        put(Bit.On_Target, self.on_target)
        put(Bit.Busy, self.busy)
        put(Bit.StandStill, v == 0.0)
        put(Bit.On_Speed, self.on_speed)
        put(Bit.Direction, self._direction)
        put(Bit.Reference_OK, self.reference_ok)
        put(Bit.PreCalc_ACK, self.precalc_ack)
        put(Bit.Error, bool(self.errors.error))
        put(Bit.Ready, self._ready)
        put(Bit.Stop_N_ACK, self._stop_n_ack)
        put(Bit.Start_ACK, self._start_ack)
        ack = _MODE_BITS.get(mode, 0) if mode else 0
        for i in range(5):
            put(Bit.Command_ACK_1 + i, bool(ack >> i & 1))
        put(Bit.Break, self.brake)
        put(Bit.ERR_Code, blink_signal(self.errors.code, cycle - self._error_since))
        put(Bit.SetupSpeed_Active_ACK, s["setup_active"])
        put(Bit.Program_Running, bool(self.program is not None and self.program.running))
        moving_up = v != 0.0 and a * v > 0.0
        moving_down = v != 0.0 and a * v < 0.0
        put(Bit.Ramp_Up, moving_up)
        put(Bit.Ramp_Down, moving_down)
        put(Bit.Err_Range_Neg, self.err_range_neg)
        put(Bit.Err_Range_Pos, self.err_range_pos)
        put(Bit.Err_Range, self.err_range_neg or self.err_range_pos or s["ls_pos"] or s["ls_neg"])
        steps = int(math.floor(p + 0.5))
        c = self.config
        period9 = c["Camshaft_Ch9_Period"]
        put(Bit.CAM9, period9 > 0 and (steps - c["Camshaft_Ch9_Start"]) % period9 < c["Camshaft_Ch9_Pulsewidth"])
        pattern = self.cam_pattern(p) if self.cam_pattern is not None else 0
        for i in range(8):
            put(Bit.CAM1 + i, bool(pattern >> i & 1))

    def _s0(self, s: dict[str, bool]) -> int:
        c = self.config
        v = S0.MBX if self._mbx_on else 0
        if err_flag(c["ErrorNotificationMode"], c["WarningNotificationMode"], bool(self.errors.error), bool(self.errors.warning), s["error_quit"]):
            v |= S0.ERR
        return int(v)

    # ================================================================== move commands (§3.9)

    def drive_command(self, opcode: int, data: bytes | tuple[int, int, int] = (0, 0, 0), source: str = "mailbox") -> int:
        """Execute a move-mode command (DRIVE_COMMAND sub-command or run-program line).

        data: Data 1..3 (MB3..MB5, LSB first). source: "mailbox" (needs the mode "Run commands
        via mailbox") or "program" (needs the run-program mode). Returns the mailbox return code;
        a command the module rejects with an error code raises that error and returns 0x01.
        """
        d = bytes(data)
        if len(d) != 3:
            raise ValueError(f"drive_command data must be 3 bytes (Data 1..3), got {len(d)}")
        needed = MODE_MAILBOX if source == "mailbox" else MODE_PROGRAM
        if source not in ("mailbox", "program"):
            raise ValueError(f"source must be 'mailbox' or 'program', got {source!r}")
        if (self.mode != needed and not (source == "program" and self._autostarted())) or self._mode_exit or not self._ready:
            return RC.ACCESS_DENIED
        handler = _COMMANDS.get(opcode)
        if handler is None:
            code = 1114 if opcode in (Opcode.TORQ, Opcode.TORQ_IMM) else 1112
            self._raise(code, f"move command {opcode:#04x} is not available on the 750-672")
            return RC.UNKNOWN_COMMAND
        try:
            return handler(self, d, source)
        except WagoError as e:
            self._raise(e.code, e.text)
            return RC.GENERAL_ERROR

    def _autostarted(self) -> bool:
        """A run program started by Program_Autostart runs while no mode is selected (program.py)."""
        return self.mode == MODE_IDLE and bool(getattr(self.program, "autostarted", False))

    @property
    def stopping(self) -> bool:
        """A STOP ramp brakes the drive (Stop1_N/Stop2_N, limit switch, mode exit, STOP_FAST)."""
        return self._stopping

    def _busy_process(self) -> bool:
        return self.busy or self._pending is not None

    def _cmd_move(self, d: bytes, source: str, immediate: bool = False, relative: bool = False) -> int:
        if not immediate and self._busy_process():
            return RC.NOT_ACCEPTED
        if not self._stop_chain_open():
            return RC.ACCESS_DENIED
        value = int.from_bytes(d, "little", signed=True)
        if relative:
            base = self._last_target if self._last_target is not None else self._state().p
            target = base + self.scaling.distance(value)
        else:
            target = self._absolute_target(value)
        return self._mbx_move(target, source)

    def _mbx_move(self, target: float, source: str) -> int:
        self._source = source
        ok = self._move(target, self.velocity, self.acc_up, self.acc_down, self.velocity_target)
        return RC.OK if ok else RC.ACCESS_DENIED

    def _cmd_move_table(self, d: bytes, source: str, immediate: bool = False, relative: bool = False) -> int:
        if not immediate and self._busy_process():
            return RC.NOT_ACCEPTED
        if not self._stop_chain_open():
            return RC.ACCESS_DENIED
        value = self.position_table(d[0], d[1] & 1)
        if relative:
            base = self._last_target if self._last_target is not None else self._state().p
            target = base + self.scaling.distance(value)
        else:
            target = self._absolute_target(value)
        return self._mbx_move(target, source)

    def _cmd_speed(self, d: bytes, source: str, immediate: bool = False) -> int:
        if not immediate and self._busy_process():
            return RC.NOT_ACCEPTED
        if not self._stop_chain_open():
            return RC.ACCESS_DENIED
        v = int.from_bytes(d[0:2], "little", signed=True)
        if not -25000 <= v <= 25000:
            raise WagoError(1117, f"SPEED velocity = {v} is outside -25000 .. 25000")
        self._source = source
        ok = self._speed(v, self.acc_up, self.acc_down)
        return RC.OK if ok else RC.ACCESS_DENIED

    def _stop_chain_open(self) -> bool:
        """Stop1_N and Stop2_N are 1: the drive may be started."""
        return self._stop_n_ack and bool(self._sig.get("stop2_n") and self._sig.get("stop1_n"))

    def _cmd_stop_fast(self, d: bytes, source: str) -> int:
        if self.program is not None and source == "mailbox" and self.program.running:
            self.program.stop(self)
        self._ref = None
        self._stop_fast()
        self.busy = False if self._at_rest() else self.busy
        return RC.OK

    def _cmd_stop_no_ramp(self, d: bytes, source: str) -> int:
        self._ref = None
        self._no_ramp()
        self.busy = False
        return RC.OK

    def _cmd_reference(self, d: bytes, source: str) -> int:
        if not self._stop_chain_open():
            return RC.ACCESS_DENIED
        swt, std, dirbit = d[2] & 1, (d[2] >> 1) & 1, (d[2] >> 2) & 1
        self._mailbox_reference = True
        self._source = source
        ok = self._start_reference(1 if std else -1, bool(swt), 1 if dirbit else -1, self._sig)
        if not ok:
            # mailbox: "error message 23" at a limit switch, no Err_Range bit needed
            return RC.ACCESS_DENIED
        return RC.OK

    def _cmd_acc_mode(self, d: bytes, source: str) -> int:
        m = d[0]
        for shift, name in ((0, "ACC_T"), (2, "ACC_M"), (4, "DEC_T"), (6, "DEC_M")):
            if (m >> shift) & 3 == 3:
                raise WagoError(1557, f"SET_ACC_MODE {name} = 3 is reserved (allowed 0 .. 2)")
        self.acc_mode = m
        return RC.OK

    def _cmd_acc(self, d: bytes, source: str) -> int:
        a = int.from_bytes(d[0:2], "little", signed=True)
        if not 1 <= a <= 32767:
            raise WagoError(1121, f"SET_ACC acceleration = {a} is outside 1 .. 32767")
        sel = d[2] & 3
        if sel in (0, 1, 3):
            self.acc_up = a
        if sel in (0, 2, 3):
            self.acc_down = a
        return RC.OK

    def _cmd_acc_param(self, d: bytes, source: str, down: bool = False) -> int:
        v = int.from_bytes(d, "little")
        if not 1 <= v <= 16777215:
            raise WagoError(1557, f"SET_ACC_PARAM_{'DOWN' if down else 'UP'} = {v} is outside 1 .. 16777215")
        if down:
            self.param_down = v
        else:
            self.param_up = v
        return RC.OK

    def _cmd_velocity(self, d: bytes, source: str, target: bool = False) -> int:
        v = int.from_bytes(d[0:2], "little", signed=True)
        lo = 0 if target else 1
        if not lo <= v <= 25000:
            raise WagoError(1117, f"SET_VELOCITY{'_TARGET' if target else ''} = {v} is outside {lo} .. 25000")
        if target:
            self.velocity_target = v
        else:
            self.velocity = v
        return RC.OK

    def _cmd_set_position(self, d: bytes, source: str, zero: bool = False) -> int:
        if not self._at_rest() or self._busy_process():
            raise WagoError(1125, "the actual value can only be set at standstill")
        value = 0 if zero else int.from_bytes(d, "little", signed=True)
        steps = self.scaling.steps(value, "SET_ACTUALPOSITION")
        period = self.config["Rotary_Axis_Period"]
        if period and not 0 <= steps < period:
            raise WagoError(1261, f"SET_ACTUALPOSITION {value} is outside the rotary axis range 0 .. {period - 1} microsteps")
        self._set_actual(float(steps))
        return RC.OK

    def _cmd_current(self, d: bytes, source: str) -> int:
        ratio = d[0]
        if ratio > 150:
            raise WagoError(1217, f"SET_CURRENT {ratio} % is above 150 %")
        for bit, phase in enumerate((CurrentPhase.STANDSTILL, CurrentPhase.RAMP_UP, CurrentPhase.DRIVE, CurrentPhase.RAMP_DOWN)):
            if d[1] >> bit & 1:
                self._ratio_set[phase] = ratio
        return RC.OK

    def __repr__(self) -> str:
        return f"Wago672(axis={self.axis.name!r}, mode={self.mode}, ready={self._ready}, error={self.errors.error})"


# signal name -> bit the module reads it from (through the links of the bit table)
_SIGNALS: dict[str, int] = {
    "enable": Bit.Enable,
    "stop2_n": Bit.Stop2_N,
    "start": Bit.Start,
    "cmd1": Bit.Command_1,
    "cmd2": Bit.Command_2,
    "cmd3": Bit.Command_3,
    "cmd4": Bit.Command_4,
    "cmd5": Bit.Command_5,
    "enable_drive": Bit.Enable_Drive,
    "reset_quit": Bit.Reset_Quit,
    "dir_pos": Bit.Direction_Pos,
    "dir_neg": Bit.Direction_Neg,
    "set_reference": Bit.Set_Reference,
    "precalc": Bit.PreCalc,
    "setup_active": Bit.SetupSpeed_Active,
    "error_quit": Bit.Error_Quit,
    "ls_pos": Bit.LimitSwitch_Pos,
    "ls_neg": Bit.LimitSwitch_Neg,
    "stop1_n": Bit.Stop1_N,
    "brake_manual": Bit.Brake_Manual,
    "freq_sel_0": Bit.Freq_Range_Sel_0,
    "freq_sel_1": Bit.Freq_Range_Sel_1,
    "acc_sel_0": Bit.Acc_Range_Sel_0,
    "acc_sel_1": Bit.Acc_Range_Sel_1,
    "set_actual": Bit.Set_Actual_Pos,
    "jog_pos": Bit.Jog_Pos,
    "jog_neg": Bit.Jog_Neg,
    "error_set": Bit.Error_Set,
}

_RATIO_NAMES = {
    CurrentPhase.STANDSTILL: "Current_Ratio_StandStill",
    CurrentPhase.RAMP_UP: "Current_Ratio_RampUp",
    CurrentPhase.DRIVE: "Current_Ratio_Drive",
    CurrentPhase.RAMP_DOWN: "Current_Ratio_RampDown",
}

_SIGNAL_ITEMS = tuple((name, int(bit)) for name, bit in _SIGNALS.items())

_COMMANDS: dict[int, Callable[[Wago672, bytes, str], int]] = {
    Opcode.MOVE: lambda dev, d, s: dev._cmd_move(d, s),
    Opcode.MOVE_IMMEDIATE: lambda dev, d, s: dev._cmd_move(d, s, immediate=True),
    Opcode.MOVE_REL: lambda dev, d, s: dev._cmd_move(d, s, relative=True),
    Opcode.MOVE_TABLE: lambda dev, d, s: dev._cmd_move_table(d, s),
    Opcode.MOVE_TABLE_IMMEDIATE: lambda dev, d, s: dev._cmd_move_table(d, s, immediate=True),
    Opcode.MOVE_TABLE_REL: lambda dev, d, s: dev._cmd_move_table(d, s, relative=True),
    Opcode.SPEED: lambda dev, d, s: dev._cmd_speed(d, s),
    Opcode.SPEED_IMMEDIATE: lambda dev, d, s: dev._cmd_speed(d, s, immediate=True),
    Opcode.STOP_FAST: Wago672._cmd_stop_fast,
    Opcode.STOP_NO_RAMP: Wago672._cmd_stop_no_ramp,
    Opcode.START_REFERENCING: Wago672._cmd_reference,
    Opcode.SET_ACC_MODE: Wago672._cmd_acc_mode,
    Opcode.SET_ACC: Wago672._cmd_acc,
    Opcode.SET_ACC_PARAM_UP: lambda dev, d, s: dev._cmd_acc_param(d, s),
    Opcode.SET_ACC_PARAM_DOWN: lambda dev, d, s: dev._cmd_acc_param(d, s, down=True),
    Opcode.SET_VELOCITY: lambda dev, d, s: dev._cmd_velocity(d, s),
    Opcode.SET_VELOCITY_TARGET: lambda dev, d, s: dev._cmd_velocity(d, s, target=True),
    Opcode.SET_ACTUALPOSITION: lambda dev, d, s: dev._cmd_set_position(d, s),
    Opcode.SET_ACTUALPOSITION_ZERO: lambda dev, d, s: dev._cmd_set_position(d, s, zero=True),
    Opcode.SET_CURRENT: Wago672._cmd_current,
}
