"""Scaling, number ranges and units of the 750-672 (manual §3.10.1, §3.10.6, §4.1; wago.md §6).

Internal units of the module:
* position: microsteps ("steps"), 64 per full step, 24-bit two's complement
  -8388608 .. +8388607 (§3.10.6.1.2);
* velocity: the process-image value v (1 .. 25000, signed for speed control) gives the
  pulse frequency f_p = v * 80 / Freq_Prescaler [Hz = microsteps/s] from the 2 MHz base clock
  (§3.10.1.1), so f_max = 2 MHz / Freq_Prescaler;
* acceleration: a = Acceleration * Acc_Multiplier / Freq_Prescaler [Hz/s = microsteps/s^2]
  (§3.10.1.2), Acceleration 1 .. 32767;
* time: TICK = 1 ms.

User units (§3.10.6.2): positions, speeds and accelerations of the process image and the
move commands are multiplied by *_Mult and divided by *_Div before internal processing:
internal = external * Mult / Div. A result outside the internal range is error 1511/1513/1515
(user -> internal) or 1512/1514/1516 (internal -> user); a divisor 0 is 1517.

Rounding (wago.md §6.2 [AMBIGUOUS]): integer arithmetic, truncation toward zero, exact
intermediates (Python integers), so a position converted there and back does not drift.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from axisline.devices.wago672.errors import WagoError

__all__ = [
    "MICROSTEPS_PER_FULL_STEP",
    "BASE_CLOCK_HZ",
    "VELOCITY_MAX",
    "ACCELERATION_MAX",
    "POSITION_MIN",
    "POSITION_MAX",
    "freq_prescaler",
    "acc_multiplier",
    "f_max",
    "pulse_frequency",
    "velocity_from_frequency",
    "acceleration",
    "time_to_f_max",
    "to_internal",
    "to_user",
    "rotor_angle",
    "mechanical_speed",
    "mechanical_speed_direct",
    "rpm",
    "mechanical_acceleration",
    "full_steps",
    "step_angle",
    "rotary_speed_limit",
    "Scaling",
]

MICROSTEPS_PER_FULL_STEP = 64
MICROSTEPS_PER_ELECTRICAL_PERIOD = 4 * MICROSTEPS_PER_FULL_STEP  # the 256 of f_m = f_p / (256 p)
BASE_CLOCK_HZ = 2_000_000
VELOCITY_MAX = 25000
ACCELERATION_MAX = 32767
POSITION_MIN, POSITION_MAX = -8388608, 8388607

_FREQ_SEL = {1: 80, 2: 20, 3: 4}  # Freq_Range_Sel '01', '10', '11'
_ACC_SEL = {1: 80, 2: 800, 3: 8000}  # Acc_Range_Sel '01', '10', '11'


def freq_prescaler(freq_range_sel: int, freq_div: int) -> int:
    """Freq_Prescaler from Freq_Range_Sel (C2.1, C2.0; C2.0 is the LSB) and Freq_Div (§3.10.1.1).

    '00' -> Freq_Div (200 when Freq_Div = 0); '01' -> 80; '10' -> 20; '11' -> 4.
    """
    if freq_range_sel not in (0, 1, 2, 3):
        raise ValueError(f"Freq_Range_Sel must be 0 .. 3, got {freq_range_sel!r}")
    if freq_range_sel:
        return _FREQ_SEL[freq_range_sel]
    if freq_div == 0:
        return 200
    if not 4 <= freq_div <= 65535:
        raise WagoError(1216, f"Freq_Div = {freq_div} is outside 4 .. 65535 (or 0)")
    return freq_div


def acc_multiplier(acc_range_sel: int, acc_fact: int) -> int:
    """Acc_Multiplier from Acc_Range_Sel (C2.3, C2.2) and Acc_Fact (§3.10.1.2): '00' -> Acc_Fact
    (8 when Acc_Fact = 0); '01' -> 80; '10' -> 800; '11' -> 8000."""
    if acc_range_sel not in (0, 1, 2, 3):
        raise ValueError(f"Acc_Range_Sel must be 0 .. 3, got {acc_range_sel!r}")
    if acc_range_sel:
        return _ACC_SEL[acc_range_sel]
    return 8 if acc_fact == 0 else acc_fact


def f_max(prescaler: int) -> float:
    """Highest pulse frequency [Hz] = 2 MHz / Freq_Prescaler (v = 25000: 25000 * 80 = 2 000 000)."""
    return BASE_CLOCK_HZ / prescaler


def pulse_frequency(v: float, prescaler: int, speed_mult: int = 1, speed_div: int = 1) -> float:
    """f_p = (Speed_Mult / Speed_Div) * 80 * v / Freq_Prescaler [microsteps/s] (§3.10.6.1.4.1)."""
    return speed_mult * 80.0 * v / (speed_div * prescaler)


def velocity_from_frequency(f_p: float, prescaler: int, speed_mult: int = 1, speed_div: int = 1) -> float:
    """The inverse of `pulse_frequency`: process-image velocity for a pulse frequency."""
    return f_p * prescaler * speed_div / (80.0 * speed_mult)


def acceleration(value: float, prescaler: int, multiplier: int, acc_mult: int = 1, acc_div: int = 1) -> float:
    """a = (Acc_Mult / Acc_Div) * Acceleration * Acc_Multiplier / Freq_Prescaler [microsteps/s^2] (§3.10.6.1.5)."""
    return acc_mult * value * multiplier / (acc_div * prescaler)


def time_to_f_max(multiplier: int, value: int = ACCELERATION_MAX) -> float:
    """Seconds from 0 to f_max at Acceleration `value`: 25000*80 / (value * Acc_Multiplier),
    independent of the prescaler (wago.md §6.1; 7.6 s / 760 ms / 76 ms / 7.6 ms)."""
    return VELOCITY_MAX * 80.0 / (value * multiplier)


def _scale(value: int, mult: int, div: int) -> int:
    """value * mult / div, truncated toward zero, exact."""
    q = abs(value) * mult // div
    return q if value >= 0 else -q


def to_internal(value: int, mult: int, div: int) -> int:
    """External (user) -> internal: value * Mult / Div, truncated toward zero."""
    if mult == 0 or div == 0:
        raise WagoError(1517, f"scaling factor is zero (Mult = {mult}, Div = {div})")
    return _scale(int(value), mult, div)


def to_user(value: int, mult: int, div: int) -> int:
    """Internal -> external (user): value * Div / Mult, truncated toward zero."""
    if mult == 0 or div == 0:
        raise WagoError(1517, f"scaling factor is zero (Mult = {mult}, Div = {div})")
    return _scale(int(value), div, mult)


def rotor_angle(s: float, full_steps_per_rev: int = 200) -> float:
    """phi [deg] = 360 * s / (64 * N) for the set-point position s (§3.10.6.1.2)."""
    return 360.0 * s / (MICROSTEPS_PER_FULL_STEP * full_steps_per_rev)


def mechanical_speed(f_p: float, pole_pairs: int = 50) -> float:
    """f_m [rev/s] = (1/p) * f_p / 256 (§3.10.1.1)."""
    return f_p / (pole_pairs * MICROSTEPS_PER_ELECTRICAL_PERIOD)


def mechanical_speed_direct(v: float, freq_div: int, pole_pairs: int = 50, speed_mult: int = 1, speed_div: int = 1) -> float:
    """f_m = (1/p) * (Speed_Mult/Speed_Div) * v / (3.2 * Freq_Div) (§4.1.2.4; §3.10.6.1.4.2
    prints 3,3 - 3.2 = 256/80 is the constant that agrees with the pulse-frequency formula)."""
    return speed_mult * v / (pole_pairs * speed_div * 3.2 * freq_div)


def rpm(f_m: float) -> float:
    """n_m = 60 * f_m [1/min]."""
    return 60.0 * f_m


def mechanical_acceleration(a: float, pole_pairs: int = 50) -> float:
    """a_m [rev/s^2] = (1/p) * a / 256 (§3.10.1.1)."""
    return a / (pole_pairs * MICROSTEPS_PER_ELECTRICAL_PERIOD)


def full_steps(step_angle_deg: float) -> float:
    """N = 360 deg / alpha (§4.1.1.1)."""
    return 360.0 / step_angle_deg


def step_angle(pole_pairs: int) -> float:
    """alpha = 180 deg / (p * s) with s = 2 lines: 90 deg / p (§4.1.1.1)."""
    return 90.0 / pole_pairs


def rotary_speed_limit(period: int, freq_div: int, speed_mult: int = 1, speed_div: int = 1) -> float:
    """Highest set-point speed of a rotary axis: (Speed_Div/Speed_Mult) * (Freq_Div/80) * 10^3 * p
    (§3.11.1.8): the axis may not pass more than one period per 1 ms TICK."""
    return speed_div / speed_mult * freq_div / 80.0 * 1000.0 * period


@dataclass(frozen=True, slots=True)
class Scaling:
    """The conversions in force: prescaler and multiplier latched from C2 while Enable = 0,
    scaling factors from the configuration table. Methods raise WagoError with the
    device's codes 1511..1516 naming the value and the range."""

    prescaler: int = 40
    multiplier: int = 1000
    pos_mult: int = 1
    pos_div: int = 1
    speed_mult: int = 1
    speed_div: int = 1
    acc_mult: int = 1
    acc_div: int = 1

    # ---- positions
    def steps(self, position: int, what: str = "position") -> int:
        """User position -> microsteps (24 bit, else 1511 UNITS_POS_INT_RESULT)."""
        s = to_internal(position, self.pos_mult, self.pos_div)
        if not POSITION_MIN <= s <= POSITION_MAX:
            raise WagoError(1511, f"{what} {position} * {self.pos_mult} / {self.pos_div} = {s} microsteps is outside {POSITION_MIN} .. {POSITION_MAX}")
        return s

    def distance(self, position: int) -> int:
        """User distance -> microsteps without the 24-bit check (relative moves may add up)."""
        return to_internal(position, self.pos_mult, self.pos_div)

    def position(self, steps: int) -> int:
        """Microsteps -> user position (24 bit, else 1512 UNITS_POS_USER_RESULT)."""
        u = to_user(steps, self.pos_mult, self.pos_div)
        if not POSITION_MIN <= u <= POSITION_MAX:
            raise WagoError(1512, f"position {steps} microsteps = {u} user units is outside {POSITION_MIN} .. {POSITION_MAX}")
        return u

    def position_float(self, steps: float) -> float:
        return steps * self.pos_div / self.pos_mult

    # ---- velocities
    def frequency(self, v: int, what: str = "Velocity") -> float:
        """User velocity -> pulse frequency [microsteps/s] (internal |v| <= 25000, else 1513)."""
        internal = to_internal(v, self.speed_mult, self.speed_div)
        if abs(internal) > VELOCITY_MAX:
            raise WagoError(1513, f"{what} {v} * {self.speed_mult} / {self.speed_div} = {internal} is outside -{VELOCITY_MAX} .. {VELOCITY_MAX}")
        return pulse_frequency(internal, self.prescaler)

    def velocity(self, f_p: float) -> int:
        """Pulse frequency -> user velocity, rounded to the nearest (1514 outside 16 bit)."""
        internal = velocity_from_frequency(f_p, self.prescaler)
        u = internal * self.speed_div / self.speed_mult
        r = int(math.copysign(math.floor(abs(u) + 0.5), u))
        if not -32768 <= r <= 32767:
            raise WagoError(1514, f"velocity {f_p:g} Hz = {r} user units is outside -32768 .. 32767")
        return r

    def velocity_float(self, f_p: float) -> float:
        return velocity_from_frequency(f_p, self.prescaler) * self.speed_div / self.speed_mult

    # ---- accelerations
    def accel(self, value: int, what: str = "Acceleration") -> float:
        """User acceleration -> microsteps/s^2 (internal 1 .. 32767, else 1515)."""
        internal = to_internal(value, self.acc_mult, self.acc_div)
        if not 1 <= internal <= ACCELERATION_MAX:
            raise WagoError(1515, f"{what} {value} * {self.acc_mult} / {self.acc_div} = {internal} is outside 1 .. {ACCELERATION_MAX}")
        return acceleration(internal, self.prescaler, self.multiplier)

    def accel_user(self, a: float) -> int:
        """microsteps/s^2 -> user acceleration (1516 outside 16 bit)."""
        internal = a * self.prescaler / self.multiplier
        u = internal * self.acc_div / self.acc_mult
        r = int(math.copysign(math.floor(abs(u) + 0.5), u))
        if not -32768 <= r <= 32767:
            raise WagoError(1516, f"acceleration {a:g} Hz/s = {r} user units is outside -32768 .. 32767")
        return r

    @property
    def f_max(self) -> float:
        return f_max(self.prescaler)
