"""Drive models: a servo with a closed velocity loop and a stepper fed with step pulses.

Both present the same small interface (:class:`Drive`) so the kernel treats them alike; only the
command differs (velocity or volts for the servo, a microstep count for the stepper).
"""

from __future__ import annotations

import math
from typing import Literal

from .interfaces import Drive
from .kinematics import NO_CROSSINGS, Crossing, bisect_crossing, linear_crossing

__all__ = ["Drive", "ServoDrive", "StepperDrive", "VelocityLoop", "ANALOG_LIMIT_VOLTS"]

ANALOG_LIMIT_VOLTS = 10.0
"""The analog velocity command saturates at +-10 V (the controller's DAC range)."""

VelocityLoop = Literal["first_order", "second_order"]

# Sub-cycle pieces the servo's motion is split into when sensors ask for crossings: a turning
# point is searched inside each, so one reversal per quarter cycle is resolved exactly.
_SERVO_PIECES = 4


class ServoDrive:
    """Servo amplifier and motor with a closed velocity loop, commanded by velocity.

    The command is a velocity in user units/s, given either digitally (:meth:`command_velocity`)
    or as the +-10 V analog signal of a classic position controller (:meth:`command_voltage`,
    scaled by ``velocity_per_volt``). The analog path models the commissioning errors of a real
    amplifier input: ``offset_volts``, a drift of ``drift_volts_per_second`` since power-up and a
    ``gain_factor`` on the scale. The digital path is ideal.

    Command path, each cycle (the command is held over the cycle, as a DAC holds its output):
    velocity command -> clamp to +-``max_velocity`` -> ramp at ``max_acceleration`` (the drive's
    acceleration limit, applied to the loop's reference) -> velocity loop -> motor.

    The velocity loop is a first-order lag (``time_constant``) or a second-order system
    (``natural_frequency`` in rad/s, ``damping``). Both are integrated with their exact solution
    for a reference that is constant or ramps linearly, so the motion does not depend on the
    cycle period. With the first-order loop the motor never exceeds either limit; the
    second-order loop may overshoot them by its own overshoot, as a real underdamped loop does.

    Disabled, the amplifier is off: the command is ignored and the motor coasts down with
    ``coast_time_constant`` (exponential decay of velocity); a coast time constant of 0 stops
    it at once, as a holding brake would. Re-enabling is bumpless: the ramp restarts from the
    actual velocity.
    """

    def __init__(
        self,
        *,
        loop: VelocityLoop = "first_order",
        time_constant: float = 0.002,
        natural_frequency: float = 600.0,
        damping: float = 0.7,
        velocity_per_volt: float = 100.0,
        max_velocity: float | None = None,
        max_acceleration: float | None = None,
        coast_time_constant: float = 0.1,
        offset_volts: float = 0.0,
        drift_volts_per_second: float = 0.0,
        gain_factor: float = 1.0,
        position: float = 0.0,
        enabled: bool = False,
    ) -> None:
        if loop not in ("first_order", "second_order"):
            raise ValueError(f"loop must be 'first_order' or 'second_order', got {loop!r}")
        if time_constant <= 0.0 or natural_frequency <= 0.0 or damping <= 0.0:
            raise ValueError("time_constant, natural_frequency and damping must be > 0")
        if coast_time_constant < 0.0:
            raise ValueError("coast_time_constant must be >= 0")
        self.loop: VelocityLoop = loop
        self.time_constant = float(time_constant)
        self.natural_frequency = float(natural_frequency)
        self.damping = float(damping)
        self.velocity_per_volt = float(velocity_per_volt)
        self.max_velocity = math.inf if max_velocity is None else float(max_velocity)
        self.max_acceleration = math.inf if max_acceleration is None else float(max_acceleration)
        self.coast_time_constant = float(coast_time_constant)
        self.offset_volts = float(offset_volts)
        self.drift_volts_per_second = float(drift_volts_per_second)
        self.gain_factor = float(gain_factor)
        self._memo_h = self._memo_tau = self._memo_decay = math.nan
        self.velocity_error = 0.0
        """Velocity (units/s) the loop loses to load, subtracted from its reference: a hook for
        load-disturbance and following-error tests."""

        self.enabled = bool(enabled)
        self.position = float(position)
        self.velocity = 0.0
        self.acceleration = 0.0
        self.voltage = 0.0
        """Last analog command after the +-10 V clamp."""
        self.saturated = False
        """True when the last analog command was clipped at +-10 V."""
        self._analog = False
        self._command = 0.0  # digital velocity command
        self._reference = 0.0  # ramped reference the loop follows
        self._elapsed = 0.0  # time since power-up, for the analog drift

        # The last cycle, kept so sensors can ask where the motor was inside it.
        self._dt = 0.0
        self._coasting = True
        self._x0 = self.position
        self._v0 = 0.0
        self._a0 = 0.0
        self._h1 = 0.0  # duration of the first (ramping) segment
        self._r1 = 0.0  # reference at the start of the first segment
        self._rho1 = 0.0  # reference slope in the first segment
        self._xm = 0.0  # state where the second (constant reference) segment starts
        self._vm = 0.0
        self._am = 0.0
        self._r2 = 0.0
        self._pieces_valid = False
        self._piece_f: list[float] = []
        self._piece_p: list[float] = []
        self._lo = self.position
        self._hi = self.position

    # -- commands ------------------------------------------------------------------------------

    def enable(self, on: bool) -> None:
        """Switch the amplifier on or off (takes effect for the next step)."""
        if on and not self.enabled:
            self._reference = self.velocity
        self.enabled = bool(on)

    def command_velocity(self, velocity: float) -> None:
        """Digital velocity command in user units/s (ideal: no offset, drift or gain error)."""
        self._analog = False
        self._command = float(velocity)

    def command_voltage(self, volts: float) -> float:
        """Analog velocity command; returns the voltage after the +-10 V clamp."""
        u = float(volts)
        # min(LIMIT, max(-LIMIT, u)) as comparisons, the same result (NaN too: -LIMIT)
        u = u if u > -ANALOG_LIMIT_VOLTS else -ANALOG_LIMIT_VOLTS
        u = u if u < ANALOG_LIMIT_VOLTS else ANALOG_LIMIT_VOLTS
        self.saturated = u != volts
        self.voltage = u
        self._analog = True
        return u

    @property
    def commanded_velocity(self) -> float:
        """Velocity the amplifier is asked for, after the analog errors and the speed clamp."""
        if self._analog:
            u = self.voltage + self.offset_volts + self.drift_volts_per_second * self._elapsed
            v = self.velocity_per_volt * self.gain_factor * u
        else:
            v = self._command
        v -= self.velocity_error
        m = self.max_velocity  # (compare, not min/max: this runs every cycle)
        return m if v > m else -m if v < -m else v

    @property
    def reference_velocity(self) -> float:
        """The ramped reference the velocity loop follows."""
        return self._reference

    def reset(self, position: float = 0.0) -> None:
        """Put the motor at rest at ``position`` (power-up state of the simulation)."""
        self.position = self._x0 = self._lo = self._hi = float(position)
        self.velocity = self.acceleration = self._reference = 0.0
        self._v0 = self._a0 = 0.0
        self._dt = 0.0
        self._pieces_valid = False

    # -- integration ---------------------------------------------------------------------------

    def _advance(
        self, x: float, v: float, a: float, r0: float, rho: float, h: float
    ) -> tuple[float, float, float]:
        """Exact state after ``h`` s of the loop following the reference ``r0 + rho*t``."""
        if self.loop == "first_order":
            tau = self.time_constant
            rho_tau = rho * tau
            e0 = v - (r0 - rho_tau)  # deviation from the ramp's steady-state response
            if h == self._memo_h and tau == self._memo_tau:
                one_minus_e = self._memo_decay  # the usual whole cycle: computed once
            else:
                one_minus_e = -math.expm1(-h / tau)
                self._memo_h, self._memo_tau, self._memo_decay = h, tau, one_minus_e
            e_h = e0 * (1.0 - one_minus_e)
            # (rho * tau and e0 * decay computed once: the same products as written out)
            return (
                x + (r0 - rho_tau) * h + 0.5 * rho * h * h + e0 * tau * one_minus_e,
                r0 + rho * h - rho_tau + e_h,
                rho - e_h / tau,
            )
        wn = self.natural_frequency
        z = self.damping
        lag = 2.0 * z * rho / wn  # steady-state velocity lag behind a ramping reference
        e0 = v - (r0 - lag)
        d0 = a - rho
        sigma = z * wn
        if abs(z - 1.0) < 1e-9:
            ec = math.exp(-sigma * h)
            es = ec * h
        elif z < 1.0:
            wd = wn * math.sqrt(1.0 - z * z)
            damp = math.exp(-sigma * h)
            ec = damp * math.cos(wd * h)
            es = damp * math.sin(wd * h) / wd
        else:
            wh = wn * math.sqrt(z * z - 1.0)
            # e^{-sigma h} cosh(wh h) written without the overflowing cosh of large arguments
            slow = math.exp((wh - sigma) * h)
            fast = math.exp(-(wh + sigma) * h)
            ec = 0.5 * (slow + fast)
            es = 0.5 * (slow - fast) / wh
        e_h = e0 * ec + (d0 + sigma * e0) * es
        d_h = d0 * ec - (wn * wn * e0 + sigma * d0) * es
        # integral of the deviation, from the loop equation itself: no quadrature needed
        int_e = -((d_h - d0) + 2.0 * sigma * (e_h - e0)) / (wn * wn)
        x_h = x + (r0 - lag) * h + 0.5 * rho * h * h + int_e
        return x_h, r0 + rho * h - lag + e_h, rho + d_h

    def _coast(self, x: float, v: float, h: float) -> tuple[float, float, float]:
        tc = self.coast_time_constant
        if tc == 0.0:
            return x, 0.0, 0.0
        one_minus_e = -math.expm1(-h / tc)
        v_h = v * (1.0 - one_minus_e)
        return x + v * tc * one_minus_e, v_h, -v_h / tc

    def step(self, dt: float) -> None:
        """Advance one cycle of ``dt`` seconds with the current command held."""
        self._dt = dt
        x, v, a = self.position, self.velocity, self.acceleration
        self._x0, self._v0, self._a0 = x, v, a
        self._pieces_valid = False
        self._coasting = not self.enabled
        if self._coasting:
            self.position, self.velocity, self.acceleration = self._coast(x, v, dt)
            self._reference = self.velocity
            self._elapsed += dt
            return
        target = self.commanded_velocity
        r = self._reference
        diff = target - r
        amax = self.max_acceleration
        if diff == 0.0 or amax == math.inf:
            h1, r1, rho1 = dt, target, 0.0
            r = target
        else:
            rho1 = amax if diff > 0.0 else -amax
            t_ramp = (diff if diff > 0.0 else -diff) / amax
            r1 = r
            if t_ramp >= dt:
                h1 = dt
                r += rho1 * dt
            else:
                h1 = t_ramp
                r = target  # snapped: the ramp ends exactly on the target
        self._h1, self._r1, self._rho1 = h1, r1, rho1
        state = self._advance(x, v, a, r1, rho1, h1)
        if h1 < dt:
            self._xm, self._vm, self._am = state
            self._r2 = target
            state = self._advance(*state, target, 0.0, dt - h1)
        self.position, self.velocity, self.acceleration = state
        self._reference = r
        self._elapsed += dt

    # -- motion inside the last cycle ----------------------------------------------------------

    def state_at(self, fraction: float) -> tuple[float, float]:
        """(position, velocity) at ``fraction`` (0..1) of the last cycle, exact."""
        t = fraction * self._dt
        if self._coasting:
            x, v, _ = self._coast(self._x0, self._v0, t)
            return x, v
        if t <= self._h1:
            x, v, _ = self._advance(self._x0, self._v0, self._a0, self._r1, self._rho1, t)
        else:
            x, v, _ = self._advance(self._xm, self._vm, self._am, self._r2, 0.0, t - self._h1)
        return x, v

    def position_at(self, fraction: float) -> float:
        """Position at ``fraction`` (0..1) of the last cycle."""
        if fraction <= 0.0:
            return self._x0
        if fraction >= 1.0:
            return self.position
        return self.state_at(fraction)[0]

    def _build_pieces(self) -> None:
        # Split the cycle into monotonic pieces: equal parts, each split again at a turning point.
        fs, ps = self._piece_f, self._piece_p
        fs.clear()
        ps.clear()
        fs.append(0.0)
        ps.append(self._x0)
        f_prev, v_prev = 0.0, self._v0
        for i in range(1, _SERVO_PIECES + 1):
            if i == _SERVO_PIECES:
                f, p, v = 1.0, self.position, self.velocity
            else:
                f = i / _SERVO_PIECES
                p, v = self.state_at(f)
            if (v_prev > 0.0 > v) or (v_prev < 0.0 < v):
                lo, hi = f_prev, f
                for _ in range(64):
                    mid = 0.5 * (lo + hi)
                    if mid <= lo or mid >= hi:
                        break
                    if (self.state_at(mid)[1] > 0.0) == (v_prev > 0.0):
                        lo = mid
                    else:
                        hi = mid
                fs.append(hi)
                ps.append(self.state_at(hi)[0])
            fs.append(f)
            ps.append(p)
            f_prev, v_prev = f, v
        self._lo, self._hi = min(ps), max(ps)
        self._pieces_valid = True

    def position_bounds(self) -> tuple[float, float]:
        """Lowest and highest position during the last cycle."""
        if self._dt == 0.0:
            return self.position, self.position
        if not self._pieces_valid:
            self._build_pieces()
        return self._lo, self._hi

    def crossings(self, x: float) -> tuple[Crossing, ...]:
        """Moments in the last cycle the position crossed ``x`` (see :mod:`.kinematics`)."""
        lo, hi = self.position_bounds()
        if x <= lo or x > hi:
            return NO_CROSSINGS
        fs, ps = self._piece_f, self._piece_p
        events: list[Crossing] = []
        for i in range(len(fs) - 1):
            pa, pb = ps[i], ps[i + 1]
            if (pa >= x) != (pb >= x):
                f = bisect_crossing(self.position_at, fs[i], fs[i + 1], pa, x)
                events.append((f, 1 if pb >= x else -1))
        return tuple(events)


class StepperDrive:
    """Stepper motor with a microstepping driver fed with step/direction pulses.

    The command is the controller's pulse counter: an absolute microstep count
    (:meth:`command_microsteps`). Each cycle the driver receives the pulses between the count it
    has reached and the commanded count, at most ``max_step_frequency`` pulses per second (the
    pulse output's limit; the remaining pulses follow in later cycles, none are lost). Pulses
    are spread evenly over the cycle, so the motor moves at constant velocity within a cycle.

    Disabled, the driver ignores its pulse input: pulses commanded meanwhile are lost, and the
    motor holds its position. The motor is modelled as ideal (it follows every pulse).

    Step loss is a later refinement: a pull-out torque curve will set ``stalled`` and let
    ``position_microsteps`` (the rotor) fall behind ``pulse_count`` (the pulses received),
    counting the difference in ``lost_microsteps``. Today both counts are always equal.
    """

    def __init__(
        self,
        *,
        steps_per_unit: float,
        microsteps: int = 64,
        max_step_frequency: float = 200_000.0,
        position_microsteps: int = 0,
        enabled: bool = False,
    ) -> None:
        if steps_per_unit <= 0.0 or microsteps < 1 or max_step_frequency <= 0.0:
            raise ValueError("steps_per_unit, microsteps and max_step_frequency must be > 0")
        self.steps_per_unit = float(steps_per_unit)
        self.microsteps = int(microsteps)
        self.max_step_frequency = float(max_step_frequency)
        """Most step pulses (microsteps) per second the pulse input accepts."""
        self.enabled = bool(enabled)
        self.pulse_count = int(position_microsteps)
        self.position_microsteps = int(position_microsteps)
        self.stalled = False
        self.lost_microsteps = 0
        self.velocity = 0.0
        self.acceleration = 0.0
        self._target = self.pulse_count
        self._lost_offset = 0  # pulses commanded while disabled, never received
        self._budget = 0.0  # pulse time left over from earlier cycles (< 1 pulse)
        self._x0 = self.position

    @property
    def microsteps_per_unit(self) -> float:
        return self.steps_per_unit * self.microsteps

    @property
    def position(self) -> float:
        """Rotor position in user units."""
        return self.position_microsteps / (self.steps_per_unit * self.microsteps)

    @property
    def position_steps(self) -> float:
        """Rotor position in full steps."""
        return self.position_microsteps / self.microsteps

    def enable(self, on: bool) -> None:
        self.enabled = bool(on)

    def command_microsteps(self, target: int) -> None:
        """Set the controller's absolute pulse count the motor shall reach."""
        self._target = int(target)

    def command_position(self, position: float) -> int:
        """Command a position in user units, rounded to the nearest microstep; returns it."""
        target = round(position * self.steps_per_unit * self.microsteps)
        self._target = target
        return target

    def step(self, dt: float) -> None:
        """Advance one cycle: emit the pending pulses, at most ``max_step_frequency * dt``."""
        self._x0 = self.position
        v_prev = self.velocity
        if not self.enabled:
            self._lost_offset = self._target - self.pulse_count
            self._budget = 0.0
            self.velocity = 0.0
            self.acceleration = (0.0 - v_prev) / dt
            return
        want = self._target - self._lost_offset - self.pulse_count
        self._budget += self.max_step_frequency * dt
        available = int(self._budget)
        # Only the fraction of a pulse period is carried: an idle output banks no pulses.
        self._budget -= available
        n = min(abs(want), available)
        if want < 0:
            n = -n
        self.pulse_count += n
        self.position_microsteps += n
        self.velocity = n / (dt * self.steps_per_unit * self.microsteps)
        self.acceleration = (self.velocity - v_prev) / dt

    def position_bounds(self) -> tuple[float, float]:
        p1 = self.position
        return (self._x0, p1) if self._x0 <= p1 else (p1, self._x0)

    def crossings(self, x: float) -> tuple[Crossing, ...]:
        """Crossings of ``x`` in the last cycle; the pulse train moves the rotor uniformly."""
        return linear_crossing(self._x0, self.position, x)
