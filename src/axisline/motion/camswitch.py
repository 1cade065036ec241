"""Cam switches: outputs that depend on a position (master or slave), evaluated once per cycle.

    from axisline.motion.camswitch import CamWindow, CamSwitchTrack, CamTable, PeriodicCam, AuxTrack
    glue = CamSwitchTrack([CamWindow(30.0, 80.0, direction=+1)], period=360.0, lead_time=0.004)
    out = glue.update(position, velocity)          # once per cycle, builds no containers

Three kinds, one per device family:

* `CamSwitchTrack`: one output switched by windows on a (possibly modulo) position, with
  an optional direction per window and lead-time compensation for actuators with a dead
  time (valves, glue guns). Used by the general cam-switch function block.
* `CamTable` and `PeriodicCam`: the WAGO 750-672 camshaft (wago.md §2.10, manual
  §3.11.1.9): CAM1 … CAM8 from a table of up to 50 (position, bit sample) entries, CAM9
  periodic.
* `AuxTrack`: the COMPAX digital auxiliary functions (compax.md §2.12): 8 bits per curve
  set point, the bits of the last set point passed, with mask (P38) and reset value (P37).

Windows (`CamSwitchTrack`)
--------------------------
A window is on while on_position <= p < off_position. On a modulo track (``period``) a
window with on_position > off_position wraps across the period end: on from on_position to
the end of the cycle and from 0 up to off_position. Without a period windows cannot wrap.

``direction`` +1 (or -1) makes a window switch only while the position moves forward
(backward), i.e. velocity > 0 (< 0); at standstill such a window is off, so a glue gun does
not drip while the line waits. Direction 0 switches either way and at standstill.

Lead time: an actuator that reacts ``lead_time`` seconds late is switched that much early,
i.e. the window is tested at the position predicted for the time the actuator acts,
p + v · lead_time. ``off_lead_time`` (default: ``lead_time``) lets switching off use a
different dead time than switching on (a valve often opens slower than it closes): the
output goes on once the position predicted with the on dead time has entered the window and
stays on until the position predicted with the off dead time has left it. The edge the
motion enters by is the on edge when moving forward and the off edge when moving backward.
A negative lead time delays the switching instead.
"""

from __future__ import annotations

import math
from bisect import bisect_right
from collections.abc import Iterable, Sequence
from dataclasses import dataclass

from axisline.motion.cam import PointTable

__all__ = [
    "COMPAX_AUX_SHIFT",
    "CAM9_PARAMETER_ERROR",
    "WAGO_CAM_TABLE_ENTRIES",
    "AuxTrack",
    "Cam9ParameterError",
    "CamSwitchTrack",
    "CamTable",
    "CamWindow",
    "PeriodicCam",
]


# ---------------------------------------------------------------------------------------
# position windows


@dataclass(frozen=True, slots=True)
class CamWindow:
    """On while on_position <= p < off_position; ``direction`` +1/-1 = only moving that way."""

    on_position: float
    off_position: float
    direction: int = 0


def _finite(name: str, value: float) -> float:
    value = float(value)
    if not math.isfinite(value):
        raise ValueError(f"{name} {value!r} not allowed: it must be a finite number")
    return value


class CamSwitchTrack:
    """One output switched by position windows (see the module doc for the rules)."""

    __slots__ = (
        "windows",
        "period",
        "lead_time",
        "off_lead_time",
        "output",
        "_on",
        "_off",
        "_length",
        "_direction",
    )

    def __init__(
        self,
        windows: Iterable[CamWindow | tuple[float, float] | tuple[float, float, int]],
        *,
        period: float | None = None,
        lead_time: float = 0.0,
        off_lead_time: float | None = None,
    ) -> None:
        if period is not None:
            period = _finite("period", period)
            if period <= 0:
                raise ValueError(f"period {period!r} not allowed: a modulo period must be > 0 (or None)")
        self.period = period
        self.lead_time = _finite("lead_time", lead_time)
        self.off_lead_time = self.lead_time if off_lead_time is None else _finite("off_lead_time", off_lead_time)
        parsed: list[CamWindow] = []
        for k, raw in enumerate(windows):
            window = raw if isinstance(raw, CamWindow) else CamWindow(*raw)
            on = _finite(f"window {k} on_position", window.on_position)
            off = _finite(f"window {k} off_position", window.off_position)
            if window.direction not in (-1, 0, 1):
                raise ValueError(
                    f"window {k}: direction {window.direction!r} not allowed: +1 (forward only), "
                    "-1 (backward only) or 0 (both)"
                )
            if period is None:
                if not on < off:
                    raise ValueError(
                        f"window {k}: on_position {on!r} must be below off_position {off!r} "
                        "(only a modulo track, with a period, has windows that wrap)"
                    )
            else:
                if not 0.0 <= on < period:
                    raise ValueError(
                        f"window {k}: on_position {on!r} not allowed: 0 <= on_position < period {period!r}"
                    )
                if not 0.0 <= off <= period:
                    raise ValueError(
                        f"window {k}: off_position {off!r} not allowed: 0 <= off_position <= period {period!r}"
                    )
                if on == off:
                    raise ValueError(
                        f"window {k}: on_position == off_position ({on!r}) is ambiguous; for a window over "
                        f"the whole cycle use on_position 0 and off_position {period!r}"
                    )
            parsed.append(CamWindow(on, off, window.direction))
        self.windows: tuple[CamWindow, ...] = tuple(parsed)
        self._on = tuple(w.on_position for w in parsed)
        self._off = tuple(w.off_position for w in parsed)
        if period is None:
            self._length = tuple(w.off_position - w.on_position for w in parsed)
        else:  # window length in the direction of the period; wraps when on > off
            self._length = tuple(
                w.off_position - w.on_position + (0.0 if w.off_position > w.on_position else period)
                for w in parsed
            )
        self._direction = tuple(w.direction for w in parsed)
        self.output = False

    def is_on(self, position: float, velocity: float = 0.0) -> bool:
        """The output for this position and velocity (no state is changed)."""
        v = velocity
        forward = v >= 0.0
        p_enter = position + v * self.lead_time
        p_leave = position + v * self.off_lead_time
        period = self.period
        on_list, off_list, length, direction = self._on, self._off, self._length, self._direction
        for i in range(len(on_list)):
            d = direction[i]
            if d > 0 and not v > 0.0:
                continue
            if d < 0 and not v < 0.0:
                continue
            on = on_list[i]
            off = off_list[i]
            if period is None:
                if forward:
                    if on <= p_enter and p_leave < off:
                        return True
                elif p_enter < off and p_leave >= on:
                    return True
            elif forward:
                # distance past the on edge; k = the pass of the on edge the enter prediction is in
                k = math.floor((p_enter - on) / period)
                if p_leave - on < k * period + length[i]:
                    return True
            else:
                # mirrored: distance below the off edge; the window is (k·P, k·P + L] there
                y_enter = off - p_enter
                k = math.ceil(y_enter / period) - 1
                if off - p_leave <= k * period + length[i]:
                    return True
        return False

    def update(self, position: float, velocity: float = 0.0) -> bool:
        """Evaluate for this cycle and keep the result in ``output``."""
        self.output = self.is_on(position, velocity)
        return self.output

    def __repr__(self) -> str:
        return (
            f"CamSwitchTrack({list(self.windows)!r}, period={self.period!r}, "
            f"lead_time={self.lead_time!r}, off_lead_time={self.off_lead_time!r})"
        )


# ---------------------------------------------------------------------------------------
# WAGO 750-672 camshaft

#: Entries of a WAGO camshaft table (wago.md §2.10, §7 "Camshaft entries 50").
WAGO_CAM_TABLE_ENTRIES = 50

#: WAGO error for a CAM9 period of 0 (wago.md error table: "1331 TBL_CAM9PARMS faulty
#: parameter for camshaft channel 9 - cycle may not be 0").
CAM9_PARAMETER_ERROR = 1331


class Cam9ParameterError(ValueError):
    """A CAM9 parameter the WAGO module rejects (error 1331 TBL_CAM9PARMS)."""

    code = CAM9_PARAMETER_ERROR
    name = "TBL_CAM9PARMS"


class CamTable:
    """WAGO camshaft CAM1 … CAM8: (position, bit sample) entries, bit n−1 = CAMn.

    The sample of an entry holds from its position up to the next entry's position; below
    the first entry the first entry's sample holds ("For positions below the first entry,
    the bit pattern of the first entry is shown", wago.md §2.10), at and above the last entry
    the last one's. Positions must be strictly ascending (the module rejects a
    non-ascending download; equal positions are rejected too, as the second entry could
    never show). Positions are in path increments (micro steps); integers stay integers.
    An empty table shows 0.
    """

    __slots__ = ("positions", "samples", "sample", "_first")

    #: The position of an unused entry in a downloaded table (INT32 0x80000000).
    INVALID_POSITION = -0x80000000

    def __init__(self, entries: Iterable[tuple[float, int]], *, max_entries: int = WAGO_CAM_TABLE_ENTRIES) -> None:
        positions: list[float] = []
        samples: list[int] = []
        for k, entry in enumerate(entries):
            try:
                position, sample = entry
            except (TypeError, ValueError):
                raise ValueError(f"entry {k + 1}: {entry!r} is not a (position, sample) pair") from None
            if isinstance(position, bool) or not isinstance(position, (int, float)) or not math.isfinite(position):
                raise ValueError(f"entry {k + 1}: position {position!r} not allowed: it must be a finite number")
            if isinstance(sample, bool) or not isinstance(sample, int) or not 0 <= sample <= 0xFF:
                raise ValueError(
                    f"entry {k + 1}: bit sample {sample!r} not allowed: an integer 0 ... 255 (bit n-1 = CAMn)"
                )
            if positions and not position > positions[-1]:
                raise ValueError(
                    f"entry {k + 1}: position {position!r} not allowed: positions must be strictly ascending "
                    f"(previous entry {positions[-1]!r})"
                )
            positions.append(position)
            samples.append(sample)
            if len(positions) > max_entries:
                raise ValueError(f"entry {k + 1}: a camshaft table holds at most {max_entries} entries")
        self.positions: tuple[float, ...] = tuple(positions)
        self.samples: tuple[int, ...] = tuple(samples)
        self._first = samples[0] if samples else 0
        self.sample = self._first

    @classmethod
    def from_device(cls, entries: Iterable[tuple[int, int]], *, max_entries: int = WAGO_CAM_TABLE_ENTRIES) -> CamTable:
        """A table as downloaded: entries at the invalid position 0x80000000 are unused and skipped."""
        used = [
            (position, sample)
            for position, sample in entries
            if position not in (cls.INVALID_POSITION, 0x80000000)
        ]
        return cls(used, max_entries=max_entries)

    def sample_at(self, position: float) -> int:
        """The 8-bit sample CAM8 … CAM1 at this position."""
        i = bisect_right(self.positions, position) - 1
        if i < 0:
            return self._first
        return self.samples[i]

    def cam(self, n: int, position: float) -> bool:
        """CAMn (1 … 8) at this position."""
        if not 1 <= n <= 8:
            raise ValueError(f"CAM{n} not allowed: the table drives CAM1 ... CAM8")
        return bool(self.sample_at(position) >> (n - 1) & 1)

    def update(self, position: float) -> int:
        """Evaluate for this cycle and keep the sample in ``sample``."""
        self.sample = self.sample_at(position)
        return self.sample

    def __len__(self) -> int:
        return len(self.positions)

    def __repr__(self) -> str:
        return f"CamTable({list(zip(self.positions, (f'0x{s:02X}' for s in self.samples)))!r})"


class PeriodicCam:
    """WAGO CAM9: on iff ((position − start) mod period) < pulse_width.

    (wago.md §2.10 [RECONSTRUCTED]; Camshaft_Ch9_Start / _Period / _Pulsewidth in path
    increments.) The modulo is the floored one, so positions below ``start`` continue the
    pattern backwards: with start 0, period 100, pulse width 50, position −60 is on
    (−60 mod 100 = 40) and −30 is off (70).
    Period 0 raises `Cam9ParameterError` (WAGO error 1331 TBL_CAM9PARMS); so does a
    negative period or pulse width, which the module's value ranges exclude.
    """

    __slots__ = ("start", "period", "pulse_width", "output")

    def __init__(self, start: float = 0, period: float = 100, pulse_width: float = 50) -> None:
        for name, value in (("start", start), ("period", period), ("pulse_width", pulse_width)):
            if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
                raise Cam9ParameterError(f"CAM9 {name} {value!r} not allowed: it must be a finite number")
        if period == 0:
            raise Cam9ParameterError(
                "CAM9 period 0 not allowed (WAGO error 1331 TBL_CAM9PARMS: cycle may not be 0); "
                "Camshaft_Ch9_Period must be 1 ... 8388607"
            )
        if period < 0:
            raise Cam9ParameterError(
                f"CAM9 period {period!r} not allowed (WAGO error 1331 TBL_CAM9PARMS); "
                "Camshaft_Ch9_Period must be 1 ... 8388607"
            )
        if pulse_width < 0:
            raise Cam9ParameterError(
                f"CAM9 pulse width {pulse_width!r} not allowed (WAGO error 1331 TBL_CAM9PARMS); "
                "Camshaft_Ch9_Pulsewidth must be 0 ... 8388607"
            )
        self.start = start
        self.period = period
        self.pulse_width = pulse_width
        self.output = False

    def is_on(self, position: float) -> bool:
        return (position - self.start) % self.period < self.pulse_width

    def update(self, position: float) -> bool:
        self.output = self.is_on(position)
        return self.output

    def __repr__(self) -> str:
        return f"PeriodicCam(start={self.start!r}, period={self.period!r}, pulse_width={self.pulse_width!r})"


# ---------------------------------------------------------------------------------------
# COMPAX digital auxiliary functions

#: P37/P38 give O7 … O14 the valences 2⁶ … 2¹³ (compax.md §2.12); the aux byte of a set
#: point has O7 in bit 0. Shift a parameter right by this to get the byte's mask.
COMPAX_AUX_SHIFT = 6


class AuxTrack:
    """The digital bits of the last set point passed, with a mask and a reset value.

    One byte per set point of an equidistant `PointTable` (COMPAX: bit 0 = O7 … bit 7 =
    O14, compax.md §2.12). The set point "passed" is the last one whose master position is
    <= the current master position within the cycle, i.e. set point k holds from its master
    position up to the next one's (position-based, the same in both directions of motion).

    ``outputs(point, previous, enabled)`` gives the new output byte: a bit outside ``mask``
    keeps its previous value (outputs masked off by P38 stay under OUTPUT control); a bit
    inside the mask is the set point's bit when the aux functions are enabled (COMPAX I15 =
    1) and the ``reset_value`` bit when they are not (I15 = 0, P37). The COMPAX personality
    adds what is device-specific (O14 taken by the label error when P33 != 0, outputs frozen
    outside synchronous operation); `from_compax` converts P37/P38 valences. The analogue
    aux channels interpolate linearly between set points: a `PointTable` over their values.
    """

    __slots__ = ("bits_per_point", "mask", "reset_value", "_keep")

    def __init__(self, bits_per_point: Sequence[int], mask: int = 0xFF, reset_value: int = 0) -> None:
        bits: list[int] = []
        for k, b in enumerate(bits_per_point):
            if isinstance(b, bool) or not isinstance(b, int) or not 0 <= b <= 0xFF:
                raise ValueError(f"set point {k}: aux bits {b!r} not allowed: an integer 0 ... 255")
            bits.append(b)
        if not bits:
            raise ValueError("AuxTrack needs the aux bits of at least one set point")
        for name, value in (("mask", mask), ("reset_value", reset_value)):
            if isinstance(value, bool) or not isinstance(value, int) or not 0 <= value <= 0xFF:
                raise ValueError(f"{name} {value!r} not allowed: an integer 0 ... 255 (bit 0 = O7 ... bit 7 = O14)")
        self.bits_per_point: tuple[int, ...] = tuple(bits)
        self.mask = mask
        self.reset_value = reset_value
        self._keep = ~mask & 0xFF

    @classmethod
    def from_compax(cls, bits_per_point: Sequence[int], p37: int, p38: int) -> AuxTrack:
        """Mask and reset value from COMPAX P38 / P37 (O7 = 2⁶ … O14 = 2¹³; P38 = 16320 = all)."""
        for name, value in (("P37", p37), ("P38", p38)):
            if isinstance(value, bool) or not isinstance(value, int) or value & ~(0xFF << COMPAX_AUX_SHIFT):
                raise ValueError(
                    f"{name} {value!r} not allowed: a sum of the valences 64 (O7) ... 8192 (O14), 0 ... 16320"
                )
        return cls(bits_per_point, mask=p38 >> COMPAX_AUX_SHIFT, reset_value=p37 >> COMPAX_AUX_SHIFT)

    def bits(self, point: int) -> int:
        """The aux byte of set point ``point``."""
        return self.bits_per_point[point]

    def outputs(self, point: int, previous: int, enabled: bool = True) -> int:
        """The output byte after passing set point ``point`` (see the class doc)."""
        source = self.bits_per_point[point] if enabled else self.reset_value
        return (previous & self._keep) | (source & self.mask)

    def outputs_at(self, table: PointTable, x: float, previous: int, enabled: bool = True) -> int:
        """`outputs` for the set point of ``table`` last passed at master position ``x`` (in the cycle)."""
        if len(table) != len(self.bits_per_point):
            raise ValueError(
                f"the table has {len(table)} set points but the aux track {len(self.bits_per_point)}: "
                "one aux byte per set point"
            )
        return self.outputs(table.last_point_passed(x), previous, enabled)

    def __repr__(self) -> str:
        return (
            f"AuxTrack({len(self.bits_per_point)} set points, mask=0x{self.mask:02X}, "
            f"reset_value=0x{self.reset_value:02X})"
        )
