"""FS701 parameters: every register of every parameter block as data, and `ParameterSet`.

Source: manual "FS 701.09" §4.2, §4.3.1 .. §4.3.7 and the register list of §11; spec
the FS701 functional specification (fs701.md) §3.3 .. §3.10, §2.1, §4, §7.

Each `Parameter` carries the manual's name, a snake_case attribute name (the snake_case of the
§11 table name; see `snake_case`), its block, the serial register code, the range and the
default *as the unit stores them* (raw integers), the unit, the number of implied decimals
(the raw value 100 of "+/- Sync Rate" is 1.00 %) and a description.

`ParameterSet` holds one value per parameter (raw integers inside, so nothing is ever rounded
twice) with typed access in engineering units::

    p = ParameterSet()
    p.sync_rate = 1.5          # %, stored as raw 150
    p.get(0x0105)              # 1.5
    p.get_raw("sync_rate")     # 150
    p.set("Cutting Length", 2500)
    p.update({"pulses_line_1000": 4096, "pulses_cut_1000": 2048})   # all or nothing

Bad values raise `ParameterRangeError` naming the parameter, the value and the allowed range;
a failed `update` leaves the set unchanged.

The functions at the end implement the manual's scaling rules: length units and encoder
pulses (§4.2, §4.3.1 "Pulses Line / 1000"), x1/x2/x4 edge counting ("Mode Counter"), the
encoder ratio rule that raises Error 05 and the frequency rules (§2.3, §6), the virtual
master's 1/2048 speed quantisation (§4.2 "Virt. Line Speed"), jog and virtual-master ramps
(§4.3.3, §4.3.1) and the printmark buffer capacity (§4.3.5).

Decisions (spec line -> choice -> why):

* Attribute names: snake_case of the §11 table name, without exception (``"+/- Sync Rate"``
  -> ``sync_rate``, ``"Pulses Line / 1000"`` -> ``pulses_line_1000``, ``"Photocell -> Cut"`` ->
  ``photocell_cut``, ``"Return Speed"`` -> ``return_speed``, ``"Freeze Mode"`` -> ``freeze_mode``);
  the §11 table is the unit's register list and the cut cycle (cutter.py) uses the same rule.
  The manual's other spellings are aliases that read and write the same value: the text's
  ``rel_return_speed`` ("Rel. Return Speed", since 09A added "Abs. Return Speed"),
  ``sync_mode`` / ``synchron_mode`` (text, screenshot and 09A history call 0x011D "Sync Mode"),
  ``virt_line_speed``, ``sync_time``, ``zero_speed_vir_master``, ``printmarks_per_length``, ...
* spec §3.4 [table error] rows 0x0111..0x0115 are shifted in §11: ranges from the text
  (Set Length Cou (Ps) 0..999 999 999, Set Length Cou (LU) 0..999 999 as text and the
  6-digit screenshot field, Printmark Edge 0..1, Deceleration 1 1..99 999 default 1000 as
  Deceleration 2 and the screenshot).
* spec §3.4 "Printm. per Length" min 0 / default 0 vs text "Range: 1 - 99" and screenshot
  "01": 1..99, default 1 (0 marks per cut has no meaning).
* Where the §11 table and the text give different limits and the table is not evidently
  shifted, the table wins (it is the unit's register list, and every table range lies inside
  the text range): Pulses Line/Cut, Accelerations, Decelerations min 1 (text 0: a zero scale
  divides by zero, a zero acceleration never reaches speed); Photocell -> Cut min 1; Gap Time
  min 10 ms (text 1); Sampling Time max 1000 ms (text 9999); Max. Correction min 1 (text 0);
  Jog Speed min 1 % (text 0); Jog ramps 0..99 s (text 01..99; 0 = step, like Ramp Vir.
  Master); Length per Pulse max 50 000 (text 99 999); Minimum Position -999 999..0 and
  Maximum Position 0..999 999 (text +-999 999 for both).
* spec §3.4 [CONFLICT] Cut Window unit "Length units" (table) vs "directly in number of
  increments of the carriage encoder" (text): carriage encoder increments. The window is
  compared with the position error, which the unit counts in carriage increments (§4.4 #3),
  and §7.5 tunes both in the same numbers (window 20, error below 30).
* spec §3.5 [CONFLICT] Max. Correction unit "Incr." (table) vs "mV" (text): mV; the text
  describes a limit of the correction *signal* to the analogue output (recommended >= 1000 mV).
* Photocell Delay "0.000 .. 500.0" (table) vs "000.0 - 500.0 ms" (text): one decimal (0.1 ms),
  raw 0..5000.
* Ana-Out Gain 000.00..320.00 with default "1000": two decimals, raw 0..32000, default raw 1000
  = 10.00 V (§7.1 "default value of 1000, which corresponds to ... 10.00 volts").
  Ana-In Gain 0..99999 with default "010.00" (screenshot "01000"): two decimals, raw 0..99999,
  default raw 1000.
* "Virt. Line Speed ... the setting is limited to the value of register Max. Line Speed":
  the register accepts its full range 0..9 999 999 (so a file may set it before Max. Line
  Speed); the *effective* speed is limited (`effective_virtual_line_speed`).
* spec §2.8/§7 E21 [DERIVED] 1/2048 quantisation, rounding mode unspecified: truncation
  (floor). The §7.1 Adjust screenshot (120 000 LU/min, virtual frequency 19 988 Hz) fits
  floor (19 987 Hz with Max. Line Speed 200 000 and 10 incr/LU) and not round-to-nearest
  (20 003 Hz); see spec §7 E26.
* spec §2.1/§7 E12 ratio rule, boundary unspecified: 16:1 and 1:16 are allowed ("beyond
  1:16 and 16:1 are not allowed"), 16.001:1 raises Error 05. Only the ratio raises Error 05
  (manual §6 names only the ratio); the frequency rules (>= ~1 kHz at max. line speed,
  <= 400 kHz) are reported as findings, not as an error.
* Which frequency the 400 kHz limit applies to: the encoder's signal frequency on the input
  (counted increments / x1,x2,x4 multiplier), a hardware input limit; the >= 1 kHz advice
  ("for best resolution of the analogue output") applies to the counted increment rate.
* "Pulses" of Pulses Line/Cut / 1000 are counted edges after the x1/x2/x4 multiplication
  (spec §2.1 [DERIVED]; §9: the Z-distance shows "the number of pulses ... including multiple
  edge count").
* Ser Unit Address 11..99: "Address numbers containing zeros like 01, 02, ..., 10, 20, etc.
  are not permitted" -> a value with a digit 0 is refused like an out-of-range value (spec §7 E13).
* Writes that make the encoder ratio illegal are stored (the unit stores them and shows
  Error 05); the ratio is a status, not a write rule.
* spec §2.3.3 [GAP] "Ramp Form" (0..15): its description is missing from the manual; the
  register stores 0..15 as the table says and gives no meaning here; the cut cycle interprets
  it (cutter.py: 0 = S-shape, the factory form, other values linear).
* spec §3.9 [GAP] CAN baud-rate codes (manual CI700): stored 0..7 without interpretation.
* spec §5.3 "change I-Time to e.g. 30" with a range 0.000..9.999 s: 30 is the raw register
  value, i.e. 0.030 s - exactly what "30" written over the serial link means (implied decimals).
* "Dir. Counter 1" default: §11 table 1, the §4.3.7 screenshot shows 0 (a commissioned unit's
  value): the table's 1 is the factory default, like Dir. Counter 2..4.
* Floats are accepted when they lie within 1e-6 of the register's resolution (0.01 for
  Sync Rate); a value with more decimals than the register has is refused, never rounded.
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator, Mapping
from dataclasses import dataclass
from typing import Any

from .parameter_table import (  # re-exported: users import them from here
    BLOCKS,
    PARAMETERS,
    PARAMETERS_BY_CODE,
    _ALL_ATTRS,
    _BY_NAME,
    Block,
    Parameter,
    ParameterError,
    ParameterRangeError,
    UnknownParameterError,
    parameter,
    parameter_table_markdown,
    snake_case,
)
from .scaling import (  # re-exported: users import them from here
    COUNTER_MULTIPLIERS,
    MAX_INPUT_FREQUENCY_HZ,
    MIN_MASTER_FREQUENCY_HZ,
    PRINTMARK_BUFFER_SIZE,
    VIRTUAL_SPEED_STEPS,
    EncoderCheck,
    Finding,
    RatioClass,
    adjust_default_speed,
    carriage_counts_per_lu,
    carriage_counts_to_lu,
    check_encoder_rules,
    count_rate_to_line_speed,
    counter_multiplier,
    counts_per_lu,
    effective_virtual_line_speed,
    encoder_ratio_class,
    encoder_signal_frequency,
    jog_acceleration,
    jog_speed,
    line_counts_per_lu,
    line_counts_to_lu,
    line_speed_to_count_rate,
    lu_to_carriage_counts,
    lu_to_line_counts,
    lu_to_physical,
    max_printmarks_between_sensor_and_carriage,
    max_return_speed,
    pulses_per_1000_lu,
    ratio_raises_error_05,
    sync_ratio,
    virtual_master_acceleration,
    virtual_master_count_rate,
    virtual_speed_quantum,
    virtual_speed_steps,
)


__all__ = [
    "Block",
    "BLOCKS",
    "Parameter",
    "PARAMETERS",
    "PARAMETERS_BY_CODE",
    "ParameterError",
    "UnknownParameterError",
    "ParameterRangeError",
    "ParameterDiff",
    "ParameterSet",
    "parameter",
    "snake_case",
    "COUNTER_MULTIPLIERS",
    "counter_multiplier",
    "counts_per_lu",
    "line_counts_per_lu",
    "carriage_counts_per_lu",
    "lu_to_line_counts",
    "line_counts_to_lu",
    "lu_to_carriage_counts",
    "carriage_counts_to_lu",
    "pulses_per_1000_lu",
    "lu_to_physical",
    "line_speed_to_count_rate",
    "count_rate_to_line_speed",
    "encoder_signal_frequency",
    "sync_ratio",
    "RatioClass",
    "encoder_ratio_class",
    "ratio_raises_error_05",
    "Finding",
    "EncoderCheck",
    "check_encoder_rules",
    "MAX_INPUT_FREQUENCY_HZ",
    "MIN_MASTER_FREQUENCY_HZ",
    "VIRTUAL_SPEED_STEPS",
    "virtual_speed_quantum",
    "virtual_speed_steps",
    "effective_virtual_line_speed",
    "virtual_master_count_rate",
    "virtual_master_acceleration",
    "jog_speed",
    "jog_acceleration",
    "adjust_default_speed",
    "max_return_speed",
    "PRINTMARK_BUFFER_SIZE",
    "max_printmarks_between_sensor_and_carriage",
    "parameter_table_markdown",
]


# --------------------------------------------------------------------------------------------
# ParameterSet


@dataclass(frozen=True, slots=True)
class ParameterDiff:
    """One difference between two parameter sets (engineering values)."""

    parameter: Parameter
    ours: int | float
    theirs: int | float

    @property
    def name(self) -> str:
        return self.parameter.attr

    def __str__(self) -> str:
        p = self.parameter
        unit = f" {p.unit}" if p.unit else ""
        return f"{p.attr} (0x{p.code:04X} {p.name}): {p.format_value(p.to_raw(self.ours))}{unit} != {p.format_value(p.to_raw(self.theirs))}{unit}"


class ParameterSet:
    """One value per FS701 parameter; typed attribute access in engineering units.

    Stored raw (integers as the unit stores them). Every write is range-checked; `update`
    checks all values before it stores any of them.
    """

    __slots__ = ("_raw", "_version")

    def __init__(self, values: Mapping["str | int", Any] | None = None) -> None:
        object.__setattr__(self, "_raw", {p.code: p.default for p in PARAMETERS})
        object.__setattr__(self, "_version", 0)  # bumped by every write (a cheap "changed?" test)
        if values:
            self.update(values)

    # ---- construction ---------------------------------------------------------------------
    @classmethod
    def defaults(cls) -> "ParameterSet":
        """The factory defaults (§11)."""
        return cls()

    @classmethod
    def from_raw(cls, values: Mapping["str | int", int]) -> "ParameterSet":
        s = cls()
        s.update_raw(values)
        return s

    def copy(self) -> "ParameterSet":
        new = ParameterSet.__new__(ParameterSet)
        object.__setattr__(new, "_raw", dict(self._raw))
        object.__setattr__(new, "_version", 0)
        return new

    # ---- access -----------------------------------------------------------------------------
    @property
    def version(self) -> int:
        """Counts the writes: a cheap "has anything been written since?" test."""
        return self._version

    def get(self, key: "str | int | Parameter") -> int | float:
        p = parameter(key)
        return p.from_raw(self._raw[p.code])

    def get_raw(self, key: "str | int | Parameter") -> int:
        return self._raw[parameter(key).code]

    def set(self, key: "str | int | Parameter", value: Any) -> None:
        p = parameter(key)
        self._raw[p.code] = p.to_raw(value)
        object.__setattr__(self, "_version", self._version + 1)

    def set_raw(self, key: "str | int | Parameter", raw: int) -> None:
        p = parameter(key)
        self._raw[p.code] = p.check_raw(raw)
        object.__setattr__(self, "_version", self._version + 1)

    def update(self, values: Mapping["str | int", Any]) -> None:
        """Set several values (engineering units); all are checked before any is stored."""
        staged = {}
        for key, value in values.items():
            p = parameter(key)
            staged[p.code] = p.to_raw(value)
        self._raw.update(staged)
        object.__setattr__(self, "_version", self._version + 1)

    def update_raw(self, values: Mapping["str | int", int]) -> None:
        staged = {}
        for key, raw in values.items():
            p = parameter(key)
            staged[p.code] = p.check_raw(raw)
        self._raw.update(staged)
        object.__setattr__(self, "_version", self._version + 1)

    def reset(self, key: "str | int | Parameter | None" = None) -> None:
        """Restore one parameter (or all) to the factory default."""
        if key is None:
            for p in PARAMETERS:
                self._raw[p.code] = p.default
        else:
            p = parameter(key)
            self._raw[p.code] = p.default
        object.__setattr__(self, "_version", self._version + 1)

    def assign(self, other: "ParameterSet") -> None:
        """Take every value of `other` (already valid by construction)."""
        self._raw.update(other._raw)
        object.__setattr__(self, "_version", self._version + 1)

    # ---- views ------------------------------------------------------------------------------
    def as_dict(self, *, raw: bool = False) -> dict[str, int | float]:
        """{attribute name: value} in §11 order (engineering units unless raw)."""
        return {p.attr: (self._raw[p.code] if raw else p.from_raw(self._raw[p.code])) for p in PARAMETERS}

    def block(self, key: str) -> dict[str, int | float]:
        if key not in BLOCKS:
            raise UnknownParameterError(f"no FS701 parameter block {key!r} (blocks: {', '.join(BLOCKS)})")
        return {p.attr: p.from_raw(self._raw[p.code]) for p in PARAMETERS if p.block == key}

    def items(self) -> Iterator[tuple[Parameter, int | float]]:
        for p in PARAMETERS:
            yield p, p.from_raw(self._raw[p.code])

    def diff(self, other: "ParameterSet") -> list[ParameterDiff]:
        """Every parameter whose value differs, in §11 order."""
        return [
            ParameterDiff(p, p.from_raw(self._raw[p.code]), p.from_raw(other._raw[p.code]))
            for p in PARAMETERS
            if self._raw[p.code] != other._raw[p.code]
        ]

    def changed_from_defaults(self) -> list[ParameterDiff]:
        return ParameterSet().diff(self)

    # ---- dunder -----------------------------------------------------------------------------
    def __getattr__(self, name: str) -> Any:
        p = _BY_NAME.get(name)
        if p is None:
            raise AttributeError(f"ParameterSet has no parameter {name!r}")
        return p.from_raw(self._raw[p.code])

    def __setattr__(self, name: str, value: Any) -> None:
        if name == "_raw" or name == "_version":  # copy / pickle restore the slots
            object.__setattr__(self, name, value)
            if name == "_raw":
                try:
                    object.__setattr__(self, "_version", self._version + 1)
                except AttributeError:
                    object.__setattr__(self, "_version", 0)
            return
        p = _BY_NAME.get(name)
        if p is None:
            raise AttributeError(f"ParameterSet has no parameter {name!r}")
        self._raw[p.code] = p.to_raw(value)
        object.__setattr__(self, "_version", self._version + 1)

    def __getitem__(self, key: "str | int") -> int | float:
        return self.get(key)

    def __setitem__(self, key: "str | int", value: Any) -> None:
        self.set(key, value)

    def __contains__(self, key: object) -> bool:
        try:
            parameter(key)  # type: ignore[arg-type]
        except ParameterError:
            return False
        return True

    def __iter__(self) -> Iterator[str]:
        return (p.attr for p in PARAMETERS)

    def __len__(self) -> int:
        return len(PARAMETERS)

    def __eq__(self, other: object) -> bool:
        return isinstance(other, ParameterSet) and self._raw == other._raw

    __hash__ = None  # type: ignore[assignment]  # mutable

    def __dir__(self) -> Iterable[str]:
        return [*object.__dir__(self), *sorted(_ALL_ATTRS)]

    def __repr__(self) -> str:
        changed = ", ".join(f"{d.name}={d.theirs!r}" for d in self.changed_from_defaults())
        return f"ParameterSet({changed})" if changed else "ParameterSet(<factory defaults>)"
