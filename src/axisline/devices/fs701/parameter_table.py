"""The FS701's parameter list as data (manual §11): the blocks, one `Parameter` per row with
its range, default, unit and serial code, and the lookup by name or code. The `ParameterSet`
that holds values is in parameters.py, whose docstring has the decisions on the list.
"""

from __future__ import annotations

import math
import re
from collections.abc import Mapping
from dataclasses import dataclass, field
from decimal import Decimal, InvalidOperation
from typing import Any

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
