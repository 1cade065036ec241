"""One CLM1.4 axis on the kernel's axis: positioning commands, drive enable and brake, monitoring.

    clm = ClmAxis(1, machine, "feed", params, image, nc_cycle_s=0.002)   # configure() runs here
    clm.position_incremental(200_000, 999)    # POI 1 +000200.000 999 (lengths in 1/1000 IU)
    err = clm.tick("automatic", enable_input=True, estop_ok=True)   # once per NC cycle
    clm.in_position, clm.lag, clm.remaining_distance

Every motion is a command of the kernel's `Axis` (move_absolute, move_velocity, halt, power),
planned by its profile generator; the CLM's part is what it commands: targets in exact
fractions of an IU (``target += distance x FAK``), velocities in per mille of Ax06, ACC / Ax09
ramps, the Ax10 jerk, and the position loop `clmloop.ClmLoop` in place of the kernel's Kv loop
(``machine.drive_by(axis, loop, volts=True)``: the +-10 V path of the simulated amplifier).
The machine file's axis unit is the CLM's IU; its v_max / a_max must be at least Ax06 / Ax08
(the kernel clamps to them as the mechanics' limits). Outputs go to the CLM process image:
Drive Enable and Brake (spec §6.3), Ax27 Position reached, Ax28 Position window, Ax14
Position error > max. deviation.

Decisions (spec line -> choice, why)
------------------------------------
1. Errata §1.1, L4461, L4530 -> v_cmd = FF + Kv x 1000/60 x lag (IU/s; the spec's "IU/min" is
   60x too weak); test_steady_lag_follows_the_kv_formula.
2. Ax12 (L4473-4482) -> volts = v_cmd / (RPM / 60 x feed constant) x Ax12 volts, clipped to
   +-10 V; the feed constant is Ax01, x Y/X only where Ax02 is used (incremental rotary table,
   L3581); test_steady_lag_follows_the_kv_formula checks the volts.
3. Ax11 feedforward (L4443-4457) -> 1 = set-point velocity, n >= 2 = its average over
   2^(n-1) cycles; test_feed_forward_removes_the_steady_lag.
4. Ax14 "mathematical model" (L4518-4532) -> the ideal closed loop (clmloop); deviation from it
   beyond Ax14 % of Ax12 RPM x Ax01 / (1000 Kv) is Runaway when the encoder moves away from the
   model (L4520: wrong direction, moving without command), else Lag (L4522: too slow, stalled);
   Lag and Runaway also drop the homed state (errata §3.8);
   test_excess_lag_when_the_drive_cannot_follow, test_runaway_with_a_reversed_encoder.
5. Ax14 output (L4504 "set only when the error message is deactivated") -> set while the
   deviation is beyond the window and its kind's message is off (mode 1 both, 2 lag, 3 runaway);
   test_ax14_output_instead_of_the_message.
6. Per mille (errata §3.2, L2230) -> v = vvv / 1000 x Ax06 (999 = 99.9 %); ACC aaa/ddd likewise
   of Ax08, and 000 = Ax08 itself as in Ax09 (L4412; a zero ramp could never start);
   test_poi_reaches_target_at_per_mille_of_ax06, test_acc_changes_the_ramp.
7. ACC (L1409 "acceptance ... immediate" vs L1454 "as for the ACC command, as soon as any
   positioning move in process has been completed") -> both hold: the values are taken at once
   for every following positioning, CON, PBK and stop, a move already running keeps its ramps
   (as FAK, L1931); test_acc_changes_the_ramp.
8. Ax10 (L4428-4430) -> the time is rounded up to 2^n NC cycles and the move is jerk limited
   with j = max(accel, decel) / that time (no ramp of the acceleration lasts longer);
   test_ax10_jerk_time_rounded_up_to_a_power_of_two_cycles.
9. FAK (L1917-1933) -> targets are exact fractions (+100 x 1.2345 = 123.45 exactly); a running
   move keeps its target; test_fak_scales_the_next_positionings.
10. POI (L2287-2289) -> target := last target + L x FAK (a running move is extended); after PBK,
    CON off or the end of a jog the last target is the point the braking ends at, so PBK + POI
    gives "the deceleration distance plus 50 IU" with a continuous 99.9 % -> 10 % transition
    (L2225-2230); test_pbk_discards_the_rest_and_poi_adds_to_the_stop_point.
11. PSA/PSI and Ax27 (L2307-2328, L4774) -> in position = the set point has reached the target
    ("positioning procedure has been completed", L2328) and |target - actual| <= Ax27; the
    adjustment goes on afterwards (L2322); test_in_position_per_ax27.
12. Immediate Stop / JST (L5879, L2077) -> brake with the current deceleration, keep the target;
    `resume` moves to it (no loss of dimensions); CON is switched off, not kept;
    test_immediate_stop_and_resume_lose_no_dimension.
13. Drive Enable (L6027-6035) -> on in Manual/Automatic with E-Stop closed, Enable Axis x and no
    fault; off at once otherwise. Brake output 1 = 24 V = released (L7407), 200 ms after Drive
    Enable (L6058), 0 at once with it (L6060). The position loop holds from Drive Enable on;
    motion is not held back for the brake (the amplifier holds against it);
    test_drive_enable_and_brake_with_200_ms_delay.
14. L6039 "In Automatic Mode, Drive Enable must be present ... at all times" -> tick returns
    40/70/A0/D0 whenever Enable Axis x is missing in Automatic; test_automatic_without_enable_is_40.
15. Travel limits (L4292-4334) -> linear axes (Ax00 type 1) with a reference (homed or absolute
    encoder): Automatic faults 46/47 on the actual position; a jog runs to the limit and stops
    there (a move_absolute at Ax07), and is dead beyond it; test_jog_at_ax07_stops_at_the_limit,
    test_travel_limit_fault_in_automatic.
16. POA (L2265, L4298, L4326) -> 48 without a reference first, then 50/51 (linear axes only, on
    the target x FAK); test_poa_errors_48_50_51.
17. A positioning while the drive is not enabled (or at 000 per mille) -> the target is taken
    and the move starts when the drive is enabled (Inhibit Operation, §6.2: "a move is blocked");
    test_move_waits_for_drive_enable.
18. CPL (L1798-1806) -> once: set point := actual (kernel power off/on within the cycle: the
    running move ends), target := actual, the Ax14 model restarts; test_cpl_clears_the_lag.
19. Jog (L5901-5918) -> Ax07 with the current ACC ramps (Ax09 in Manual, L1413); releasing the
    key brakes with the deceleration; jog(0) ends only a jog, never a program's move;
    test_jog_at_ax07_stops_at_the_limit.
20. Rotary table (Ax00 type 2, L3501-3610, errata §3.10) -> IUT = Ax01 (incremental encoder,
    L3573) or Ax01 x the Ax19 ratio (absolute, Fig. 7-6); all table arithmetic is exact
    (Fractions: targets, IUT, the feed constant Ax01 x Y/X = 360/590, the increment); the kernel
    axis stays unwrapped and the table position is its value modulo IUT;
    tests/devices/clm/test_rotary.py::test_360_over_590_does_not_drift_over_a_million_revolutions.
21. POA on the table (L3601-3605) -> the target (x FAK) must lie in 0..IUT (else 50 below /
    51 above, the travel-limit codes); shortest way: the signed distance (target - position)
    mod IUT, taken backwards when more than IUT/2 (exactly half: forwards); programmed
    direction: the sign of the POA value is the direction and its magnitude the target (so in
    that mode a negative value is allowed; "-000000.000" is +0: the sign of 0 is not stored);
    a target equal to the position does not move; test_shortest_way, test_programmed_direction.
22. RTM / Ax05 (L2468-2486, L4344) -> RTM 1 shortest, 2 programmed, 0 back to Ax05 (0
    programmed, 1 shortest), > 2 unchanged; RTM needs type 2 (else no function) and a
    reference (else 48); Ax05 returns at power up, error acknowledge and the end of Parameter
    mode, not at Manual <-> Automatic; test_rtm_and_ax05_codes.
23. SAC (Figs. 5-22..5-24, L2502-2584) -> a coordinate shift s against the initial (homing)
    frame: m 0 sets s := value ("offset ... referenced to the initial coordinate system", not
    added to a previous SAC), m 1 makes the present target read value; rotary (type 0) not
    homed: the actual position becomes value and the axis is homed (m 0/1); rotary m 9: the
    reference is cancelled and the actual position reads 0; linear / table not homed: 48;
    Ax20 controlled axis: 1B; the travel limits are checked in the initial frame; clearing an
    error or Parameter mode restores the initial frame; test_sac_table_per_motion_type.
24. HOM (L1997-2026) -> starts the homing of Ax24 (homing.py) and proceeds after one cycle;
    with an absolute encoder, a type digit 4 (passive, flying cutoff only) or a drive that is
    not enabled or still moving: 52 HOM Command; the Homing input (Ax23) starts it on a
    rising edge in Manual. The Homed output (Ax24) is set when homing ends, cleared when it
    starts, at Lag / Runaway and on leaving Parameter mode, never rewritten in between (the
    program may clear it, "the axis remains homed", L3719); stop, Immediate Stop, a mode
    change or a fault end a running homing (to be started again, L3770-3775);
    tests/devices/clm/test_homing.py::test_hom_and_akn_on_the_homed_output.
25. Measuring wheel mode (Ax00 modes 3/4, §7.2): the axis takes the wheel of its master encoder
    (``attach_wheel``, master_encoder.py) and a `measuring_wheel.WheelMode` closes the loop
    through it (Version 1) or corrects the targets (Version 2); POA/PSA in Version 1 is 0A;
    decisions in measuring_wheel.py, tests in tests/devices/clm/test_measuring_wheel.py.
26. Open Feed Roll (Ax30, §7.10): `feedroll.OpenFeedRoll` opens the loop in position and holds
    feeds until the input is 0; decisions in feedroll.py.
27. Ax21 Drive Direction (L4669-4676, figure lost: three digits, "Designated directions can be
    combined"; L8731 "The designated direction for position detection (encoder) and/or for the
    analog output are opposite of the cable connection ... change designated direction in
    Parameter Ax21") -> the first digit turns the encoder's counting direction, the second the
    analog output's polarity (any digit but 0 turns, as parameters decision 8 leaves the digits
    unchecked); both together reverse the axis' direction of motion on unchanged wiring (the
    "combination"); the third has no function. Taken with the other parameters on leaving
    Parameter mode (kernel `Machine.set_directions`). Tests:
    tests/devices/clm/test_axis.py::test_ax21_turns_a_reversed_encoder_round,
    test_ax21_output_alone_runs_away, test_ax21_both_reverse_the_motion.
28. Flying cutoff (Ax00 mode 5, axis 1; L3933, L3947) -> the feedforward is on whatever A111
    says (its averaging digit kept when set), POI / PSI run at A106 whatever velocity they
    program; the carriage is coupled by `synchronize` (cutoff.py, the kernel's GearInPos) and
    returns by `move_to`. tests/devices/clm/test_cutoff.py::test_poi_on_axis_1_runs_at_a106,
    test_consecutive_pieces_have_the_programmed_length.
"""

from __future__ import annotations

import math
from fractions import Fraction
from typing import Any

from .axisdrive import BRAKE_DELAY_S, DRIVE_OUTPUTS, DriveMonitoring
from .axisref import AxisReferences, _f
from .axisstop import StopAndJog
from .clmloop import ClmLoop
from .errors import ClmError, axis_fault
from .feed_signals import FeedSignals
from .feedroll import OpenFeedRoll
from .image import ProcessImage
from .measuring_wheel import WheelAxis
from .operands import Operand
from .parameters import ParameterSet
from .slave import Follower

__all__ = ["ClmAxis", "DRIVE_OUTPUTS", "BRAKE_DELAY_S"]


def _bit_place(op: Operand) -> tuple[int, int]:
    at, shift, _ = ProcessImage.locate(op)
    return at, 1 << shift

_MILLI = 1000  # program lengths are 1/1000 IU
_MILLIONTH = 1_000_000  # FAK f.ffffff


class ClmAxis(WheelAxis, OpenFeedRoll, StopAndJog, DriveMonitoring, AxisReferences):
    """CLM axis `number` (1-4) on the machine's kernel axis `axis_name`; see the module docstring."""

    # slave / synchronous axis (slave.py): the Follower of an Ax00 mode 1/2 axis, and the CLM's
    # axes by number (set by the personality) to find the master
    follower: Follower | None = None
    peers: dict[int, Any] = {}
    cutoff_axis = False  # axis 1 in Ax00 mode 5 (flying cutoff, cutoff.py)
    _ramp_override: float | None = None  # move_to's own ramps (cutoff.py's optimised return)

    def __init__(self, number: int, machine: Any, axis_name: str, params: ParameterSet, image: ProcessImage, nc_cycle_s: float) -> None:
        if number not in DRIVE_OUTPUTS:
            raise ValueError(f"a CLM axis is 1..4, not {number}")
        self.number = number
        self.machine = machine
        self.axis_name = axis_name
        self.axis = machine.axis(axis_name)
        self.image = image
        self.nc_cycle_s = float(nc_cycle_s)
        self.loop = ClmLoop(self.axis, machine.period)
        self._enable_out, self._brake_out = DRIVE_OUTPUTS[number]
        # (byte, bit mask) of the two outputs written every cycle (axisdrive._outputs)
        self._enable_bit, self._brake_bit = (_bit_place(op) for op in DRIVE_OUTPUTS[number])
        self._brake_cycles = math.ceil(BRAKE_DELAY_S / self.nc_cycle_s - 1e-9)
        self._drive_on = False
        self._on_cycles = 0
        self._fault = False
        self._switched_on = True  # !MxON / !MxOFF (kept through mode changes and faults)
        self._homed = False
        self._tx: Fraction | None = None  # programmed target (axis frame), exact
        self._tf: float | None = None  # the same as a float (read every cycle)
        self._speed = 0.0  # IU/s of the positioning to the target
        self._kept = False  # Immediate Stop / JST: the rest waits for resume()
        self._blocked = False  # waits for Drive Enable (or a velocity)
        self._con: float | None = None  # CON velocity, IU/s
        self._jog = 0
        self._braking = False  # a move_velocity(0) that ends in halt()
        self.configure(params)

    # ------------------------------------------------------------------ parameters

    def configure(self, params: ParameterSet) -> None:
        """Read Ax.. (after Parameter mode) and install the CLM position loop on the kernel axis."""
        a = f"A{self.number}"

        def num(pid: str, name: str) -> Fraction:
            return _f(params.get(a + pid).number(name))

        feed = num("01", "feed_constant")
        if params.used(a + "02"):
            gear = params.get(a + "02")
            feed = feed * _f(gear["output_revolutions"]) / _f(gear["input_revolutions"])
        self._feed = feed
        rpm = num("12", "max_encoder_speed")
        self._full_speed = float(rpm / 60 * feed)
        self._vmax = num("06", "maximum_velocity")
        self._vjog = float(num("07", "jog_velocity"))
        self._a08 = num("08", "acceleration")
        self._ramps: dict[int, float] = {}  # per mille -> IU/s^2 of Ax08 (worked out once each, `_ramp`)
        self._ax09 = (int(num("09", "acceleration")), int(num("09", "deceleration")))
        self._jerk_time = self._round_jerk_time(float(num("10", "jerk_constant")))
        kv = num("11", "kv_factor")
        p14 = params.get(a + "14")
        self._monitor_mode = int(p14["monitoring_mode"])
        self.window = float(_f(p14["window_percent"]) / 100 * rpm * feed / (1000 * kv))
        self._ax14_out: Operand = p14["deviation_output"]
        p27, p28 = params.get(a + "27"), params.get(a + "28")
        self._ax27_out: Operand = p27["position_reached_output"]
        self.threshold = float(p27["switching_threshold"])
        self._ax28_out: Operand = p28["position_window_output"]
        self._ax28 = float(p28["position_window"])
        # where the three outputs are, None where not programmed (00.00.0): written every cycle
        self._ax14_place, self._ax27_place, self._ax28_place = (
            None if op.unset else ProcessImage.locate(op) for op in (self._ax14_out, self._ax27_out, self._ax28_out))
        self._min = num("03", "min_travel_limit")
        self._max = num("04", "max_travel_limit")
        self._min_f, self._max_f = float(self._min), float(self._max)
        self._linear = params.motion_type(self.number) == 1
        self._absolute = params.encoder_type(self.number) in (1, 2)
        self._enabled = self.number in params.enabled_axes()
        # slave / synchronous axis (slave.py): a new Follower (FOL defaults) after Parameter mode
        if self.follower is not None:
            self.follower.detach()
        mode = params.axis_mode(self.number)
        self.cutoff_axis = self.number == 1 and mode == 5  # flying cutoff (cutoff.py)
        self.follower = Follower(self, mode, int(params.get(a + "00")["master"])) if mode in (1, 2) else None
        self._configure_table_and_homing(params, feed)
        self._params = params
        self._configure_wheel()
        self._configure_feed_roll(params, self.number)
        self.feed_signals = FeedSignals(params, self.number, self.image, self.nc_cycle_s)  # Ax29, Ax32
        feedforward = int(num("11", "feedforward"))
        if self.cutoff_axis:  # "'Feedforward' is always activated, independently of ... A111" (L3933)
            feedforward = max(1, feedforward)
        self.loop.configure(kv=float(kv), feedforward=feedforward, full_speed=self._full_speed,
                            full_volts=float(num("12", "command_voltage")), window=self.window)
        self.machine.drive_by(self.axis_name, self.loop, volts=True)
        p21 = params.get(a + "21")  # decision 27
        self.machine.set_directions(self.axis_name, feedback=-1 if int(p21["encoder_direction"]) else 1,
                                    output=-1 if int(p21["output_direction"]) else 1)
        self.reset_defaults()

    def _round_jerk_time(self, seconds: float) -> float | None:
        """Ax10 rounded up to 2^n NC cycles (L4428-4430); None: off."""
        if seconds <= 0.0:
            return None
        n = max(0, math.ceil(math.log2(seconds / self.nc_cycle_s) - 1e-9))
        return 2**n * self.nc_cycle_s

    # ------------------------------------------------------------------ settings

    def set_acceleration(self, accel: int, decel: int) -> None:
        """ACC: per mille of Ax08, 000 = Ax08 (decisions 6, 7)."""
        for value in (accel, decel):
            if not 0 <= value <= 999:
                raise ValueError(f"ACC takes 000..999 per mille, not {value}")
        self._acc = (accel, decel)

    def set_factor(self, factor: int) -> None:
        """FAK: f.ffffff as millionths (decision 9)."""
        if factor < 0:
            raise ValueError(f"FAK is 0.000000..9.999999, not {factor}")
        self._factor = Fraction(factor, _MILLIONTH)

    def reset_defaults(self) -> None:
        """Mode change / error / power up: ACC -> Ax09 (L1413), FAK -> 1 (L1933), CON off (L1721),
        a kept or blocked remaining distance dropped; a moving axis brakes."""
        self._acc = self._ax09
        self._factor = Fraction(1)
        if self._kept or self._blocked:
            self._kept = self._blocked = False
            self._target = None
        if self._con is not None or self._jog or not self.motion_done:
            self.stop_motion()

    #: AEO (override.py decision 12): IU/s^2 for both ramps of the following positionings, or None
    aeo_acceleration: float | None = None

    @property
    def acceleration(self) -> float:
        a = self.aeo_acceleration
        return self._ramp(self._acc[0]) if a is None else a

    @property
    def deceleration(self) -> float:
        a = self.aeo_acceleration
        return self._ramp(self._acc[1]) if a is None else a

    @property
    def ax09_acceleration(self) -> float:
        """Ax09's acceleration in IU/s^2 (per mille of Ax08, decision 6): AEO's "Parameter Ax09"."""
        return self._ramp(self._ax09[0])

    def _ramp(self, per_mille: int) -> float:
        ramp = self._ramps.get(per_mille)
        if ramp is None:  # (asked every cycle by the flying cutoff; Ax08 changes only in `configure`)
            ramp = self._ramps[per_mille] = float(self._a08 if per_mille == 0 else self._a08 * per_mille / 1000)
        return ramp

    def _jerk(self) -> float | None:
        t = self._jerk_time
        return None if t is None else max(self.acceleration, self.deceleration) / t

    # ------------------------------------------------------------------ positioning

    def _check(self) -> None:
        if not self._enabled:
            raise ClmError(axis_fault(0x0E, self.number), f"axis {self.number} is not enabled in B000")

    def _velocity(self, per_mille: int) -> float:
        if not -999 <= per_mille <= 999:
            raise ValueError(f"a velocity is 000..999 per mille of Ax06, not {per_mille}")
        return float(self._vmax * per_mille / 1000)

    def position_absolute(self, target: int, per_mille: int) -> None:
        """POA / PSA: target (1/1000 IU) x FAK; 48 without a reference, 50/51 beyond Ax03/Ax04."""
        self._check()
        n = self.number
        if self.wheel is not None and self.wheel.version == 1:  # measuring_wheel.py decision 3
            raise ClmError("0A", f"POA/PSA on axis {n}: in measuring wheel mode Version 1 (A{n}00 mode 3) only relative distances are traversed (L4198)")
        if not self.homed:
            raise ClmError(axis_fault(0x08, n), f"POA/PSA on axis {n} needs a reference (homing or an absolute encoder, L2265)")
        if self.iut is not None:
            goal = self._table_goal(target)
            self.feed_signals.new_feed()
            self._move_to(goal, self._velocity(per_mille))
            return
        goal = Fraction(target, _MILLI) * self._factor
        if self.wheel is not None:  # Version 2: the compiled difference (measuring_wheel.py 4)
            goal += self.wheel.start_movement()
        initial = goal - self._sac_shift  # the travel limits stay in the initial frame (decision 23)
        if self._linear and initial < self._min:
            raise ClmError(axis_fault(0x10, n), f"target {float(goal):.3f} is below Ax03 = {float(self._min):.3f} (L4298)")
        if self._linear and initial > self._max:
            raise ClmError(axis_fault(0x11, n), f"target {float(goal):.3f} is above Ax04 = {float(self._max):.3f} (L4326)")
        speed = self._velocity(per_mille)
        self.feed_signals.new_feed()
        self._move_to(goal, speed)

    def position_incremental(self, distance: int, per_mille: int) -> None:
        """POI / PSI: the target grows by distance (1/1000 IU) x FAK (decision 10)."""
        self._check()
        speed = self._velocity(per_mille) if not self.cutoff_axis else float(self._vmax)  # A106 (L3947)
        self.feed_signals.new_feed()  # Ax29 (feed_signals.py)
        goal = self._base() + Fraction(distance, _MILLI) * self._factor
        if self.wheel is not None:  # Version 2: the compiled difference (measuring_wheel.py 4)
            goal += self.wheel.start_movement()
        self._move_to(goal, speed)

    def _base(self) -> Fraction:
        if self._target is None and self._following:  # slave: the own part's frame (slave.py 7)
            return Fraction(self.follower.u)  # type: ignore[union-attr]
        return self._target if self._target is not None else Fraction(self.axis.command_position)

    @property
    def _following(self) -> bool:
        """Slave / synchronous axis coupled: positionings are the Follower's own part."""
        return self.follower is not None and self.follower.attached

    def _move_to(self, goal: Fraction, speed: float, ramp: float | None = None) -> None:
        self._ramp_override = ramp  # (the flying cutoff's optimised return, cutoff.py; else ACC)
        self._con = None
        self._jog = 0
        self._kept = False
        self._braking = False
        self._target = goal
        self._speed = abs(speed)
        self._start()

    # -- velocity functions hook (override.py owns it: B017/VEO override, VCC) ------------------
    override: Any = None  # None, or programmed IU/s -> commanded IU/s, applied in _start (override.py)

    def change_speed(self, speed: float | None = None) -> None:
        """VCC (a new programmed speed) or an override change (None): replan the running
        positioning at once (kernel move_absolute, ABORTING); nothing else is touched."""
        if speed is not None:
            self._speed = abs(speed)
        if self._target is not None and self._con is None and not (self._jog or self._kept or self._blocked or self._braking) and not self.motion_done:
            self._start()

    # -- end of the velocity functions hook ------------------------------------------------------

    # -- registration hook (registration.py: SRM offset move, SRP correction, RMI suspend/resume) --
    def move_to(self, goal: Fraction, speed: float | None = None, ramp: float | None = None) -> None:
        """Position to the exact `goal` (IU, axis frame) at `speed` IU/s (None: the last speed),
        with `ramp` IU/s^2 for both ramps (None: the ACC ramps)."""
        self._check()
        self._move_to(Fraction(goal), self._speed if speed is None else abs(speed), ramp)

    def shift_target(self, delta: Fraction) -> None:
        """Move the programmed target by `delta` IU (a running positioning is replanned)."""
        if self._target is not None and delta:
            self._move_to(self._target + delta, self._speed)

    @property
    def speed(self) -> float:
        """IU/s of the last positioning."""
        return self._speed

    def per_mille_speed(self, per_mille: int) -> float:
        return abs(self._velocity(per_mille))

    # -- end of the registration hook --------------------------------------------------------------

    # -- flying cutoff hook (cutoff.py) ----------------------------------------------------------
    @property
    def maximum_velocity(self) -> float:
        """A106 (Ax06), IU/s: the return and the POI/PSI speed in flying cutoff (L3947)."""
        return float(self._vmax)

    @property
    def max_travel(self) -> float:
        """Ax04, IU."""
        return self._max_f

    def synchronize(self, gear: Any) -> None:
        """Hand the kernel axis to `gear` (a GearInPos); no programmed target while coupled."""
        self._check()
        self._con = None
        self._jog = 0
        self._kept = self._blocked = self._braking = False
        self._target = None
        cmd = gear.gear_in()
        if cmd.error:
            raise ClmError("0A", f"axis {self.number}: the flying cutoff could not couple the carriage ({cmd.error_text})")

    # -- end of the flying cutoff hook -------------------------------------------------------------

    def _start(self) -> None:
        """Hand the target (or CON) to the kernel; blocked while the drive is off (decision 17)."""
        ax = self.axis
        if not (self._drive_on and ax.powered) or self.feed_roll_open:  # (feedroll.py decision 2)
            self._blocked = True
            return
        if self._following:  # slave: added to the following in velocity (slave.py 7)
            f = self.follower
            assert f is not None
            self._blocked = False
            if self._con is not None:
                f.own_velocity(self._con, self.acceleration, self.deceleration, self._jerk())
            elif self._target is not None and self._speed > 0.0:
                f.own_move(float(self._target), self._speed if self.override is None else self.override(self._speed),
                           self.acceleration, self.deceleration, self._jerk())
            else:
                self._blocked = self._target is not None
            return
        if self._con is not None:
            cmd = ax.move_velocity(self._con, acceleration=self.acceleration, deceleration=self.deceleration, jerk=self._jerk())
        elif self._target is not None and self._speed > 0.0:
            ramp = self._ramp_override
            cmd = ax.move_absolute(float(self._target), velocity=self._speed if self.override is None else self.override(self._speed),
                                   acceleration=self.acceleration if ramp is None else ramp,
                                   deceleration=self.deceleration if ramp is None else ramp, jerk=self._jerk())
        else:
            self._blocked = self._target is not None  # 000 per mille: the target waits for a velocity
            return
        self._blocked = bool(cmd.error)

    def continuous(self, on: bool, signed_per_mille: int) -> None:
        """CON: run at the signed per mille of Ax06, or brake (CON off)."""
        self._check()
        if on:
            self._kept = False
            self._jog = 0
            self._braking = False
            self._target = None
            self._con = self._velocity(signed_per_mille)
            self._start()
        elif self._con is not None:
            self.stop_motion()

    # ------------------------------------------------------------------ references

    @property
    def homed(self) -> bool:
        """A reference: homed, or an absolute encoder (L2265)."""
        return self._homed or self._absolute

    @homed.setter
    def homed(self, value: bool) -> None:
        self._homed = bool(value)

    def set_actual(self, position: float) -> None:
        """SET V047/V048/Vx00, SAC, homing: the actual position becomes `position` (no motion)."""
        ax = self.axis
        delta = position - ax.actual_position
        ax.set_position(delta, relative=True)
        if self._target is not None:
            self._target += Fraction(delta)
        self.loop.resync()

    # ------------------------------------------------------------------ state

    @property
    def motion_done(self) -> bool:
        """The set point has reached its target: nothing running, kept or waiting."""
        ax = self.axis
        f = self.follower
        if f is not None and f.attached:  # (_following) slave: the own part has ended (the following goes on)
            return (self._con is None and not self._jog and not self._kept and not self._blocked and not self._braking
                    and f.own_done)
        return (self._con is None and not self._jog and not self._kept and not self._blocked and not self._braking
                and ax.motion_ended and ax.command_velocity == 0.0)

    @property
    def in_position(self) -> bool:
        """The target reached within the Ax27 switching threshold (decision 11)."""
        return self._at_target(self.threshold)

    def _at_target(self, window: float) -> bool:
        if not (self._drive_on and self.motion_done):
            return False
        f = self.follower
        if f is not None and f.attached:  # (_following) slave: the own part's set point at its target (slave.py 7)
            return self._tf is None or abs(self._tf - f.u) <= window
        goal = self._tf if self._tf is not None else self.axis.command_position
        return abs(goal - self.axis.actual_position) <= window

    @property
    def _target(self) -> Fraction | None:
        return self._tx

    @_target.setter
    def _target(self, value: Fraction | None) -> None:
        self._tx = value
        self._tf = None if value is None else float(value)

    @property
    def target(self) -> float | None:
        return self._tf

    @property
    def exact_target(self) -> Fraction | None:
        """The programmed target in exact IU (lengths x FAK are summed without rounding)."""
        return self._tx  # (= _target, read every cycle by restart.tick)

    @property
    def actual_position(self) -> float:
        return self.axis.actual_position

    @property
    def command_position(self) -> float:
        return self.axis.command_position

    @property
    def lag(self) -> float:
        """Set point - actual position (the CLM's position lag)."""
        return self.axis.command_position - self.axis.actual_position

    @property
    def actual_velocity(self) -> float:
        return self.axis.actual_velocity

    @property
    def remaining_distance(self) -> float:
        """Target - actual position while a target is programmed (the CTA's rest, L1059)."""
        return 0.0 if self._tf is None else self._tf - self.axis.actual_position

    @property
    def rpm(self) -> float:
        """Encoder speed, 1/min (Status 48): actual velocity / feed constant x 60."""
        return self.axis.actual_velocity * 60.0 / float(self._feed)

    @property
    def volts(self) -> float:
        return self.loop.volts

    def __repr__(self) -> str:
        return (f"ClmAxis({self.number}, {self.axis_name!r}, drive={'on' if self._drive_on else 'off'}, "
                f"target={self.target}, actual={self.actual_position:.3f})")
