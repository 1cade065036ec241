"""A curve of the cam memory made ready for the cam operation (camop.py decision D1).

`PreparedCurve(record)` takes a curve record (curves.CurveRecord, or anything with its fields)
and holds what the cam operation reads every cycle: the set points as fractions of S_T in an
equidistant `PointTable` over one master cycle (the fraction 0x7FFFFF read as exactly 1.0,
the full slave cycle), the digital aux functions as an `AuxTrack`, the two analogue channels
(None: none, or 0 everywhere), and the curve parameters M_E, M_S, M_A, M_B, S_0, the label
and correction positions. A record that no cam can run (fewer than 2 set points, M_T <= 0,
a master position outside 0 ... 1) is refused with E103.
"""

from __future__ import annotations

import math
from typing import Any

from axisline.devices.compax import E_VALUE, CompaxError
from axisline.motion.cam import FRACTION_ONE, PointTable
from axisline.motion.camswitch import AuxTrack

__all__ = ["PreparedCurve"]

_FULL = (FRACTION_ONE - 1) / FRACTION_ONE  # 0x7FFFFF as a fraction: the full slave cycle


def _fraction(value: Any) -> float:
    f = float(value)
    if f >= _FULL - 1e-12:
        return 1.0 if f < 1.0 + 1e-9 else f  # 0x7FFFFF (0.9999999) = the full slave cycle (D1)
    return f


def _signed_byte(value: Any) -> float:
    v = int(value)
    return float(v - 256 if v > 127 else v)


class PreparedCurve:
    """A curve of the cam memory made ready for the cam operation (see D1)."""

    __slots__ = (
        "number", "master_cycle", "slave_cycle", "fractions", "table", "aux", "analog",
        "me", "ms", "ma", "mb", "s0", "label_set_point", "label_window", "k1", "k2", "open",
        "f_first", "f_last", "record",
    )  # fmt: skip

    def __init__(self, record: Any) -> None:
        self.record = record
        self.number = int(getattr(record, "number", 0))
        self.master_cycle = float(record.master_cycle)
        self.slave_cycle = float(record.slave_cycle)
        points = getattr(record, "set_points", None)
        if points is None:
            table = record.to_point_table()
            points = [s / self.slave_cycle for s in table.slave]
        fr = [_fraction(f) for f in points]
        if len(fr) < 2:
            raise CompaxError(
                f"curve {self.number}: {len(fr)} set point(s) not allowed, a curve needs at least 2",
                code=E_VALUE, field="set_points", value=len(fr), allowed=">= 2",
            )
        if not (math.isfinite(self.master_cycle) and self.master_cycle > 0):
            raise CompaxError(
                f"curve {self.number}: master cycle {self.master_cycle!r} not allowed, it must be > 0",
                code=E_VALUE, field="master_cycle", value=self.master_cycle, allowed="> 0",
            )
        self.fractions = tuple(fr)
        self.table = PointTable.equidistant(fr, 1.0, max_points=max(len(fr), 2))
        aux = getattr(record, "aux_digital", None)
        self.aux = AuxTrack(list(aux)) if aux is not None and len(aux) == len(fr) else None
        # an analogue channel of zeros everywhere is None: 0 V without a table to search every cycle
        self.analog = tuple(
            PointTable.equidistant(ch, 1.0, max_points=max(len(ch), 2)) if ch is not None and any(ch) else None
            for ch in _analog_channels(record, len(fr))
        )
        self.me = float(getattr(record, "coupling", 0.0) or 0.0)
        self.ms = float(getattr(record, "synchronous", 0.0) or 0.0)
        self.ma = float(getattr(record, "decoupling", 0.0) or 0.0)
        self.mb = float(getattr(record, "braking", 0.0) or 0.0)
        self.s0 = _fraction(getattr(record, "standstill", 0.0) or 0.0)
        self.label_set_point = float(getattr(record, "label_set_point", 0.0) or 0.0)
        self.label_window = float(getattr(record, "label_window", 0.0) or 0.0)
        self.k1 = float(getattr(record, "correction_enable", 0.0) or 0.0)
        self.k2 = float(getattr(record, "correction_disable", 0.0) or 0.0)
        for name in ("me", "ms", "ma", "mb"):
            value = getattr(self, name)
            if not 0.0 <= value < 1.0:
                if value == 1.0 or _fraction(value) == 1.0:
                    setattr(self, name, 0.0)  # the end of the cycle is the start of the next
                else:
                    raise CompaxError(
                        f"curve {self.number}: {name} = {value!r} not allowed, a master position is a fraction 0 ... <1 of M_T",
                        code=E_VALUE, field=name, value=value, allowed="0 <= value < 1",
                    )
        self.f_first = fr[0]
        self.f_last = fr[-1]
        self.open = fr[-1] != fr[0]

    def __repr__(self) -> str:
        return (
            f"PreparedCurve({self.number}, M_T={self.master_cycle:g}, S_T={self.slave_cycle:g}, "
            f"{len(self.fractions)} points, {'open' if self.open else 'closed'})"
        )


def _analog_channels(record: Any, n: int) -> tuple[list[float] | None, list[float] | None]:
    """The two analogue aux channels of a record (signed bytes per set point), if it has them."""
    pairs = getattr(record, "aux_analog", None)
    if pairs is not None and len(pairs) == n:
        return [_signed_byte(p[0]) for p in pairs], [_signed_byte(p[1]) for p in pairs]
    out: list[list[float] | None] = []
    for names in (("aux_analog0", "aux_analogue0", "analog0"), ("aux_analog1", "aux_analogue1", "analog1")):
        channel = None
        for name in names:
            values = getattr(record, name, None)
            if values is not None and len(values) == n:
                channel = [_signed_byte(v) for v in values]
                break
        out.append(channel)
    return out[0], out[1]
