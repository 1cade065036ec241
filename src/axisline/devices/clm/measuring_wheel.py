"""CLM1.4 measuring wheel mode (manual §7.2 L3203-3250; Ax00 modes 3/4, Ax16, Ax27, Ax31,
C000-C007; spec §4.2), the feed length measurement FUN (L1981-1995) and Status 09 (L6951-6973).

    [device]
    master_encoder_1 = "wheel"          # the wheel of axis 1 (master encoder 2: axis 2, L4228)

    axis.wheel                          # WheelMode of an axis in Ax00 mode 3 / 4, else None
    axis.wheel.active, .wheel_position, .motor_position, .tolerance_2
    op_fun(rt, task, ins)               # the FUN handler (execute.HANDLERS["FUN"])
    status_09(rt)                       # the Status 09 reply body

A feed roll slips on the material, so its motor encoder does not measure the material; a
measuring wheel rolling on the material does. Master encoder n (master_encoder.py) hands itself
to axis n; in Ax00 mode 3 or 4 the axis makes a `WheelMode` of it. Every NC cycle the position
loop (clmloop.ClmLoop, its ``feedback``) reports the motor encoder's position; WheelMode takes
the motor's and the wheel's movement of the cycle (the wheel's counts x its IU per count) and,
while the wheel is active, adds their difference to ``gain`` (wheel travel - motor travel):

* **Version 1** (mode 3, L3246): the loop's actual position is motor + gain: the position loop
  closes through the wheel; the motor encoder only monitors (Ax16).
* **Version 2** (mode 4, L3247): the loop stays on the motor; the motor - wheel difference of
  the movement is added to the motor's target until the motor is within Ax27 of it, then the
  differences are compiled and added to the next movement.

Decisions (spec line -> choice, why)
------------------------------------
1. L3229 "switch between measuring wheel encoder and motor encoder at any time", L4198 "at
   times an external encoder detects the position" -> the axis position is one frame: it moves
   with the wheel while the wheel is active and with the motor otherwise (gain += wheel - motor
   movement only while active), so switching never makes the position jump and a feed in
   progress goes on to the same target. test_switching_encoders_keeps_the_position.
2. L3229, L4831 "the repositioning comes from the servo drive in Manual Mode and from the
   measuring wheel encoder in Automatic Mode" -> active = Automatic and (Ax31 ``00.00.0`` or its
   input 1); Manual, Parameter mode and a missing Ax31 signal: the motor encoder.
   test_manual_repositions_on_the_motor_encoder, test_switching_encoders_keeps_the_position.
3. L4198 "Only relative distances are traversed" (Version 1) -> POA / PSA on a mode-3 axis is
   fault 0A "Invalid Prg Cmd" naming the line: the wheel frame drifts from the motor's, an
   absolute target in it would be a position nobody can check. Version 2 positions absolutely
   as a normal axis (its frame is the motor's). test_poa_in_version_1_is_0a.
4. L3247 (Version 2) -> from the start of a positioning (POI/PSI/POA/PSA: "the current
   movement"), its target is the programmed one plus the motor - wheel difference measured
   since (replanned whenever the difference changes by a count) until |target - motor| <= Ax27
   ("as soon as the motor reaches the switching threshold"); the difference after that, while
   the axis stands too, is "compiled" and added to the next positioning's target when it starts.
   test_version_2_corrects_the_feed_and_compiles_the_rest.
5. Ax16 (L4609-4621; units not stated, spec §5.2) -> the two-digit windows are whole IU (the
   manual compares the two encoders' "values", positions in IU, as Ax27 / Ax29 do; a
   percentage is named as such where the CLM uses one, Ax14); |motor - wheel travel| since the
   start of the current wheel revolution (4 x C000 counts, master_encoder.py decision 1) is
   compared while the wheel is active and the drive is enabled, the measurement restarting each
   revolution and on activation. Beyond window 1: fault 4C / 7C "Encoder Fault" (L8891); beyond
   window 2: the Ax16 output, which then holds the result of the revolution (cleared at the end
   of a revolution that stayed within window 2, so steady slip does not make it flicker); 00 =
   that window off. A wheel that loses contact (L3231-3240) is stopped by whichever monitoring
   comes first: Ax14 (the loop's position stops following: lag) or window 1 (4C).
   test_ax16_window_1_faults_4c, test_ax16_window_2_output,
   test_wheel_losing_contact_is_stopped_by_the_monitoring.
6. A mode-3/4 axis whose wheel is not wired on the plant (``device.master_encoder_n``) or whose
   C000/C002 (C004/C006) are out of range runs on its motor encoder as with the Ax31 signal off
   (C000/C002 are range-checked on leaving Parameter mode while mode 3/4 uses them, L4162);
   Status 09 then answers 09. After Parameter mode in the same mode the wheel's difference and
   the compiled rest carry over (the position goes on); a change of mode starts them at 0.
   test_without_a_wheel_the_axis_runs_on_the_motor, test_parameter_mode_keeps_the_wheel_position.
7. FUN (L1981-1995; syntax lost: seven digits ME1, ME2, axes 1-4, material, commands.py
   C-LOST) -> a channel measures from its first FUN 0 or 1 on (V040 etc.: "Measurement must be
   activated using the FUN command", L1376); before that it reads 0. Current = position now -
   position at the (re)start, live (V040/V042 master encoders in IU, Vx11 the axis' actual
   position, in measuring wheel mode its position from the wheel as Status 09's, so that both
   versions measure the material fed); 0 buffers the current value (V041/V043/Vx12) then
   restarts, 1 restarts keeping the buffer, 2 leaves the channel. The material channel (V026
   current, V025 buffered, L1371-1372, L1993) measures the material through the tool in flying
   cutoff: master encoder 1 less the carriage (cutoff.py: "the movements of the carriage and
   the material movements are detected"); without the flying cutoff it reads 0. A channel whose
   encoder or axis is missing reads 0. One cycle. test_fun_measures_feed_lengths.
8. Status 09 ``Xs09__evmmmmm.mmm_vnnnnnn.nnn_`` (L6951-6973) -> two blanks after 09 as
   printed, both values 6.3 with sign (status.py decision 1), e = ``A`` when axis 1 is homed;
   m = axis 1's position from the wheel (motor + the wheel - motor travel while active: "the
   sums of all measuring wheel encoder movements are added"), n = the motor encoder position
   (V047). Axis 1 not in mode 3/4: error 10; no wheel: 09 (status decision 5). V047 / V048 read
   the motor encoder position of axes 1 / 2 live; SET V047 while not homed sets the motor
   encoder's reading (the wheel difference stays). test_status_09_and_v047,
   test_set_v047_sets_the_motor_encoder.
"""

from __future__ import annotations

from fractions import Fraction
from typing import TYPE_CHECKING, Any

from .errors import ClmError, axis_fault, serial_code
from .image import ProcessImage
from .operands import Operand

if TYPE_CHECKING:
    from .nc import NcTask
    from .program import Instruction

__all__ = ["FeedLengths", "WheelAxis", "WheelMode", "install", "op_fun", "status_09"]

_SCALE = 1_000_000  # variables in millionths
image_place = ProcessImage.locate  # (byte, shift, mask) of an operand in the image


class WheelMode:
    """Measuring wheel mode of one axis (1 or 2) on its master encoder; see the module docstring."""

    def __init__(self, axis: Any, encoder: Any, params: Any) -> None:
        n = axis.number
        self.axis = axis
        self.encoder = encoder
        self.version = 1 if params.axis_mode(n) == 3 else 2
        self._input: Operand = params.get(f"A{n}31")["measuring_wheel_active_input"]
        self._input_place = None if self._input.unset else image_place(self._input)
        p16 = params.get(f"A{n}16")
        self.window_1 = float(p16.number("window_1"))
        self.window_2 = float(p16.number("window_2"))
        self._output: Operand = p16["tolerance_2_output"]
        self._output_place = None if self._output.unset else image_place(self._output)
        self.set_up = bool(encoder.set_up)  # decision 6
        self.active = False
        self.gain = 0.0  # wheel travel - motor travel while active, IU (decision 1)
        self._last: tuple[float, int] | None = None  # (motor, wheel counts) of the last cycle
        # Version 2 (decision 4): motor - wheel difference not yet in a target, and the part of
        # it already added to the running movement
        self.measured = 0.0
        self._applied = 0.0
        self.correcting = False
        # Ax16 (decision 5)
        self._ref: int | None = None  # wheel counts at the start of the revolution
        self._motor_travel = 0.0
        self._wheel_travel = 0.0
        self._over_2 = False  # window 2 exceeded in this revolution
        self.tolerance_2 = False

    def carry(self, old: WheelMode) -> None:
        """After Parameter mode: the frame and the compiled difference of the WheelMode before."""
        self.gain, self._last, self.measured = old.gain, old._last, old.measured - old._applied

    # -- the position loop's view (POSITION_LOOP, every cycle) ---------------------------------

    def actual(self, motor: float) -> float:
        """The loop's actual position for the motor encoder's `motor` (plant frame)."""
        counts = int(self.encoder.counts)
        last = self._last
        self._last = (motor, counts)
        if last is not None and self.active:
            dm = motor - last[0]
            dw = self.encoder.travel(counts - last[1])  # this cycle's scale: FAK 5 / C002 changes do not jump
            self.gain += dw - dm
            if self.version == 2:
                self.measured += dm - dw
            if self._ref is None:
                self._ref = last[1]
            self._motor_travel += dm
            self._wheel_travel += dw
            per_revolution = self.encoder.counts_per_revolution
            if per_revolution and abs(counts - self._ref) >= per_revolution:  # a revolution: measure again
                self.tolerance_2 = self._over_2 or self._exceeds(self.window_2)
                self._restart(counts)
        elif not self.active:
            self._restart(None)
        return motor + self.gain if self.version == 1 else motor

    def _restart(self, counts: int | None) -> None:
        self._ref = counts
        self._motor_travel = self._wheel_travel = 0.0
        self._over_2 = False

    def _exceeds(self, window: float) -> bool:
        return window > 0.0 and abs(self._motor_travel - self._wheel_travel) > window

    # -- the axis' NC cycle (LOGIC, from ClmAxis.tick) ------------------------------------------

    def tick(self, mode: str, image: Any, drive_on: bool) -> ClmError | None:
        """Ax31, Ax16 and the Version 2 correction; returns the Encoder Fault (decision 5)."""
        place = self._input_place
        on = mode == "automatic" and self.set_up and (place is None or bool(image.data[place[0]] >> place[1] & 1))
        if on != self.active:
            self.active = on
            if not on and self.correcting:  # the correction stops with the wheel
                self._end_correction()
        fault = None
        if self.active and drive_on:
            if self._exceeds(self.window_1):
                n = self.axis.number
                fault = ClmError(axis_fault(0x0C, n), (
                    f"motor {self._motor_travel:+.3f} IU, wheel {self._wheel_travel:+.3f} IU within one wheel "
                    f"revolution, difference beyond the A{n}16 window 1 = {self.window_1:g} IU (L4615, L8895)"))
            if self._exceeds(self.window_2):
                self._over_2 = self.tolerance_2 = True
        elif not drive_on:
            self._restart(None)
        place = self._output_place
        if place is not None:
            at, shift, _ = place
            image.data[at] = image.data[at] | 1 << shift if self.tolerance_2 else image.data[at] & ~(1 << shift)
        if self.correcting:
            self._correct()
        return fault

    # -- Version 2 (decision 4) -----------------------------------------------------------------

    def start_movement(self) -> Fraction:
        """A positioning starts: the compiled difference, to be added to its target."""
        if self.version != 2:
            return Fraction(0)
        if self.correcting:  # the movement before keeps what it got; its rest is compiled
            self._end_correction()
        compiled = Fraction(self.measured).limit_denominator(_SCALE)
        self._applied = float(compiled)
        self.correcting = True
        if not self.active:  # no wheel now: only the compiled part
            self._end_correction()
        return compiled

    def _correct(self) -> None:
        axis = self.axis
        target = axis.target
        if target is None or axis._braking or axis._con is not None or axis._jog:  # the positioning was dropped (PBK, drive off)
            self._end_correction()
            return
        if abs(target - axis.motor_position) <= axis.threshold:  # the switching threshold (Ax27)
            self._end_correction()
            return
        delta = self.measured - self._applied
        if abs(delta) >= abs(float(self.encoder.scale)):  # a count's worth: replan
            step = Fraction(delta).limit_denominator(_SCALE)
            self._applied += float(step)
            axis.retarget(step)

    def _end_correction(self) -> None:
        self.correcting = False
        self.measured -= self._applied  # what the target got; the rest is compiled from here on
        self._applied = 0.0

    # -- positions ----------------------------------------------------------------------------

    @property
    def motor_position(self) -> float:
        """The motor encoder's position in the axis frame (V047 / V048, Status 09 n)."""
        actual = self.axis.actual_position
        return actual - self.gain if self.version == 1 else actual

    @property
    def wheel_position(self) -> float:
        """The axis position from the wheel (Status 09 m, decision 8)."""
        return self.motor_position + self.gain


class WheelAxis:
    """The measuring wheel's part of `axis.ClmAxis` (a mixin; the axis' state is kept there)."""

    number: int
    axis: Any
    loop: Any
    image: Any
    threshold: float
    _params: Any
    _target: Fraction | None
    _kept: bool
    _blocked: bool
    _braking: bool
    _con: float | None
    _jog: int
    _drive_on: bool
    _fault: bool
    # the master encoder of this axis' number, and the WheelMode while Ax00 is mode 3/4 with it
    wheel: WheelMode | None = None
    _wheel_encoder: Any = None

    def attach_wheel(self, encoder: Any) -> None:
        """Master encoder `number` is this axis' measuring wheel (L4228; master_encoder.py)."""
        self._wheel_encoder = encoder
        self._configure_wheel()

    def _configure_wheel(self) -> None:
        """A WheelMode in Ax00 mode 3/4 with a wheel attached (axes 1, 2), else none; after
        Parameter mode too (the axis' configure calls it)."""
        mode = self._params.axis_mode(self.number)
        encoder = self._wheel_encoder
        old = self.wheel
        new = WheelMode(self, encoder, self._params) if mode in (3, 4) and encoder is not None and self.number in (1, 2) else None
        if old is not None and new is not None and new.version == old.version:
            new.carry(old)  # Parameter mode left in the same mode: the position goes on where it was
        self.wheel = new
        self.loop.feedback = new

    def retarget(self, delta: Fraction) -> None:
        """Version 2: the target moves by `delta` IU and the running positioning is replanned (a
        kept or blocked one takes it when it starts); nothing else changes."""
        if self._target is None or not delta:
            return
        self._target = self._target + delta
        if not (self._kept or self._blocked or self._braking or self._con is not None or self._jog):
            self._start()  # type: ignore[attr-defined]

    @property
    def motor_position(self) -> float:
        """The motor encoder's position (V047 / V048): the actual position unless the wheel
        closes the loop (Version 1)."""
        return self.axis.actual_position if self.wheel is None else self.wheel.motor_position

    def set_motor_actual(self, position: float) -> None:
        """SET V047 / V048 while not homed: the motor encoder reads `position`; the difference
        the wheel measured stays (decision 8)."""
        ax = self.axis
        self.set_actual(position + (ax.actual_position - self.motor_position))  # type: ignore[attr-defined]

    def _wheel_tick(self, mode: str, fault: ClmError | None) -> ClmError | None:
        """After the drive's cycle (axisdrive.py, which calls it when there is a wheel): Ax31,
        Ax16, the Version 2 correction."""
        wheel = self.wheel
        if wheel is not None:
            wheel_fault = wheel.tick(mode, self.image, self._drive_on)
            if wheel_fault is not None and fault is None and not self._fault:
                self.fault_stop()  # type: ignore[attr-defined]
                fault = wheel_fault
        return fault


# -- FUN: feed length measurement (decision 7) -----------------------------------------------------

# the FUN digits in commands.py's order, and the variables (current, buffered) of each channel
CHANNELS = ("me1", "me2", "axis1", "axis2", "axis3", "axis4", "material")
_VARIABLES = {"me1": (40, 41), "me2": (42, 43), "axis1": (111, 112), "axis2": (211, 212), "axis3": (311, 312), "axis4": (411, 412),
              "material": (26, 25)}  # (current, buffered): V026 / V025 (L1371-1372)


class FeedLengths:
    """The FUN channels of one CLM: where each measurement started and what it buffered."""

    def __init__(self, rt: Any) -> None:
        self.rt = rt
        self.start: dict[str, Fraction] = {}  # a channel measures once it has a start
        self.buffered: dict[str, Fraction] = {}
        self._by_variable = {v: (name, i) for name, pair in _VARIABLES.items() for i, v in enumerate(pair)}

    def position(self, channel: str) -> Fraction | None:
        """The channel's position now (IU), None when its encoder or axis is missing."""
        rt = self.rt
        if channel in ("me1", "me2"):
            me = rt.master_encoder if channel == "me1" else getattr(rt, "master_encoder_2", None)
            return None if me is None else me.position
        if channel.startswith("axis"):
            axis = rt.axes.get(int(channel[4:]))
            if axis is None:
                return None
            wheel = getattr(axis, "wheel", None)  # measuring wheel mode: the material's feed
            return Fraction(axis.actual_position if wheel is None else wheel.wheel_position)
        cutoff = getattr(rt, "cutoff", None)  # the material through the tool (cutoff.py): master - carriage
        return None if cutoff is None else cutoff.material_point()

    def current(self, channel: str) -> Fraction:
        start = self.start.get(channel)
        now = self.position(channel)
        return Fraction(0) if start is None or now is None else now - start

    def fun(self, channel: str, digit: str) -> None:
        if digit == "2":
            return
        now = self.position(channel)
        if now is None:
            return
        if digit == "0":
            self.buffered[channel] = self.current(channel)
        self.start[channel] = now

    def variable(self, number: int) -> int | None:
        """V040-V043, Vx11, Vx12 in millionths; None for another variable."""
        found = self._by_variable.get(number)
        if found is None:
            return None
        channel, buffered = found
        value = self.buffered.get(channel, Fraction(0)) if buffered else self.current(channel)
        return round(value * _SCALE)


def feed_lengths(rt: Any) -> FeedLengths:
    """The runtime's FUN channels (made, with the variable hook, on first use)."""
    install(rt)
    return rt.feed_lengths  # type: ignore[no-any-return]


def op_fun(rt: Any, task: NcTask, ins: Instruction) -> int | None:
    """FUN d d d d d d d: per channel 0 buffer + restart, 1 restart, 2 nothing; one cycle."""
    lengths = feed_lengths(rt)
    for channel, digit in zip(CHANNELS, ins.values):
        lengths.fun(channel, str(digit))
    return task.pc + 1


# -- system variables and Status 09 (decision 8) -----------------------------------------------------


def install(rt: Any) -> None:
    """Let V040-V043, V047, V048, Vx11 and Vx12 read live: the runtime's system-variable hook is
    chained (once) so that these come from here and every other from the runtime."""
    if getattr(rt, "feed_lengths", None) is not None:
        return
    lengths = FeedLengths(rt)
    rt.feed_lengths = lengths
    variables = rt.memory.variables
    previous = variables.system

    def system(number: int) -> int | None:
        if number in (47, 48):
            axis = rt.axes.get(number - 46)
            wheel = getattr(axis, "wheel", None)
            if wheel is not None:
                return round(wheel.motor_position * _SCALE)
        value = lengths.variable(number)
        if value is not None:
            return value
        return None if previous is None else previous(number)

    variables.system = system


def status_09(rt: Any) -> str:
    """The Status 09 body ``09__evmmmmmm.mmm_vnnnnnn.nnn_``; ClmError 10 / 09 when it has none."""
    from .status import _fixed  # (status.py calls this module: imported here, not at the top)

    if rt.memory.parameters.axis_mode(1) not in (3, 4):
        raise ClmError(serial_code(10), "Status 09: axis 1 is not in measuring wheel mode (A100 mode 3 or 4)")
    axis = rt.axes.get(1)
    wheel = getattr(axis, "wheel", None)
    if wheel is None or not wheel.set_up:
        raise ClmError(serial_code(9), "Status 09: axis 1 has no measuring wheel (device.master_encoder_1, C000/C002)")
    homed = "A" if axis.homed else " "
    return f"09  {homed}{_fixed(wheel.wheel_position, 6, 3)} {_fixed(wheel.motor_position, 6, 3)} "
