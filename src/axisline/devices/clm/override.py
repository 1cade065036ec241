"""CLM1.4 velocity functions: the B017 / VEO velocity override, VCC and AEO (manual §7.3
L3251-3360, VCC L2808-2859, VEO L2861-2944, AEO L1442-1468, B017 L5216-5247; spec §3.6, §4.3).

    vf = VelocityFunctions(rt)        # one per runtime (rt.velocity); installs ClmAxis.override
    vf.tick()                         # once per NC cycle, after the inputs are in the image
    vf.set_veo(axis, source=4, value=700, limit=True)       # VEO 1 4 1 700 1
    wait = vf.vcc_start(axis, 50_000, 250, 0)               # VCC 1 +000050.000 250 0 0
    vf.vcc_poll(axis, wait)           # True: the velocity changed, the task goes on

The override acts on the positioning speed through the one hook in `axis.ClmAxis`
(``override``: programmed IU/s -> commanded IU/s, and ``change_speed``: replan the running
positioning with the kernel's on-the-fly ABORTING move_absolute). Whenever the override's
value changes (an input, the analog voltage, a VEO), the running positioning is replanned at
once: the override is "infinitely variable" (L3253).

Sources (B017 digit per axis, or VEO's source):
* analog input AE1..AE4: F = volts / 10, 0 V..10 V -> 0..1 (Fig. 7-1, 7-2, L3266-3280);
* binary I1.01.0 (2^0) .. I1.01.7 (2^7): F = sum / 255 (Fig. 7-4, L3346-3360);
* Gray I1.01.4 (2^0) .. I1.01.7 (2^3): the 16-step table of L3297-3316 (`GRAY_PERCENT`).

Decisions (spec line -> choice, why)
------------------------------------
1. Errata §3.2 "Gray override is a 16-step non-linear table" (L3297-3316) -> the 4 inputs
   read as g (I1.01.4 = 2^0) are the reflected Gray code of the switch step n (g = n ^ (n >> 1),
   every printed row is exactly that), the velocity is GRAY_PERCENT[n] % of the programmed one;
   test_gray_table_is_the_manual_table, test_gray_example_on_the_plant (L3320-3342: 250 mm/s x
   2 % = 5 mm/s).
2. Binary (L3356 "Sum of all Decimal Values / 255") -> F = byte I1.01 / 255, 255 = 100 %;
   test_binary_and_analog_factors, test_binary_override_on_the_plant.
3. Analog (L3277 "F = 0 - 1 corresponds to 0V - 10V") -> F = volts / 10 clipped to 0..1 (a
   negative voltage is 0); the volts come from the personality's ``analog_inputs`` (AE1..AE4 on
   an `AnalogIO`); the volts are B017's averaged 12-bit reading the personality passes each cycle (analog.py decisions 1, 2);
   test_analog_override_on_the_plant.
4. Errata §3.2 "VEO limit (of Vmax) is not the same as VEO factor (of the programmed velocity)"
   (L2869-2872) -> factor: v = programmed x vvv / 1000; limit: v = min(programmed, vvv / 1000 x
   Ax06); the B017 sources always act as a factor ("V_o = V_p x F"), with VEO f = 1 as a limit
   F x Ax06; test_veo_example_programs_a_b_c (Figs. 5-34..5-36: A 999 limit unchanged, B 70 %
   cap, C half).
5. L2872 "VEO has priority over B017" -> an active VEO replaces the B017 source of its axis
   (they are not multiplied); VEO s = 0 cancels the VEO (B017 applies again), like the change
   of mode "between Automatic and Manual" (L2876); the cancel is done on any change of mode
   (errata §3.8 "VEO off on mode change"); test_veo_priority_and_cancel.
6. VEO's source digit s (spec §12.3 #1: modes 1-3 not described) -> 1 = the analog input
   with the axis' number, 2 = binary, 3 = Gray, 4 = the command's value vvv, 5 = master
   encoder 1 (L2880); the third digit x (undescribed, 1 and 0 in the examples) is read and not
   used; test_veo_sources_1_to_3.
7. Override 0 (0 V, Gray 0000, binary 0) -> the positioning is replanned to a crawl of
   1e-6 x Ax06 (the kernel refuses a 0 velocity; 0.5 um/s on a 500 mm/s axis is standstill for
   every practical purpose) and goes on when the override rises; test_zero_override_stands_still.
8. Errata open point "VCC switching on actual or command position" -> on the actual position
   (encoder): mode 0 counts the distance "traversed" (L2818) by the drive from the actual
   position where the last positioning was started; mode 1 (L2838 "depends on the
   acceleration, the difference in velocity and the position lag") starts the ramp (from the
   set point, at most one NC cycle early) so that the set point reaches the new velocity at P:
   the drive follows the same velocity-over-position curve one lag time later, so the actual
   position is at P then too; seen from the actual position the ramp starts "position lag"
   earlier, as L2838 says; test_vcc_mode0_example, test_vcc_mode1_example.
9. VCC's last two digits (spec §3.6 [AMBIGUOUS], both equal in every example) -> the first of
   them is the mode, the second is read and not used. Mode 0 with |P| >= the length of the last
   positioning is skipped (L2822); no positioning in progress -> proceed; vvv = 000 is the
   crawl of decision 7; the override applies to the VCC velocity as to any programmed one
   (L2865 "all of the programmed traversing commands"); test_vcc_mode0_skipped_beyond_the_move.
10. VCC mode 1 needs a reference (L2844 "must be homed") -> fault 48 without one; a negative
    switching point on a rotary table (motion type 2) -> 1E (B018 list); test_vcc_errors.
11. Master encoder 1 (VEO mode 5 L2880-2893, AEO L1448-1466) -> both need the axis in Ax00 mode
    0 and master encoder 1 set up (master_encoder.py decision 6: wired on the plant with
    ``device.master_encoder_1``, C000 and C002 in range); otherwise the command proceeds at
    once (L2880, L1450); test_veo5_and_aeo_without_master.
12. VEO 5 (Fig. 5-33) -> override = |V011| / Ax06 x multiplier, taken every cycle (the
    running positioning is replanned when it changes); the multiplier is 1 (FOL edits it, but
    FOL has no function on a normal axis, slave.py decision 3); use digit 0 = factor of the
    programmed velocity, 1 = limit override x Ax06, as the other sources (decision 4). L2889
    vs L2891: the overridden velocity is capped at Ax06, and while a positioning runs an
    uncapped programmed x factor above 1.25 x Ax06 is fault 4D (x = axis, "Max. Override");
    test_veo5_scales_the_feed_with_the_line, test_veo5_above_125_percent_is_4d.
13. AEO a x y sss mmm (commands decision C-LOST) -> while on, every cycle a = Ax09 x V011^2 /
    Ax06^2 x sss / 1000 (Fig. 5-5), not below mmm per mille of Ax09, "Parameter Ax09" being
    Ax09's acceleration in IU/s^2; it serves both ramps of every positioning started after it
    (a running one keeps its ramps: "as for the ACC command ... completed", L1454, axis
    decision 7); AEO x = 0 or a change of mode ends it (like ACC's reset to Ax09, L1413);
    test_aeo_acceleration_follows_the_line.
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from typing import TYPE_CHECKING, Any

from .errors import ClmError, axis_fault
from .operands import Operand

if TYPE_CHECKING:
    from .runtime import ClmRuntime

__all__ = [
    "GRAY_PERCENT", "VelocityFunctions", "Veo", "aeo_acceleration", "analog_factor", "binary_factor",
    "gray_factor", "gray_step", "veo_master_override",
]

#: velocity in % of the programmed one for the step switch's positions 0..15 (L3297-3316)
GRAY_PERCENT = (0, 1, 2, 4, 6, 8, 10, 20, 30, 40, 50, 60, 70, 80, 90, 100)
#: B017 override digit: 1-4 analog input 1-4, 5 binary, 6 Gray (L5239-5245)
B017_BINARY, B017_GRAY = 5, 6
OVERRIDE_BYTE = Operand("I", 1, 1)  # I1.01: binary I1.01.0-7, Gray I1.01.4-7
CRAWL = 1e-6  # decision 7: the speed of "0 %", of Ax06
MAX_OVERRIDE = Fraction(5, 4)  # L2889: error 4D beyond 1.25 Vmax


def gray_step(code: int) -> int:
    """The switch step n whose reflected Gray code n ^ (n >> 1) is `code` (0..15)."""
    n = 0
    while code:
        n ^= code
        code >>= 1
    return n


def gray_factor(code: int) -> Fraction:
    """I1.01.4..7 as a 4-bit value (I1.01.4 = 2^0) -> the override factor (decision 1)."""
    return Fraction(GRAY_PERCENT[gray_step(code & 0x0F)], 100)


def binary_factor(byte: int) -> Fraction:
    """I1.01.0..7 -> sum / 255 (decision 2)."""
    return Fraction(byte & 0xFF, 255)


def analog_factor(volts: float) -> float:
    """0 V..10 V -> 0..1, clipped (decision 3)."""
    return min(1.0, max(0.0, volts / 10.0))


def veo_master_override(master_velocity: float, vmax: float, multiplier: float = 1.0) -> float:
    """VEO mode 5 (Fig. 5-33, L2884): master encoder velocity / Ax06 x multiplier."""
    return master_velocity / vmax * multiplier


def aeo_acceleration(ax09: float, master_velocity: float, vmax: float, scale_per_mille: int, minimum: float) -> float:
    """AEO (Fig. 5-5, L1458-1466): Ax09 x v_me^2 / Ax06^2 x scale / 1000, not below the minimum."""
    return max(minimum, ax09 * master_velocity**2 / vmax**2 * scale_per_mille / 1000)


@dataclass
class Veo:
    """A VEO in force on one axis: its source (1-5), value (per mille) and use (limit or factor)."""

    source: int
    value: int
    limit: bool


@dataclass
class VccWait:
    mode: int
    position: Fraction  # P, IU
    speed: float  # the new programmed speed, IU/s


class _AxisOverride:
    """The override of one axis: (factor, limit) now, applied to a programmed speed."""

    def __init__(self, vmax: float) -> None:
        self.vmax = vmax
        self.factor: float | None = None
        self.limit: float | None = None

    def apply(self, speed: float) -> float:
        v = speed
        if self.factor is not None:
            v *= self.factor
        if self.limit is not None:
            v = min(v, self.limit)
        return max(v, CRAWL * self.vmax) if (self.factor is not None or self.limit is not None) else v


class VelocityFunctions:
    """The velocity functions of one CLM runtime (see the module docstring)."""

    def __init__(self, rt: ClmRuntime) -> None:
        self.rt = rt
        self.analog_volts = [0.0, 0.0, 0.0, 0.0]  # AE1..AE4, set by the personality each cycle
        self.veo: dict[int, Veo] = {}
        self.starts: dict[int, float] = {}  # actual position where the last positioning started
        self._mode: str | None = None
        self._state: dict[int, _AxisOverride] = {}
        self._b017: dict[int, int] = {}  # B017's override source per axis (taken at a mode change)
        self._b017_any = False  # any of them not 0 (asked every cycle)
        self.aeo_on: dict[int, tuple[int, int]] = {}  # axis -> (scale, minimum per mille), AEO on
        self._idle = False  # no source in use and every factor reset: nothing to do per cycle
        self.needs_analog = False
        for n, axis in rt.axes.items():
            if hasattr(axis, "change_speed"):  # a ClmAxis (the runtime tests' fake axes have no hook)
                ov = _AxisOverride(self._vmax(n))
                self._state[n] = ov
                axis.override = ov.apply

    def _vmax(self, n: int) -> float:
        return float(self.rt.memory.parameters.get(f"A{n}06").number("maximum_velocity"))

    # -- the cycle ------------------------------------------------------------------------

    def tick(self) -> None:
        """Cancel VEO on a change of mode; take the override values; replan on a change."""
        mode = self.rt.modes.mode
        if mode != self._mode:
            if self._mode is not None:
                self.veo.clear()  # decision 5
                for n in self.aeo_on:  # decision 13
                    self.rt.axes[n].aeo_acceleration = None
                self.aeo_on.clear()
            self._mode = mode
            b017 = self.rt.memory.parameters.get("B017")
            for n, ov in self._state.items():
                ov.vmax = self._vmax(n)  # Parameter mode may have changed Ax06 and B017
                self._b017[n] = int(b017[f"override_axis_{n}"])
            self._b017_any = any(self._b017.values())
            self._update_needs_analog()
        if not self._state:
            return
        if self.aeo_on:
            self._aeo_tick()
        if not self.veo and not self._b017_any:
            if self._idle:  # the common case: no override at all costs nothing per cycle
                return
            self._idle = True  # one pass more: the factors go back to none
        else:
            self._idle = False
        for n, ov in self._state.items():
            factor, limit = self._override(n, self._b017[n], ov.vmax)
            if factor != ov.factor or limit != ov.limit:
                ov.factor, ov.limit = factor, limit
                self.rt.axes[n].change_speed()
            veo = self.veo.get(n)
            if veo is not None and veo.source == 5 and factor is not None:
                axis = self.rt.axes[n]
                if axis.target is not None and not axis.motion_done and axis.speed * factor > MAX_OVERRIDE * ov.vmax:
                    raise ClmError(axis_fault(0x0D, n), f"VEO 5: axis {n} at {axis.speed * factor:.1f} IU/s > 1.25 x Ax06 (L2889)")

    def _master_velocity(self) -> float:
        me = self.rt.master_encoder
        return 0.0 if me is None else abs(me.velocity)

    def _aeo_tick(self) -> None:
        v = self._master_velocity()
        for n, (scale, minimum) in self.aeo_on.items():
            axis = self.rt.axes[n]
            a09 = axis.ax09_acceleration
            axis.aeo_acceleration = aeo_acceleration(a09, v, self._vmax(n), scale, a09 * minimum / 1000)

    def _override(self, n: int, b017: int, vmax: float) -> tuple[float | None, float | None]:
        veo = self.veo.get(n)
        if veo is None:
            f = self._source_factor(n, b017)
            return (None if f is None else float(f)), None
        if veo.source == 4:
            f = Fraction(veo.value, 1000)
        elif veo.source == 5:  # decision 12: capped at Ax06
            m = veo_master_override(self._master_velocity(), vmax)
            return (None, min(m, 1.0) * vmax) if veo.limit else (m, vmax)
        else:
            f = self._source_factor(n, {1: n, 2: B017_BINARY, 3: B017_GRAY}[veo.source])
            assert f is not None
        return (None, float(f) * vmax) if veo.limit else (float(f), None)

    def _source_factor(self, n: int, source: int) -> Fraction | float | None:
        if source == 0:
            return None
        if source <= 4:
            return analog_factor(self.analog_volts[source - 1])
        byte = self.rt.image.get(OVERRIDE_BYTE)
        return binary_factor(byte) if source == B017_BINARY else gray_factor(byte >> 4)

    def _update_needs_analog(self) -> None:
        """Whether an override reads AE1..AE4 (B017 sources 1-4, VEO source 1): the personality
        samples the analog inputs only then."""
        self.needs_analog = any(1 <= s <= 4 for s in self._b017.values()) or any(v.source == 1 for v in self.veo.values())

    # -- commands -------------------------------------------------------------------------

    def set_veo(self, axis: Any, source: int, value: int, limit: bool) -> None:
        """VEO a s x vvv f (decisions 4-6, 11): in force at once, a running positioning is replanned."""
        n = axis.number
        params = self.rt.memory.parameters
        if source == 0:
            self.veo.pop(n, None)
        elif source == 5:
            if not self.master_ready(n):
                return  # L2880 "Otherwise, the program proceeds to the following instruction"
            self.veo[n] = Veo(source, value, limit)
        else:
            self.veo[n] = Veo(source, value, limit)
        self._update_needs_analog()
        ov = self._state.get(n)
        if ov is not None:
            factor, lim = self._override(n, int(params.get("B017")[f"override_axis_{n}"]), ov.vmax)
            if (factor, lim) != (ov.factor, ov.limit):
                ov.factor, ov.limit = factor, lim
                axis.change_speed()

    def master_ready(self, n: int) -> bool:
        """Axis `n` a normal axis and master encoder 1 set up (decision 11)."""
        me = self.rt.master_encoder
        return me is not None and self.rt.memory.parameters.axis_mode(n) == 0 and me.set_up

    def aeo(self, axis: Any, on: bool, scale: int = 1000, minimum: int = 0) -> None:
        """AEO (decisions 11, 13): without master encoder 1 set up it does nothing (L1448-1450)."""
        n = axis.number
        if not on:
            if self.aeo_on.pop(n, None) is not None:
                axis.aeo_acceleration = None
            return
        if not self.master_ready(n):
            return
        self.aeo_on[n] = (scale, minimum)
        self._aeo_tick()

    def positioned(self, axis: Any) -> None:
        """A POA/POI/PSA/PSI starts now: VCC mode 0 measures from here (decision 8)."""
        self.starts[axis.number] = axis.actual_position

    def vcc_start(self, axis: Any, position: int, per_mille: int, mode: int) -> VccWait | None:
        """VCC a P vvv m x: the wait, or None to go on at once (decisions 8-10)."""
        n = axis.number
        p = Fraction(position, 1000)
        params = self.rt.memory.parameters
        if mode == 1:
            if not axis.homed:
                raise ClmError(axis_fault(0x08, n), f"VCC mode 1 on axis {n} needs a reference (L2844)")
            if params.motion_type(n) == 2 and p < 0:
                raise ClmError("1E", f"VCC on rotary table axis {n} with a negative switching point {float(p):.3f}")
        speed = max(self._vmax(n) * per_mille / 1000, CRAWL * self._vmax(n))
        return VccWait(mode, p, speed)

    def vcc_poll(self, axis: Any, wait: VccWait) -> bool:
        """True when the velocity has been changed (or the VCC is skipped): the task goes on."""
        target = axis.target
        if target is None or axis.motion_done:
            return True  # no positioning in progress
        if wait.mode == 0:
            start = self.starts.get(axis.number)
            if start is None:
                return True
            length = target - start
            if abs(wait.position) >= abs(length):
                return True  # L2822: not executed
            traversed = (axis.actual_position - start) * (1 if length >= 0 else -1)
            if traversed < abs(wait.position):
                return False
            axis.change_speed(wait.speed)
            return True
        x = axis.command_position
        sign = 1.0 if target >= x else -1.0
        v1 = abs(axis.axis.command_velocity)
        v2 = axis.override(wait.speed) if axis.override is not None else wait.speed
        ramp = axis.deceleration if v2 < v1 else axis.acceleration
        d = abs(v1 * v1 - v2 * v2) / (2 * ramp)
        remaining = sign * (float(wait.position) - x)  # decision 8: the set point reaches v2 at P
        if remaining > d + v1 * self.rt.nc_cycle_s:
            return False
        axis.change_speed(wait.speed)
        return True
