"""The CLM1.4's parameters as data: every id, its fields in the CLM's columns, ranges, defaults.

Manual chapter 8 (L4118-5695), the transmission table Figs. 9-14..9-16 (L6590-6672), spec §5.
One row per parameter; the axis rows (``Ax00``..``Ax42``) are one table that `PARAMETERS`
expands for axes 1-4 (``A100``..``A442``), as the manual does ("The data structure is
identical for all four axes", L4146).

Fields are listed **left to right as transmitted**. The manual lists the labels of a
parameter figure from the rightmost field to the leftmost (spec §0; e.g. Ax24 "Homing Type,
Search Velocity, Search Direction, Output Homed" for ``Q1.00.0 -100 0``), so every row below
reads the manual's label list backwards; where the figure is lost the layout is reconstructed
and the reasoning is in the numbered list of `axisline.devices.clm.parameters`.

A field is one of:

* ``digit``: one decimal digit;
* ``number``: ``int_digits`` digits, then ``.`` and ``decimals`` digits when there are any,
  with a leading ``+``/``-`` when ``signed`` (``-111111.111`` is signed 6.3);
* ``operand``: a bit operand ``I1.00.0`` / ``Q1.00.2`` / ``M2.02.0``, ``00.00.0`` = none;
* ``hex``: upper-case hex digits (B019's memory address);
* ``sign``: a lone ``+``/``-`` (Ax24's search direction, written against its velocity).

``glued`` marks a field written without a blank before it (B018's seven output-byte digits,
Ax24's ``-100``). ``allowed`` (a set of values) or ``low``/``high`` (a range) say what the
CLM accepts; a field with neither is not range-checked (reserved, "in preparation", or its
meaning is lost with the figure). Ranges are checked only when the parameter is in use (see
`ParameterSet.used`).
"""

from __future__ import annotations

from dataclasses import dataclass
from decimal import Decimal

__all__ = ["AXIS_ROWS", "GENERAL_ROWS", "ENCODER_ROWS", "MIN_MAX", "Field", "Row"]

Limit = int | Decimal


@dataclass(frozen=True, slots=True)
class Field:
    name: str
    kind: str  # 'digit' | 'number' | 'operand' | 'hex' | 'sign'
    int_digits: int = 1  # digits of a digit / number / hex field
    decimals: int = 0
    signed: bool = False
    glued: bool = False
    allowed: tuple[Limit, ...] | None = None
    low: Limit | None = None
    high: Limit | None = None
    unit: str = ""
    meaning: str = ""

    @property
    def columns(self) -> int:
        """The field's width in the CLM's columns."""
        if self.kind == "operand":
            return 7
        if self.kind == "sign":
            return 1
        return int(self.signed) + self.int_digits + (self.decimals + 1 if self.decimals else 0)

    @property
    def form(self) -> str:
        """The field's column form, as the manual draws it: ``+dddddd.ddd``, ``Q1.00.0``."""
        if self.kind == "operand":
            return "I1.00.0 (00.00.0 = none)"
        if self.kind == "sign":
            return "+ or -"
        if self.kind == "hex":
            return "h" * self.int_digits
        head = ("+" if self.signed else "") + "d" * self.int_digits
        return f"{head}.{'d' * self.decimals}" if self.decimals else head

    @property
    def checked(self) -> bool:
        return self.allowed is not None or self.low is not None or self.high is not None

    def range_text(self) -> str:
        if self.allowed is not None:
            return ", ".join(str(v) for v in self.allowed)
        lo = "" if self.low is None else str(self.low)
        hi = "" if self.high is None else str(self.high)
        return f"{lo}..{hi}"


@dataclass(frozen=True, slots=True)
class Row:
    """One parameter of the manual: ``key`` is ``B002``, ``Ax01`` or ``C000``."""

    key: str
    name: str
    fields: tuple[Field, ...]
    default: str  # the default data in CLM columns
    lines: str  # where the manual describes it
    sample: str  # the line of its sample telegram (Figs. 9-14..9-16)
    restricted: bool = False  # '*': "only with permission of the machine builder" (L5614)


# -- field builders: the table reads like the manual's figures --------------------------------------


def digit(name: str, allowed: tuple[int, ...] | None = None, meaning: str = "", *, glued: bool = False, low: int | None = None, high: int | None = None) -> Field:
    return Field(name, "digit", 1, allowed=allowed, low=low, high=high, meaning=meaning, glued=glued)


def number(
    name: str,
    int_digits: int,
    decimals: int = 0,
    *,
    signed: bool = False,
    low: Limit | None = None,
    high: Limit | None = None,
    allowed: tuple[Limit, ...] | None = None,
    unit: str = "",
    meaning: str = "",
    glued: bool = False,
) -> Field:
    return Field(name, "number", int_digits, decimals, signed, glued, allowed, low, high, unit, meaning)


def operand(name: str, meaning: str) -> Field:
    return Field(name, "operand", meaning=meaning)


def instruction(name: str, meaning: str) -> Field:
    """An NC instruction number 0000-2999 ("greater than 2999" is refused, L6818)."""
    return number(name, 4, low=0, high=2999, meaning=meaning)


def _d(text: str) -> Decimal:
    return Decimal(text)


ON_OFF = (0, 1)

# Fig. 8-15 "Parameter Input Range" (L5678-5695), exactly: key -> (designation, unit, min, max).
# Ax05's row is blank in the manual; its range is in the Ax05 text (L4352-4353).
MIN_MAX: dict[str, tuple[str, str, Decimal | None, Decimal | None]] = {
    "Ax01": ("Feed Constant", "IU", _d("0.0100"), _d("5000.00000")),
    "Ax05": ("Modulo Value", "IU", None, None),
    "Ax06": ("Maximum Velocity", "IU/s", _d("0.100"), _d("50000.000")),
    "Ax07": ("Jog Velocity", "IU/s", _d("0.100"), _d("50000.000")),
    "Ax08": ("Acceleration", "IU/sec²", _d("1"), _d("999999")),
    "Ax10": ("Jerk Constant", "", _d("0.000"), _d("1.024")),
    "Ax11": ("KV Factor", "", _d("0.01"), _d("20.00")),
    "Ax12": ("Drive Sensitivity", "Volts", _d("0.5"), _d("10.0")),
    "Ax19": ("Encoder Data", "", _d("100"), _d("10000")),
    "C000": ("Master Encoder 1, Data", "", _d("100"), _d("10000")),
    "C002": ("Master Encoder 1, Feed Constant", "IU", _d("0.0100"), _d("5000.00000")),
    "C004": ("Master Encoder 2, Data", "", _d("100"), _d("10000")),
    "C006": ("Master Encoder 2, Feed Constant", "IU", _d("0.0100"), _d("5000.00000")),
}


def _min(key: str) -> Decimal:
    low = MIN_MAX[key][2]
    assert low is not None
    return low


def _max(key: str) -> Decimal:
    high = MIN_MAX[key][3]
    assert high is not None
    return high


BAUD_RATES = (0, 300, 600, 1200, 2400, 4800, 9600, 19200, 38400, 57600, 115200)  # L6313-6327
CYCLE_TIMES = tuple(_d(t) for t in ("0.0", "1.0", "1.1", "1.2", "1.3", "1.4", "1.5", "1.6", "1.7", "1.8", "1.9", "2.0", "2.5", "3.0", "3.5", "4.0"))  # L5097-5119


def _interface_format() -> tuple[Field, ...]:
    """B002 / B004 (L5018-5052, L6307-6327)."""
    return (
        number("baud_rate", 6, allowed=BAUD_RATES, unit="baud", meaning="000000 = interface off (L6327)"),
        digit("function", ON_OFF, "0 = data interface, 1 = decade switch IDS01 (L6301; reconstructed)"),
        digit("parity", (0, 1, 2), "0 = none, 1/2 = with parity check (L6257; which of odd/even is lost)"),
        digit("data_bits", (7, 8), "7 or 8 data bits (L6256)"),
        digit("stop_bits", (1, 2), "1 or 2 stop bits (L6258)"),
    )


def _interface_functions() -> tuple[Field, ...]:
    """B003 / B005 (L6331-6362): labels listed Reserved .. Handshake, i.e. right to left."""
    return (
        digit("handshake_checksum", (0, 1, 2, 3), "0 checksum on/RTS-CTS off, 1 off/off, 2 on/on, 3 off/on (L6349-6353)"),
        digit("confirmation", ON_OFF, "1 = send 'Y CR LF' after a complete, correct set (L6345-6362)"),
        number("station_number", 2, low=0, high=32, meaning="RS485 station 01-32 (L6343); 00 = RS232"),
        digit("auto_error_message", ON_OFF, "1 = send an error message on a fault, RS232 only (L6340)"),
        number("response_delay", 3, low=0, high=999, unit="ms", meaning="RS485 response delay, 000 = none (L6337-6338)"),
        number("reserved", 3, meaning="reserved (L6335)"),
    )


GENERAL_ROWS: tuple[Row, ...] = (
    Row("B000", "Enable Axis", (
        digit("enable_axis_2", ON_OFF, "1 = axis 2 enabled; axis 1 always works (L4158)"),
        digit("enable_axis_3", ON_OFF, "1 = axis 3 enabled (needs the 4-axis expansion, L8461)"),
        digit("enable_axis_4", ON_OFF, "1 = axis 4 enabled"),
    ), "0 0 0", "L5008-5012", "L6591"),
    Row("B001", "Display", (
        digit("language", None, "display language (index 'Language Selection 8-34'; codes lost)"),
        digit("write_protection", ON_OFF, "1 = program input via the keypad disabled (L1095)"),
    ), "0 0", "L5014-5016, L1095", "L6592"),
    Row("B002", "RS Interface Format X6", _interface_format(), "019200 0 1 8 1", "L5018-5040, L6307-6327", "L6593"),
    Row("B003", "RS Interface Functions X6", _interface_functions(), "0 1 00 0 000 000", "L6331-6362", "L6594"),
    Row("B004", "RS Interface Format X8", _interface_format(), "000000 0 0 0 0", "L5042-5052", "L6595"),
    Row("B005", "RS Interface Functions X8", _interface_functions(), "0 0 00 0 000 000", "L6331-6362", "L6596"),
    Row("B006", "Reserved (Free)", (), "", "L5054-5056", "L6597"),
    Row("B007", "Reserved (Free)", (), "", "L5058-5060", "L6598"),
    Row("B008", "Fieldbus Formats", (
        digit("process_data_format", (0, 1, 2), "Format 0/1/2: process data channel lengths (Fig. 10-4, L7568-7572)"),
        digit("hardware_system_signals", ON_OFF, "'CLM Hardware System Signal Enabled' (L5077)"),
        digit("operating_mode", (0, 3), "fieldbus operating mode 0 or 3 (3 = hardware OR Profibus inputs, L5067, L7576-7624)"),
        digit("profibus_system_signals", ON_OFF, "'Profibus System Signal Enabled' (L5073)"),
        number("slave_address", 2, low=0, high=99, meaning="slave address 1-99, 00 at delivery (L7515-7527)"),
    ), "0 0 0 0 00", "L5062-5081, L7515-7578", "L6599"),
    Row("B009", "Reserved (Free)", (), "", "L5083-5087", "L6600"),
    Row("B010", "Cycle Time", (
        number("cycle_time", 1, 1, allowed=CYCLE_TIMES, unit="ms", meaning="0.0 = 2/3/4 ms for 1-2/3/4 axes (L5113-5119)"),
    ), "0.0", "L5089-5128", "L6601"),
    Row("B011", "Start Task 2 & 3", (
        instruction("task_2_start", "start instruction of Task 2, 0000 = Task 2 not used (L3424-3428)"),
        instruction("task_3_start", "start instruction of Task 3, 0000 = Task 3 not used (L3445-3455)"),
        digit("reserved", None, "meaning lost (display '0222 0333 1', L5134; both examples write 0)"),
    ), "0000 0000 0", "L5130-5138, L3424-3455", "L6602"),
    Row("B012", "Start Task 4 & 5", (
        instruction("task_4_start", "start instruction of Task 4, 0000 = not used (L3471)"),
        instruction("task_5_start", "start instruction of Task 5, 0000 = not used (L3471)"),
    ), "0000 0000", "L5140-5150", "L6603"),
    Row("B013", "Logic Task", (), "", "L5152-5157", "L6604"),
    Row("B014", "Manual Vector", (
        operand("start_input", "rising edge starts the manual vector program (L5171)"),
        digit("start_on_mode_change", ON_OFF, "'00.00.0 1 xxxx': start only via a change of operating mode (L5171)"),
        instruction("start_instruction", "start instruction of the manual vector program (L5171)"),
    ), "00.00.0 0 0000", "L5159-5175, L3383-3389", "L6605"),
    Row("B015", "Interrupt Vector", (
        operand("interrupt_input", "00.00.0 = vector deactivated (L5198)"),
        digit("vector_mode", (0, 1, 2, 3), "0/2 inhibited during JSR, 1/3 always; 0/1 rising, 2/3 falling edge (L5190-5196)"),
        digit("interrupt_positioning", ON_OFF, "1 = a positioning in progress is interrupted (L5187-5188)"),
        instruction("interrupt_address", "interrupt program address (L5185)"),
    ), "00.00.0 0 0 0000", "L5177-5202", "L6606"),
    Row("B016", "Restart Vector", (
        instruction("restart_instruction", "start of the re-start program, 0000 = none (L5210-5212)"),
    ), "0000", "L5204-5214", "L6607"),
    Row("B017", "Analog Input / Override", (
        digit("analog_averaging", None, "0 none .. 9: averaging of the analog inputs (L5220-5231, table misaligned)"),
        digit("override_axis_1", (0, 1, 2, 3, 4, 5, 6), "0 off, 1-4 analog input 1-4, 5 binary I1.01.0-7, 6 Gray I1.01.4-7 (L5239-5245)"),
        digit("override_axis_2", (0, 1, 2, 3, 4, 5, 6), "as axis 1"),
        digit("override_axis_3", (0, 1, 2, 3, 4, 5, 6), "as axis 1"),
        digit("override_axis_4", (0, 1, 2, 3, 4, 5, 6), "as axis 1"),
        digit("reserved", None, "sixth digit of the verified sample, meaning lost"),
    ), "0 0 0 0 0 0", "L5216-5247", "L6608"),
    Row("B018", "Clear Outputs", (
        digit("fault_code_output", (0, 1, 2, 3, 4, 5, 6), "0 off, 1-6 = fault code on output byte Q1.00-Q1.05 (L5267-5281)"),
        *(
            digit(f"clear_q1_0{byte}", (0, 1, 2), "0 clear on fault/E-Stop, 1 keep until cleared, 2 never clear (L5287-5293)", glued=byte > 0)
            for byte in range(7)
        ),
    ), "0 0000000", "L5249-5452", "L6609"),
    Row("B019", "Memory Display", (
        digit("memory_display", None, "memory display setting (L5457; codes lost)"),
        Field("default_address", "hex", 6, meaning="address shown after power-on or a fault (L5457)"),
        Field("reserved", "hex", 2, meaning="meaning lost"),
        Field("reserved_2", "hex", 2, meaning="meaning lost"),
    ), "2 FF0000 00 00", "L5454-5470", "L6610"),
)

_MASTERS = (0, 1, 2, 3, 5)

AXIS_ROWS: tuple[Row, ...] = (
    Row("Ax00", "Mode", (
        digit("master", _MASTERS, "master of a synchronous/slave axis: 1-3 = axis 1-3, 5 = master encoder 1 (L4202-4226)"),
        digit("reserved", None, "fifth digit of the sample, meaning lost"),
        digit("test_mode", ON_OFF, "1 = flying cutoff test mode, material simulated (L3968)"),
        digit("mode", (0, 1, 2, 3, 4, 5), "0 normal, 1 synchronous, 2 slave, 3/4 measuring wheel V1/V2, 5 flying cutoff (L4194-4200)"),
        digit("motion_type", (0, 1, 2), "0 rotary, 1 linear, 2 rotary table (L4186-4192, L2518)"),
    ), "1 0 0 0 0", "L4182-4228", "L6615", restricted=True),
    Row("Ax01", "Feed Constant", (
        number("feed_constant", 4, 5, low=_min("Ax01"), high=_max("Ax01"), unit="IU", meaning="load travel per gear output revolution; defines the IU (L4236-4252)"),
    ), "0010.00000", "L4230-4252", "L6616", restricted=True),
    Row("Ax02", "Gear", (
        number("input_revolutions", 4, low=1, high=9999, meaning="X: input revolutions of the load gear (L4262-4276)"),
        number("output_revolutions", 4, low=1, high=9999, meaning="Y: output revolutions, X >= Y (L3565-3567)"),
    ), "0000 0000", "L4254-4278, L3560-3583", "L6617", restricted=True),
    Row("Ax03", "Minimum Travel Limit Value", (
        number("min_travel_limit", 6, 3, signed=True, unit="IU", meaning="from home, without Ax25 (L4290-4309)"),
    ), "-111111.111", "L4280-4312", "L6618"),
    Row("Ax04", "Maximum Travel Limit Value", (
        number("max_travel_limit", 6, 3, signed=True, low=_d("0"), unit="IU", meaning="always positive (L4338)"),
    ), "+100000.000", "L4314-4338", "L6619"),
    Row("Ax05", "Modulo Value", (
        number("modulo_value", 6, 3, low=_d("0.000"), high=_d("200000.000"), unit="IU", meaning="in preparation (L4346-4353)"),
        digit("direction", ON_OFF, "0 = programmed direction, 1 = shortest path (L4344-4345)"),
    ), "000000.000 0", "L4340-4353", "L6620"),
    Row("Ax06", "Maximum Velocity", (
        number("maximum_velocity", 6, 3, low=_min("Ax06"), high=_max("Ax06"), unit="IU/s", meaning="at most RPM (Ax12) / 60 x feed constant (L4363-4374)"),
    ), "000100.000", "L4355-4374", "L6621"),
    Row("Ax07", "Jog Velocity", (
        number("jog_velocity", 6, 3, low=_min("Ax07"), high=_max("Ax07"), unit="IU/s", meaning="Manual mode jog, Ax07 <= Ax06 (L4382-4388)"),
    ), "000100.000", "L4376-4388", "L6622"),
    Row("Ax08", "Acceleration Rate", (
        number("acceleration", 6, low=1, high=999999, unit="IU/s²", meaning="L4396-4400"),
    ), "000010", "L4390-4400", "L6623", restricted=True),
    Row("Ax09", "Acceleration / Deceleration Rate", (
        number("acceleration", 3, low=0, high=999, unit="‰ of Ax08", meaning="000 = Ax08 itself (L4410-4412)"),
        number("deceleration", 3, low=0, high=999, unit="‰ of Ax08", meaning="000 = Ax08 itself (L4408, L4412)"),
    ), "000 000", "L4402-4412", "L6624", restricted=True),
    Row("Ax10", "Jerk Constant", (
        number("jerk_constant", 1, 3, low=_min("Ax10"), high=_max("Ax10"), unit="s", meaning="0 = jerk limiting off (L4424-4430)"),
    ), "0.000", "L4414-4435", "L6625"),
    Row("Ax11", "Kv Factor", (
        number("kv_factor", 2, 2, low=_min("Ax11"), high=_max("Ax11"), meaning="Kv = 1: 1 mm lag at 1 m/min (L4459-4463)"),
        digit("feedforward", None, "0 off, 1 on, 2-9 on with averaging of 2..256 values (L4443-4453)"),
    ), "01.00 0", "L4437-4471", "L6626", restricted=True),
    Row("Ax12", "Drive Sensitivity", (
        number("max_encoder_speed", 5, low=1, high=9999, unit="RPM", meaning="max. encoder velocity 0001-9999 (L4478)"),
        number("command_voltage", 2, 1, low=_min("Ax12"), high=_max("Ax12"), unit="V", meaning="command value at max. velocity 00.5-10.0 (L4477)"),
    ), "03000 10.0", "L4473-4486", "L6627", restricted=True),
    Row("Ax13", "Reserved (Free)", (), "", "L4488", "L6628"),
    Row("Ax14", "Position Monitoring Window", (
        digit("monitoring_mode", (0, 1, 2, 3), "0 runaway+lag on, 1 both off, 2 runaway only, 3 lag only (L4510-4516)"),
        number("window_percent", 3, low=1, high=100, unit="%", meaning="of the maximum position deviation (L4506-4508)"),
        operand("deviation_output", "'Position error > Max. allowable deviation' (L4502-4504)"),
    ), "0 010 00.00.0", "L4492-4579", "L6629"),
    Row("Ax15", "Feed Angle Monitoring / Interrupt", (
        operand("feed_angle_input", "no signal: no feed; drop during feed: error (L4589-4597)"),
        operand("interrupt_input", "no signal: positioning held until it returns (L4599-4607)"),
    ), "00.00.0 00.00.0", "L4581-4607", "L6630"),
    Row("Ax16", "Encoder Difference", (
        number("window_1", 2, meaning="measuring wheel vs drive encoder: error 'Encoder Fault Ax'; 00 = off (L4615, L4621)"),
        number("window_2", 2, meaning="output 'Tolerance 2 exceeded'; 00 = off (L4617, L4621)"),
        operand("tolerance_2_output", "'Monitoring Window 2 Tolerance exceeded' (L4617, L6129)"),
    ), "00 00 00.00.0", "L4609-4621", "L6631"),
    Row("Ax17", "Absolute Encoder Monitoring Window", (
        number("monitoring_window", 4, 3, unit="IU", meaning="not described in the manual (L4623)"),
    ), "0000.000", "L4623", "L6632"),
    Row("Ax18", "Reserved (Free)", (), "", "L4627", "L6633"),
    Row("Ax19", "Encoder Data", (
        number("pulses", 5, meaning="pulses per revolution, or resolution bits for single-turn (L4646-4651)"),
        number("revolutions", 4, meaning="multi-turn revolutions, single-turn bits, rotary table ratio (L4635-4644, L3521)"),
    ), "01024 1024", "L4631-4659", "L6634"),
    Row("Ax20", "Encoder Type", (
        digit("encoder_number", None, "as C001's encoder number (L5508); meaning for an axis lost"),
        digit("encoder_type", (0, 1, 2, 3), "0 incremental, 1 single-turn, 2 multi-turn absolute, 3 controlled axis (L4655-4657, L8499)"),
        number("data_bits", 2, meaning="absolute encoder data bits: single-turn 12-21, multi-turn 21-24 (L4656-4659)"),
        digit("track_monitoring", ON_OFF, "0 = enabled, 1 = disabled (as C001, L5499-5500)"),
    ), "0 0 00 1", "L4661-4667", "L6635"),
    Row("Ax21", "Drive Direction", (
        digit("encoder_direction", None, "not 0 = count the encoder the other way (figure lost; L8731 'designated direction for position detection', axis.py decision 27)"),
        digit("output_direction", None, "not 0 = turn the analog output's polarity (L8731 'for the analog output', axis.py decision 27)"),
        digit("direction_3", None, "figure lost; no function in axisline (axis.py decision 27)"),
    ), "0 0 0", "L4669-4676", "L6636"),
    Row("Ax22", "Absolute Encoder Home Position", (
        number("reserved", 2, meaning="in preparation (L4680)"),
        number("home_position", 6, 3, signed=True, unit="IU", meaning="in preparation (L4680)"),
    ), "00 +000000.000", "L4678-4686", "L6637"),
    Row("Ax23", "Homing I/O", (
        operand("homing_input", "rising edge starts homing in Manual; 00.00.0 = HOM only (L4696-4700)"),
        operand("home_switch_input", "the home switch cam (L4694)"),
    ), "00.00.0 00.00.0", "L4688-4704", "L6638"),
    Row("Ax24", "Homing Search Distance", (
        operand("homed_output", "set when the axis is homed (L4726, L3713)"),
        Field("search_direction", "sign", meaning="+/- (L4724)"),
        number("search_velocity", 3, low=0, high=999, unit="‰ of Ax06", meaning="L4722", glued=True),
        digit("homing_type", (0, 1, 2, 3, 4), "0-4 = Options 1-5 (L4712-4720)"),
    ), "00.00.0 -100 0", "L4706-4741", "L6639"),
    Row("Ax25", "Homing Offset", (
        number("homing_offset", 5, 3, signed=True, unit="IU", meaning="shift of the zero point after homing (L4749-4754)"),
    ), "-00000.000", "L4743-4754", "L6640"),
    Row("Ax26", "Reserved (Free)", (), "", "L4756-4759", "L6641"),
    Row("Ax27", "Switching Threshold", (
        operand("position_reached_output", "'Position reached'; 00.00.0 = no output (L4769-4770)"),
        number("switching_threshold", 4, 3, unit="IU", meaning="PSA/PSI completion window (L4767-4774, L2309)"),
    ), "00.00.0 0010.000", "L4761-4774", "L6642"),
    Row("Ax28", "Position Window", (
        operand("position_window_output", "'Axis is in the last programmed position'; in preparation (L4778-4786)"),
        number("position_window", 4, 3, unit="IU", meaning="in preparation"),
    ), "00.00.0 0000.000", "L4776-4786", "L6643"),
    Row("Ax29", "Presignaling", (
        operand("presignal_output", "00.00.0 = presignaling not activated (L4800-4802)"),
        number("pulse_time", 1, 1, unit="s", meaning="output time, 0.0 = constant signal (L4796-4798)"),
        number("distance", 4, unit="IU", meaning="distance from the target (L4794)"),
    ), "00.00.0 1.0 0000", "L4788-4808", "L6644"),
    Row("Ax30", "Open Feed Roll", (
        operand("open_feed_roll_input", "00.00.0 = function not programmed (L4818, L3807)"),
        operand("open_feed_roll_output", "'Open Feed Roll Enabled' (L4816)"),
    ), "00.00.0 00.00.0", "L4810-4820", "L6645"),
    Row("Ax31", "Measuring Wheel Mode", (
        operand("measuring_wheel_active_input", "00.00.0 = measuring wheel always active (L4828-4829)"),
    ), "00.00.0", "L4822-4831", "L6646"),
    Row("Ax32", "Various Functions", (
        operand("velocity_reached_output", "'Target Velocity Reached' (L4840)"),
        operand("deceleration_active_output", "'Deceleration Active' (L4839)"),
    ), "00.00.0 00.00.0", "L4833-4840", "L6647"),
    Row("Ax33", "Cut Inhibit", (
        operand("cut_inhibit_input", "flying cutoff, axis 1 (L4849-4855)"),
        operand("cut_inhibit_output", "flying cutoff, axis 1 (L4848)"),
    ), "00.00.0 00.00.0", "L4842-4855", "L6648"),
    Row("Ax34", "Cut Vector", (
        operand("immediate_cut_input", "00.00.0 = off (L4871-4877)"),
        instruction("manual_cut_start", "start instruction of the manual cut vector program (L4869)"),
        digit("indexing", ON_OFF, "1 = indexing activated (L4863-4867)"),
    ), "00.00.0 0100 0", "L4857-4893", "L6649"),
    Row("Ax35", "Reverse Inhibit", (
        operand("reverse_inhibit_input", "00.00.0 = off (L4903-4906)"),
        number("reserved", 5, meaning="reserved (L4901)"),
    ), "00.00.0 00000", "L4895-4908", "L6650"),
    Row("Ax36", "Rapid Stop", (
        operand("rapid_stop_input", "00.00.0 = off (L4918-4925)"),
        instruction("rapid_stop_start", "start of the rapid stop program, 0000 = none (L4916, L4927)"),
    ), "00.00.0 0000", "L4910-4929", "L6651"),
    Row("Ax37", "Maximum Stroke", (
        number("maximum_stroke", 5, unit="IU", meaning="stroke length; figure lost (L4935)"),
        instruction("maximum_stroke_start", "start of the retract program, 0000 = none (L4935-4937)"),
    ), "00000 0000", "L4931-4945", "L6652"),
    Row("Ax38", "Functions 2", (
        operand("start_at_0000_input", "signal in Manual: next Automatic starts at 0000 (L4960)"),
        digit("always_start_at_0000", ON_OFF, "'Always begin user program in Instruction 0000' (L4957-4959)"),
        digit("raster_detection", ON_OFF, "LMR/LMK raster by level or by edge (L4955; which is 0 is lost)"),
    ), "00.00.0 0 0", "L4947-4964", "L6653"),
    Row("Ax39", "Reverse Optimization 1", (
        operand("reverse_optimization_input", "L5964"),
        operand("reverse_optimization_output", "L6128"),
    ), "00.00.0 00.00.0", "L4966-4968, L5964, L6128", "L6654"),
    Row("Ax40", "Reverse Optimization 2", (
        number("wait_time", 1, 2, unit="s", meaning="wait in the original position (L4978)"),
        number("velocity_window", 3, meaning="material velocity rise that switches to Ax08 (L4976)"),
        number("minimum_acceleration", 3, meaning="minimum reverse acceleration (L4974)"),
    ), "0.00 000 000", "L4970-4978", "L6655"),
    Row("Ax41", "Tool Width", (
        number("tool_width", 2, 2, unit="IU", meaning="added to the LML length (L4986-4988)"),
    ), "00.00", "L4980-4990", "L6656"),
    Row("Ax42", "Crop Cut", (
        number("crop_cut_length", 4, 2, unit="IU", meaning="L5000-5002"),
        operand("crop_cut_input", "00.00.0 = off (L4998-4999)"),
    ), "0000.00 00.00.0", "L4992-5004", "L6657"),
)


def _encoder_type() -> tuple[Field, ...]:
    """C001 / C005 (L5481-5513): labels listed Averaging .. Encoder number, i.e. right to left."""
    return (
        digit("encoder_number", None, "5 = master encoder 1 is incremental encoder 5, X1 (L5508-5509)"),
        digit("encoder_type", (0, 1, 2), "0 incremental, 1 single-turn, 2 multi-turn (1, 2 in preparation, L5504-5506)"),
        number("data_bits", 2, meaning="absolute encoder data bits, in preparation (L5502)"),
        digit("track_monitoring", ON_OFF, "0 = enabled, 1 = disabled (L5499-5500)"),
        digit("encoder_direction", ON_OFF, "0 = do not turn, 1 = turn (L5495-5497)"),
        digit("averaging", (0, 1, 2, 3, 4, 5, 6, 7), "master pulses, 0 off, 1-7 = 2..128 values, flying cutoff (L5485-5493)"),
    )


ENCODER_ROWS: tuple[Row, ...] = (
    Row("C000", "Master Encoder 1, Data", (
        number("graduation", 5, low=int(_min("C000")), high=int(_max("C000")), meaning="pulses per encoder revolution (L5479)"),
        number("revolutions", 4, meaning="absolute encoder, in preparation (L5478)"),
    ), "01250 0000", "L5474-5479", "L6662"),
    Row("C001", "Master Encoder 1, Type", _encoder_type(), "0 0 00 0 0 0", "L5481-5513", "L6663"),
    Row("C002", "Master Encoder 1, Feed Constant", (
        number("feed_constant", 4, 5, low=_min("C002"), high=_max("C002"), unit="IU", meaning="L5521-5523"),
    ), "0020.00000", "L5515-5523", "L6664"),
    Row("C003", "Master Encoder 1, Offset", (
        number("offset", 5, 3, signed=True, unit="IU", meaning="'currently has no function' (L5531)"),
    ), "+00000.000", "L5525-5531", "L6665"),
    Row("C004", "Master Encoder 2, Data", (
        number("graduation", 5, low=int(_min("C004")), high=int(_max("C004")), meaning="pulses per encoder revolution (L5541)"),
        number("revolutions", 4, meaning="absolute encoder, in preparation (L5539)"),
    ), "01250 0000", "L5533-5541", "L6666"),
    Row("C005", "Master Encoder 2, Type", _encoder_type(), "0 0 00 0 0 0", "L5543-5547", "L6667"),
    Row("C006", "Master Encoder 2, Feed Constant", (
        number("feed_constant", 4, 5, low=_min("C006"), high=_max("C006"), unit="IU", meaning="L5553-5555"),
    ), "0000.00000", "L5549-5555", "L6668"),
    Row("C007", "Master Encoder 2, Offset", (
        number("offset", 5, 3, signed=True, unit="IU", meaning="'currently has no function' (L5561)"),
    ), "+00000.000", "L5557-5561", "L6669"),
    Row("C008", "Master Encoder 1, Internal", (
        operand("no_material_input", "material speed from the variable while set; 00.00.0 = off (L5571-5576)"),
        number("material_speed_variable", 3, meaning="variable number (610 = V610) with the speed in IU/s (L5569)"),
    ), "00.00.0 000", "L5563-5582", "L6670"),
)
