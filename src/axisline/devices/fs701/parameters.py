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

import math
import re
from collections.abc import Iterable, Iterator, Mapping
from dataclasses import dataclass, field
from decimal import Decimal, InvalidOperation
from typing import Any

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
# data model


@dataclass(frozen=True, slots=True)
class Block:
    """A register card of the OS5.1 software: 32 consecutive serial codes from `base`.

    `number` is the unit's block number: the parameter blocks count from Basic Settings = 1 in
    steps of 32 codes from 0x0100, which is why the Communication card's unused registers read
    "Block15 8" .. "Block15 31" in the §4.3.6 screenshot (0x02C0 = block 15).
    """

    key: str
    title: str
    number: int
    base: int
    section: str

    @property
    def codes(self) -> range:
        return range(self.base, self.base + 32)


BLOCKS: dict[str, Block] = {
    b.key: b
    for b in (
        Block("general", "General Parameters", 0, 0x0000, "§4.2"),
        Block("basic_settings", "Basic Settings", 1, 0x0100, "§4.3.1"),
        Block("control_loop", "Control Loop Settings", 2, 0x0120, "§4.3.2"),
        Block("jog_home_ref", "Jog / Home / Ref. Settings", 3, 0x0140, "§4.3.3"),
        Block("monitoring", "Monitoring Settings", 4, 0x0160, "§4.3.4"),
        Block("additional_cuts", "Additional Cuts", 5, 0x0180, "§4.3.5"),
        Block("communication", "Communication Settings", 15, 0x02C0, "§4.3.6"),
        Block("set_up", "Set-Up Settings", 16, 0x02E0, "§4.3.7"),
    )
}


def snake_case(name: str) -> str:
    """The attribute name of a manual name: lower case, every run of other characters -> "_".

    "+/- Sync Rate" -> "sync_rate", "Pulses Line / 1000" -> "pulses_line_1000",
    "Photocell -> Cut" -> "photocell_cut", "Test Cut. Length" -> "test_cut_length".
    """
    return re.sub(r"[^a-z0-9]+", "_", name.lower()).strip("_")


class ParameterError(ValueError):
    """A parameter name, code or value the FS701 does not accept."""


class UnknownParameterError(ParameterError, KeyError):
    """No parameter of that name or serial code."""

    def __str__(self) -> str:  # KeyError would quote the message
        return str(self.args[0]) if self.args else ""


class ParameterRangeError(ParameterError):
    """A value outside the parameter's range (or not representable at its resolution)."""

    def __init__(self, param: "Parameter", value: Any, reason: str | None = None) -> None:
        self.parameter = param
        self.value = value
        self.minimum = param.minimum_value
        self.maximum = param.maximum_value
        unit = f" {param.unit}" if param.unit else ""
        allowed = f"{param.format_value(param.minimum)}..{param.format_value(param.maximum)}{unit}"
        what = reason or f"is outside the allowed range {allowed}"
        if reason and "allowed" not in reason:
            what = f"{reason} (allowed {allowed})"
        shown = str(value) if isinstance(value, Decimal) else repr(value)
        super().__init__(f"{param.name} ({param.attr}, 0x{param.code:04X}): value {shown} {what}")


@dataclass(frozen=True, slots=True)
class Parameter:
    """One parameter register. Range and default are raw (as the unit stores them)."""

    name: str  # the §11 table name
    attr: str  # snake_case attribute name
    block: str  # key of BLOCKS
    code: int  # serial code
    minimum: int  # raw
    maximum: int  # raw
    default: int  # raw
    unit: str = ""
    decimals: int = 0  # implied decimals: engineering value = raw / 10**decimals
    description: str = ""
    aliases: tuple[str, ...] = ()
    choices: Mapping[int, str] = field(default_factory=dict, compare=False)  # meaning of coded settings
    forbid_zero_digit: bool = False  # Ser Unit Address: addresses with a 0 digit are broadcast

    @property
    def scale(self) -> int:
        return 10**self.decimals

    @property
    def minimum_value(self) -> int | float:
        return self.from_raw(self.minimum)

    @property
    def maximum_value(self) -> int | float:
        return self.from_raw(self.maximum)

    @property
    def default_value(self) -> int | float:
        return self.from_raw(self.default)

    @property
    def signed(self) -> bool:
        return self.minimum < 0

    @property
    def digits(self) -> int:
        """Decimal digits of the largest magnitude (the width of the OS5.1 field)."""
        return max(len(str(abs(self.minimum))), len(str(abs(self.maximum))), self.decimals + 1)

    def from_raw(self, raw: int) -> int | float:
        """Engineering value of a raw register value (int when the register has no decimals)."""
        return raw if self.decimals == 0 else raw / self.scale

    def format_value(self, raw: int) -> str:
        """The raw value written with its decimal point ("-9.99", "1000", "500.0")."""
        if self.decimals == 0:
            return str(raw)
        sign = "-" if raw < 0 else ""
        whole, frac = divmod(abs(raw), self.scale)
        return f"{sign}{whole}.{frac:0{self.decimals}d}"

    def to_raw(self, value: Any) -> int:
        """Raw register value of an engineering value, range-checked.

        int, float, Decimal or a decimal string ("1.50", "+0.25"). Raises ParameterRangeError
        (naming the parameter, the value and the range) for anything the unit would refuse.
        """
        if isinstance(value, bool):
            raise ParameterRangeError(self, value, "is a bool; give a number")
        scaled: Decimal
        if isinstance(value, int):
            raw = value * self.scale
        else:
            if isinstance(value, float):
                if not math.isfinite(value):
                    raise ParameterRangeError(self, value, "is not a finite number")
                exact = value * self.scale
                nearest = round(exact)
                # floats carry binary noise (0.1 + 0.2); accept what is a step within 1e-6
                if abs(exact - nearest) > 1e-6:
                    raise ParameterRangeError(
                        self, value, f"has more decimals than the register's resolution {self._resolution()}"
                    )
                raw = int(nearest)
            else:
                try:
                    dec = value if isinstance(value, Decimal) else Decimal(str(value).strip())
                except (InvalidOperation, ValueError):
                    raise ParameterRangeError(self, value, "is not a number") from None
                if not dec.is_finite():
                    raise ParameterRangeError(self, value, "is not a finite number")
                scaled = dec.scaleb(self.decimals)
                if scaled != scaled.to_integral_value():
                    raise ParameterRangeError(
                        self, value, f"has more decimals than the register's resolution {self._resolution()}"
                    )
                raw = int(scaled)
        self.check_raw(raw, shown=value)
        return raw

    def check_raw(self, raw: Any, shown: Any = None) -> int:
        """Check a raw value; returns it. Raises ParameterRangeError."""
        shown = raw if shown is None else shown
        if isinstance(raw, bool) or not isinstance(raw, int):
            raise ParameterRangeError(self, shown, "is not an integer raw value")
        if not self.minimum <= raw <= self.maximum:
            raise ParameterRangeError(self, shown)
        if self.forbid_zero_digit and "0" in str(raw):
            raise ParameterRangeError(
                self,
                shown,
                "contains the digit 0 (reserved for broadcast addresses; "
                f"allowed {self.minimum}..{self.maximum} without a digit 0)",
            )
        return raw

    def _resolution(self) -> str:
        return "1" if self.decimals == 0 else "0." + "0" * (self.decimals - 1) + "1"

    @property
    def names(self) -> tuple[str, ...]:
        return (self.attr, *self.aliases)


def _p(
    block: str,
    code: int,
    name: str,
    attr: str,
    minimum: int,
    maximum: int,
    default: int,
    unit: str = "",
    description: str = "",
    *,
    decimals: int = 0,
    aliases: tuple[str, ...] = (),
    choices: Mapping[int, str] | None = None,
    forbid_zero_digit: bool = False,
) -> Parameter:
    return Parameter(
        name=name,
        attr=attr,
        block=block,
        code=code,
        minimum=minimum,
        maximum=maximum,
        default=default,
        unit=unit,
        decimals=decimals,
        description=description,
        aliases=aliases,
        choices=dict(choices or {}),
        forbid_zero_digit=forbid_zero_digit,
    )


LU = "LU"
LU_MIN = "LU/min"
LU_S2 = "LU/s²"
_EDGES = {0: "x1 (one edge per encoder period)", 1: "x2", 2: "x4 (all four edges)"}
_DIR = {0: "count down on A leads B (reverse)", 1: "count up on A leads B (forward)"}
_INDEX_SEL = {0: "not used with this application", 1: "not used", 2: "not used"}

# fmt: off
PARAMETERS: tuple[Parameter, ...] = (
    # ---- General Parameters (§4.2) -------------------------------------------------------
    _p("general", 0x0000, "Cutting Length", "cutting_length", 1, 999_999, 1000, LU,
       "Length cut while input 'Cut Test Length' is LOW (§4.2)."),
    _p("general", 0x0001, "Test Cut. Length", "test_cut_length", 1, 999_999, 1000, LU,
       "Length cut while 'Cut Test Length' is HIGH or was shortly HIGH during the previous cycle (§4.2)."),
    _p("general", 0x0002, "Virtual Line Speed", "virtual_line_speed", 0, 9_999_999, 10_000, LU_MIN,
       "Speed of the virtual master; limited to Max. Line Speed, resolution 1/2048 of it (§4.2).",
       aliases=("virt_line_speed",)),
    # ---- Basic Settings (§4.3.1) ---------------------------------------------------------
    _p("basic_settings", 0x0100, "Pulses Line / 1000", "pulses_line_1000", 1, 999_999, 1000, "Incr.",
       "Line encoder increments counted (after x1/x2/x4) while the line moves 1000 LU (§4.3.1).",
       aliases=("pulses_line",)),
    _p("basic_settings", 0x0101, "Pulses Cut / 1000", "pulses_cut_1000", 1, 999_999, 1000, "Incr.",
       "Carriage encoder increments counted while the carriage moves 1000 LU (§4.3.1).",
       aliases=("pulses_cut",)),
    _p("basic_settings", 0x0102, "Acceleration 1", "acceleration_1", 1, 99_999, 1000, LU_S2,
       "Carriage acceleration in forward motion; linear-ramp equivalent, S-ramp peak x1.25 (§4.3.1).",
       aliases=("acceleration1",)),
    _p("basic_settings", 0x0103, "Acceleration 2", "acceleration_2", 1, 99_999, 1000, LU_S2,
       "Carriage acceleration in reverse motion (§4.3.1).", aliases=("acceleration2",)),
    _p("basic_settings", 0x0104, "Ramp Form", "ramp_form", 0, 15, 0, "",
       "Ramp shape; the manual's description is missing (spec §2.3.3 [GAP]); S-shape is the factory form."),
    _p("basic_settings", 0x0105, "+/- Sync Rate", "sync_rate", -999, 999, 0, "%",
       "Variation of the synchronous speed; does not change the cutting length (§4.3.1).",
       decimals=2, aliases=("synchron_rate",)),
    _p("basic_settings", 0x0106, "Return Speed", "return_speed", 1, 999, 100, "x line speed",
       "Maximum return speed as a multiple of the actual line speed; used only if required (§4.3.1).",
       decimals=2, aliases=("rel_return_speed",)),
    _p("basic_settings", 0x0107, "Edge Sense", "edge_sense", 0, 1, 0, "",
       "Active edge of input 'Cut completed' (§4.3.1).",
       choices={0: "rising edge ends the synchronous phase", 1: "falling edge ends the synchronous phase"}),
    _p("basic_settings", 0x0108, "Synchron Time", "synchron_time", 1, 9999, 1, "ms",
       "Delay between reaching synchronous speed and 'Ready to cut' (§4.3.1).", aliases=("sync_time",)),
    _p("basic_settings", 0x0109, "Cut Window", "cut_window", 1, 99, 50, "Incr.",
       "Tolerance window around the cutting position, in carriage encoder increments (§4.3.1).",),
    _p("basic_settings", 0x010A, "Sync Samples", "sync_samples", 1, 9999, 1, "cycles",
       "Consecutive control cycles inside the cut window before 'Ready to cut' (§4.3.1).",),
    _p("basic_settings", 0x010B, "Tool Width", "tool_width", 0, 999, 0, LU,
       "Compensation of the width of the saw blade or cutting tool (§4.3.1)."),
    _p("basic_settings", 0x010C, "Cutting Mode", "cutting_mode", 1, 3, 1, "",
       "Operation mode (§4.3.1).",
       choices={1: "cut to length (no print mark)", 2: "cut to print marks",
                3: "cut to print marks with additional cuts (§4.3.5)"}),
    _p("basic_settings", 0x010D, "Photocell -> Cut", "photocell_cut", 1, 999_999, 1000, LU,
       "Distance from the print-mark sensor to the carriage home position (modes 2, 3) (§4.3.1).",
       aliases=("photocell_to_cut",)),
    _p("basic_settings", 0x010E, "Gap Length", "gap_length", 0, 9999, 0, LU,
       "Gap made after the cut by a short acceleration of the tool; 0 = unused (§4.3.1)."),
    _p("basic_settings", 0x010F, "Gap Time", "gap_time", 10, 9999, 10, "ms",
       "Time to make the gap (§4.3.1)."),
    _p("basic_settings", 0x0110, "Ramp Vir. Master", "ramp_vir_master", 0, 999, 1, "s",
       "Virtual master ramp time between standstill and Max. Line Speed (§4.3.1).",
       aliases=("ramp_virtual_master",)),
    _p("basic_settings", 0x0111, "Set Length Cou (Ps)", "set_length_cou_ps", 0, 999_999_999, 0, "Incr.",
       "Material length counter preset at Start, in master pulses; cleared after use (§4.3.1).",
       aliases=("set_length_counter_pulses",)),
    _p("basic_settings", 0x0112, "Set Length Cou (LU)", "set_length_cou_lu", 0, 999_999, 0, LU,
       "Material length counter preset at Start, in LU; cleared after use (§4.3.1).",
       aliases=("set_length_counter_lu",)),
    _p("basic_settings", 0x0113, "Printmark Edge", "printmark_edge", 0, 1, 0, "",
       "Active edge of the print-mark sensor (§4.3.1).",
       choices={0: "rising edge (input HIGH while a mark is seen)", 1: "falling edge (input LOW while a mark is seen)"}),
    _p("basic_settings", 0x0114, "Virt. Printmarks", "virt_printmarks", 0, 1, 0, "",
       "Fill the print-mark buffer with virtual marks at Start (§4.3.1).",
       choices={0: "disabled", 1: "virtual print marks at start"}),
    _p("basic_settings", 0x0115, "Deceleration 1", "deceleration_1", 1, 99_999, 1000, LU_S2,
       "Carriage deceleration in forward motion (§4.3.1).", aliases=("deceleration1",)),
    _p("basic_settings", 0x0116, "Deceleration 2", "deceleration_2", 1, 99_999, 1000, LU_S2,
       "Carriage deceleration in reverse motion (§4.3.1).", aliases=("deceleration2",)),
    _p("basic_settings", 0x0117, "Printmark Offset", "printmark_offset", -99_999, 99_999, 0, LU,
       "Fine adjustment of the cut against the print mark; + leads the mark (§4.3.1)."),
    _p("basic_settings", 0x0118, "Photocell Delay", "photocell_delay", 0, 5000, 0, "ms",
       "Dead time of the print-mark sensor, compensated in the detected position (§4.3.1).", decimals=1),
    _p("basic_settings", 0x0119, "Printm. per Length", "printm_per_length", 1, 99, 1, "",
       "Print marks between two cuts; the cut uses one of them (§4.3.1).",
       aliases=("printmarks_per_length",)),
    _p("basic_settings", 0x011A, "Printmark Window", "printmark_window", 0, 9999, 0, LU,
       "Symmetric window around the taught print-mark position; 0 = every mark counts (§4.3.1)."),
    _p("basic_settings", 0x011B, "Missing Printmarks", "missing_printmarks", 0, 99, 0, "sheets",
       "Sheets without a mark in the window until output 'No Printmark'; 0 = off (§4.3.1)."),
    _p("basic_settings", 0x011C, "Abs. Return Speed", "abs_return_speed", 0, 9_999_999, 0, LU_MIN,
       "Absolute return speed; 0 = Rel. Return Speed is valid (§4.3.1)."),
    _p("basic_settings", 0x011D, "Freeze Mode", "freeze_mode", 0, 2, 0, "",
       "Control mode during the synchronous phase with input 'Sync Mode Enable'; must be 0 normally (§4.3.1).",
       aliases=("sync_mode", "synchron_mode"),
       choices={0: "normal", 1: "special (ask motrona; semantics not documented)", 2: "special (not documented)"}),
    # ---- Control Loop Settings (§4.3.2) --------------------------------------------------
    _p("control_loop", 0x0120, "P-Gain", "p_gain", 0, 9999, 1000, "",
       "Proportional gain of the position loop; recommended 500..2500 (§4.3.2)."),
    _p("control_loop", 0x0121, "I Time", "i_time", 0, 9999, 0, "s",
       "Integration time; 0.000 = proportional only (§4.3.2).", decimals=3),
    _p("control_loop", 0x0122, "Max. Correction", "max_correction", 1, 9999, 9999, "mV",
       "Limit of the proportional correction signal; recommended >= 1000 mV (§4.3.2)."),
    _p("control_loop", 0x0123, "Max. Line Speed", "max_line_speed", 1, 9_999_999, 100_000, LU_MIN,
       "Maximum line speed: internal scaling, 100 % of jog speed, ramp reference (§4.3.2)."),
    _p("control_loop", 0x0124, "Sampling Time", "sampling_time", 1, 1000, 1, "ms",
       "Filter time of the line-speed feed-forward signal (§4.3.2)."),
    # ---- Jog / Home / Ref. Settings (§4.3.3) ---------------------------------------------
    _p("jog_home_ref", 0x0140, "Home Window", "home_window", 1, 999, 100, LU,
       "Window around the home position for output 'Home' and the 'cut not possible' check (§4.3.3)."),
    _p("jog_home_ref", 0x0141, "Minimum Position", "minimum_position", -999_999, 0, -999_999, LU,
       "Rear software limit switch, from the zero position (§4.3.3).", aliases=("min_position",)),
    _p("jog_home_ref", 0x0142, "Maximum Position", "maximum_position", 0, 999_999, 999_999, LU,
       "Front software limit switch (Stop state only) (§4.3.3).", aliases=("max_position",)),
    _p("jog_home_ref", 0x0143, "Alarm Position", "alarm_position", 0, 999_999, 999_999, LU,
       "Forward position that sets output 'Alarm' in automatic operation (§4.3.3)."),
    _p("jog_home_ref", 0x0144, "Jog Speed Forw.", "jog_speed_forw", 1, 100, 10, "%",
       "Forward jog speed in % of Max. Line Speed (§4.3.3)."),
    _p("jog_home_ref", 0x0145, "Jog Ramp Up Forw.", "jog_ramp_up_forw", 0, 99, 1, "s",
       "Forward jog acceleration time for standstill -> Max. Line Speed (§4.3.3)."),
    _p("jog_home_ref", 0x0146, "Jog Ramp Dw. Forw.", "jog_ramp_dw_forw", 0, 99, 1, "s",
       "Forward jog deceleration time for Max. Line Speed -> standstill (§4.3.3)."),
    _p("jog_home_ref", 0x0147, "Jog Speed Rev.", "jog_speed_rev", 1, 100, 10, "%",
       "Reverse jog speed in % of Max. Line Speed (§4.3.3)."),
    _p("jog_home_ref", 0x0148, "Jog Ramp Up Rev.", "jog_ramp_up_rev", 0, 99, 1, "s",
       "Reverse jog acceleration time (§4.3.3)."),
    _p("jog_home_ref", 0x0149, "Jog Ramp Dw. Rev.", "jog_ramp_dw_rev", 0, 99, 1, "s",
       "Reverse jog deceleration time (§4.3.3)."),
    # ---- Monitoring Settings (§4.3.4) ----------------------------------------------------
    _p("monitoring", 0x0160, "Zero Speed Master", "zero_speed_master", 0, 999_999, 0, LU_MIN,
       "Standstill definition of the line encoder for output 'Master in motion' (§4.3.4)."),
    _p("monitoring", 0x0161, "Zero Speed Vir. Ma.", "zero_speed_vir_ma", 0, 999_999, 0, LU_MIN,
       "Standstill definition of the virtual master for output 'Vir. M. in motion' (§4.3.4).",
       aliases=("zero_speed_vir_master",)),
    _p("monitoring", 0x0162, "LED Function", "led_function", 0, 1, 0, "",
       "Function of the 6 LEDs (§4.3.4, §5).",
       choices={0: "LEDs show hardware outputs Out1..Out6", 1: "LEDs show the carriage position error"}),
    _p("monitoring", 0x0163, "Length per Pulse", "length_per_pulse", 1, 50_000, 1000, LU,
       "Line length per pulse of output 'Length Pulses', duty 1:1 (§4.3.4)."),
    _p("monitoring", 0x0164, "Master Rev. Limit", "master_rev_limit", 0, 99_999, 0, LU,
       "Reverse line movement that sets output 'Master Reverse'; 0 = off (§4.3.4).",
       aliases=("mast_rev_limit",)),
    _p("monitoring", 0x0170, "Batch Counter", "batch_counter", 0, 9_999_999_999, 0, "pcs",
       "Cuts of normal length in automatic operation; not saved at power-down (§4.3.4)."),
    _p("monitoring", 0x0171, "Waste Counter", "waste_counter", 0, 9_999_999_999, 0, "pcs",
       "Waste pieces: immediate cuts and test-length cuts; not saved at power-down (§4.3.4)."),
    # ---- Additional Cuts (§4.3.5) --------------------------------------------------------
    _p("additional_cuts", 0x0180, "Additional Cuts", "additional_cuts", 0, 3, 0, "",
       "Supplementary cuts per print mark in Cutting Mode 3 (§4.3.5)."),
    _p("additional_cuts", 0x0181, "Add. Cut 1 Length", "add_cut_1_length", 0, 999_999, 0, LU,
       "Length of the first additional cut (ends at the trigger mark) (§4.3.5)."),
    _p("additional_cuts", 0x0182, "Add. Cut 2 Length", "add_cut_2_length", 0, 999_999, 0, LU,
       "Length of the second additional cut (§4.3.5)."),
    _p("additional_cuts", 0x0183, "Add. Cut 3 Length", "add_cut_3_length", 0, 999_999, 0, LU,
       "Length of the third additional cut (§4.3.5)."),
    # ---- Communication Settings (§4.3.6) -------------------------------------------------
    _p("communication", 0x02C0, "Can Unit Address", "can_unit_address", 1, 127, 1, "",
       "CANopen node id (manual CI700) (§4.3.6)."),
    _p("communication", 0x02C1, "Can Baud Rate", "can_baud_rate", 0, 7, 1, "",
       "CAN baud-rate code; the code table is in manual CI700 (spec [GAP]) (§4.3.6)."),
    _p("communication", 0x02C2, "Can Config.", "can_config", 0, 255, 0, "", "CAN configuration (CI700) (§4.3.6)."),
    _p("communication", 0x02C3, "Can Tx Par", "can_tx_par", 0, 255, 0, "", "CAN transmit parameter (CI700) (§4.3.6)."),
    _p("communication", 0x02C4, "Can Rx Par", "can_rx_par", 0, 255, 0, "", "CAN receive parameter (CI700) (§4.3.6)."),
    _p("communication", 0x02C5, "Ser Unit Address", "ser_unit_address", 11, 99, 11, "",
       "Serial unit address; addresses with a digit 0 are reserved for broadcast (§4.3.6).",
       forbid_zero_digit=True),
    _p("communication", 0x02C6, "Ser Baud Rate", "ser_baud_rate", 0, 4, 2, "",
       "Serial baud rate (§4.3.6).",
       choices={0: "38400 bit/s", 1: "19200 bit/s", 2: "9600 bit/s", 3: "4800 bit/s", 4: "2400 bit/s"}),
    _p("communication", 0x02C7, "Ser Data Format", "ser_data_format", 0, 9, 0, "",
       "Serial data bits / parity / stop bits (§4.3.6).",
       choices={0: "7E1", 1: "7E2", 2: "7O1", 3: "7O2", 4: "7N1", 5: "7N2", 6: "8E1", 7: "8O1", 8: "8N1", 9: "8N2"}),
    # ---- Set-Up Settings (§4.3.7) --------------------------------------------------------
    *(
        p
        for n in range(1, 5)
        for p in (
            _p("set_up", 0x02E0 + 2 * (n - 1), f"Mode Counter {n}", f"mode_counter_{n}", 0, 2, 0, "",
               f"Edges counted on encoder input {n} (§4.3.7)" + (" (line encoder)." if n == 1 else
               " (carriage encoder)." if n == 2 else " (not used by FS701)."), choices=_EDGES),
            _p("set_up", 0x02E1 + 2 * (n - 1), f"Dir. Counter {n}", f"dir_counter_{n}", 0, 1, 1, "",
               f"Counting direction of encoder input {n} against the A/B phase (§4.3.7).", choices=_DIR),
        )
    ),
    *(
        p
        for n in range(1, 5)
        for p in (
            _p("set_up", 0x02E8 + 2 * (n - 1), f"Ana-Out Offset {n}", f"ana_out_offset_{n}", -2047, 2047, 0,
               "1/2047 FS", f"Zero of analogue output {n}: -2047..+2047 = -100..+100 % of full scale (§4.3.7)"
               + ("; Ana-Out 2 is the carriage speed reference." if n == 2 else "."),
               aliases=(f"ana_out_{n}_offset",)),
            _p("set_up", 0x02E9 + 2 * (n - 1), f"Ana-Out Gain {n}", f"ana_out_gain_{n}", 0, 32_000, 1000, "V",
               f"Full-scale voltage of analogue output {n}; 10.00 = 10 V (§4.3.7).", decimals=2,
               aliases=(f"ana_out_{n}_gain",)),
        )
    ),
    *(
        p
        for n in range(1, 5)
        for p in (
            _p("set_up", 0x02F0 + 2 * (n - 1), f"Ana-In {n} Offset", f"ana_in_{n}_offset", -9999, 9999, 0, "",
               "Not used with this application (§4.3.7).", aliases=(f"ana_in_offset_{n}",)),
            _p("set_up", 0x02F1 + 2 * (n - 1), f"Ana-In {n} Gain", f"ana_in_{n}_gain", 0, 99_999, 1000, "",
               "Not used with this application (§4.3.7).", decimals=2, aliases=(f"ana_in_gain_{n}",)),
        )
    ),
    _p("set_up", 0x02F8, "Index Output", "index_output", 2, 65_500, 2000, "Incr.",
       "Index distance of the frequency output; 'not used with this application' (§4.3.7)."),
    _p("set_up", 0x02F9, "Frequency Output", "frequency_output", -500_000, 500_000, 50_000, "Hz",
       "For factory testing purpose only (§4.3.7)."),
    _p("set_up", 0x02FA, "Dir. Frequency", "dir_frequency", 0, 1, 1, "",
       "Counting direction of the virtual master frequency (§4.3.7).", choices={0: "reverse", 1: "forward"}),
    _p("set_up", 0x02FB, "Frequency Select", "frequency_select", 0, 1, 1, "",
       "Source of connector 'Encoder Output' (§4.3.7).",
       choices={0: "same signal as input Encoder1", 1: "virtual master axis"}),
    *(
        _p("set_up", 0x02FC + n - 1, f"Index {n} select", f"index_{n}_select", 0, 2, 0, "",
           "Not used with this application (§4.3.7).", choices=_INDEX_SEL)
        for n in range(1, 5)
    ),
)
# fmt: on

PARAMETERS_BY_CODE: dict[int, Parameter] = {p.code: p for p in PARAMETERS}
_BY_NAME: dict[str, Parameter] = {}
for _prm in PARAMETERS:
    for _n in (*_prm.names, snake_case(_prm.name)):
        if _BY_NAME.get(_n, _prm) is not _prm:  # pragma: no cover - guarded by the tests
            raise RuntimeError(f"parameter name {_n!r} used twice")
        _BY_NAME[_n] = _prm
del _prm, _n
_ALL_ATTRS = frozenset(_BY_NAME)


def parameter(key: "str | int | Parameter") -> Parameter:
    """The parameter of a name (attribute, alias or manual name) or serial code.

    Raises UnknownParameterError naming the key.
    """
    if isinstance(key, Parameter):
        return key
    if isinstance(key, bool):
        raise UnknownParameterError(f"no FS701 parameter {key!r}")
    if isinstance(key, int):
        try:
            return PARAMETERS_BY_CODE[key]
        except KeyError:
            raise UnknownParameterError(f"no FS701 parameter at serial code 0x{key:04X} ({key})") from None
    if isinstance(key, str):
        found = _BY_NAME.get(key) or _BY_NAME.get(snake_case(key))
        if found is not None:
            return found
        raise UnknownParameterError(f"no FS701 parameter named {key!r}")
    raise UnknownParameterError(f"no FS701 parameter {key!r} (give a name or a serial code)")


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


# --------------------------------------------------------------------------------------------
# length units and encoder scaling (§4.2, §4.3.1, §4.3.7; spec §2.1)

COUNTER_MULTIPLIERS: dict[int, int] = {0: 1, 1: 2, 2: 4}  # "Mode Counter": 0 = x1, 1 = x2, 2 = x4


def counter_multiplier(mode: int) -> int:
    """Edges counted per encoder period for a "Mode Counter" setting (0 -> 1, 1 -> 2, 2 -> 4)."""
    try:
        return COUNTER_MULTIPLIERS[mode]
    except KeyError:
        raise ParameterError(f"Mode Counter {mode!r} is not 0 (x1), 1 (x2) or 2 (x4)") from None


def counts_per_lu(pulses_per_1000: int | float) -> float:
    """Counted increments per length unit: Pulses .. / 1000 divided by 1000 (§4.3.1)."""
    return pulses_per_1000 / 1000.0


def line_counts_per_lu(params: ParameterSet) -> float:
    """kL: line encoder increments per LU."""
    return counts_per_lu(params.get_raw("pulses_line_1000"))


def carriage_counts_per_lu(params: ParameterSet) -> float:
    """kC: carriage encoder increments per LU."""
    return counts_per_lu(params.get_raw("pulses_cut_1000"))


def lu_to_line_counts(lu: float, params: ParameterSet) -> float:
    return lu * params.get_raw("pulses_line_1000") / 1000.0


def line_counts_to_lu(counts: float, params: ParameterSet) -> float:
    return counts * 1000.0 / params.get_raw("pulses_line_1000")


def lu_to_carriage_counts(lu: float, params: ParameterSet) -> float:
    return lu * params.get_raw("pulses_cut_1000") / 1000.0


def carriage_counts_to_lu(counts: float, params: ParameterSet) -> float:
    return counts * 1000.0 / params.get_raw("pulses_cut_1000")


def pulses_per_1000_lu(ppr: int, multiplier: int, lu_per_revolution: float) -> float:
    """The "Pulses .. / 1000" setting of an encoder: ppr x multiplier edges per revolution,
    `lu_per_revolution` LU of travel per revolution (e.g. a measuring wheel's circumference).
    Round the result to an integer for the register; the rounding error is a cutting error
    proportional to the length (§9 "Is the synchronous ratio correct?").
    """
    if ppr <= 0 or lu_per_revolution <= 0:
        raise ParameterError(f"ppr ({ppr}) and LU per revolution ({lu_per_revolution}) must be positive")
    if multiplier not in (1, 2, 4):
        raise ParameterError(f"multiplier {multiplier!r} is not 1, 2 or 4")
    return ppr * multiplier * 1000.0 / lu_per_revolution


def lu_to_physical(lu: float, lu_size: float) -> float:
    """A length in LU expressed in the physical unit one LU stands for (§4.2: with
    LU = 0.1 mm, 1000 LU are 100.0 mm)."""
    return lu * lu_size


def line_speed_to_count_rate(speed_lu_min: float, pulses_per_1000: int | float) -> float:
    """Counted increments per second at a speed in LU/min."""
    return speed_lu_min / 60.0 * pulses_per_1000 / 1000.0


def count_rate_to_line_speed(count_rate: float, pulses_per_1000: int | float) -> float:
    """LU/min from counted increments per second (process value "Line Speed" from "Master Freq.")."""
    return count_rate * 60.0 * 1000.0 / pulses_per_1000


def encoder_signal_frequency(speed_lu_min: float, pulses_per_1000: int | float, mode_counter: int) -> float:
    """Signal frequency (Hz) on the encoder input: counted rate / x1,x2,x4 multiplier."""
    return line_speed_to_count_rate(speed_lu_min, pulses_per_1000) / counter_multiplier(mode_counter)


def sync_ratio(params: ParameterSet) -> float:
    """Carriage increments per line increment in the synchronous phase:
    kC / kL x (1 + Sync Rate / 100) (spec §2.1 [DERIVED]; the Sync Rate changes the synchronous
    speed only, never the cutting length)."""
    return (
        params.get_raw("pulses_cut_1000") / params.get_raw("pulses_line_1000") * (1.0 + params.sync_rate / 100.0)
    )


class RatioClass:
    """Classes of the line : carriage pulse ratio (§2.3)."""

    ACCEPTABLE = "acceptable"  # 5:1 .. 1:5
    MISMATCHED = "mismatched"  # beyond 5:1 up to 16:1 (and 1:5 .. 1:16): works, not recommended
    NOT_ALLOWED = "not allowed"  # beyond 16:1 / 1:16 -> Error 05


def encoder_ratio_class(pulses_line_1000: int, pulses_cut_1000: int) -> str:
    """Classify Pulses Line/1000 : Pulses Cut/1000 (exact integer comparisons)."""
    hi, lo = max(pulses_line_1000, pulses_cut_1000), min(pulses_line_1000, pulses_cut_1000)
    if lo <= 0:
        return RatioClass.NOT_ALLOWED
    if hi > 16 * lo:
        return RatioClass.NOT_ALLOWED
    if hi > 5 * lo:
        return RatioClass.MISMATCHED
    return RatioClass.ACCEPTABLE


def ratio_raises_error_05(pulses_line_1000: int, pulses_cut_1000: int) -> bool:
    """Error 05 "Val. Range exceed": the ratio is beyond 16:1 or 1:16 (§2.3, §6)."""
    return encoder_ratio_class(pulses_line_1000, pulses_cut_1000) == RatioClass.NOT_ALLOWED


MAX_INPUT_FREQUENCY_HZ = 400_000.0  # §2.3 "must not exceed the maximum level of 400 kHz"
MIN_MASTER_FREQUENCY_HZ = 1_000.0  # §2.3 "at least about 1 kHz" at maximum line speed


@dataclass(frozen=True, slots=True)
class Finding:
    """One result of the encoder rules: severity "error" (Error 05), "warning" or "advice"."""

    severity: str
    rule: str
    message: str


@dataclass(frozen=True, slots=True)
class EncoderCheck:
    ratio: float  # pulses line / pulses cut
    ratio_class: str
    error_05: bool
    master_count_rate_hz: float  # counted line increments per second at Max. Line Speed
    master_signal_hz: float
    carriage_signal_hz: float  # carriage encoder at Max. Line Speed (synchronous)
    findings: tuple[Finding, ...]

    @property
    def ok(self) -> bool:
        return not any(f.severity in ("error", "warning") for f in self.findings)


def check_encoder_rules(params: ParameterSet) -> EncoderCheck:
    """The encoder rules of §2.3 for a parameter set.

    Error 05 (ratio beyond 16:1 / 1:16); warnings: an input above 400 kHz at Max. Line Speed,
    a master count rate below ~1 kHz at Max. Line Speed; advice: ratio outside 5:1 .. 1:5.
    """
    pl, pc = params.get_raw("pulses_line_1000"), params.get_raw("pulses_cut_1000")
    vmax = params.get_raw("max_line_speed")
    cls = encoder_ratio_class(pl, pc)
    count_rate = line_speed_to_count_rate(vmax, pl)
    f_master = encoder_signal_frequency(vmax, pl, params.mode_counter_1)
    f_carriage = encoder_signal_frequency(vmax, pc, params.mode_counter_2)
    findings: list[Finding] = []
    if cls == RatioClass.NOT_ALLOWED:
        findings.append(
            Finding("error", "ratio", f"Error 05: Pulses Line/1000 : Pulses Cut/1000 = {pl}:{pc} is beyond 16:1 / 1:16 (§2.3, §6)")
        )
    elif cls == RatioClass.MISMATCHED:
        findings.append(
            Finding("advice", "ratio", f"ratio {pl}:{pc} is outside the acceptable 5:1 .. 1:5; consider x1/x2/x4 (§2.3)")
        )
    for label, f in (("master", f_master), ("carriage", f_carriage)):
        if f > MAX_INPUT_FREQUENCY_HZ:
            findings.append(
                Finding("warning", "max_frequency", f"{label} encoder signal {f:.0f} Hz at Max. Line Speed exceeds 400 kHz (§2.3)")
            )
    if count_rate < MIN_MASTER_FREQUENCY_HZ:
        findings.append(
            Finding("warning", "min_frequency", f"master count rate {count_rate:.1f} Hz at Max. Line Speed is below about 1 kHz (§2.3)")
        )
    return EncoderCheck(pl / pc, cls, cls == RatioClass.NOT_ALLOWED, count_rate, f_master, f_carriage, tuple(findings))


# --------------------------------------------------------------------------------------------
# virtual master (§4.2, §4.3.1, §4.3.7)

VIRTUAL_SPEED_STEPS = 2048  # "Internal resolution = 1/2048 of Max Line Speed"


def virtual_speed_quantum(max_line_speed: int) -> float:
    """The virtual master's speed resolution in LU/min: Max. Line Speed / 2048."""
    return max_line_speed / VIRTUAL_SPEED_STEPS


def virtual_speed_steps(virtual_line_speed: int, max_line_speed: int) -> int:
    """Internal speed steps (0..2048): the setting limited to Max. Line Speed, truncated."""
    if max_line_speed <= 0:
        raise ParameterError(f"Max. Line Speed {max_line_speed!r} must be positive")
    v = min(max(virtual_line_speed, 0), max_line_speed)
    return v * VIRTUAL_SPEED_STEPS // max_line_speed


def effective_virtual_line_speed(virtual_line_speed: int, max_line_speed: int) -> float:
    """Speed the virtual master really runs (LU/min): steps x Max. Line Speed / 2048."""
    return virtual_speed_steps(virtual_line_speed, max_line_speed) * max_line_speed / VIRTUAL_SPEED_STEPS


def virtual_master_count_rate(params: ParameterSet) -> float:
    """Signed increments per second the virtual master generates at its set speed
    ("Dir. Frequency": 1 = forward, 0 = reverse)."""
    v = effective_virtual_line_speed(params.get_raw("virtual_line_speed"), params.get_raw("max_line_speed"))
    rate = line_speed_to_count_rate(v, params.get_raw("pulses_line_1000"))
    return rate if params.dir_frequency == 1 else -rate


def virtual_master_acceleration(params: ParameterSet) -> float:
    """LU/s² of the virtual master ramp: Max. Line Speed in "Ramp Vir. Master" seconds
    (inf for 0 s = step)."""
    t = params.get_raw("ramp_vir_master")
    vmax = params.get_raw("max_line_speed") / 60.0
    return math.inf if t == 0 else vmax / t


# --------------------------------------------------------------------------------------------
# jog, adjust, return speed, print-mark buffer


def jog_speed(params: ParameterSet, forward: bool = True) -> float:
    """Jog speed in LU/min: Jog Speed % of Max. Line Speed (§4.3.3)."""
    pct = params.jog_speed_forw if forward else params.jog_speed_rev
    return pct / 100.0 * params.get_raw("max_line_speed")


def jog_acceleration(params: ParameterSet, forward: bool = True, up: bool = True) -> float:
    """Jog acceleration (up) or deceleration (down) in LU/s²: the ramp time is for a change
    between standstill and Max. Line Speed (§4.3.3); inf for 0 s."""
    if forward:
        t = params.jog_ramp_up_forw if up else params.jog_ramp_dw_forw
    else:
        t = params.jog_ramp_up_rev if up else params.jog_ramp_dw_rev
    vmax = params.get_raw("max_line_speed") / 60.0
    return math.inf if t == 0 else vmax / t


def adjust_default_speed(max_line_speed: int) -> float:
    """Default "Vir. Master Speed" of the Adjust program: 10 % of Max. Line Speed (§7.1)."""
    return max_line_speed * 0.10


def max_return_speed(params: ParameterSet, line_speed_lu_min: float) -> float:
    """Upper limit of the return speed (LU/min): Abs. Return Speed when not 0, else
    Rel. Return Speed x actual line speed (§4.3.1)."""
    absolute = params.get_raw("abs_return_speed")
    if absolute:
        return float(absolute)
    return params.return_speed * abs(line_speed_lu_min)


PRINTMARK_BUFFER_SIZE = 64  # cutting positions (§4.3.1, §4.3.5)


def max_printmarks_between_sensor_and_carriage(additional_cuts: int) -> int:
    """64 cutting positions shared by each mark and its additional cuts: 64, 32, 21, 16 (§4.3.5)."""
    if additional_cuts not in (0, 1, 2, 3):
        raise ParameterError(f"Additional Cuts {additional_cuts!r} is outside 0..3")
    return PRINTMARK_BUFFER_SIZE // (additional_cuts + 1)


# --------------------------------------------------------------------------------------------
# documentation


def parameter_table_markdown() -> str:
    """The parameter list as a Markdown table (for docs/)."""
    lines = [
        "| Code | Name | Attribute | Block | Min | Max | Default | Unit | Description |",
        "|---|---|---|---|---|---|---|---|---|",
    ]
    for p in PARAMETERS:
        lines.append(
            f"| 0x{p.code:04X} | {p.name} | `{p.attr}` | {BLOCKS[p.block].title} | {p.format_value(p.minimum)} | "
            f"{p.format_value(p.maximum)} | {p.format_value(p.default)} | {p.unit} | {p.description} |"
        )
    return "\n".join(lines) + "\n"
