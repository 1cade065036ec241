"""COMPAX XX70 master reference chain: from the master encoder (or internal time base) to the
master position in the curve (compax.md §1.3 pipeline, §2.5, §2.10, §2.15, §2.16).

    chain = MasterChain(params, encoder=enc)          # params: P30 P31 P35 P39 P98 P143 P179
    chain.select_curve(360.0)                          # SETC: scaled master cycle M_T*, P31 rules
    chain.setm(35.0)                                   # SETM 35: position := 35 % of M_T*
    wraps = chain.update(cycle, i16)                   # once per 1 ms cycle (the device's tick)
    chain.fraction, chain.cycle_position, chain.velocity, chain.s44, ...

Pipeline, per 1 ms sample (the order of the manual's block structure, §7):

    source (P30 units digit): 0 = encoder channel 1 (P144 = 4: 4x quadrature, 4·P143
             increments per encoder revolution), 1 = internal time base (100 virtual encoder
             revolutions per minute, ramped over P39 after enabling)
      -> enable gate (I16 per P31, "If no curve has been selected since Power on, I16 is not
             taken into account")
      -> x P35 (master factor; a new value is taken at once, or at the end of the master cycle
             while synchronous when the tens digit of P30 is 1; then ramped at 1/P179 per ms)
      -> + injected label correction (master related label synchronisation, P33 = 1)
      -> master position modulo the scaled master cycle M_T* = M_T·4·P143/P98 [increments]

Exactness: the master position is kept as an integer number of increments plus a float
fraction in [0, 1), and M_T* the same way. With P35 = 1 and an integer M_T* (the manual's
first drift-free condition, §2.20) every quantity stays an integer and the chain never
drifts, however long it runs; with a fractional P35 or M_T* only the fraction carries
rounding, which does not accumulate in the integer part.

Status values (§2.19): S41 master rotation speed [1/min], S42 master position [increments],
S44 master position [per mille of M_T], S46 sign of the master speed.

Decisions (spec points that concern this file; the manual wins over the spec):

* MC1 S41 "master rotation speed" (§2.19, §2.15 [DERIVED]/[GAP] "units of the internal
  time-base rotation speed"): the manual's own formula "Master rotation speed = 100 min⁻¹ ·
  P35 · P98 / M_T" only agrees with its note ("the master cycle is travelled 100 times in 1
  minute", "with M_T = 100·P98 the cycle rate per minute can be set directly in P35") when
  the rotation is one master cycle ("Each cycle corresponds to one cam rotation", §3). S41
  is therefore master cycles per minute for both sources; with the default P98 = M_T it is
  also the encoder speed. The internal time base runs at 100·P35 virtual encoder revolutions
  per minute (400·P35·P143 increments/min). Tests: test_internal_time_base_cycle_rates
  (§7 X16), test_s41_is_master_cycles_per_minute.
* MC2 P31 = 0 / 9 enabling (§2.10): "After Power On I16 must be 0 so as to be able to
  perceive the ascending edge" -> P31 = 0 enables on a rising edge of I16 and disables on
  I16 = 0 (static); I16 already 1 at the first SETC does not enable. At the enabling edge the
  counter is preset to the SETM value (P31 = 9 was made "where I16 is only used for the
  statical enabling ... and not for resetting the counter channel", §6), and counting starts
  at the increment latched at the edge (interrupt input: "exactly counted without any time
  lag"); P31 = 9 starts "in the next sampling cycle" without a latch or a preset.
  Tests: test_p31_0_*, test_p31_9_*.
* MC3 Preset (§2.10 [DERIVED], §14.6.1 "Once I16=1 is recognised, S44 also begins to operate
  from the value in S50"): SETM x sets the master position at once and is kept as the preset
  for every later enabling (off -> on) in P31 = 0 ... 5 until the next SETC; without a SETM
  since the SETC the position is not preset ("Without the command SETM x the curve would
  start according to the actual master position"). Test: test_setm_preset_at_each_enabling.
* MC4 P31 = 2 (§2.10): a rising edge after SETC enables and latches; counting goes on while
  I16 = 1 or once an edge has been seen since the last SETC; SETC with I16 = 0 disables, SETC
  with I16 = 1 lets counting run until I16 falls ("With I16="1", the master position
  measurement continues to operate!"). With the internal time base P31 = 2 works as 0 (§2.10).
  Test: test_p31_2_*.
* MC5 P31 = 3 / 5 "for one master cycle" (§2.10): counting from the enabling edge up to the
  end of the master cycle (the next wrap; increments beyond it are dropped, the position
  stays at 0). P31 = 3 goes on for another cycle when I16 is still 1 at that moment
  ("automatic triggering"); every new rising edge starts another cycle without a SETC (the
  application: "a product which is placed on a belt at different distances"); SETC disables.
  P31 = 4 enables at an edge after SETC and disables only at the next SETC. The parameter
  table's variant wording of 3/4 ([CONFLICT]) is not used (the spec: use §19.1).
  Tests: test_p31_3_*, test_p31_4_*, test_p31_5_*.
* MC6 P31 = 1 with the internal time base (no zero pulse exists): works as P31 = 0.
* MC7 Value range (§2.5, §4 formula 3 "M_T·4·P143/P98 ≤ 4 000 000"): a curve whose scaled
  master cycle exceeds 4 000 000 increments (or is not > 0) is refused at SETC with
  CompaxError code E_VALUE (103; the supplement numbers no error for it).
  Test: test_value_range_rule.
* MC8 P179 ramp (§2.16 [CONFLICT] "2^23 ms ≈ 5.8 h"): the definition "P179 displays how many
  ms it takes for P35 to alter by 1.0" is used (slope 1/P179 per ms; P179 ≤ 1: a step).
  Test: test_p179_ramp (§7 X18).
* MC9 S42 (§2.19 "increments will be reset when there is an overflow ... value range
  ±8 000 000"): the counted (scaled) increments, restarting from 0 when they pass ±8 000 000
  (remainder kept, sign of the count). Test: test_s42_overflow.
* MC11 V_ext in "P35_new = P35_old · V_ext / P98" (§2.15 [GAP]: "Units of V_ext not given"): the
  external master speed (before P35) in master units per 1/100 minute, the unit in which the
  time base's rate 100 min⁻¹ · P98 makes the formula an identity of speeds. Test:
  test_jump_free_switch_to_the_internal_time_base.
* MC10 A new master cycle at SETC keeps the counted increments and reduces them into the new
  scaled cycle; SETC also clears the SETM preset (MC3).
"""

from __future__ import annotations

import math
from fractions import Fraction
from typing import Any

from axisline.devices.compax import CompaxError

__all__ = [
    "DEFAULTS",
    "jump_free_p35",
    "MAX_SCALED_CYCLE",
    "S42_RANGE",
    "MasterChain",
    "param",
    "scaled_master_cycle",
    "valid_values",
]

#: §2.5: "M_T · 4 · P143 / P98 ≤ 4 000 000".
MAX_SCALED_CYCLE = 4_000_000
#: §2.19 S42 "value range ±8 000 000".
S42_RANGE = 8_000_000

E_VALUE = 103  # axisline's "value does not fit" (devices/compax/__init__.py)

#: Values used when the parameter object does not hold a number (the manual's defaults, §3).
DEFAULTS: dict[int, float] = {
    11: 4_000_000,  # positive software limit (off)
    12: -4_000_000,  # negative software limit (off)
    30: 0,
    31: 0,
    32: 0.0,
    33: 0,
    34: 0,
    35: 1.0,
    36: 1.0,
    37: 0,
    38: 0,
    39: 0,
    79: 1.0,
    93: 3,
    98: 360.0,
    143: 4096,
    144: 4,
    179: 0,
    180: 0,
    210: 0,
    233: 0,
    234: 0,
}


def param(params: Any, number: int) -> Any:
    """The valid value of parameter ``number`` (``params[number]``), or the manual's default."""
    try:
        value = params[number]
    except (KeyError, IndexError, LookupError):
        return DEFAULTS.get(number, 0)
    if value is None:
        return DEFAULTS.get(number, 0)
    return value


class _WithDefaults:
    """``table[n]``: the valid value of a parameter object without a plain table of valid values
    (a mapping holding only some numbers), or the manual's default (`param`)."""

    __slots__ = ("_params",)

    def __init__(self, params: Any) -> None:
        self._params = params

    def __getitem__(self, number: int) -> Any:
        return param(self._params, number)


def valid_values(params: Any) -> Any:
    """What the 1 ms cycle reads the valid parameter values from: ``table[n]``.

    A `parameters.Parameters` keeps them as a plain dict (``valid_values``, every number present,
    each value checked when it was written), read without a check per read; any other parameter
    object is read through `param` (its ``params[n]``, or the default)."""
    table = getattr(params, "valid_values", None)
    if isinstance(table, dict):
        return table
    return _WithDefaults(params)


def jump_free_p35(p35_old: float, v_ext: float, p98: float) -> float:
    """P35 for a jump-free switch from the encoder channel to the internal time base (§2.15):
    "P35_new = P35_old · V_ext / P98" with V_ext the external master speed in master units per
    1/100 minute (decision MC11): the time base runs 100·P35·P98 master units per minute."""
    return p35_old * v_ext / p98


def scaled_master_cycle(master_cycle: float, p143: float, p98: float) -> Fraction:
    """M_T* = M_T · 4 · P143 / P98, exactly (the decimal values as written)."""
    mt = Fraction(str(master_cycle)) if isinstance(master_cycle, float) else Fraction(master_cycle)
    lines = Fraction(str(p143)) if isinstance(p143, float) else Fraction(p143)
    dist = Fraction(str(p98)) if isinstance(p98, float) else Fraction(p98)
    if dist <= 0:
        raise CompaxError(f"P98 = {p98!r} not allowed: the master distance per encoder revolution must be > 0",
                          code=E_VALUE, field="P98", value=p98, allowed="> 0")
    return mt * 4 * lines / dist


class MasterChain:
    """The COMPAX master channel; see the module docstring.

    ``encoder``: any object with an integer ``counts`` (4x evaluated increments), optionally
    ``delta(new, old)`` for a counter that wraps (plant.encoder.IncrementalEncoder). Not
    needed with the internal time base (P30 = 1).
    """

    def __init__(self, params: Any, encoder: Any = None, period: float = 0.001) -> None:
        if not (isinstance(period, (int, float)) and math.isfinite(period) and period > 0):
            raise ValueError(f"period must be a number of seconds > 0, got {period!r}")
        self.params = params
        self._pv = valid_values(params)  # the valid values, read every cycle
        self.encoder = encoder
        self.period = float(period)
        self._ms_per_cycle = self.period * 1000.0
        # scaled master cycle M_T* = _mt_i + _mt_f increments, M_T in master units
        self.master_cycle = 360.0
        self._mt_i = 16384
        self._mt_f = 0.0
        self._mt = 16384.0
        self.scaled_cycle = 16384.0  # M_T* in increments (read-only outside; = _mt)
        # position in the cycle: _pi + _pf increments, 0 <= _pi + _pf < M_T*
        self._pi = 0
        self._pf = 0.0
        self._count_i = 0  # counted increments (S42), unbounded here
        self._count_f = 0.0
        # P31 gate
        self.curve_selected = False
        self.counting = False
        self._latched = False  # P31 = 2: a rising edge since the last SETC
        self._one_cycle = False  # P31 = 3 / 5: counting until the end of this master cycle
        self._zero_armed = False  # P31 = 1: waiting for the encoder zero pulse
        self._i16 = False
        self._preset: float | None = None  # SETM preset, fraction of the cycle
        # source
        self._raw: int | None = None
        self._delta_of: Any = None  # the encoder whose `delta` is in _delta_fn
        self._delta_fn: Any = None
        self._tb_start: int | None = None  # cycle at which the time base was enabled
        self._tb_pos = 0.0
        # P35
        self.p35 = float(param(params, 35))  # effective (ramped) factor
        self._p35_target = self.p35
        self._p35_pending: float | None = None  # triggered transfer waiting for the cycle end
        self._p35_from = self.p35  # value at the start of the running ramp
        self._p35_n = 0  # cycles since the start of the running ramp
        self._inject = 0.0
        # per-cycle results
        self.delta: int | float = 0.0  # scaled increments counted this cycle (incl. injected correction)
        self.velocity = 0.0  # scaled increments / s
        self.acceleration = 0.0
        self.wraps = 0
        self._sign = 0
        self.encoder_frequency = 0.0  # increments per ms before P35 (S13/S14 code 37)
        self.synchronous = False  # set by the cam operation: O16 (for the triggered P35)
        self._cycle: int | None = None

    # ------------------------------------------------------------------ configuration

    @property
    def internal(self) -> bool:
        """P30 units digit 1: internal time base."""
        return int(self._pv[30]) % 10 == 1

    def _checked(self, master_cycle: float) -> Fraction:
        """M_T* of a master cycle, or the SETC error of the value-range rule (decision MC7)."""
        p98 = self._pv[98]
        p143 = self._pv[143]
        mt = scaled_master_cycle(master_cycle, p143, p98)
        if not 0 < mt <= MAX_SCALED_CYCLE:
            raise CompaxError(
                f"scaled master cycle M_T* = M_T·4·P143/P98 = {float(mt):.6g} increments (M_T = {master_cycle!r}, "
                f"P143 = {p143!r}, P98 = {p98!r}) not allowed: it must be > 0 and <= 4 000 000 (§4.5.3)",
                code=E_VALUE, field="M_T", value=master_cycle, allowed="0 < M_T·4·P143/P98 <= 4000000",
            )
        return mt

    def _set_cycle(self, master_cycle: float) -> None:
        mt = self._checked(master_cycle)
        whole = math.floor(mt)
        self.master_cycle = float(master_cycle)
        self._mt_i = int(whole)
        self._mt_f = float(mt - whole)
        self._mt = float(mt)
        self.scaled_cycle = self._mt
        self._reduce()

    def check_cycle(self, master_cycle: float) -> None:
        """Raise the SETC error for a master cycle outside the value range (no change)."""
        self._checked(master_cycle)

    def select_curve(self, master_cycle: float, *, linking: bool = False) -> None:
        """SETC: the new curve's master cycle; the P31 rules of a curve selection (§2.10).

        ``linking``: a curve selected during cam operation for curve linking (§2.14): the
        master counting is not disabled ("the master signals can only be disabled with
        SETC n, when n linked curves have been processed").
        """
        self.check_cycle(master_cycle)
        if linking:
            return  # the cycle changes at the transfer (set_cycle)
        self._set_cycle(master_cycle)
        self.curve_selected = True
        self._preset = None
        mode = self._mode()
        if mode in (2, 3, 4, 5):
            self._latched = False
            if mode == 2 and self.counting and self._i16:
                pass  # "With I16="1", the master position measurement continues to operate!"
            else:
                self.counting = False
                self._one_cycle = False

    def set_cycle(self, master_cycle: float) -> None:
        """A linked curve takes over: its master cycle applies from now (position kept)."""
        self._set_cycle(master_cycle)

    def setm(self, percent: float) -> None:
        """SETM x: master position := x/100 · M_T*; kept as the preset for the next enabling."""
        x = float(percent)
        if not (math.isfinite(x) and 0.0 <= x <= 100.0):
            raise CompaxError(f"SETM {percent!r} not allowed: 0.000 ... 100.000 %", code=E_VALUE,
                              field="SETM", value=percent, allowed="0 ... 100")
        self._preset = x / 100.0
        self._set_fraction(self._preset)

    def _set_fraction(self, fraction: float) -> None:
        if fraction >= 1.0:
            fraction = 0.0  # 100 % of the cycle is the start of the next one
        if self._mt_f == 0.0 and fraction * self._mt_i == int(fraction * self._mt_i):
            self._pi, self._pf = int(fraction * self._mt_i), 0.0
        else:
            pos = fraction * self._mt
            whole = math.floor(pos)
            self._pi, self._pf = int(whole), pos - whole
        self._reduce()

    def block(self) -> None:
        """Counting off until the next enabling by I16 (E25 software limit, §2.4)."""
        self.counting = False
        self._latched = False
        self._one_cycle = False
        self._zero_armed = False
        self._tb_start = None

    def inject(self, increments: float) -> None:
        """Label correction pulses into the master position integrator (added at the next update)."""
        self._inject += increments

    # ------------------------------------------------------------------ read-outs

    @property
    def cycle_position(self) -> float:
        """Master position in the cycle, increments (0 <= p < M_T*)."""
        return self._pi + self._pf

    @property
    def fraction(self) -> float:
        """Master position as a fraction of the master cycle, 0 <= u < 1."""
        u = (self._pi + self._pf) / self._mt
        return u if u < 1.0 else math.nextafter(1.0, 0.0)

    @property
    def position(self) -> float:
        """Master position in the cycle, master units (0 ... M_T)."""
        return self.fraction * self.master_cycle

    @property
    def increments(self) -> tuple[int, float]:
        """(integer, fraction) of the position in the cycle, exact."""
        return self._pi, self._pf

    @property
    def s41(self) -> float:
        """Master rotation speed: master cycles per minute (decision MC1)."""
        return self.velocity * 60.0 / self._mt

    @property
    def s42(self) -> float:
        """Counted master increments, restarting at ±8 000 000 (decision MC9)."""
        return math.fmod(self._count_i + self._count_f, S42_RANGE)

    @property
    def s44(self) -> float:
        """Master position in per mille of the master cycle."""
        return 1000.0 * (self._pi + self._pf) / self._mt

    @property
    def s46(self) -> int:
        """Sign of the master speed: 0 positive (or standing), 1 negative."""
        return self._sign

    # ------------------------------------------------------------------ per cycle

    def _mode(self) -> int:
        pv = self._pv
        mode = int(pv[31])
        if mode in (1, 2) and int(pv[30]) % 10 == 1:
            return 0  # §2.10 "P31="2" is handled ... with internal time base ... like P31="0"" (MC6 for 1)
        return mode

    def _p35_target_now(self, target: float) -> None:
        """A new effective target for P35: ramp to it at 1/P179 per ms from the value reached."""
        self._p35_target = target
        self._p35_from = self.p35
        self._p35_n = 0
        if float(self._pv[179]) <= 1.0:
            self.p35 = target  # "at 0 (or 1): for a jump-like adjustment of P35"

    def _p35_update(self) -> None:
        target = float(self._pv[35])
        if target == self._p35_target and self.p35 == target:
            self._p35_pending = None  # no new value and no ramp running: nothing to do
            return
        if target != self._p35_target:
            if int(self._pv[30]) // 10 == 1 and self.synchronous:
                self._p35_pending = target  # §2.16: taken at the end of the master cycle
            else:
                self._p35_pending = None
                self._p35_target_now(target)  # "Otherwise P35 is always transferred immediately."
        else:
            self._p35_pending = None
        diff = self._p35_target - self._p35_from
        if self.p35 != self._p35_target:
            # closed form from the start of the ramp: the slope is exact and the end is the target
            self._p35_n += 1
            step = self._p35_n * self._ms_per_cycle / float(self._pv[179])
            self.p35 = self._p35_target if step >= abs(diff) else self._p35_from + math.copysign(step, diff)

    def _source_delta(self, cycle: int, enabled_now: bool, latch: int | None) -> int | float:
        """Master increments of this cycle before P35 (only while counting)."""
        if int(self._pv[30]) % 10 == 1:  # the internal time base
            if not self.counting:
                self._tb_start = None
                self._tb_pos = 0.0
                return 0.0
            if self._tb_start is None or enabled_now:
                self._tb_start = cycle  # the P39 ramp starts at the enabling (§2.15)
                self._tb_pos = 0.0
            t = (cycle - self._tb_start) * self.period
            rate = 100.0 * 4.0 * float(self._pv[143]) / 60.0  # increments / s before P35
            ramp = float(self._pv[39]) / 1000.0
            if ramp > 0.0 and t < ramp:
                pos = 0.5 * rate * t * t / ramp
            else:
                pos = rate * (t - 0.5 * ramp) if ramp > 0.0 else rate * t
            d = pos - self._tb_pos
            self._tb_pos = pos
            return d
        enc = self.encoder
        if enc is None:
            return 0
        raw = int(enc.counts)
        prev = self._raw
        self._raw = raw
        if prev is None or not self.counting:
            return 0
        if enabled_now:
            prev = latch if latch is not None else raw
        if enc is not self._delta_of:  # the encoder's wrap-aware difference, looked up once per encoder
            self._delta_of = enc
            delta_fn = getattr(enc, "delta", None)
            self._delta_fn = delta_fn if callable(delta_fn) else None
        delta_fn = self._delta_fn
        return delta_fn(raw, prev) if delta_fn is not None else raw - prev

    def update(
        self,
        cycle: int,
        i16: bool,
        *,
        i16_latch: int | None = None,
        zero_pulse: int | None = None,
    ) -> int:
        """One 1 ms sample: gate, P35, integrate, wrap. Returns the number of master-cycle wraps
        (+ forward, - backward) of this cycle.

        ``i16_latch``: encoder count latched at the rising edge of I16 in this cycle (the
        interrupt input), None: the edge counts at the sample. ``zero_pulse``: encoder count
        latched at an encoder zero pulse passed in this cycle (P31 = 1).
        """
        if cycle == self._cycle:
            return self.wraps
        self._cycle = cycle
        i16 = bool(i16)
        rising = i16 and not self._i16
        self._i16 = i16
        was_counting = self.counting
        latch = None
        if self.curve_selected:
            mode = self._mode()
            if mode in (0, 9):
                if rising:
                    self.counting = True
                    latch = i16_latch if mode == 0 else None
                if not i16:
                    self.counting = False
            elif mode == 1:
                if rising:
                    self._zero_armed = True
                if not i16:
                    self._zero_armed = False
                    self.counting = False
                elif self._zero_armed and not self.counting and zero_pulse is not None:
                    self.counting = True
                    self._zero_armed = False
                    latch = zero_pulse
            elif mode == 2:
                if rising:
                    self.counting = True
                    self._latched = True
                    latch = i16_latch
                elif not i16 and not self._latched:
                    self.counting = False
            elif mode in (3, 5):
                if rising and not self.counting:
                    self.counting = True
                    self._one_cycle = True
                    latch = i16_latch
            elif mode == 4:
                if rising and not self.counting:
                    self.counting = True
                    latch = i16_latch
        enabled_now = self.counting and not was_counting
        if enabled_now and self._preset is not None and int(self._pv[31]) != 9:
            self._set_fraction(self._preset)  # MC3: preset at the enabling
        d_src = self._source_delta(cycle, enabled_now, latch)
        self.encoder_frequency = d_src / self._ms_per_cycle
        self._p35_update()
        p35 = self.p35
        d: int | float  # whole increments stay an int (exact, drift-free)
        if p35 == 1.0:
            d = d_src
        elif p35 == int(p35) and isinstance(d_src, int):
            d = d_src * int(p35)
        else:
            d = d_src * p35
        d_total: int | float = d + self._inject if self._inject else d
        self._inject = 0.0
        if type(d_total) is int:  # whole increments (the encoder at P35 = 1): `_advance` inline
            self._pi += d_total
            self._count_i += d_total
        else:
            self._advance(d_total)
        v = d_total / self.period
        self.acceleration = (v - self.velocity) / self.period
        self.velocity = v
        self.delta = d_total
        if v > 0.0:
            self._sign = 0
        elif v < 0.0:
            self._sign = 1
        pi = self._pi
        if 0 <= pi < self._mt_i or (pi == self._mt_i and self._pf < self._mt_f):
            wraps = 0  # still inside the cycle (`_reduce`'s first test, inline)
        else:
            wraps = self._reduce()
        if wraps > 0:
            if self._one_cycle:
                if int(self._pv[31]) == 3 and i16:
                    pass  # "If I16 is still "1" at the end of the master cycle, automatic triggering occurs."
                else:
                    self.counting = False
                    self._one_cycle = False
                    self._pi, self._pf = 0, 0.0  # the cycle ends here: the increments beyond are not counted
            if self._p35_pending is not None:
                self._p35_target_now(self._p35_pending)  # triggered transfer at the cycle end (§2.16)
                self._p35_pending = None
        self.wraps = wraps
        return wraps

    # ------------------------------------------------------------------ integer arithmetic

    def _advance(self, d: int | float) -> None:
        if type(d) is int:
            self._pi += d
            self._count_i += d
            return
        t = self._pf + d
        w = math.floor(t)
        self._pi += int(w)
        self._pf = t - w
        if self._pf >= 1.0:
            self._pf -= 1.0
            self._pi += 1
        t = self._count_f + d
        w = math.floor(t)
        self._count_i += int(w)
        self._count_f = t - w

    def _reduce(self) -> int:
        """Bring the position into [0, M_T*); returns the wraps (+ forward, - backward)."""
        mi, mf = self._mt_i, self._mt_f
        pi, pf = self._pi, self._pf
        if 0 <= pi and (pi < mi or (pi == mi and pf < mf)):
            return 0
        if mf == 0.0:
            n, pi = divmod(pi, mi)
        else:
            n = math.floor((pi + pf) / self._mt)
            pi -= n * mi
            pf -= n * mf
            w = math.floor(pf)
            pi += int(w)
            pf -= w
            # correct a rounding of the float estimate by one cycle either way
            while pi < 0 or (pi == 0 and pf < 0.0):
                pi += mi
                pf += mf
                if pf >= 1.0:
                    pf -= 1.0
                    pi += 1
                n -= 1
            while pi > mi or (pi == mi and pf >= mf):
                pi -= mi
                pf -= mf
                if pf < 0.0:
                    pf += 1.0
                    pi -= 1
                n += 1
        self._pi, self._pf = pi, pf
        return int(n)
