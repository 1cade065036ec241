"""The 512-byte configuration table of the 750-672 (manual §4.6, §3.10.2; wago.md §4).

Every address is an entry of `ENTRIES` (data, not code): address, the manual's name, type,
FACTORY_DEFAULT value, allowed range, unit/meaning and the device's error code for a value
outside the range where the manual names one. The table tiles 0..511 without gaps:

    0 .. 127    direct parameters
    128 .. 223  pointer table: config byte N = source bit of linkable target bit N (Ptr_<name>)
    224 .. 376  filters, trace, ident, reserved
    380 .. 511  extended parameters (current controller, supply monitoring, target windows)

Values are little-endian ("the lowest value byte occupies the given address", §3.10.2).
`ConfigTable` gives typed access by name and by address, byte access for the mailbox's
CONFIG_SET_PTR/CONFIG_WR/CONFIG_RD (1 .. 4 bytes, else 1161 CONFIG_WRITE_SIZE), a check of
the cross-field rules (`validate`: current-controller password 1162, supply limits 1817),
atomic save/load of the whole table (a 512-byte data set, 128 x 32 bit as the configuration
download of §3.9) and restore of the FACTORY_DEFAULT values.

A rejected write leaves the table as it was: every affected entry is checked first, then
all are stored.

Decisions (wago.md §4.1/§4.2):
* [AMBIGUOUS] addresses 8..13 are not documented: three reserved UINT16 that read 0 and
  accept and drop writes.
* [CONFLICT] defaults Freq_Div 40 / Acc_Fact 1000 (§4.6) against 200 / 80 (§3.10.2 excerpt):
  the §4.6 values are the FACTORY_DEFAULT here; `ConfigTable(defaults={...})` takes others.
* Freq_Div and Acc_Fact accept 0 besides their printed ranges: C2 '00' with Freq_Div = 0 gives
  the prescaler 200, with Acc_Fact = 0 the factor 8 (§3.7.2, §3.10.1), so 0 is a valid setting.
* SetupSpeed accepts 0 ("When the value 0 is specified, a 1 value is automatically accepted",
  §4.6); the module runs jog at speed 1 then.
* Drive_Range_Pos range printed "+0x7fffffff ... 0x7fffffff": taken as -8388607 .. 8388607,
  like Drive_Range_Neg (24-bit positions).
* Reference_Offset is printed UINT32 with range ±8388607: stored signed (INT32).
* Acceleration_Modes: a reserved value 3 in any of the four 2-bit fields is rejected with
  1557 MCALC_PARA (the movement calculator could not use it).
* Reserved entries keep what is written (within their printed range); they have no effect.
"""

from __future__ import annotations

import itertools
import os
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from pathlib import Path

from axisline.kernel.atomic import atomic_write_bytes

__all__ = [
    "TABLE_SIZE",
    "CONF_VERSION",
    "TYPES",
    "ConfigEntry",
    "ENTRIES",
    "ConfigValueError",
    "ConfigTable",
    "current_password",
]

TABLE_SIZE = 512
CONF_VERSION = 4  # ConfVersion of the data sets this software reads (state variable 15)

# type -> (size in bytes, signed)
TYPES: dict[str, tuple[int, bool]] = {
    "UINT8": (1, False),
    "INT8": (1, True),
    "UINT16": (2, False),
    "INT16": (2, True),
    "UINT32": (4, False),
    "INT32": (4, True),
}


@dataclass(frozen=True, slots=True)
class ConfigEntry:
    """One configuration variable. `allowed`: extra admissible values outside lo..hi."""

    address: int
    name: str
    type: str
    default: int
    lo: int
    hi: int
    meaning: str = ""
    error_code: int | None = None  # the device's code for a value outside the range
    allowed: tuple[int, ...] = ()
    multiple_of: int = 1  # Motor_Steps_per_Rev must be divisible by 4
    ignored: bool = False  # undocumented bytes: read 0, writes dropped

    @property
    def size(self) -> int:
        return TYPES[self.type][0]

    @property
    def signed(self) -> bool:
        return TYPES[self.type][1]

    @property
    def range_text(self) -> str:
        text = f"{self.lo} .. {self.hi}"
        if self.allowed:
            text += " or " + ", ".join(str(a) for a in self.allowed)
        if self.multiple_of != 1:
            text += f" (a multiple of {self.multiple_of})"
        return text

    def admits(self, value: int) -> bool:
        if value in self.allowed:
            return True
        return self.lo <= value <= self.hi and value % self.multiple_of == 0


def _type_range(t: str) -> tuple[int, int]:
    size, signed = TYPES[t]
    bits = 8 * size
    return (-(1 << (bits - 1)), (1 << (bits - 1)) - 1) if signed else (0, (1 << bits) - 1)


def _e(addr, name, t, default, lo=None, hi=None, meaning="", code=None, **kw) -> ConfigEntry:
    tlo, thi = _type_range(t)
    return ConfigEntry(addr, name, t, default, tlo if lo is None else lo, thi if hi is None else hi, meaning, code, **kw)


_U24 = 16777215
_P24 = 8388607

# ------------------------------------------------------------------ 0 .. 127 direct parameters
_DIRECT = [
    _e(0, "User_Conf_Id", "UINT16", 0, 0, 50000, "dataset number, freely assignable; > 50000 reserved"),
    _e(2, "ConfVersion", "UINT8", CONF_VERSION, 0, 254, "structure version of the data set; only known versions are read"),
    _e(3, "Application_Selector", "UINT8", 1, 1, 1, "1: positioning controller (the only application of the 750-672)", 1214),
    _e(4, "Freq_Div", "UINT16", 40, 4, 32767, "frequency prescaler when Freq_Range_Sel = '00' (0: 200); f_max = 2 MHz / Freq_Div", 1216, allowed=(0,)),
    _e(6, "Acc_Fact", "UINT16", 1000, 1, 32767, "acceleration factor when Acc_Range_Sel = '00' (0: 8)", allowed=(0,)),
    _e(8, "Reserved_8", "UINT16", 0, meaning="not documented (wago.md §4.1): reads 0, writes dropped", ignored=True),
    _e(10, "Reserved_10", "UINT16", 0, meaning="not documented: reads 0, writes dropped", ignored=True),
    _e(12, "Reserved_12", "UINT16", 0, meaning="not documented: reads 0, writes dropped", ignored=True),
    _e(14, "Current", "UINT8", 50, 0, 50, "motor rated current (peak) [0.1 A]", 1213),
    _e(15, "Current_Ratio_StandStill", "UINT8", 33, 0, 150, "current at standstill [% of Current]; 0 blocks the modulation", 1217),
    _e(16, "Current_Ratio_RampUp", "UINT8", 100, 0, 150, "current in the acceleration phase [% of Current]", 1217),
    _e(17, "Current_Ratio_Drive", "UINT8", 50, 0, 150, "current at constant speed [% of Current]", 1217),
    _e(18, "Current_Ratio_RampDown", "UINT8", 100, 0, 150, "current in the deceleration phase [% of Current]", 1217),
    _e(19, "HwSwConfig", "UINT8", 0, 0, 255, "bit 2 Drive_Direction (1: rotation inverted), bit 7 Program_Autostart"),
    _e(20, "Pos_Mult", "UINT16", 1, 1, 65535, "position scaling: internal = external * Pos_Mult / Pos_Div", 1517),
    _e(22, "Pos_Div", "UINT16", 1, 1, 65535, "position scaling divisor", 1517),
    _e(24, "Enc_Mult", "UINT16", 1, 1, 65535, "reserved (encoder scaling, 750-673)", 1517),
    _e(26, "Enc_Div", "UINT16", 1, 1, 65535, "reserved (encoder scaling, 750-673)", 1517),
    _e(28, "Speed_Mult", "UINT16", 1, 1, 65535, "speed scaling multiplier", 1517),
    _e(30, "Speed_Div", "UINT16", 1, 1, 65535, "speed scaling divisor", 1517),
    _e(32, "Acc_Mult", "UINT16", 1, 1, 65535, "acceleration scaling multiplier", 1517),
    _e(34, "Acc_Div", "UINT16", 1, 1, 65535, "acceleration scaling divisor", 1517),
    _e(36, "Reserved_36", "UINT16", 0),
    _e(38, "Reserved_38", "UINT16", 0),
    _e(40, "Speed", "INT16", 3000, 1, 25000, "default positioning speed of move commands until SET_VELOCITY", 1117),
    _e(42, "Speed_Limit", "INT16", 25000, 1, 25000, "maximum speed; a faster set point turns the drive off (1212)", 1211),
    _e(44, "SetupSpeed", "INT16", 3000, 0, 25000, "jog and referencing speed; 0 runs at 1", 1211),
    _e(46, "Acceleration_Stop_Fast", "INT16", 30000, 0, 32767, "STOP deceleration (Stop1_N/Stop2_N, limit switches, mode exit); 0: current acceleration", 1121),
    _e(48, "Acceleration_RampUp", "INT16", 1000, 0, 32767, "default acceleration of the acceleration phase", 1121),
    _e(50, "Acceleration_RampDown", "INT16", 1000, 0, 32767, "default acceleration of the deceleration phase", 1121),
    _e(52, "Acceleration_RampUp_Param", "INT32", 300, 0, 16777216, "Acc_ParamUp: jerk time [ms] / ramp time [ms] / ramp path [position units]", 1557),
    _e(56, "Acceleration_RampDown_Param", "INT32", 300, 0, 16777216, "Acc_ParamDown: jerk time [ms] / ramp time [ms] / ramp path [position units]", 1557),
    _e(60, "Acceleration_Modes", "UINT8", 0, 0, 255, "b0-1 AccType, b2-3 AccParam, b4-5 DecType, b6-7 DecParam (3 reserved)", 1557),
    _e(61, "Current_Ratio_Stop", "UINT8", 150, 0, 150, "current in STOP mode [% of Current]", 1217),
    _e(62, "SetupAcceleration", "UINT16", 1000, 0, 32767, "acceleration of jog and referencing", 1121),
    _e(64, "Rotary_Axis_Period", "INT32", 0, 0, 16777216, "microsteps per turn of a rotary axis; 0: linear axis"),
    _e(68, "Drive_Range_Neg", "INT32", -_P24, -_P24, _P24, "software limit, negative direction [position units]"),
    _e(72, "Drive_Range_Pos", "INT32", _P24, -_P24, _P24, "software limit, positive direction [position units]"),
    _e(76, "Reserved_76", "UINT32", 0),
    _e(80, "Reserved_80", "UINT32", 0),
    _e(84, "PWM_Period", "UINT32", 0, meaning="no meaning"),
    _e(88, "Camshaft_Ch9_Start", "INT32", 0, -_P24, _P24, "CAM9 starting edge [microsteps]", 1331),
    _e(92, "Camshaft_Ch9_Period", "INT32", 100, 1, _P24, "CAM9 period [microsteps]; 0 is rejected", 1331),
    _e(96, "Camshaft_Ch9_Pulsewidth", "INT32", 50, 0, _P24, "CAM9 pulse width [microsteps]", 1331),
    _e(100, "Braketime_Turn_On", "UINT32", 0, 0, _P24, "brake make time [ms]: delay of a start with the brake applied"),
    _e(104, "Braketime_Turn_Off", "UINT32", 0, 0, _P24, "brake break time [ms]: brake applied this long before the target"),
    _e(108, "Reference_Offset", "INT32", 0, -_P24, _P24, "reference switch position [position units] (reference edge, SetActual_Pos)"),
    _e(112, "Reference_Mode", "UINT8", 0, 0, 255, "b0: 0 reference switch, 1 limit switch; b1: 0 negative end, 1 positive end"),
    _e(113, "ErrorNotificationMode", "UINT8", 0x06, 0, 255, "b0 SystemFlagEnable (errors on S0.6), b1 OverTemperature as error, b2 MotorOff as error"),
    _e(114, "Reserved_114", "INT16", 0),
    _e(116, "WarningNotificationMode", "INT8", 0x18, meaning="b0 SystemFlagEnable (warnings on S0.6), b1 OverTemperature as warning"),
    _e(117, "Reserved_117", "INT8", 0),
    _e(118, "Reserved_118", "INT16", 0, 0, 32767),
    _e(120, "Reserved_120", "INT16", 0, 0, 32767),
    _e(122, "Reserved_122", "INT16", 0, 0, 32767),
    _e(124, "Reserved_124", "INT32", 0),
]

# ------------------------------------------------------------------ 128 .. 223 pointer table
# (address = target bit number, default = FACTORY_DEFAULT source bit), manual §4.6 / wago.md §5.2
_POINTERS: list[tuple[int, str, int]] = (
    [(128 + i, f"Ptr_KBUS_ST1_{i}", 0x10 + i) for i in range(8)]
    + [(136 + i, f"Ptr_KBUS_ST2_{i}", 0x08 + i) for i in range(8)]
    + [(144 + i, f"Ptr_KBUS_ST3_{i}", 0x30 + i) for i in range(6)]
    + [(150, "Ptr_KBUS_ST3_6", 0x05), (151, "Ptr_KBUS_ST3_7", 0x04)]
    + [(152 + i, f"Ptr_UserBit_{i}", 0x02) for i in range(8)]
    + [(160, "Ptr_OUT1", 0x08), (161, "Ptr_OUT2", 0x0F)]
    + [(162 + i, f"Reserved_{162 + i}", 0x00) for i in range(6)]
    + [(168 + i, f"Ptr_FILT{i + 1}", 0x00) for i in range(8)]
    + [(176, "Ptr_Enable", 0x40), (177, "Ptr_Stop2_N", 0x41), (178, "Ptr_Start", 0x42)]
    + [(179 + i, f"Ptr_Command[{i + 1}]", 0x43 + i) for i in range(5)]
    + [
        (184, "Ptr_Enable_Drive", 0x01),
        (185, "Ptr_Reset_Quit", 0x57),
        (186, "Ptr_Direction_Pos", 0x52),
        (187, "Ptr_Direction_Neg", 0x53),
        (188, "Ptr_Set_Reference", 0x31),
        (189, "Ptr_PreCalc", 0x4E),
        (190, "Ptr_SetupSpeed_Active", 0x02),
        (191, "Ptr_Error_Quit", 0x4F),
        (192, "Ptr_LimitSwitch_Pos", 0x34),
        (193, "Ptr_LimitSwitch_Neg", 0x35),
        (194, "Ptr_Stop1_N", 0x30),
        (195, "Break_Manual", 0x02),  # the manual's spelling (Brake_Manual, bit 0xC3)
        (196, "Ptr_Freq_Range_Sel_0", 0x48),
        (197, "Ptr_Freq_Range_Sel_1", 0x49),
        (198, "Ptr_Acc_Range_Sel_0", 0x4A),
        (199, "Ptr_Acc_Range_Sel_1", 0x4B),
        (200, "Ptr_Set_Actual_POS", 0x50),
        (201, "Reserved_201", 0x00),
        (202, "Ptr_Jog_Pos", 0x32),
        (203, "Ptr_Jog_Neg", 0x33),
    ]
    + [(204 + i, f"Reserved_{204 + i}", 0x00) for i in range(4)]
    + [
        (208, "Ptr_LED_B", 0x09),
        (209, "Ptr_LED_C", 0x1B),
        (210, "Ptr_LED_D", 0x11),
        (211, "Ptr_LED_A", 0x19),
        (212, "Ptr_LED_E", 0x26),
        (213, "Ptr_LED_F", 0x27),
    ]
    + [(214 + i, f"Reserved_{214 + i}", 0x00) for i in range(7)]
    + [(221, "Reserved_221", 0x00), (222, "Ptr_Trace_Trigger", 0x09), (223, "Ptr_Trace_Armed", 0x03)]
)
_POINTER_ENTRIES = [
    _e(a, n, "UINT8", d, 0, 255, f"source bit of linkable bit {a:#04x}" + (" (Error_Set)" if a == 221 else ""))
    for a, n, d in _POINTERS
]

# ------------------------------------------------------------------ 224 .. 376
_FILTER_FUNCTIONS = (
    "0 no filtering, 1 inversion, 2 start edge, 3 low pass, 4 pulse expansion, 5 monoflop, 6 delay, "
    "7 arithmetic, 8 counter up, 9 counter up to zero, 10 counter down, 11 counter down to zero"
)
_MIDDLE = (
    [_e(224 + i, f"Filter{i + 1}_Function", "UINT8", 0, 0, 11, _FILTER_FUNCTIONS, 1246) for i in range(8)]
    + [_e(232 + 4 * i, f"Filter{i + 1}_Time", "UINT32", 0, 0, _U24, "filter time constant [ms]") for i in range(8)]
    + [
        _e(264, "TraceVar1", "UINT32", 1, 0, _U24, "state variable 1 of the data recorder (1: actual position)"),
        _e(268, "TraceVar2", "UINT32", 2, 0, _U24, "state variable 2 of the data recorder (2: output frequency)"),
        _e(272, "TraceMsecCycleTime", "UINT32", 1, 0, _U24, "sampling period of the data recorder [ms]"),
        _e(276, "IdentNumber", "UINT32", 750672, 0, 99999999, "WAGO 8-digit ID number"),
    ]
    + [_e(a, f"Reserved_{a}", "UINT32", 0, 0, _U24) for a in range(280, 377, 4)]
)

# ------------------------------------------------------------------ 380 .. 511 extended
_EXTENDED = [
    _e(380, "MotorAlign", "UINT8", 0, meaning="no meaning (750-673)"),
    _e(381, "Fan_Config", "UINT8", 0, 0, 2, "0 normal (on above 60 degC, 10 min overtravel), 1 disabled, 2 always on"),
    _e(382, "Reserved_382", "UINT16", 0),
    _e(384, "Current_Ctrl_Hysteresis", "UINT16", 50, 0, 5000, "width of the current band [mA]"),
    _e(386, "Reserved_386", "UINT16", 0),
    _e(388, "Current_Ctrl_TZMin", "UINT16", 2, 1, 65535, "3-point controller: wait at state zero before switching band [us*4]"),
    _e(390, "Reserved_390", "UINT16", 0),
    _e(392, "Current_Ctrl_TZMax", "UINT16", 30, 1, 65535, "3-point controller: maximum time from state zero [us*4]"),
    _e(394, "Current_Pass2", "UINT16", 0xC0F0, meaning="password = 384 XOR 388 XOR 392 XOR 396 XOR 0xC0DE (else 1162)"),
    _e(396, "Current_Ctrl_Type", "UINT16", 0, 0, 1, "0 three-point, 1 two-point controller", 1859),
    _e(398, "Reserved_398", "UINT16", 0),
    _e(400, "Reserved_400", "UINT32", 0),
    _e(404, "Reserved_404", "UINT16", 0),
    _e(406, "Warn_Treshold_Temperature", "UINT16", 700, 0, 800, "output stage warning temperature [0.1 degC]"),
    _e(408, "DC_Link_Umin", "UINT16", 150, 150, 800, "minimum intermediate circuit voltage [0.1 V] (below: 1816)", 1817),
    _e(410, "DC_Link_Umax", "UINT16", 800, 0, 800, "maximum intermediate circuit voltage [0.1 V] (above: 1815)", 1817),
    _e(412, "Trace_QuickVar_Index", "UINT8", 0, meaning="index of the fast DSP variable (every 1 ms)"),
    _e(413, "Encoder_Config", "UINT8", 0, meaning="no meaning (672)"),
    _e(414, "Encoder_Config_QDECCTL", "UINT16", 0, meaning="no meaning"),
    _e(416, "Encoder_Resolution", "UINT32", 2000, 1, 6777215, "no meaning (672)", 1818),
    _e(420, "Motor_Steps_per_Rev", "UINT16", 200, 4, 10000, "full steps per motor revolution (1.8 deg: 200), divisible by 4", 1819, multiple_of=4),
    _e(422, "Reserved_422", "UINT16", 0),
    _e(424, "Reserved_424", "UINT16", 0),
    _e(426, "Encoder_IndexMeasurementJitterRange", "UINT16", 20, meaning="no meaning"),
    _e(428, "SpeedMeasureTimeA", "UINT32", 100, 0, 65535, "no meaning", 1823),
    _e(432, "SpeedMeasureTimeoutA", "UINT32", 100, 0, 65535, "no meaning", 1824),
    _e(436, "SpeedMeasureTimeV", "UINT32", 3, 0, 65535, "no meaning", 1825),
    _e(440, "SpeedMeasureTimeoutV", "UINT32", 0, 0, 65535, "no meaning", 1826),
    _e(444, "Controller_v_Kp", "UINT32", 32000, 0, 0x7FFFFFF, "no meaning"),
    _e(448, "Controller_v_ITi", "UINT32", 16000, 0, 0x7FFFFFF, "no meaning"),
    _e(452, "Controller_s_Kp", "UINT32", 2000, 0, 0x7FFFFFF, "no meaning"),
    _e(456, "Controller_s_ITi", "UINT32", 0, 0, 0x7FFFFFF, "no meaning"),
    _e(460, "Controller_s_Td", "UINT32", 0, 0, _U24, "no meaning"),
    _e(464, "Controller_s_Tddi", "UINT32", 0, 0, 0xFFFF, "no meaning"),
    _e(468, "Reserved_468", "UINT16", 0),
    _e(470, "TargetWindowSpeed", "UINT16", 2, 0, 0x7FFF, "speed window of On_Speed (and On_Target in speed control) [speed units]"),
    _e(472, "TargetWindowPosition", "UINT32", 0, 0, 0xFFFFFFFF, "position window of On_Target [position units]"),
    _e(476, "Reserved_476", "UINT32", 0, 0, _U24),
    _e(480, "Speed_Filter", "UINT16", 16384, meaning="no meaning"),
    _e(482, "TrackingError_Range_Speed", "UINT16", 100, 0, 0x7FFF, "no meaning (672)"),
    _e(484, "TrackingError_Range_Position", "UINT32", 100, meaning="no meaning (672)"),
    _e(488, "TrackingError_Delay", "UINT32", 100, meaning="no meaning"),
    _e(492, "ControllerMinLimit", "UINT16", 8, 1, 0x7FF, "input limitation of the position regulator (x16), from v3504"),
    _e(494, "Reserved_494", "UINT16", 0, meaning="not listed by the manual (between 492 UINT16 and 496)"),
    _e(496, "Reserved_496", "UINT32", 0, 0, _U24),
    _e(500, "Reserved_500", "UINT32", 0, 0, _U24),
    _e(504, "Reserved_504", "UINT32", 0, 0, _U24),
    _e(508, "Reserved_508", "UINT32", 0, 0, _U24),
]

ENTRIES: tuple[ConfigEntry, ...] = tuple(_DIRECT + _POINTER_ENTRIES + _MIDDLE + _EXTENDED)

_BY_NAME: dict[str, ConfigEntry] = {e.name: e for e in ENTRIES}
_BY_ADDRESS: dict[int, ConfigEntry] = {e.address: e for e in ENTRIES}
_OWNER: list[ConfigEntry] = []  # byte address -> entry covering it
for _entry in ENTRIES:
    if _entry.address != len(_OWNER):
        raise AssertionError(f"configuration table gap or overlap at {len(_OWNER)} ({_entry.name})")
    _OWNER.extend([_entry] * _entry.size)
if len(_OWNER) != TABLE_SIZE or len(_BY_NAME) != len(ENTRIES):
    raise AssertionError("configuration table does not tile 0..511 with unique names")
del _entry


class ConfigValueError(ValueError):
    """A configuration value outside its range (or a rule between values broken).

    `code`: the device's error code where the manual names one (else None); `field`,
    `value` and `allowed` say what was wrong.
    """

    def __init__(self, code: int | None, field: str, value: object, allowed: str, why: str = "") -> None:
        prefix = f"error {code}: " if code is not None else ""
        text = why or f"{field} = {value!r} is outside the allowed range {allowed}"
        super().__init__(prefix + text)
        self.code = code
        self.field = field
        self.value = value
        self.allowed = allowed


def current_password(hysteresis: int, tz_min: int, tz_max: int, ctrl_type: int) -> int:
    """Current_Pass2 for the current-controller parameters (§4.6, wago.md §9.8)."""
    return (hysteresis ^ tz_min ^ tz_max ^ ctrl_type ^ 0xC0DE) & 0xFFFF


def _encode(entry: ConfigEntry, value: int) -> bytes:
    return int(value).to_bytes(entry.size, "little", signed=entry.signed)


def _decode(entry: ConfigEntry, raw: bytes) -> int:
    return int.from_bytes(raw, "little", signed=entry.signed)


def _check(entry: ConfigEntry, value: object) -> int:
    if isinstance(value, bool) or not isinstance(value, int):
        raise ConfigValueError(entry.error_code, entry.name, value, entry.range_text, f"{entry.name} must be an integer, got {value!r}")
    if not entry.ignored and not entry.admits(value):
        raise ConfigValueError(entry.error_code, entry.name, value, entry.range_text)
    if entry.name == "Acceleration_Modes":
        for shift, field in ((0, "AccType"), (2, "AccParam"), (4, "DecType"), (6, "DecParam")):
            if (value >> shift) & 3 == 3:
                raise ConfigValueError(
                    1557, entry.name, value, "each 2-bit field 0 .. 2",
                    f"Acceleration_Modes = {value:#04x}: {field} = 3 is reserved (allowed 0 .. 2)",
                )
    return value


_GENERATIONS = itertools.count(1)


class _Values(dict):
    """name or address -> value, decoded at the first read after a change (`ConfigTable.values`)."""

    __slots__ = ("_table",)

    def __init__(self, table: ConfigTable) -> None:
        super().__init__()
        self._table = table

    def __missing__(self, key: str | int) -> int:
        value = self._table._read(key)  # KeyError naming the key when there is no such entry
        self[key] = value
        return value


class ConfigTable:
    """The configuration data set in RAM: 512 bytes with typed access.

    `defaults`: FACTORY_DEFAULT overrides by name (e.g. the alternative defaults of
    wago.md §4.2). `generation` changes with every change of the values, and no two tables
    share one, so the device can cache what it derives from them (the bit links).

    `values`: the values by name (or address) as a plain dict, for the device's 1 ms tick,
    which reads dozens of them: a value is decoded at its first read and kept until the next
    change. Read only: every write goes through `set`/`update`/... and their range checks.
    """

    def __init__(self, defaults: Mapping[str, int] | None = None) -> None:
        self._factory = bytearray(TABLE_SIZE)
        for e in ENTRIES:
            self._factory[e.address : e.address + e.size] = _encode(e, e.default)
        if defaults:
            staged = {}
            for name, value in defaults.items():
                e = self.entry(name)
                staged[e] = _check(e, value)
            for e, value in staged.items():
                self._factory[e.address : e.address + e.size] = _encode(e, value)
        self._data = bytearray(self._factory)
        self.values = _Values(self)
        self.generation = next(_GENERATIONS)

    def _changed(self) -> None:
        self.values.clear()
        self.generation = next(_GENERATIONS)

    # ---- lookup
    @staticmethod
    def entry(key: str | int) -> ConfigEntry:
        """The entry named `key`, or the one starting at address `key`."""
        if isinstance(key, str):
            e = _BY_NAME.get(key)
            if e is None:
                raise KeyError(f"no configuration variable named {key!r}")
            return e
        if isinstance(key, bool) or not isinstance(key, int):
            raise KeyError(f"configuration key must be a name or an address, got {key!r}")
        e = _BY_ADDRESS.get(key)
        if e is None:
            if 0 <= key < TABLE_SIZE:
                owner = _OWNER[key]
                raise KeyError(f"address {key} lies inside {owner.name} (address {owner.address}, {owner.size} bytes)")
            raise KeyError(f"address {key} is outside the configuration table 0 .. {TABLE_SIZE - 1}")
        return e

    @staticmethod
    def entries() -> tuple[ConfigEntry, ...]:
        return ENTRIES

    # ---- typed access
    def get(self, key: str | int) -> int:
        return self.values[key]

    def _read(self, key: str | int) -> int:
        e = self.entry(key)
        return 0 if e.ignored else _decode(e, bytes(self._data[e.address : e.address + e.size]))

    __getitem__ = get

    def set(self, key: str | int, value: int) -> None:
        """Store one value after its range check (ConfigValueError names field, value, range)."""
        e = self.entry(key)
        value = _check(e, value)
        if e.ignored:
            return
        self._data[e.address : e.address + e.size] = _encode(e, value)
        self._changed()

    __setitem__ = set

    def update(self, values: Mapping[str, int] | Iterable[tuple[str | int, int]]) -> None:
        """Set several values: all are checked before any is stored."""
        items = list(values.items()) if isinstance(values, Mapping) else list(values)
        staged = [(self.entry(k), v) for k, v in items]
        for e, v in staged:
            _check(e, v)
        for e, v in staged:
            if not e.ignored:
                self._data[e.address : e.address + e.size] = _encode(e, v)
        self._changed()

    # ---- byte access (mailbox CONFIG_RD / CONFIG_WR)
    def read_bytes(self, address: int, size: int) -> bytes:
        """`size` (1..4) bytes from `address`, LSB first; ignored bytes read 0."""
        self._span("read", address, size)
        return bytes(0 if _OWNER[a].ignored else self._data[a] for a in range(address, address + size))

    def write_bytes(self, address: int, data: bytes) -> None:
        """Write 1..4 raw bytes at `address` (may cover parts of entries); every entry touched
        is checked with its new value before anything is stored (1161 for a bad size)."""
        data = bytes(data)
        self._span("write", address, len(data))
        new = bytearray(self._data)
        new[address : address + len(data)] = data
        touched = {id(e): e for e in _OWNER[address : address + len(data)]}.values()
        for e in touched:
            if not e.ignored:
                _check(e, _decode(e, bytes(new[e.address : e.address + e.size])))
        for e in touched:
            if not e.ignored:
                self._data[e.address : e.address + e.size] = new[e.address : e.address + e.size]
        self._changed()

    @staticmethod
    def _span(what: str, address: int, size: int) -> None:
        if isinstance(size, bool) or not isinstance(size, int) or not 1 <= size <= 4:
            raise ConfigValueError(1161, "size", size, "1 .. 4", f"CONFIG {what} size = {size!r} bytes is outside 1 .. 4 (1161 CONFIG_WRITE_SIZE)")
        if isinstance(address, bool) or not isinstance(address, int) or not 0 <= address <= TABLE_SIZE - size:
            raise ConfigValueError(None, "address", address, f"0 .. {TABLE_SIZE - size}", f"configuration address {address!r} with {size} bytes is outside 0 .. {TABLE_SIZE - 1}")

    # ---- whole table
    def to_bytes(self) -> bytes:
        """The 512-byte data set (ignored bytes as 0)."""
        out = bytearray(self._data)
        for e in ENTRIES:
            if e.ignored:
                out[e.address : e.address + e.size] = bytes(e.size)
        return bytes(out)

    def load_bytes(self, data: bytes) -> None:
        """Replace the whole table with a 512-byte data set after checking every entry and
        the rules between them; on any error nothing changes."""
        data = bytes(data)
        if len(data) != TABLE_SIZE:
            raise ConfigValueError(None, "data set", len(data), f"{TABLE_SIZE} bytes", f"a configuration data set is {TABLE_SIZE} bytes, got {len(data)}")
        version = data[2]
        if version != CONF_VERSION:
            raise ConfigValueError(None, "ConfVersion", version, str(CONF_VERSION), f"ConfVersion = {version} is not the known data set version {CONF_VERSION}")
        for e in ENTRIES:
            if not e.ignored:
                _check(e, _decode(e, data[e.address : e.address + e.size]))
        self.validate(data)
        self._data = bytearray(data)
        for e in ENTRIES:
            if e.ignored:
                self._data[e.address : e.address + e.size] = bytes(e.size)
        self._changed()

    def validate(self, data: bytes | None = None) -> None:
        """The rules between entries: current-controller password (1162) and supply limits (1817)."""
        raw = bytes(self._data if data is None else data)

        def val(name: str) -> int:
            e = _BY_NAME[name]
            return _decode(e, raw[e.address : e.address + e.size])

        expected = current_password(val("Current_Ctrl_Hysteresis"), val("Current_Ctrl_TZMin"), val("Current_Ctrl_TZMax"), val("Current_Ctrl_Type"))
        if val("Current_Pass2") != expected:
            raise ConfigValueError(
                1162, "Current_Pass2", val("Current_Pass2"), f"{expected:#06x}",
                f"Current_Pass2 = {val('Current_Pass2'):#06x} does not match the current-controller parameters "
                f"(384 XOR 388 XOR 392 XOR 396 XOR 0xC0DE = {expected:#06x})",
            )
        if val("DC_Link_Umin") >= val("DC_Link_Umax"):
            raise ConfigValueError(
                1817, "DC_Link_Umin", val("DC_Link_Umin"), f"below DC_Link_Umax = {val('DC_Link_Umax')}",
                f"DC_Link_Umin = {val('DC_Link_Umin')} must be below DC_Link_Umax = {val('DC_Link_Umax')} (0.1 V)",
            )

    def restore_defaults(self) -> None:
        """FACTORY_DEFAULT values (CONFIG_RESTORE 2)."""
        self._data = bytearray(self._factory)
        self._changed()

    def factory_bytes(self) -> bytes:
        return bytes(self._factory)

    def save(self, path: str | os.PathLike[str]) -> None:
        """Write the 512-byte data set atomically (a reader sees the old file or the new one)."""
        atomic_write_bytes(path, self.to_bytes())

    def load(self, path: str | os.PathLike[str]) -> None:
        """Read a data set written by `save` (checked as `load_bytes`)."""
        self.load_bytes(Path(path).read_bytes())

    def copy(self) -> ConfigTable:
        other = ConfigTable.__new__(ConfigTable)
        other._factory = bytearray(self._factory)
        other._data = bytearray(self._data)
        other.values = _Values(other)
        other.generation = next(_GENERATIONS)
        return other

    def __repr__(self) -> str:
        changed = [e.name for e in ENTRIES if not e.ignored and self.get(e.name) != _decode(e, bytes(self._factory[e.address : e.address + e.size]))]
        return f"ConfigTable(changed={changed})"
