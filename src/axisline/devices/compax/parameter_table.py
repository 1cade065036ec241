"""The COMPAX XX70 cam parameters as data: one `ParamSpec` per row of the manual's parameter
list (compax.md §3, manual §23), and `Validity`, when a written value takes effect.

`parameters.Parameters` is the store that checks and keeps the values; the decisions taken on
the list are in its docstring (parameters.py).
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import Enum
from typing import Any

from axisline.devices.compax.valueranges import _AUX_BITS

__all__ = ["PARAMETERS", "ParamSpec", "Validity"]


class Validity(str, Enum):
    """When a written value becomes effective ("valid from" column of §23)."""

    IMMEDIATE = "immediately"
    VP = "VP"
    VC = "VC"
    VP_SETC = "VP & SETC"
    VP_CURVE_ZERO = "VP & next curve zero point or SETC"
    VP_NEXT_CURVE = "VP & next curve (10...12: or at the end of the current cycle)"
    VP_CYCLE_END = "VP & at the end of the current curve cycle (or LOOP)"
    VP_P35 = "VP (P30 >= 10 and synchronous: at the end of the master cycle)"


@dataclass(frozen=True, slots=True)
class ParamSpec:
    """One parameter: the manual's row, as data.

    ``minimum``/``maximum`` None: not limited by the manual (any finite number).
    ``allowed``: the only values accepted (codes). ``bitmask``: only these bits may be set.
    ``decimals``: resolution (0 for integer parameters). ``documented=False``: a standard
    COMPAX parameter the supplement only references; its range is not checked beyond the
    type and what the supplement says.
    """

    number: int
    meaning: str
    unit: str
    minimum: float | None
    default: float
    maximum: float | None
    valid_from: Validity
    allowed: tuple[int, ...] | None = None
    meanings: tuple[tuple[int, str], ...] = ()
    decimals: int = 0
    bitmask: int | None = None
    documented: bool = True
    source: str = ""
    notes: str = ""

    @property
    def integer(self) -> bool:
        return self.decimals == 0

    def range_text(self) -> str:
        """What is allowed, for error messages."""
        if self.allowed is not None:
            return "one of " + ", ".join(str(v) for v in self.allowed)
        if self.bitmask is not None:
            return f"a sum of the valences {', '.join(str(1 << b) for b in range(24) if self.bitmask >> b & 1)} (0 ... {self.bitmask})"
        lo = "-inf" if self.minimum is None else _fmt(self.minimum, self.decimals)
        hi = "+inf" if self.maximum is None else _fmt(self.maximum, self.decimals)
        kind = "an integer" if self.integer else "a number"
        return f"{kind} {lo} ... {hi}"


def _fmt(value: float, decimals: int) -> str:
    if decimals == 0:
        return str(int(value))
    return f"{value:.{decimals}f}"


def _p(number: int, meaning: str, unit: str, minimum: float | None, default: float, maximum: float | None,
       valid_from: Validity, **kw: Any) -> ParamSpec:
    return ParamSpec(number, meaning, unit, minimum, default, maximum, valid_from, **kw)


_V = Validity
_DA_QUANTITIES = tuple(range(0, 19)) + tuple(range(20, 25))
_P31_MEANINGS = (
    (0, "I16='1' statical enabling, I16='0' statical disabling"),
    (1, "I16='1' enabling rounded off with the encoder zero pulse; I16='0' disabling"),
    (2, "enabling after SETC n by a positive edge of I16; disabling by a further SETC n and I16='0'"),
    (3, "enabling after SETC n by a positive edge of I16; disabled automatically after one master cycle, not when I16='1'"),
    (4, "enabling after SETC n by a positive edge of I16; disabling by a further SETC n independent of I16"),
    (5, "enabling after SETC n by a positive edge of I16; disabled automatically after one master cycle, independent of I16"),
    (9, "I16='1' statical enabling for HEDA coupling (counter channel not reset)"),
)

_SPECS: tuple[ParamSpec, ...] = (
    # --- standard parameters the supplement references (§3.5) -----------------------------
    _p(1, "Standard parameter; must be 0 for POSR CAM ('Set P1=0!', §9)", "", None, 0, None, _V.VP,
       decimals=3, documented=False, source="§9"),
    _p(6, "Reserve time used by the STOP ramp (standard parameter)", "ms", 0, 0, None, _V.VP,
       decimals=3, documented=False, source="§12.0.1"),
    _p(11, "Software end limit, positive (+4 000 000 switches supervision off)", "according to P90",
       1, 4_000_000, 4_000_000, _V.VP, decimals=3, source="§4.4"),
    _p(12, "Software end limit, negative (-4 000 000 switches supervision off)", "according to P90",
       -4_000_000, -4_000_000, -1, _V.VP, decimals=3, source="§4.4"),
    _p(13, "Tracking error limit (standard parameter; upper bound of P79)", "according to P90",
       0, 10, None, _V.VP, decimals=3, documented=False, source="§23 (P79 < P13)"),
    _p(18, "HEDA: bit 0 PLC data interface, bit 1 fast start on I15, bit 3 fast start on HEDA", "",
       None, 0, None, _V.VP, bitmask=0b1011, source="§6, §23",
       notes="bits 1 and 3 only with the standard device CPX XX00; PLC data interface after Power on"),
    _p(21, "Factor for position calculation (standard parameter; 1 for drift-free operation)", "",
       None, 1, None, _V.VP, decimals=6, documented=False, source="§24"),
    # --- cam parameters (§23) -------------------------------------------------------------
    _p(30, "Select master input", "", None, 0, None, _V.VP, allowed=(0, 1, 10, 11),
       meanings=((0, "coupled to the master by an encoder"),
                 (1, "not coupled: internal time base simulates the master speed"),
                 (10, "encoder; P35 accepted only when the master cycle is reached"),
                 (11, "internal time base; P35 accepted only when the master cycle is reached")),
       source="§16, §17, §23"),
    _p(31, "Operation mode of I16 'enabling of master position'", "", None, 0, None, _V.VP,
       allowed=(0, 1, 2, 3, 4, 5, 9), meanings=_P31_MEANINGS, source="§19.1, §23",
       notes="with the internal time base (P30=1) P31=2 is treated like P31=0; P31=1 not with HEDA"),
    _p(32, "Distance of label sensor", "unit of the corresponding cycle", 0, 0, None, _V.VP_CYCLE_END,
       decimals=6, source="§14.1, §15.3.2, §23", notes="max 10·M_T (10·S_T): check_label_sensor_distance"),
    _p(33, "Operation mode of label synchronization", "", None, 0, None, _V.VP_NEXT_CURVE,
       allowed=(0, 1, 2, 10, 11, 12),
       meanings=((0, "no label synchronization"), (1, "master related"), (2, "slave related"),
                 (10, "none, accepted at the end of the current cycle"),
                 (11, "master related, accepted at the end of the current cycle"),
                 (12, "slave related, accepted at the end of the current cycle")),
       source="§14.6.1, §15.3.2, §23"),
    _p(34, "Coupling mode (bit sum)", "", None, 0, None, _V.VP_SETC, allowed=tuple(range(8)),
       meanings=((0, "without coupling and decoupling positions"),
                 (1, "bit 0: with coupling and decoupling positions M_E / M_A"),
                 (2, "bit 1: leave cam operation after decoupling"),
                 (4, "bit 2: leave curve when the loop counter terminates, at the end of the master cycle")),
       source="§11, §12, §15.1, §23", notes="M_S and M_B are taken into account independently of P34"),
    _p(35, "Factor in the master input channel (scaling factor for master)", "", -1000, 1, 1000, _V.VP_P35,
       decimals=6, source="§17, §18, §23", notes="ramped with P179"),
    _p(36, "Scaling factor for slave", "", -1000, 1, 1000, _V.VP_CURVE_ZERO, decimals=6,
       source="§23 footnote 5"),
    _p(37, "Reset value for digital auxiliary functions (O7 = 64 ... O14 = 8192)", "", None, 0, None, _V.VP,
       bitmask=_AUX_BITS, source="§13.1.2"),
    _p(38, "Mask for digital auxiliary functions (O7 = 64 ... O14 = 8192; 16320 = all)", "", None, 0, None,
       _V.VP, bitmask=_AUX_BITS, source="§13.1.1"),
    _p(39, "Ramp time of internal time base", "ms", 0, 0, 4_000_000, _V.VP, decimals=3, source="§16, §23"),
    *(
        _p(n, "Operation parameter (argument of SETC .P4x, SETM .P4x, LOOP .P4x)", "", None, 0, None,
           _V.IMMEDIATE, decimals=3, documented=False, source="§9")
        for n in range(40, 50)
    ),
    _p(68, "Filter for external speed feed forward (0: filter off)", "%", 0, 0, 550, _V.VP, decimals=3,
       source="§23 footnote 6"),
    _p(71, "D/A monitor option D1: gain channel 0", "", None, 0, None, _V.VP, decimals=3, documented=False,
       source="§13.2", notes="P71=10: 100 % = 1 V; P71=100: 100 % = 10 V"),
    _p(72, "D/A monitor option D1: gain channel 1", "", None, 0, None, _V.VP, decimals=3, documented=False,
       source="§13.2"),
    _p(73, "D/A monitor option D1: quantity on channel 0 (1...18 standard, 20...24 cam)", "", None, 0, None,
       _V.VP, allowed=_DA_QUANTITIES, source="§13.2"),
    _p(74, "D/A monitor option D1: quantity on channel 1 (1...18 standard, 20...24 cam)", "", None, 0, None,
       _V.VP, allowed=_DA_QUANTITIES, source="§13.2"),
    _p(76, "Service D/A monitor channel 2: quantity (pre-comma), gain (post-comma x 10 000 000)", "", 0, 0,
       24.9999999, _V.VP, decimals=7, source="§13.2"),
    _p(77, "Service D/A monitor channel 3: quantity (pre-comma), gain (post-comma x 10 000 000)", "", 0, 0,
       24.9999999, _V.VP, decimals=7, source="§13.2"),
    _p(79, "Max. acceptable tracking warning (indicated by O15)", "according to P90", 0, 1, None, _V.VP,
       decimals=3, source="§19.2, §23", notes="must be < P13"),
    # --- drive / roller feed (§23: P80...P88 'only apply to the drive type Roller Feed') ----
    _p(80, "Drive type", "", None, 16, None, _V.VC, allowed=(2, 4, 8, 16, 32),
       meanings=((2, "spindle drive"), (4, "rack and pinion"), (8, "timing belt"), (16, "universal drive"),
                 (32, "roller feed (supplement)")), source="§4.3, §23"),
    _p(82, "Moment of inertia of the feed rollers", "kgcm²", 0, 0, 70_000, _V.VC, decimals=3, source="§23"),
    _p(83, "Circumference of the slave feed rollers (universal drive: distance per motor revolution)",
       "mm (P90)", 0.001, 30, 4_000_000, _V.VC, decimals=3, source="§4.2.2, §4.3, §23",
       notes="roller feed: 30...3000 mm; universal drive in increments: 2^n, n = 4...16"),
    _p(84, "Moment of inertia of gear box and clutch (to the drive axis)", "kgcm²", 0, 0, 200, _V.VC,
       decimals=2, source="§23"),
    _p(85, "Gear ratio (motor : gear)", "", 1, 1, 100, _V.VC, decimals=7, source="§23"),
    _p(88, "Translatory moved mass", "kg", 0, 0, 500, _V.VC, decimals=3, source="§23"),
    _p(90, "Units for distance indication", "", None, 1, None, _V.VC, allowed=(0, 1, 2, 3),
       meanings=((0, "increments (supplement)"), (1, "mm"), (2, "inch"),
                 (3, "degree (supplement; millidegree in the universal drive)")), source="§4.2, §23"),
    _p(93, "Operation mode", "", None, 3, None, _V.IMMEDIATE, allowed=(1, 2, 3, 4),
       meanings=((1, "normal"), (2, "endless"), (3, "reset mode (supplement, default)"), (4, "speed control")),
       source="§4.1, §23"),
    _p(98, "Distance of master axis per encoder revolution", "unit of M_T", 0, 360, 4_000_000, _V.VC,
       decimals=3, source="§4.5.1, §23"),
    _p(143, "Encoder pulses per revolution (channel 1)", "", 128, 4096, 2_000_000, _V.VC, source="§4.5.2, §23"),
    _p(144, "Master input channel", "", None, 4, None, _V.VC, allowed=(4,),
       meanings=((4, "encoder module E2 or E4 (channel 1)"),), source="§5, §23"),
    _p(179, "Ramp for P35 (ms per change of 1.0; 0 or 1: jump)", "ms", 0, 0, 4_000_000, _V.VP, source="§18, §23"),
    _p(180, "Label correction limitation", "%", 0, 100, None, _V.VP, decimals=3, source="§14.6",
       notes="0, 100 or >100: initial correction unlimited"),
    _p(184, "HEDA process value sent (master)", "", None, 0, None, _V.VP, allowed=(0, 40, 42, 43, 44, 45, 46),
       meanings=((40, "encoder position + period duration"), (42, "internal time base / encoder rate before P35"),
                 (43, "scaled master position before P35"), (44, "position set point, resolver increments"),
                 (45, "position actual value, resolver increments"), (46, "differentiated resolver position")),
       source="§6"),
    _p(188, "HEDA process value received (slave)", "", None, 0, None, _V.VP, allowed=(0, 40, 42, 43, 140),
       meanings=((40, "encoder coupling (master P184=40)"), (42, "internal time base"),
                 (43, "normalized master position"), (140, "encoder coupling for other input signals")),
       source="§6"),
    _p(210, "Parallel mode", "", None, 0, None, _V.IMMEDIATE, allowed=(0, 1),
       meanings=((0, "linear processing of the program memory"),
                 (1, "program continues during positioning, stops at the next positioning command")),
       source="§15.1, §23"),
    _p(212, "HEDA variant restriction (standard parameter; XX60 with P212=3/4 not as HEDA slave)", "", None, 0,
       None, _V.VP, decimals=0, documented=False, source="§6"),
    _p(215, "Direction of rotation (standard parameter)", "", None, 0, None, _V.VP, decimals=0, documented=False,
       source="§14.6.1"),
    _p(233, "Optimizing indicator shown on S13 (XX70: 31, 32, 33, 37)", "", 0, 0, None, _V.VP, documented=False,
       source="§21"),
    _p(234, "Optimizing indicator shown on S14 (XX70: 31, 32, 33, 37)", "", 0, 0, None, _V.VP, documented=False,
       source="§21"),
    _p(243, "HEDA operation mode", "", None, 0, None, _V.VP, allowed=(0, 1, 2),
       meanings=((0, "P250=0: independent single axis; P250=1...9: slave to IPM"), (1, "COMPAX as master"),
                 (2, "passive slave to a COMPAX master")), source="§6"),
    _p(245, "Outputs O1...O8 assigned to the HEDA bus", "", 0, 0, 255, _V.IMMEDIATE, source="§6"),
    _p(246, "Outputs O9...O16 assigned to the HEDA bus", "", 0, 0, 255, _V.IMMEDIATE, source="§6"),
    _p(247, "HEDA: max. average errors in transmission", "", 0, 5, None, _V.VP, documented=False, source="§6"),
    _p(248, "HEDA: max. errors in transmission", "", 0, 15, None, _V.VP, documented=False, source="§6"),
    _p(249, "HEDA: synchronization supervision", "", 0, 10, None, _V.VP, documented=False, source="§6"),
    _p(250, "HEDA device address", "", 0, 0, 9, _V.VP, source="§6"),
)

#: Every parameter by number.
PARAMETERS: dict[int, ParamSpec] = {spec.number: spec for spec in _SPECS}
