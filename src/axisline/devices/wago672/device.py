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

Seams for the second engineer (the mailbox engine, tables, run programs, camshaft, bit linking):
seams.py lists them; `mailbox.attach(dev)` plugs them in.

The module is one class in layers, by what they do (state.py declares the state and says why a
chain): drive.py (output stage, axis hand-over, STOP ramps, scaling and ramps, current, brake and
errors), watches.py (limit switches, software limits, end of motions, flags, the source bits),
modes.py (mode selection, Start, positioning, speed control, PreCalc, referencing, jog),
commands.py (the move commands of DRIVE_COMMAND and run programs) and this file (power-on, the
process image, the tick and read-outs); seams.py has the mailbox, run program, position table and
input wiring hooks. Each part lists the decisions
it takes; D1 .. D26 are numbered across them.

The 1 ms tick reads what the PLC and the inputs set through the bit table's links, which are
resolved once per configuration change (bits.py), and reads the configuration as plain values
(`ConfigTable.values`, checked when written), so a tick costs no more than the module's logic.

Decisions ([AMBIGUOUS]/[CONFLICT]/[RECONSTRUCTED] points of wago.md; the manual wins):
* D16 Acknowledging a 2xxx error (Error_Quit edge or DIAG_QUIT_ERROR) performs the warm start
  (volatile state lost, Reset bit set; the `on_warm_start` hook lets the table manager reload the
  saved configuration and tables); 3xxx errors stay until power-off.
* D21 Ready does not wait for Reset_Quit (wago.md §10.3 item 28).
* D22 Overcurrent shutdown 1413 can be acknowledged once the thermal model has cooled back to 0
  ("a phase with reduced current must follow, in order for the module's thermal model to return
  to its original state", §4.1.4.3). Output-stage temperature and DC-link voltage are simulated
  values (`environment`); above Warn_Treshold_Temperature it is 1894 (ErrorNotificationMode
  bit 1, default) or warning 5893 (WarningNotificationMode bit 1); DC link outside
  DC_Link_Umin/Umax is 1816/1815.
* D24 Positions: user -> microsteps and microsteps -> user truncate toward zero; the set point is
  reported as its nearest microstep (units.py).

Tests: D16, D22 test_errors.py (test_warm_start_error_is_acknowledged_by_a_warm_start,
test_boost_current_at_standstill_trips_1413_after_10_s, test_output_stage_temperature_error_or_warning);
D21 test_enable_chain.py::test_enable_gives_ready_and_stop2_n_with_di1_gives_stop_n_ack; D24
test_units.py::test_6_2_truncation_toward_zero_and_range_errors.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from typing import Any

from axisline.devices.wago672.bits import SPREAD, Bit, BitTable
from axisline.devices.wago672.commands import RC, MoveCommands, Opcode
from axisline.devices.wago672.config_table import CONF_VERSION, ConfigTable, ConfigValueError
from axisline.devices.wago672.drive import TICK
from axisline.devices.wago672.errors import ErrorMemory, WagoError
from axisline.devices.wago672.image import C0, MODE_IDLE, MODE_JOG, MODE_POSITIONING, MODE_PROGRAM, MODE_SPEED, InputImage, OutputImage
from axisline.devices.wago672.signals import SIGNAL_BITS, Signals
from axisline.devices.wago672.seams import Inputs, MailboxHandler, NoMailbox, RunProgram, no_position_table
from axisline.devices.wago672.thermal import CurrentPhase, OvercurrentModel
from axisline.devices.wago672.trajectory import Feed, Ramp
from axisline.motion.axis import Axis, AxisState, ErrorId

__all__ = ["Wago672", "NoMailbox", "MailboxHandler", "RunProgram", "Opcode", "RC", "TICK"]



class Wago672(MoveCommands):
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
        self.inputs = Inputs(inputs)
        self.config = config if config is not None else ConfigTable()
        try:
            self.config.validate()
        except ConfigValueError as e:
            raise ValueError(f"configuration table not usable: {e}") from None
        self.bits = BitTable(self.config)
        self._signal_bits = self.bits.group(SIGNAL_BITS)
        self._status_bits = self.bits.group(_STATUS_BITS)
        self.errors = ErrorMemory()
        self.mailbox = mailbox if mailbox is not None else NoMailbox()
        self.program = program
        self.position_table = no_position_table
        self.cam_pattern = None
        self.eeprom_writing = False  # set by the table manager: LED A flashes at 10 Hz
        self.on_warm_start = None  # table manager: reload EEPROM data
        # second engineer's parts (mailbox.attach): called each tick after the source bits are
        # written (filters, data recorder, autostart, EEPROM jobs), and extra state variables
        self.tick_hooks = []
        self.extra_variables = {}
        self.stepping_timeout_ms = 0  # SteppingMode (D4): 0 = JogMode without time limit
        self.reference_on_target = True  # D5: On_Target after a PI reference run
        # simulated environment of the output stage (D22): temperature [degC], DC link [V]
        self.environment = {"stage_temperature": 40.0, "dc_link_voltage": 55.0}
        self._k = axis.scale.counts_per_unit  # microsteps per axis unit
        self.feed = Feed(self._k, axis.period)
        self._sync_cmd = None
        self._take_outputs(OutputImage())
        self._out_raw = None  # the bytes `_out` was decoded from
        self._last_write = None
        self._cycle = None
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
        self._motion = None  # "position", "speed", "stop", "jog", "reference"
        self._stopping = False  # a STOP ramp runs (Current_Ratio_Stop)
        self._target = None  # position target [microsteps, unwrapped]
        self._last_target = None  # MOVE_REL base (D18)
        self._v_set = 0  # commanded speed [user units] for On_Speed
        self._v_set_f = 0.0  # [microsteps/s]
        self._pending = None  # deferred set point (D8)
        self._cur_up = self._cur_down = Ramp("trapezoid", 1.0)
        self._precalc = None
        self._source = "pi"  # who started the running task: "pi", "mailbox", "program"
        self._mailbox_reference = False
        self.err_range_pos = False
        self.err_range_neg = False
        self._range_block = 0  # a refused reference start at this limit switch (+1/-1)
        self._ls_special = 0  # +1/-1: on that limit switch after a limit-switch reference run
        self._ls_left = None
        self._jog_dir = 0
        self._jog_block = False
        self._jog_started = 0
        self._jog_ls = 0
        self._jog_outside = False
        self._ref = None
        self._ref_pending_shift = 0.0
        self._brake_auto = False
        self._overcurrent = OvercurrentModel()
        self.current_phase = CurrentPhase.OFF
        self.phase_current = 0.0
        self.current_ratio = 0
        self._ratio_set = {}  # SET_CURRENT values (else the configuration's)
        self._error_since = 0
        self._bad_selection = 0
        self._prev = Signals()
        self._sig = Signals()
        self._sp = (0.0, 0.0, 0.0, 0.0)
        self._mbx_on = False
        self._mbx_reply = bytes(6)
        self._sources_word = -1  # the source bits are written at the first tick
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
        c = self.config.values
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
        if isinstance(data, OutputImage):
            self._take_outputs(data)
            self._out_raw = None
        elif data != self._out_raw:  # a PLC writes the same image most cycles: decode it once
            self._take_outputs(OutputImage.from_bytes(data))
            self._out_raw = bytes(data)
        self._last_write = self._cycle if self._cycle is not None else 0

    def _take_outputs(self, out: OutputImage) -> None:
        self._out = out
        # KBUS_CTRL1_0 .. KBUS_CTRL3_7 (0x40 .. 0x57): C1, C2, C3 bit by bit, for the next ticks
        self._control_bits = SPREAD[out.c1] + SPREAD[out.c2] + SPREAD[out.c3]

    def read_inputs(self) -> bytes:
        """The 12 input bytes for the PLC as of the last tick."""
        s0, s1, s2, s3 = self._status
        return bytes((s0, 0)) + self._input_data() + bytes((s3, s2, s1))

    def input_image(self) -> InputImage:
        s0, s1, s2, s3 = self._status
        return InputImage(s0, s1, s2, s3, self._input_data())

    def _input_data(self) -> bytes:
        """D0..D6 of the input image: the mode's actual values, or MB0..MB5 of the mailbox's reply
        (the fields are in range by construction: `_reported` clamps them)."""
        if self._mbx_on:
            return self._mbx_reply + b"\x00"
        pos, vel = self._reported()
        if self.mode == MODE_PROGRAM:  # ProgramActuals: velocity, command counter, position
            counter = self.program.counter if self.program is not None else 0
            middle = (counter & 0xFFFF).to_bytes(2, "little")
        else:  # PositioningActuals: velocity, reserved, position
            middle = b"\x00\x00"
        return vel.to_bytes(2, "little", signed=True) + middle + (pos & 0xFFFFFF).to_bytes(3, "little")

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
        # only the asked variable is worked out: the recorder reads some every cycle
        if index in (0, 1024):
            return self._cycle or 0
        if index in (1, 2, 1025, 1026):
            pos, vel = self._reported()
            return pos if index in (1, 1025) else vel
        if index == 9:
            return 8  # hardware version: 8 = 750-672
        if index == 15:
            return CONF_VERSION
        if index == 16:
            return self.config.values["ConfVersion"]
        if index in (20, 55):
            return self.scaling.prescaler
        if index == 21:
            return self._overcurrent.state_variable
        if index == 24:
            return int(round(self._sp[0]))
        if index == 25:
            return int(round(self._sp[1]))
        if index == 30:
            return int(round(self._target)) if self._target is not None else int(round(self._v_set_f))
        if index == 31:
            return self.scaling.multiplier
        if index == 41:
            return self.program.counter if self.program is not None else 0
        if index == 43:
            return int(round(self._v_set_f))
        if index == 56:
            return self.current_ratio
        if index == 1046:
            return int(round(self.environment["stage_temperature"] * 10))
        if index == 1048:
            return int(round(self.environment["dc_link_voltage"] * 10))
        return 0

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

    def _tick(self, cycle: int) -> None:
        b = self.bits
        out = self._out
        # ---- 1 sources: inputs and control bytes
        field = b.field
        field[_INPUT1 : _INPUT1 + 6] = self.inputs.levels()
        field[_KBUS_CTRL1_0:_KBUS_CTRL1_0 + 24] = self._control_bits
        field[_KBUS_ACTIVE] = self._last_write is not None and cycle - self._last_write <= 100
        # ---- 2 the signals this module consumes, through their links
        try:
            s = self._read_signals()
        except WagoError as e:
            self._raise(e.code, e.text)
            s = self._sig  # the last tick's (all 0 before the first)
        self._sig = s
        prev = self._prev
        # rising edges: only these four are used
        start_edge = s.start and not prev.start
        precalc_edge = s.precalc and not prev.precalc
        # ---- 3 reset handshake and latched scaling
        if s.reset_quit:
            self.reset_flag = False
        if not s.enable:
            self._latch_scaling()
        # ---- 4 error sources and Error_Quit
        self._watch_environment(s)
        if s.error_quit and not prev.error_quit:
            self.quit_errors()
        # ---- 5 Ready and the output stage
        ready = s.enable and not self.errors.error
        if self._ready and not ready:
            self._lose_ready()
        self._ready = ready
        self._stage_on = ready and s.enable_drive
        if not self._stage_on and self._motion is not None:
            self._no_ramp(stopped=True)
        self._axis_power(self._stage_on)
        if not self._stage_on:
            self.feed.hold(self._axis_steps())
        # ---- 6 the stop chain (Stop2_N, Stop1_N)
        stop_ok = s.stop2_n and s.stop1_n
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
        if start_edge:
            self._on_start(s)
        elif not s.start:
            self._start_ack = False
        if self.mode in (MODE_POSITIONING, MODE_SPEED):
            self._precalc_step(s, precalc_edge)
        elif self._precalc is not None or self.precalc_ack:
            self._precalc, self.precalc_ack = None, False
        if s.set_actual and not prev.set_actual and self._stage_on and self._at_rest() and self._motion is None:
            try:
                self._set_actual(self.scaling.steps(self.config.values["Reference_Offset"], "Reference_Offset"))
            except WagoError as e:
                self._raise(e.code, e.text)
        # ---- 9 mode work: referencing, jog, program, mailbox, deferred set points
        if self._ref is not None and self._ref.active and self._stage_on:
            self._ref.step(s.set_reference, s.ls_pos, s.ls_neg)
        if self.mode == MODE_JOG and not self._mode_exit and self._stage_on and stop_ok:
            self._jog_step(s, cycle)
        if self.program is not None and (self.mode == MODE_PROGRAM or self._autostarted()) and self._ready:
            self.program.tick(cycle, self)
        self._mbx_on = bool(out.c0 & _C0_MBX)
        if self._mbx_on:
            self._mbx_reply = bytes(self.mailbox.exchange(out.mailbox_request, self))[:6].ljust(6, b"\x00")
        if self._pending is not None and self._stage_on:
            if self.feed.state(self._c_plan())[2] == 0.0:  # the last set point's acceleration
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
        s0 = self._s0(s)
        st = b.word(self._status_bits)  # S1, S2, S3 (KBUS_ST1_0 ..), OUT1, OUT2
        self._status = (s0, st & 0xFF, (st >> 8) & 0xFF, (st >> 16) & 0xFF)
        self._outputs = ((st >> 24) & 1 == 1, (st >> 25) & 1 == 1)
        self._prev = s

    def _read_signals(self) -> Signals:
        return Signals(self.bits.word(self._signal_bits), True)

    # ================================================================== errors
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

    def _watch_environment(self, s: Signals) -> None:
        # (the causes are methods, not lambdas: a closure would cost an allocation every tick)
        c = self.config.values
        if s.error_set:
            self._raise(1358, "Error_Set is 1", cause=self._error_set_active)
        temp = self.environment["stage_temperature"]
        if temp * 10.0 > c["Warn_Treshold_Temperature"]:
            text = f"output stage {temp:g} degC above Warn_Treshold_Temperature {c['Warn_Treshold_Temperature'] / 10:g} degC"
            if c["ErrorNotificationMode"] & 2:
                self._raise(1894, text, cause=self._over_temperature)
            elif c["WarningNotificationMode"] & 2:
                self._raise(5893, text, cause=self._over_temperature)
        u = self.environment["dc_link_voltage"] * 10.0
        if u > c["DC_Link_Umax"]:
            self._raise(1815, f"DC link {u / 10:g} V above DC_Link_Umax {c['DC_Link_Umax'] / 10:g} V", cause=self._dc_link_high)
        elif u < c["DC_Link_Umin"]:
            self._raise(1816, f"DC link {u / 10:g} V below DC_Link_Umin {c['DC_Link_Umin'] / 10:g} V", cause=self._dc_link_low)
        if self.axis.state is AxisState.ERROR_STOP:
            code = 1892 if self.axis.error_id == ErrorId.FOLLOWING_ERROR else 1811
            self._raise(code, f"axis {self.axis.name}: {self.axis.error_text}")

    def _error_set_active(self) -> bool:
        return self._sig.error_set

    def _over_temperature(self) -> bool:
        return self.environment["stage_temperature"] * 10.0 > self.config.values["Warn_Treshold_Temperature"]

    def _dc_link_high(self) -> bool:
        return self.environment["dc_link_voltage"] * 10.0 > self.config.values["DC_Link_Umax"]

    def _dc_link_low(self) -> bool:
        return self.environment["dc_link_voltage"] * 10.0 < self.config.values["DC_Link_Umin"]

    def __repr__(self) -> str:
        return f"Wago672(axis={self.axis.name!r}, mode={self.mode}, ready={self._ready}, error={self.errors.error})"


# what the PLC and the outputs see: S1, S2, S3 (eight bits each from KBUS_ST1_0 on), OUT1, OUT2
_STATUS_BITS = tuple(range(Bit.KBUS_ST1_0, Bit.KBUS_ST1_0 + 24)) + (int(Bit.OUT1), int(Bit.OUT2))
_INPUT1 = int(Bit.Input1)
_KBUS_CTRL1_0 = int(Bit.KBUS_CTRL1_0)  # KBUS_CTRL2_0 and KBUS_CTRL3_0 follow it
_KBUS_ACTIVE = int(Bit.KBUS_Active)
_C0_MBX = int(C0.MBX)
