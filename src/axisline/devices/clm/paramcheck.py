"""How the CLM's parameters fit together: the cross-parameter checks run on leaving Parameter mode.

Split from `parameters` (which reads, writes and range-checks each parameter by itself): a check
here runs only on parameters in use whose own ranges passed, so one wrong value is reported once,
where it is. The decisions these checks rest on are in `parameters`' docstring (11-13).
"""

from __future__ import annotations

from collections.abc import Callable
from decimal import Decimal
from fractions import Fraction
from typing import TYPE_CHECKING

from .errors import ClmError
from .operands import Operand
from .paramtable import MIN_MAX

if TYPE_CHECKING:
    from .parameters import ParameterSet, ParamValue

__all__ = ["interaction_errors"]

INVALID = "02"  # fault "INVALID Parameter" (L8262)
_MODE_NAMES = {0: "normal feed axis", 1: "synchronous axis", 2: "slave axis", 3: "measuring wheel V1", 4: "measuring wheel V2", 5: "flying cutoff"}
_MASTER_NAMES = {0: "none", 1: "axis 1", 2: "axis 2", 3: "axis 3", 5: "master encoder 1"}

# Ax00 per axis (L4202-4226): mode -> masters allowed (None: the mode has no master).
_AXIS_MODES: dict[int, dict[int, frozenset[int] | None]] = {
    1: {0: None, 2: frozenset({5}), 3: None, 4: None, 5: None},
    2: {0: None, 1: frozenset({1}), 2: frozenset({1, 5}), 3: None, 4: None},
    3: {0: None, 1: frozenset({1, 2}), 2: frozenset({1, 2, 5})},
    4: {0: None, 1: frozenset({1, 2, 3}), 2: frozenset({1, 2, 3, 5})},
}


def interaction_errors(params: ParameterSet, bad: set[str], axes_fitted: int) -> list[ClmError]:
    """Every cross-parameter fault of `params` (the ids in `bad` failed their own range check)."""
    return _Interactions(params, bad, axes_fitted).run()


def _unset(value: object) -> bool:
    return isinstance(value, Operand) and value.unset


# -- how parameters fit together ----------------------------------------------------------------------


class _Interactions:
    """The cross-parameter checks. A check runs only on parameters in use whose own ranges passed
    (`bad` holds the ids that failed), so one wrong value is reported once, where it is."""

    def __init__(self, params: ParameterSet, bad: set[str], axes_fitted: int) -> None:
        self.p = params
        self.bad = bad
        self.axes_fitted = axes_fitted
        self.errors: list[ClmError] = []

    def run(self) -> list[ClmError]:
        checks = (self.axis_mode, self.encoder_bits, self.encoder_data, self.travel_limit_sign, self.gear,
                  self.vmax, self.jog, self.homing_offset_iut, self.feedforward, self.homing_type)
        for axis in self.p.enabled_axes():
            for check in checks:
                check(axis)
        if self.p.flying_cutoff():
            self.flying_cutoff()
        self.hardware()
        return self.errors

    def ok(self, *pids: str) -> bool:
        return all(self.p.used(pid) and pid not in self.bad for pid in pids)

    def fail(self, pid: str, detail: str, code: str = INVALID) -> None:
        self.errors.append(ClmError(code, detail, pid))
        self.bad.add(pid)

    def n(self, pid: str, name: str) -> Decimal:
        return self.p.get(pid).number(name)

    def text(self, pid: str, name: str) -> str:
        from .parameters import _format_field  # only when a check fails; parameters imports this module

        spec = self.p.get(pid).spec
        return _format_field(pid, spec.fields[spec.index(name)], self.p.get(pid)[name])

    def axis_mode(self, axis: int) -> None:
        """Ax00: "The following operating modes are possible" per axis, with their masters (L4202-4226)."""
        pid = f"A{axis}00"
        if not self.ok(pid):
            return
        mode, master = int(self.n(pid, "mode")), int(self.n(pid, "master"))
        masters = _AXIS_MODES[axis]
        if mode not in masters:
            possible = ", ".join(f"{m} {_MODE_NAMES[m]}" for m in masters)
            self.fail(pid, f"mode = {mode} ({_MODE_NAMES[mode]}) is not possible for axis {axis}: {possible} (L4202-4226)")
            return
        allowed = masters[mode]
        if allowed is not None and master not in allowed:
            names = ", ".join(f"{m} {_MASTER_NAMES[m]}" for m in sorted(allowed))
            self.fail(pid, f"master = {master}: axis {axis} as {_MODE_NAMES[mode]} may follow {names} (L4202-4226)")

    def encoder_bits(self, axis: int) -> None:
        """Ax20: single-turn encoders have 12-21 data bits, multi-turn 21-24 (L4655-4657)."""
        pid = f"A{axis}20"
        if not self.ok(pid):
            return
        bits = int(self.n(pid, "data_bits"))
        span = {1: (12, 21, "single-turn"), 2: (21, 24, "multi-turn")}.get(self.p.encoder_type(axis))
        if span is not None and not span[0] <= bits <= span[1]:
            self.fail(pid, f"data_bits = {bits:02d}: a {span[2]} absolute encoder has {span[0]}..{span[1]} data bits (L4655-4657)")

    def encoder_data(self, axis: int) -> None:
        """Ax19 per encoder type (L4637-4659; Fig. 8-15's 100-10000 is the incremental case)."""
        pid, p20 = f"A{axis}19", f"A{axis}20"
        if not self.ok(pid):
            return
        pulses, revolutions = int(self.n(pid, "pulses")), int(self.n(pid, "revolutions"))
        kind = self.p.encoder_type(axis)
        low, high = (int(limit or 0) for limit in MIN_MAX["Ax19"][2:])
        if kind == 0 and not low <= pulses <= high:
            self.fail(pid, f"pulses = {pulses:05d}: an incremental encoder has {low:05d}..{high:05d} pulses per revolution (L4648, L5689)")
        elif kind == 2 and not 16 <= pulses <= 4096:
            self.fail(pid, f"pulses = {pulses:05d}: a multi-turn absolute encoder has 00016..04096 (L4649)")
        elif kind == 2 and self.ok(p20):
            most = 2 ** (int(self.n(p20, "data_bits")) - 12)
            if not 1 <= revolutions <= most:
                self.fail(pid, f"revolutions = {revolutions:04d}: a {self.text(p20, 'data_bits')}-bit multi-turn encoder has 0001..{most:04d} (L4638-4641)")
        elif kind == 1 and not (7 <= pulses <= 21 and 0 <= revolutions <= 14):
            self.fail(pid, f"{pulses:05d} {revolutions:04d}: a single-turn encoder takes resolution bits 00007..00021, revolution bits 0000..0014 (L4642, L4650)")
        elif kind == 1 and self.ok(p20) and pulses + revolutions > int(self.n(p20, "data_bits")):
            self.fail(pid, f"{pulses} + {revolutions} bits are more than the {self.text(p20, 'data_bits')} data bits of Ax20 (L4659)")

    def travel_limit_sign(self, axis: int) -> None:
        """Ax03: "always input as a negative value" (incremental, L4302), "positive" (absolute, L4309)."""
        pid = f"A{axis}03"
        if not self.ok(pid):
            return
        limit, kind = self.n(pid, "min_travel_limit"), self.p.encoder_type(axis)
        if kind == 0 and limit > 0:
            self.fail(pid, f"min_travel_limit = {self.text(pid, 'min_travel_limit')}: with an incremental encoder it is negative (L4302)")
        elif kind in (1, 2) and limit < 0:
            self.fail(pid, f"min_travel_limit = {self.text(pid, 'min_travel_limit')}: with an absolute encoder it is positive (L4309)")

    def gear(self, axis: int) -> None:
        """Ax02: X >= Y (L3565-3567)."""
        pid = f"A{axis}02"
        if self.ok(pid) and self.n(pid, "input_revolutions") < self.n(pid, "output_revolutions"):
            self.fail(pid, f"{self.p.data(pid)}: input revolutions X must be >= output revolutions Y (L3565-3567)")

    def feed_constant(self, axis: int) -> Fraction | None:
        """IU per encoder revolution: Ax01, or Ax01 x Y / X on an incremental rotary table (L3579-3581)."""
        p01, p02 = f"A{axis}01", f"A{axis}02"
        if not self.ok(p01):
            return None
        feed = Fraction(self.n(p01, "feed_constant"))
        if self.p.used(p02):
            if not self.ok(p02):
                return None
            feed = feed * Fraction(self.n(p02, "output_revolutions")) / Fraction(self.n(p02, "input_revolutions"))
        return feed

    def vmax(self, axis: int) -> None:
        """Ax06 <= possible Vmax = RPM (Ax12) / 60 x feed constant (L4363-4372); equal is allowed (errata §3.4)."""
        p06, p12 = f"A{axis}06", f"A{axis}12"
        feed = self.feed_constant(axis)
        if feed is None or not self.ok(p06, p12):
            return
        rpm = int(self.n(p12, "max_encoder_speed"))
        possible = rpm * feed / 60
        if Fraction(self.n(p06, "maximum_velocity")) > possible:
            geared = ", Ax01 x Y/X: L3581" if self.p.used(f"A{axis}02") else ""
            self.fail(p06, f"maximum_velocity = {self.text(p06, 'maximum_velocity')} IU/s is more than the possible Vmax = "
                           f"{rpm} RPM / 60 x {float(feed):.5f} IU = {float(possible):.3f} IU/s (L4363-4372{geared})")

    def jog(self, axis: int) -> None:
        """Ax07 <= Ax06 (L4388)."""
        p06, p07 = f"A{axis}06", f"A{axis}07"
        if self.ok(p06, p07) and self.n(p07, "jog_velocity") > self.n(p06, "maximum_velocity"):
            self.fail(p07, f"jog_velocity = {self.text(p07, 'jog_velocity')} IU/s is more than Ax06 = {self.text(p06, 'maximum_velocity')} IU/s (L4388)")

    def homing_offset_iut(self, axis: int) -> None:
        """Rotary table: Ax25 "may not exceed the value IUT" (L3552, L3593); IUT as in decision 12."""
        p01, p19, p25 = f"A{axis}01", f"A{axis}19", f"A{axis}25"
        if self.p.motion_type(axis) != 2 or not self.ok(p01, p25):
            return
        iut = Fraction(self.n(p01, "feed_constant"))
        kind = self.p.encoder_type(axis)
        if kind in (1, 2):
            if not self.ok(p19, f"A{axis}20"):
                return
            revolutions = int(self.n(p19, "revolutions"))
            iut *= 2**revolutions if kind == 1 else revolutions
        if abs(Fraction(self.n(p25, "homing_offset"))) > iut:
            self.fail(p25, f"homing_offset = {self.text(p25, 'homing_offset')} exceeds IUT = {float(iut):.3f} IU per table revolution (L3552, L3593)")

    def feedforward(self, axis: int) -> None:
        """Ax11: "Feedforward can only be turned on for Flying Cutoff or Slave Axis" (L4457, L3489)."""
        pid = f"A{axis}11"
        feedforward = int(self.n(pid, "feedforward"))
        if self.ok(pid, f"A{axis}00") and feedforward != 0 and self.p.axis_mode(axis) not in (1, 2, 5):
            self.fail(pid, f"feedforward = {feedforward}: only a slave, synchronous or flying cutoff axis has feedforward (L4457, L3489)")

    def homing_type(self, axis: int) -> None:
        """Ax24: Options 2 and 3 not for flying cutoff, Option 5 only for it (L4739-4741)."""
        pid = f"A{axis}24"
        if not self.ok(pid, f"A{axis}00"):
            return
        kind, cutoff = int(self.n(pid, "homing_type")), axis == 1 and self.p.flying_cutoff()
        if cutoff and kind in (1, 2):
            self.fail(pid, f"homing_type = {kind} (Option {kind + 1}) is not permitted for flying cutoff (L4739)")
        elif not cutoff and kind == 4:
            self.fail(pid, "homing_type = 4 (Option 5, passive homing) is permitted only for flying cutoff (L4741)")

    def flying_cutoff(self) -> None:
        """Axis 1 in flying cutoff: what must be off (L3933-3941) and the offset's sign (L4754)."""
        for pid, is_off, what, line in _CUTOFF_OFF:
            if pid not in self.bad and not is_off(self.p.get(pid)):
                self.fail(pid, f"{self.p.get(pid)} in flying cutoff: {what} ({line})")
        if "A125" not in self.bad and self.n("A125", "homing_offset") > 0:
            self.fail("A125", f"homing_offset = {self.text('A125', 'homing_offset')}: flying cutoff takes only a negative offset (L4754)")

    def hardware(self) -> None:
        """Error 17: axis 3 or 4 enabled without the 4-axis expansion (L8461); decision 13."""
        extra = [a for a in self.p.enabled_axes() if a > self.axes_fitted]
        if extra:
            self.fail("B000", f"axis {', '.join(map(str, extra))} enabled, the CLM has {self.axes_fitted} axes (L8461)", code="17")


def _off(*names: str) -> Callable[[ParamValue], bool]:
    """All named fields off: operands 00.00.0, numbers 0."""
    return lambda value: all(_unset(value[n]) if isinstance(value[n], Operand) else value.number(n) == 0 for n in names)


# Flying cutoff (L3933-3941): parameter, "off", what must be off, manual line.
_CUTOFF_OFF: tuple[tuple[str, Callable[[ParamValue], bool], str, str], ...] = (
    ("A109", _off("acceleration", "deceleration"), "acceleration and deceleration may not be reduced: 000 000", "L3933"),
    ("A110", _off("jerk_constant"), "jerk limiting must be off: 0.000", "L3935"),
    ("A115", _off("feed_angle_input", "interrupt_input"), "feed angle monitoring and interrupt must be off", "L3936"),
    ("A130", _off("open_feed_roll_input"), "open feed roll must be off: input 00.00.0", "L3937"),
    ("A132", _off("velocity_reached_output", "deceleration_active_output"), "deceleration active / velocity reached must be off", "L3938"),
    ("B015", _off("interrupt_input"), "the interrupt vector must be off: input 00.00.0", "L3939"),
    ("B016", _off("restart_instruction"), "the restart vector must be off: 0000", "L3940"),
    ("B017", _off("override_axis_1"), "the override of axis 1 must be off", "L3941"),
)
