"""FS701 position loop: feed-forward + P + I -> the +-10 V analogue output Ana-Out 2.

    loop = PositionLoop(settings, period)          # settings: cutter.CutterSettings
    volts = loop.update(set_position, set_velocity, actual_position)   # LU, LU/s, LU
    loop.position_error, loop.feed_forward_value, loop.correction_value, loop.integral_value

The control law (manual §4.3.2, §4.3.7, §7; spec §2.4, §2.5):

    e     = (set point - actual) in carriage increments        "Position Error" #3 (+: lags)
    FF    = (set-point velocity + lead x set-point acceleration) / Max. Line Speed x Ana-Out Gain 2
                                                                        "Feed Forw. Value" #4
            (lead: the acceleration feed-forward, L10, an axisline extension; 0 = the FS701)
    P     = clamp(FF of the speed P-Gain/100 [1/s] x e [LU], +-Max. Correction)  #5
    I     = I + P x T / I-Time (I-Time > 0), clamped to +-Max. Correction       #6
    u     = clamp(FF + P + I + Ana-Out Offset 2 / 2047 x Ana-Out Gain 2, +-10 V), 12-bit DAC

The set-point velocity is the carriage's scheduled speed: line speed x R while synchronous
(the line speed filtered over Sampling Time by the line master), the ramp's speed during the
approach, deceleration and return.

Adjust / commissioning procedures (manual §7, run against a simulated carriage drive driven
through `command_voltage`, always with the virtual master as reference):
    direction_check(...)   §7.2: does "Up" move the carriage forward, does its counter count up
    tune_gain(...)         §7.3: Ana-Out Gain 2 so that the differential counter stays at zero
    tune_offset(...)       Ana-Out Offset 2 so that the carriage stands without correction
    cycle_test(...)        §7.4 "Cycle": ramps up and down, reports the differential counter
    tune_lead(...)         L10: the acceleration feed-forward's lead from the counter on ramps

Decisions (spec [GAP]/[CONFLICT] points of the loop; tests in test_cutter_loop.py):
 L1 Feed-forward scaling (spec §2.5 [DERIVED]): 100 % feed-forward = Max. Line Speed ("used for
    internal scaling", manual §4.3.2) = Ana-Out Gain volts (the full-scale output "directly in
    volts"). The Adjust screenshot agrees (Max. Line Speed "20 000000" unreadable; 120000 LU/min
    with gain 10.16 V gives 1.51 V for a Max. Line Speed of about 800000).
    Test: test_cutter_loop.py::test_feed_forward_scaling_l1.
 L2 P-Gain scaling (spec §2.4 [GAP], §8 item 3): the P correction is the feed-forward voltage
    of the speed P-Gain/100 [1/s] x position error [LU]: with a matched Ana-Out Gain the loop
    gain is Kv = P-Gain/100 1/s whatever the length unit and encoder resolution (the manual's
    recommended 500..2500 = 5..25 /s, the range an analogue carriage drive with 10..40 ms of
    lag stays stable in, which is what §7.4 asks the user to find). A reading as "DAC steps per
    increment" would make the loop gain proportional to the encoder frequency (0.5 /s at the
    manual's 1 kHz minimum), which no setting could make work. Test: test_p_gain_scaling_l2.
 L3 Max. Correction unit (spec §3.5 [CONFLICT]): mV (manual text "Setting range 0 - 9999 mV,
    recommended >= 1000 mV"; table "Incr."). It limits the P correction; the integral is
    clamped to the same value (anti-windup). The output "Max. Correction" is set while the P
    correction is at the limit. Test: test_max_correction_limits_and_flags_l3.
 L4 I-Time (spec §2.4): integral of the P correction with integration time I-Time (a constant
    error e doubles its correction after I-Time); 0 = off.
    Test: test_integral_doubles_a_constant_error_after_i_time_l4_and_is_clamped.
 L5 Ana-Out Offset (spec §2.5 [DERIVED]): Offset/2047 x Ana-Out Gain (percent of full scale);
    E14: +2047 at 10.00 V and zero demand = +10 V. Test: test_e14_offset_is_a_fraction_of_full_scale_l5.
 L6 Sync Mode / "Freeze Mode" 1 and 2 (spec §2.4 [GAP]): with the input Sync Mode Enable during
    the synchronous cutting phase: 1 = correction off (feed-forward only: a clamp holds the
    material), 2 = correction frozen at its value when the phase began. 0 = normal.
    Tests: test_sync_mode_freezes_or_drops_the_correction_l6,
    test_cutter_applies_reset_diff_counter_and_sync_mode_inputs.
 L7 Reset Diff. Counter: the error counter is held at 0 (the offset between set point and
    actual is re-taken every cycle) and the integral cleared: feed-forward only; released, the
    counter counts from 0 again. Test: test_reset_diff_counter_opens_the_loop_l7.
 L8 DAC: 12 bit over +-10 V (4.88 mV per step), after the clamp.
    Test: test_output_is_clamped_to_10_volts_and_quantised_l8.
 L9 Gain tuning (§7.3 [DERIVED]): with P only at the constant adjust speed the mean
    differential counter settles where K (G v/v_max + kp e) = v (kp = Kv G / (kC v_max)), so the
    gain that zeroes it is G (1 + Kv e / (kC v)) whatever the drive's K: Newton steps until the
    gain moves by less than 0.002 V, rounded to 0.01 V; a last run checks |e| <= 8 (E16). The
    counter is taken relative to its value standing still: an offset the Ana-Out Offset left
    (its step is 0.05 % of full scale) would otherwise go into the gain, 0.2 % at a 10 % adjust
    speed, 1.5 increments of lag at 66 m/min in the example. The adjust speed (the Adjust
    card's Vir. Master Speed) is [device.adjust] speed, default 10 % of Max. Line Speed (E15);
    near the working speed the DAC's 4.9 mV step is a smaller fraction of the output. Offset
    tuning holds still in closed loop: the mean P correction is the drive's offset (iterated).
    Tests: test_e16_gain_tuning_centres_the_differential_counter, test_offset_tuning_*,
    test_direction_check_*, test_cycle_test_reports_the_differential_counter_e17, E15 defaults:
    test_e15_adjust_speed_defaults_to_10_percent_of_max_line_speed;
    test_feed_forward.py::test_gain_tuning_is_not_fooled_by_an_offset_l9.
 L10 Acceleration feed-forward (axisline, not in the manual; [device] acceleration_feed_forward):
    the feed-forward is taken for the set-point velocity plus lead x set-point acceleration.
    The FS701's loop (feed-forward + P + I) lets the carriage fall behind a ramping line by
    e = kC a (drive lag + T/2 + Sampling Time/2) / Kv: about 5 increments per m/s² in the
    example, which issue 4's bar (2 increments at 1 m/s²) does not allow and which no P-Gain
    the manual allows removes (I-Time winds up in the approach). The lead is measured by the
    Adjust program (`tune_lead`, "auto"): with P only the carriage ramps up and down at the
    adjust speed, and half the difference of the mean counter on the two ramps is the lag
    still missing (offset and gain errors cancel); it comes out as the drive's lag plus half
    a cycle (the held output). 0 (default) is the FS701's loop, unchanged, for a parameter
    set brought over from a real unit. The line's acceleration comes from cutter.py C26.
    Tests: test_feed_forward.py (the lead in the loop, its measurement for 3 and 6 ms drives,
    the 1 m/s² line within 2 increments with it and beyond 3 without).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

__all__ = [
    "PositionLoop",
    "DAC_LIMIT_VOLTS",
    "DAC_STEPS",
    "AdjustResult",
    "direction_check",
    "tune_gain",
    "tune_offset",
    "cycle_test",
    "tune_lead",
    "LEAD_MAX_MS",
]

DAC_LIMIT_VOLTS = 10.0
DAC_STEPS = 2048  # 12 bit signed: +-2048 steps over +-10 V
OFFSET_FULL_SCALE = 2047  # Ana-Out Offset range -2047..+2047 = -100..+100 %
LEAD_MAX_MS = 100.0  # the acceleration feed-forward's lead (L10): 0..100 ms
RAMP_MAX_S = 2.0  # the lead measurement's ramps last at most this long
_DAC_STEP = DAC_LIMIT_VOLTS / DAC_STEPS


class PositionLoop:
    """The FS701 PI position loop with feed-forward (module docstring)."""

    def __init__(self, settings: Any, period: float, *, dac: bool = True) -> None:
        self.settings = settings
        self.period = float(period)
        self.dac = dac
        self._version = -1  # the constants are computed at the first update
        self.reset()

    def reset(self) -> None:
        self.position_error = 0.0  # increments (#3)
        self.feed_forward_value = 0.0  # V (#4)
        self.correction_value = 0.0  # V (#5)
        self.integral_value = 0.0  # V (#6)
        self.output = 0.0  # V after clamp and DAC
        self.at_max_correction = False
        self.saturated = False
        self._e_offset = 0.0  # Reset Diff. Counter (L7)
        self._frozen: float | None = None  # Sync Mode 2 (L6)

    def off(self) -> float:
        """Controller disabled: analogue output 0 V (manual: Control Enable OFF)."""
        self.feed_forward_value = self.correction_value = self.integral_value = 0.0
        self.output = 0.0
        self.at_max_correction = False
        return 0.0

    # ------------------------------------------------------------------ scaling

    @property
    def gain_volts(self) -> float:
        return float(self.settings.ana_out_gain_2)

    def feed_forward(self, velocity: float) -> float:
        """L1: volts for a carriage speed (LU/s)."""
        return velocity / self.settings.v_max_line * self.gain_volts

    def p_volts_per_increment(self) -> float:
        """L2: P correction volts per increment of position error (Kv = P-Gain/100 1/s)."""
        s = self.settings
        return s.p_gain / 100.0 / s.cut_counts_per_lu / s.v_max_line * self.gain_volts

    def offset_volts(self) -> float:
        """L5."""
        return self.settings.ana_out_offset_2 / OFFSET_FULL_SCALE * self.gain_volts

    def kv(self, volts_to_velocity: float) -> float:
        """Position-loop gain (1/s) with a drive of `volts_to_velocity` LU/s per volt."""
        return self.p_volts_per_increment() * self.settings.cut_counts_per_lu * volts_to_velocity

    @staticmethod
    def quantise(volts: float) -> float:
        return round(volts / _DAC_STEP) * _DAC_STEP

    # ------------------------------------------------------------------ per cycle

    def _constants(self) -> None:
        """The loop's constants from the settings, again after a settings write (version)."""
        s = self.settings
        self._version = s.version
        self._kc = s.cut_counts_per_lu
        self._v_max = s.v_max_line
        self._gain = self.gain_volts
        self._kp = self.p_volts_per_increment()
        self._offset = self.offset_volts()
        self._max_corr = s.max_correction / 1000.0
        self._lead = s.acc_feed_forward / 1000.0

    def update(
        self,
        set_position: float,
        set_velocity: float,
        actual_position: float,
        *,
        reset: bool = False,
        sync_mode: bool = False,
        set_acceleration: float = 0.0,
    ) -> float:
        """Ana-Out 2 volts of this cycle (positions LU, velocity LU/s, acceleration LU/s²)."""
        s = self.settings
        if s.version != self._version:
            self._constants()
        raw = (set_position - actual_position) * self._kc
        # feed_forward(set_velocity + lead x set_acceleration): L1, L10
        ff = (set_velocity + self._lead * set_acceleration) / self._v_max * self._gain
        self.feed_forward_value = ff
        max_corr = self._max_corr
        if reset:
            # L7: the differential counter is held at zero, the PI part is off
            self._e_offset = raw
            self.position_error = 0.0
            self.correction_value = 0.0
            self.integral_value = 0.0
            self.at_max_correction = False
            self._frozen = None
            corr = 0.0
        else:
            e = raw - self._e_offset
            self.position_error = e
            mode = int(getattr(s, "freeze_mode", 0)) if sync_mode else 0
            if mode == 1:
                corr = 0.0
                self.correction_value = 0.0
                self._frozen = None
            elif mode == 2:
                if self._frozen is None:
                    self._frozen = self.correction_value + self.integral_value
                corr = self._frozen
            else:
                self._frozen = None
                p = self._kp * e
                self.at_max_correction = p >= max_corr or p <= -max_corr
                if p > max_corr:
                    p = max_corr
                elif p < -max_corr:
                    p = -max_corr
                self.correction_value = p
                if s.i_time > 0.0:
                    i = self.integral_value + p * self.period / s.i_time
                    if i > max_corr:
                        i = max_corr
                    elif i < -max_corr:
                        i = -max_corr
                    self.integral_value = i
                else:
                    self.integral_value = 0.0
                corr = p + self.integral_value
        u = ff + corr + self._offset
        self.saturated = u > DAC_LIMIT_VOLTS or u < -DAC_LIMIT_VOLTS
        if u > DAC_LIMIT_VOLTS:
            u = DAC_LIMIT_VOLTS
        elif u < -DAC_LIMIT_VOLTS:
            u = -DAC_LIMIT_VOLTS
        if self.dac:
            u = self.quantise(u)
        self.output = u
        return u


# ====================================================================== Adjust program (§7)


@dataclass
class AdjustResult:
    """Outcome of an Adjust procedure."""

    ok: bool
    message: str
    ana_out_gain_2: float = math.nan  # V
    ana_out_offset_2: int = 0
    dir_counter_2: int = 1
    carriage_forward: bool = True
    differential_min: float = math.nan  # increments
    differential_max: float = math.nan
    iterations: int = 0
    acc_feed_forward: float = math.nan  # ms (tune_lead)


class _AdjustRig:
    """The Adjust program's loop: virtual master reference -> carriage drive (command_voltage).

    drive: ServoDrive-like (command_voltage, step, enable, position); counts: callable giving
    the carriage encoder counter (increments, after the Dir. Counter 2 sign) after each step.
    The reference is the virtual master's increments scaled by Pulses Cut/Pulses Line (the
    carriage runs at the virtual line speed); the differential counter = reference - counts.
    """

    def __init__(self, settings: Any, period: float, drive: Any, counts: Any) -> None:
        self.s = settings
        self.period = float(period)
        self.drive = drive
        self.counts = counts
        self.loop = PositionLoop(settings, period)
        self.mean_correction = 0.0

    def run(
        self,
        speed_lu_min: float,
        ramp_time: float,
        seconds: float,
        *,
        closed_loop: bool = True,
        profile: Any = None,
        settle: float = 0.0,
    ) -> tuple[float, float, float, list[float]]:
        """Ramp to speed (or follow `profile(t) -> v LU/s`), return (min, max, mean of the
        differential counter after `settle` s, trace of the counter). `mean_correction`: the
        mean P correction (V) after `settle`."""
        s = self.s
        T = self.period
        drive = self.drive
        drive.enable(True)
        kc = s.cut_counts_per_lu
        v_target = speed_lu_min / 60.0
        acc = (s.v_max_line / ramp_time) if ramp_time > 0 else s.v_max_line / T
        c0 = self.counts()
        ref = 0.0  # LU of the reference since the start
        v = 0.0
        lo, hi, acc_sum, n = math.inf, -math.inf, 0.0, 0
        corr_sum = 0.0
        trace: list[float] = []
        steps = int(round(seconds / T))
        self.loop.reset()
        for k in range(steps):
            t = k * T
            if profile is not None:
                v_new = profile(t)
            else:
                dv = v_target - v
                step = acc * T
                v_new = v + (dv if abs(dv) <= step else math.copysign(step, dv))
            ref += 0.5 * (v + v_new) * T
            a = (v_new - v) / T
            v = v_new
            actual = (self.counts() - c0) / kc
            volts = self.loop.update(ref, v, actual, reset=not closed_loop, set_acceleration=a)
            drive.command_voltage(volts)
            drive.step(T)
            e = self.loop.position_error if closed_loop else (ref - actual) * kc
            trace.append(e)
            if t >= settle:
                lo = min(lo, e)
                hi = max(hi, e)
                acc_sum += e
                corr_sum += self.loop.correction_value
                n += 1
        self.mean_correction = corr_sum / n if n else 0.0
        # ramp down (Down key)
        for _ in range(int(round(max(v, 0.0) / acc / T)) + 2):
            v_new = max(v - acc * T, 0.0)
            a = (v_new - v) / T
            v = v_new
            ref += v * T
            actual = (self.counts() - c0) / kc
            drive.command_voltage(self.loop.update(ref, v, actual, reset=not closed_loop, set_acceleration=a))
            drive.step(T)
        drive.command_voltage(0.0)
        return lo, hi, (acc_sum / n if n else math.nan), trace


def _up_hold_down(t: float, acc: float, speed: float, t_ramp: float, hold: float) -> float:
    """The Adjust runs' speed profile at `t`: up at `acc` for `t_ramp`, `hold` at `speed`,
    down again, then 0."""
    if t < t_ramp:
        return acc * t
    if t < t_ramp + hold:
        return speed
    if t < 2 * t_ramp + hold:
        return speed - acc * (t - t_ramp - hold)
    return 0.0


def _adjust_speed(settings: Any, speed_lu_min: float | None) -> float:
    """§7.1: Vir. Master Speed default 10 % of Max. Line Speed (E15)."""
    return 0.1 * settings.max_line_speed if speed_lu_min is None else float(speed_lu_min)


def direction_check(
    settings: Any,
    period: float,
    drive: Any,
    counts: Any,
    *,
    speed_lu_min: float | None = None,
    ramp_time: float = 1.0,
    seconds: float = 0.5,
    carriage_position: Any = None,
) -> AdjustResult:
    """§7.2 Slave: "Up" in open loop (Reset on); does the carriage move forward and does its
    counter count up? Returns the Dir. Counter 2 setting that makes it count up.

    carriage_position: callable giving the carriage's physical position (LU) to check the
    drive polarity (None: the drive's `position`)."""
    pos = carriage_position if carriage_position is not None else (lambda: drive.position)
    rig = _AdjustRig(settings, period, drive, counts)
    c0, x0 = counts(), pos()
    rig.run(_adjust_speed(settings, speed_lu_min), ramp_time, seconds, closed_loop=False)
    dc, dx = counts() - c0, pos() - x0
    forward = dx > 0
    count_up = dc > 0
    if not forward:
        return AdjustResult(False, "the carriage moves backward on 'Up': the analogue polarity or the drive direction is wrong",
                            carriage_forward=False, dir_counter_2=settings.dir_counter_2)
    dir2 = settings.dir_counter_2 if count_up else 1 - settings.dir_counter_2
    msg = "directions correct" if count_up else "the carriage counter counts down: toggle Dir. Counter 2"
    return AdjustResult(True, msg, dir_counter_2=dir2, carriage_forward=True)


def tune_gain(
    settings: Any,
    period: float,
    drive: Any,
    counts: Any,
    *,
    speed_lu_min: float | None = None,
    ramp_time: float = 1.0,
    run_seconds: float = 1.5,
    tolerance: float = 8.0,
    max_iterations: int = 6,
) -> AdjustResult:
    """§7.3: find Ana-Out Gain 2 so that the differential counter stays around zero (L9, E16).

    Runs closed loop (P only, I-Time ignored) at the adjust speed; the mean counter after the
    ramp, less the counter standing still, gives the gain that zeroes it (Newton, L9). The
    setting is changed in `settings` (0.01 V resolution) and reported."""
    speed = _adjust_speed(settings, speed_lu_min)
    i_time = settings.i_time
    settings.i_time = 0.0  # manual §7: integration off for the first steps
    try:
        settle = speed / 60.0 / (settings.v_max_line / ramp_time) + 0.5 if ramp_time > 0 else 0.5
        settle = min(settle, run_seconds * 0.8)

        # the differential counter standing still: what is left of the drive's offset after
        # Ana-Out Offset 2 (one offset step is ~0.05 % of full scale). The gain is right when
        # the counter at speed is where it stands still (L9); zeroing it at the adjust speed
        # would make the gain cover the offset, wrong in proportion at other speeds.
        _, _, standstill, _ = _AdjustRig(settings, period, drive, counts).run(0.0, 0.0, 0.6, settle=0.3)

        def mean_error(g: float) -> tuple[float, float, float]:
            settings.ana_out_gain_2 = g
            rig = _AdjustRig(settings, period, drive, counts)
            lo, hi, mean, _ = rig.run(speed, ramp_time, run_seconds, settle=settle)
            return mean - standstill, lo, hi

        # Newton on the P-only balance K (G v/v_max + kp e) = v with kp = Kv G / (kC v_max): the
        # gain that zeroes e is G (1 + Kv e / (kC v)), whatever the drive's K (L9). One step is
        # exact in that model; it repeats until the gain moves by less than 0.002 V (a fifth of
        # the register's step: an error criterion would stop 0.2 % off at a low adjust speed)
        v = speed / 60.0
        kv = settings.p_gain / 100.0
        kc = settings.cut_counts_per_lu
        if v <= 0.0 or kv <= 0.0:
            return AdjustResult(False, "gain tuning needs an adjust speed and a P-Gain above 0")
        g1 = float(settings.ana_out_gain_2)
        it = 0
        while it < max_iterations:
            e1, _, _ = mean_error(g1)
            it += 1
            g2 = min(max(g1 * (1.0 + kv * e1 / (kc * v)), 0.01), 320.0)
            done = abs(g2 - g1) < 0.002
            g1 = g2
            if done:
                break
        g = round(g1, 2)
        mean, lo, hi = mean_error(g)
        it += 1
        ok = max(abs(lo), abs(hi)) <= tolerance
        settings.ana_out_gain_2 = g
        msg = f"Ana-Out Gain 2 = {g:.2f} V; differential counter {lo:+.1f} .. {hi:+.1f} increments"
        return AdjustResult(ok, msg, ana_out_gain_2=g, differential_min=lo, differential_max=hi, iterations=it)
    finally:
        settings.i_time = i_time


def tune_offset(
    settings: Any,
    period: float,
    drive: Any,
    counts: Any,
    *,
    seconds: float = 1.0,
) -> AdjustResult:
    """Ana-Out Offset 2 so that the carriage stands still without correction: hold position
    in closed loop (P only) at zero speed; the settled correction is the drive's offset."""
    i_time = settings.i_time
    settings.i_time = 0.0
    try:
        off = settings.ana_out_offset_2
        lo = hi = math.nan
        for it in range(1, 4):
            rig = _AdjustRig(settings, period, drive, counts)
            lo, hi, _, _ = rig.run(0.0, 0.0, seconds, settle=seconds * 0.5)
            # the mean P correction while holding still is what the drive's offset needs
            step = rig.mean_correction / settings.ana_out_gain_2 * OFFSET_FULL_SCALE
            new = int(round(off + step))
            new = max(-OFFSET_FULL_SCALE, min(OFFSET_FULL_SCALE, new))
            if new == off:
                break
            off = settings.ana_out_offset_2 = new
        ok = max(abs(lo), abs(hi)) <= 2.0
        return AdjustResult(ok, f"Ana-Out Offset 2 = {off:+d}", ana_out_offset_2=off,
                            differential_min=lo, differential_max=hi, iterations=it)
    finally:
        settings.i_time = i_time


def cycle_test(
    settings: Any,
    period: float,
    drive: Any,
    counts: Any,
    *,
    speed_lu_min: float | None = None,
    ramp_time: float = 1.0,
    cycles: int = 2,
    tolerance: float = 30.0,
) -> AdjustResult:
    """§7.4 "Cycle": the drive ramps up and down continuously; reports the differential
    counter's range (stable operation: within `tolerance`, spec E17: 30 increments)."""
    speed = _adjust_speed(settings, speed_lu_min) / 60.0
    acc = settings.v_max_line / ramp_time if ramp_time > 0 else speed / period
    t_ramp = speed / acc
    hold = max(0.2, t_ramp)
    period_t = 2.0 * (t_ramp + hold)

    def profile(t: float) -> float:
        return _up_hold_down(t % period_t, acc, speed, t_ramp, hold)

    rig = _AdjustRig(settings, period, drive, counts)
    lo, hi, _, _ = rig.run(0.0, ramp_time, cycles * period_t, profile=profile)
    ok = max(abs(lo), abs(hi)) <= tolerance
    return AdjustResult(ok, f"differential counter {lo:+.1f} .. {hi:+.1f} increments while cycling",
                        differential_min=lo, differential_max=hi, iterations=cycles)


def tune_lead(
    settings: Any,
    period: float,
    drive: Any,
    counts: Any,
    *,
    speed_lu_min: float | None = None,
    ramp_seconds: float = 0.4,
    max_iterations: int = 5,
) -> AdjustResult:
    """L10: the acceleration feed-forward's lead (ms) from the differential counter on ramps.

    With P only, a ramp of acceleration a leaves the counter at e = kC a (lead needed - lead)
    / Kv (Kv = P-Gain/100 with a tuned Ana-Out Gain 2): the velocity the drive falls short by
    is a x the time it lags. The carriage ramps up to the adjust speed and down again in
    `ramp_seconds` or 8/Kv (at most Acceleration 1, and then at most that or RAMP_MAX_S long:
    a lower top speed); half the difference of the mean counter over the settled part of the
    two ramps (offset and gain errors cancel) corrects the lead, again until it moves by less
    than 0.05 ms. `settings.acc_feed_forward` is set (0.1 ms). A ramp too gentle to show the lead
    on the counter (under 0.2 increments per ms) is refused with the reason."""
    speed = _adjust_speed(settings, speed_lu_min) / 60.0
    kv = settings.p_gain / 100.0
    if speed <= 0.0 or kv <= 0.0:
        return AdjustResult(False, "the lead needs an adjust speed and a P-Gain above 0")
    # the ramps last long enough for the loop to settle in their first 60 % (8/Kv), and at
    # most that or RAMP_MAX_S: a gentle Acceleration 1 gets a lower top speed, not a longer run
    t_min = max(ramp_seconds, 8.0 / kv)
    acc = min(speed / t_min, float(settings.acceleration_1))
    t_max = max(RAMP_MAX_S, t_min)
    if speed / acc > t_max:
        speed = acc * t_max
    t_ramp = speed / acc
    hold = 0.2
    T = float(period)
    kc = settings.cut_counts_per_lu
    # what 1 ms of lead is worth on the counter: below 0.2 increments the mean counter (good
    # to a few hundredths) cannot place the lead to a few tenths of a millisecond
    per_ms = kc * acc * 0.001 / kv
    if per_ms < 0.2:
        return AdjustResult(
            False,
            f"the lead cannot be measured: a ramp of {acc:g} LU/s² (Acceleration 1) moves the counter only "
            f"{per_ms:.2f} increments per ms of lead; raise Acceleration 1 or the adjust speed",
        )

    def profile(t: float) -> float:
        return _up_hold_down(t, acc, speed, t_ramp, hold)

    # the settled part of each ramp: its last 40 % (from 4.8/Kv on: the start's transient is
    # down to 1 %)
    n = int(round(t_ramp / T))
    first = n - int(0.4 * n)
    up = slice(first, n)
    down = slice(n + int(round(hold / T)) + first, n + int(round(hold / T)) + n)
    i_time = settings.i_time
    settings.i_time = 0.0
    lead = float(settings.acc_feed_forward)
    try:
        it = 0
        step = math.inf
        while it < max_iterations and abs(step) >= 0.05:
            settings.acc_feed_forward = lead
            rig = _AdjustRig(settings, T, drive, counts)
            _, _, _, trace = rig.run(0.0, 0.0, 2.0 * t_ramp + hold + 0.1, profile=profile)
            e_up = sum(trace[up]) / len(trace[up])
            e_down = sum(trace[down]) / len(trace[down])
            step = 0.5 * (e_up - e_down) / kc * kv / acc * 1000.0  # ms
            lead = min(max(lead + step, 0.0), LEAD_MAX_MS)
            it += 1
        lead = round(lead, 1)
        settings.acc_feed_forward = lead
        ok = abs(step) < 0.05 and 0.0 < lead < LEAD_MAX_MS
        msg = f"acceleration feed-forward lead = {lead:.1f} ms" + ("" if ok else " (did not settle)")
        return AdjustResult(ok, msg, iterations=it, acc_feed_forward=lead)
    finally:
        settings.i_time = i_time
