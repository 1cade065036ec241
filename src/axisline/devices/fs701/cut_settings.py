"""The FS701 cutter's settings (`CutterSettings`, from the parameters) with the values derived
from them, and the geometry of a cut cycle they give: the approach, the return, the S-ramp
limits (cutter.py describes the cycle and its decisions).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields
from typing import Any

from mypy_extensions import mypyc_attr

from axisline.motion.profiles import Limits, Profile, State, plan, plan_velocity

from .cut_states import _BIG, _S_JERK_FRACTION, _V_EPS, S_RAMP_PEAK_FACTOR

__all__ = ["CutterSettings", "approach_geometry", "return_profile", "s_ramp_limits", "v_return_max"]

# manual names that differ between the parameter table (§11, canonical here) and the text
_ALIASES: dict[str, tuple[str, ...]] = {
    "virtual_line_speed": ("virt_line_speed",),
    "return_speed": ("rel_return_speed",),
    "freeze_mode": ("sync_mode", "synchron_mode"),
    "zero_speed_vir_ma": ("zero_speed_vir_master",),
    "master_rev_limit": ("mast_rev_limit",),
    "printm_per_length": ("printmarks_per_length", "printm_per_leng"),
    "missing_printmarks": ("missing_printm",),
    "set_length_cou_ps": ("set_length_cou_pulses", "setlengthcou_ps"),
    "set_length_cou_lu": ("setlengthcou_lu",),
    "photocell_cut": ("photocell_to_cut",),
    "p_gain": ("pgain",),
    "ana_out_gain_2": ("ana_out_2_gain",),
    "ana_out_offset_2": ("ana_out_2_offset",),
}


@mypyc_attr(native_class=False)  # (compiled: a plain Python class, see CutterSettings)
class _DerivedSettings:
    """The values CutterSettings derives from its fields (`_derive`): declared here, in a base
    that is not a dataclass, so that they are instance attributes and not fields."""

    version: int  # counts the writes
    line_counts_per_lu: float
    cut_counts_per_lu: float
    ratio_error: bool
    v_max_line: float
    sync_ratio: float
    s_ramps: bool
    line_speed_lag: float


# a plain Python class also when this module is compiled: _derive writes its __dict__
@mypyc_attr(native_class=False)
@dataclass
class CutterSettings(_DerivedSettings):
    """The parameters the cut cycle and the position loop use.

    Field names are the snake_case of the manual's parameter names (§11 table name where table
    and text differ; `from_parameters` also accepts the text names), units and defaults are the
    manual's (table defaults; where the table rows 0x0111-0x0115 are visibly shifted, the text
    and the screenshot: Deceleration 1 = 1000, Printm. per Length = 1, spec §3.4).
    """

    # General parameters (§4.2)
    cutting_length: int = 1000  # LU
    test_cut_length: int = 1000  # LU
    virtual_line_speed: int = 10000  # LU/min
    # Basic settings (§4.3.1)
    pulses_line_1000: int = 1000  # increments per 1000 LU (line)
    pulses_cut_1000: int = 1000  # increments per 1000 LU (carriage)
    acceleration_1: int = 1000  # LU/s^2 forward
    acceleration_2: int = 1000  # LU/s^2 reverse
    ramp_form: int = 0  # C1: 0 S-ramp, else linear
    sync_rate: float = 0.0  # % (+/- 9.99)
    return_speed: float = 1.00  # Rel. Return Speed, x line speed
    edge_sense: int = 0  # 0 rising, 1 falling edge of Cut completed
    synchron_time: int = 1  # ms
    cut_window: int = 50  # carriage increments (C5)
    sync_samples: int = 1  # cycles
    tool_width: int = 0  # LU
    cutting_mode: int = 1  # 1 length, 2 print mark, 3 print mark + additional cuts
    photocell_cut: int = 1000  # LU, "Photocell -> Cut"
    gap_length: int = 0  # LU
    gap_time: int = 10  # ms
    ramp_vir_master: int = 1  # s, 0 -> max line speed
    set_length_cou_ps: int = 0  # increments
    set_length_cou_lu: int = 0  # LU
    printmark_edge: int = 0  # 0 rising, 1 falling
    virt_printmarks: int = 0  # 0/1
    deceleration_1: int = 1000  # LU/s^2 forward
    deceleration_2: int = 1000  # LU/s^2 reverse
    printmark_offset: int = 0  # LU, + moves the cut forward (leading the mark)
    photocell_delay: float = 0.0  # ms (0.1 ms resolution)
    printm_per_length: int = 1
    printmark_window: int = 0  # LU, 0 = disabled
    missing_printmarks: int = 0  # sheets, 0 = disabled
    abs_return_speed: int = 0  # LU/min, 0 -> Rel. Return Speed
    freeze_mode: int = 0  # "Sync Mode" in the text (loop.py L6)
    # Control loop (§4.3.2)
    p_gain: int = 1000
    i_time: float = 0.0  # s
    max_correction: int = 9999  # mV (loop.py L3)
    max_line_speed: int = 100000  # LU/min
    sampling_time: int = 1  # ms
    # Jog / Home / Ref (§4.3.3)
    home_window: int = 100  # LU
    minimum_position: int = -999999  # LU
    maximum_position: int = 999999  # LU
    alarm_position: int = 999999  # LU
    jog_speed_forw: int = 10  # % of Max. Line Speed
    jog_ramp_up_forw: int = 1  # s for 0 -> Max. Line Speed
    jog_ramp_dw_forw: int = 1
    jog_speed_rev: int = 10
    jog_ramp_up_rev: int = 1
    jog_ramp_dw_rev: int = 1
    # Monitoring (§4.3.4)
    zero_speed_master: int = 0  # LU/min
    zero_speed_vir_ma: int = 0  # LU/min
    length_per_pulse: int = 1000  # LU
    master_rev_limit: int = 0  # LU, 0 = off
    batch_counter: int = 0
    waste_counter: int = 0
    # Additional cuts (§4.3.5)
    additional_cuts: int = 0
    add_cut_1_length: int = 0
    add_cut_2_length: int = 0
    add_cut_3_length: int = 0
    # Set-up (§4.3.7)
    mode_counter_1: int = 0  # 0 x1, 1 x2, 2 x4 (line)
    dir_counter_1: int = 1
    mode_counter_2: int = 0  # carriage
    dir_counter_2: int = 1
    ana_out_offset_2: int = 0  # -2047..2047 = -100..100 % of full scale
    ana_out_gain_2: float = 10.00  # V full scale (the register shows 1000 = 10.00 V)
    dir_frequency: int = 1  # virtual master direction 1 forward
    # axisline, not an FS701 register ([device] acceleration_feed_forward, loop.py L10)
    acc_feed_forward: float = 0.0  # ms of velocity lead: 0 = the FS701's loop

    # ------------------------------------------------------------------ construction

    @classmethod
    def from_parameters(cls, source: Any, **overrides: Any) -> "CutterSettings":
        """Fill from a parameter set by name: a mapping, or an object with attributes.

        Every field is looked up under its name and its aliases (manual text names); missing
        ones keep the default. A `.value` attribute on a looked-up object is used (parameter
        objects). Ana-Out Gain values above 320 are read as the raw register (1000 = 10.00 V).
        """
        values: dict[str, Any] = {}
        mapping = isinstance(source, dict)
        for f in fields(cls):
            for name in (f.name, *_ALIASES.get(f.name, ())):
                v = source.get(name) if mapping else getattr(source, name, None)
                if v is not None:
                    v = getattr(v, "value", v)
                    values[f.name] = v
                    break
        values.update(overrides)
        gain = values.get("ana_out_gain_2")
        if gain is not None and float(gain) > 320.0:
            values["ana_out_gain_2"] = float(gain) / 100.0
        return cls(**values)

    # ------------------------------------------------------------------ derived values

    def __post_init__(self) -> None:
        object.__setattr__(self, "version", 0)
        self._derive()

    def __setattr__(self, name: str, value: Any) -> None:
        object.__setattr__(self, name, value)
        if "version" in self.__dict__:  # (not during __init__: __post_init__ derives once)
            self._derive()

    def _derive(self) -> None:
        """The values the cut cycle reads every cycle, computed when a setting is written (rare)
        instead of on every read; `version` counts the writes (a cheap "changed?" test for
        values cached elsewhere, e.g. the position loop's gains)."""
        d = self.__dict__
        # scaling (C20) -- kL, kC: line / carriage encoder increments (after x1/x2/x4) per LU
        d["line_counts_per_lu"] = self.pulses_line_1000 / 1000.0
        d["cut_counts_per_lu"] = self.pulses_cut_1000 / 1000.0
        # Error 05: Pulses Line/1000 : Pulses Cut/1000 beyond 16:1 or 1:16 (16 itself allowed)
        pl, pc = self.pulses_line_1000, self.pulses_cut_1000
        d["ratio_error"] = True if pl <= 0 or pc <= 0 else (pl > 16 * pc or pc > 16 * pl)
        # Max. Line Speed in LU/s (100 % of the feed-forward, jog and virtual-master scaling)
        d["v_max_line"] = self.max_line_speed / 60.0
        # R = 1 + Sync Rate/100: carriage speed / line speed while synchronous
        d["sync_ratio"] = 1.0 + self.sync_rate / 100.0
        d["s_ramps"] = self.ramp_form == 0
        # s the measured line speed is late (Sampling Time / 2): made up with the acceleration
        # feed-forward, which it would otherwise lack (loop.py L10); 0 without it, as the FS701
        d["line_speed_lag"] = self.sampling_time / 2000.0 if self.acc_feed_forward > 0.0 else 0.0
        d["version"] += 1

    @staticmethod
    def _multiplier(mode: int) -> int:
        return {0: 1, 1: 2, 2: 4}[int(mode)]

    @property
    def line_multiplier(self) -> int:
        return self._multiplier(self.mode_counter_1)

    @property
    def cut_multiplier(self) -> int:
        return self._multiplier(self.mode_counter_2)

    @property
    def line_lines_per_lu(self) -> float:
        """Encoder lines per LU of the line encoder (for a plant IncrementalEncoder)."""
        return self.line_counts_per_lu / self.line_multiplier

    @property
    def cut_lines_per_lu(self) -> float:
        return self.cut_counts_per_lu / self.cut_multiplier

    def lu_to_line_counts(self, lu: float) -> float:
        return lu * self.line_counts_per_lu

    def line_counts_to_lu(self, counts: float) -> float:
        return counts / self.line_counts_per_lu

    def lu_to_cut_counts(self, lu: float) -> float:
        return lu * self.cut_counts_per_lu

    def cut_counts_to_lu(self, counts: float) -> float:
        return counts / self.cut_counts_per_lu

    def virtual_speed_effective(self) -> float:
        """Virt. Line Speed after the limit to Max. Line Speed and the 1/2048 quantisation (C18), LU/min."""
        mls = self.max_line_speed
        v = min(max(self.virtual_line_speed, 0), mls)
        return math.floor(v * 2048 / mls) * mls / 2048.0

    def jog(self, forward: bool, period: float) -> tuple[float, float, float]:
        """(speed LU/s, acceleration, deceleration LU/s^2) of a jog (C14, E22)."""
        vm = self.v_max_line
        if forward:
            pct, up, dw = self.jog_speed_forw, self.jog_ramp_up_forw, self.jog_ramp_dw_forw
        else:
            pct, up, dw = self.jog_speed_rev, self.jog_ramp_up_rev, self.jog_ramp_dw_rev
        v = vm * pct / 100.0
        a = vm / up if up > 0 else vm / period
        d = vm / dw if dw > 0 else vm / period
        return v, a, d


def s_ramp_limits(s_ramp: bool, acceleration: float, dv: float) -> tuple[str, Limits]:
    """Shape and limits of an FS701 ramp of `dv` at an `acceleration` setting (C1).

    Linear: constant acceleration. S-ramp: trapezoidal acceleration with jerk phases of 20 %
    of the ramp time: the peak is 1.25 x the setting and the ramp lasts dv / setting, as long as
    the linear ramp."""
    a = float(acceleration)
    if not s_ramp or dv <= 0.0:
        return "trapezoid", Limits(v=_BIG, a=a, d=a)
    peak = S_RAMP_PEAK_FACTOR * a
    t_ramp = dv / a
    j = peak / (_S_JERK_FRACTION * t_ramp)
    return "jerk", Limits(v=_BIG, a=peak, d=peak, j=j)


# ---------------------------------------------------------------------- cycle geometry
# (functions of the settings, shared by the cutter and the envelope calculator)


def approach_geometry(s: CutterSettings, V: float) -> tuple[Profile | None, float, float, float]:
    """(profile in tau, tau_a, s_sync, master travel during the ramp) for line speed V (LU/s)."""
    R = s.sync_ratio
    vs = R * V
    if vs <= _V_EPS:
        return None, 0.0, 0.0, 0.0
    shape, lim = s_ramp_limits(s.s_ramps, s.acceleration_1, vs)
    prof = plan_velocity(shape, State(0.0, 0.0, 0.0), vs, lim)
    tau_a = prof.duration
    s_sync = prof.sample(tau_a)[0]  # carriage travel at the end of the ramp
    return prof, tau_a, s_sync, V * tau_a


def v_return_max(s: CutterSettings, line_speed: float) -> float:
    """Peak return speed (LU/s): Abs. Return Speed, else Rel. Return Speed x line speed, at
    least the reverse jog speed (C4/C19)."""
    if s.abs_return_speed > 0:
        return s.abs_return_speed / 60.0
    v_floor = s.v_max_line * s.jog_speed_rev / 100.0  # C4/C19
    return max(s.return_speed * abs(line_speed), v_floor)


def return_profile(s: CutterSettings, start: State, home: float, v_r: float) -> Profile | None:
    """The return from `start` to `home` at speed `v_r` with Acc./Dec. 2 (None: already home)."""
    if abs(start.p - home) < 1e-12 and start.v == 0.0 and start.a == 0.0:
        return None
    a2, d2 = float(s.acceleration_2), float(s.deceleration_2)
    if s.s_ramps:
        j = S_RAMP_PEAK_FACTOR * max(a2, d2) / (_S_JERK_FRACTION * v_r / max(a2, d2))
        return plan("jerk", start, State(home, 0.0), Limits(v=v_r, a=1.25 * a2, d=1.25 * d2, j=j))
    return plan("trapezoid", start, State(home, 0.0), Limits(v=v_r, a=a2, d=d2))
