"""One 1 ms cycle of the COMPAX device around its cam operation (personality.py's `tick`, the part
that runs every cycle; the start-up list stays with the personality).

    cycle = DeviceCycle(op, run, log, label, period, i14=sensor, i16=sensor, encoder=enc,
                        io=machine.io, outputs=((16, "knife_sync"), ...), status=live_status)
    cycle.tick(n)                     # after the start-up list's line of cycle n

In order: the program memory's interpreter runs one set (`programrun.ProgramRun.tick`); the
label sensor's sub-cycle edges of the last plant step go to the label synchronisation (I14
wired to a print-mark sensor or switch); I16 wired to a sensor latches the master encoder at
its rising edge, interpolated in the cycle; the cam operation runs (`camop.CamOperation.tick`);
the interpreter notes LOOP starts, transfers and ends (`ProgramRun.watch`); the cycle log
(`report.CycleLog`) takes the labels, the correction, the tracking error, the O15 / O16
changes and the master-cycle wraps; an error of the cam operation becomes S30; and O1 ... O16
are written to the io outputs wired to them in the cycle the output image changes (decision
P2 of personality.py).
"""

from __future__ import annotations

import math
from typing import Any

from axisline.devices.compax.camop import CamOperation
from axisline.devices.compax.label import LabelSync

__all__ = ["DeviceCycle"]

_O15, _O16 = 1 << 14, 1 << 15  # bits of the output image (CamOperation.out: bit n-1 = On)
_O15_O16 = _O15 | _O16


class DeviceCycle:
    """The COMPAX device's per-cycle work around the cam operation (see the module docstring).

    op, label: the cam operation and its label synchronisation. run: the program memory's
    interpreter (`ProgramRun`). log: the `CycleLog`. i14 / i16: the sensors wired to I14 / I16
    (objects with ``name`` and ``edges``), or None. encoder: the master encoder (``counts``,
    optionally ``delta``), or None. io: the machine's digital I/O (``write``). outputs:
    (n, io output name) for each On wired. status: the live status values (S30 is set there).
    """

    def __init__(self, op: CamOperation, run: Any, log: Any, label: LabelSync, period: float, *,
                 i14: Any = None, i16: Any = None, encoder: Any = None, io: Any = None,
                 outputs: tuple[tuple[int, str], ...] = (), status: Any = None) -> None:
        self.op = op
        self.run = run
        self.log = log
        self.label = label
        self.period = float(period)
        self.i14 = i14
        self.i16 = i16
        self.encoder = encoder
        self.io = io
        self.outputs = outputs
        self.status = status
        #: labels of the cycle (S51, S52), from `LabelSync.on_label`
        self.accepted: list[tuple[float, float]] = []
        self._corrected = 0.0  # label.corrected when the log last took it
        self._edge_seen: dict[str, float] = {}
        self._enc_prev: int | None = None
        self._op_error = 0
        self._logged_out = -1  # O15 / O16 bits the log has seen (-1: none yet)
        self._written_out = -1  # the output image last written to the io outputs (-1: none yet)

    def _new_edges(self, sensor: Any) -> list[Any]:
        """Edges of the sensor not handed over yet (those of the last plant step)."""
        last = self._edge_seen.get(sensor.name, -math.inf)
        out = []
        for e in reversed(sensor.edges):
            if e.time <= last:
                break
            out.append(e)
        if out:
            out.reverse()
            self._edge_seen[sensor.name] = out[-1].time
        return out

    def tick(self, cycle: int) -> None:
        op = self.op
        t = cycle * self.period
        self.run.tick(cycle)  # the program memory's interpreter, before the cam operation
        i14, i16 = self.i14, self.i16
        i14_edges: list[tuple[float, bool]] | None = None
        latch: int | None = None
        fresh: list[Any] = []
        if i14 is not None:
            fresh = self._new_edges(i14)
            i14_edges = [(e.fraction, e.rising) for e in fresh] if fresh else []
        if i16 is not None:
            edges = fresh if i16 is i14 else self._new_edges(i16)  # I14 and I16 may be one sensor
            enc = self.encoder
            raw = int(enc.counts) if enc is not None else None
            prev = self._enc_prev
            if raw is not None and prev is not None:
                rising = next((e for e in edges if e.rising), None) if edges else None
                if rising is not None:
                    delta = getattr(enc, "delta", None)
                    moved = delta(raw, prev) if callable(delta) else raw - prev
                    latch = prev + round(rising.fraction * moved)
            self._enc_prev = raw  # (only the I16 latch reads it)
        op.tick(cycle, i14_edges=i14_edges, i16_latch=latch)
        self.run.watch(cycle)
        # records of the cycle
        log = self.log
        label = self.label
        curve = op.curve
        if self.accepted:
            length = 0.0
            if curve is not None:
                length = curve.slave_cycle * op.p36 if label.mode == 2 else curve.master_cycle
            for s51, s52 in self.accepted:
                log.label(t, s51, s52, length)
            self.accepted.clear()
        if label.corrected != self._corrected:
            log.correction(1000.0 * (label.corrected - self._corrected))
            self._corrected = label.corrected
        log.tracking(op.axis.following_error)
        out = op.out
        if out & _O15_O16 != self._logged_out:  # the log keeps the changes of O15 / O16
            self._logged_out = out & _O15_O16
            log.outputs(t, bool(out & _O15), bool(out & _O16))
        wraps = op.chain.wraps
        if curve is not None and wraps > 0:
            for _ in range(wraps):
                log.wrap(t, curve=int(op.status(43)), state=op.state.value,
                         label_ok=label.o14 if label.mode != 0 else True, synchronous=bool(out & _O16))
        if op.last_error != self._op_error:
            self._op_error = op.last_error
            if op.last_error:
                self.status[30] = op.last_error
        if out != self._written_out and self.outputs:
            # the io outputs wired to O1 ... O16 are the device's alone: written when one changes
            self._written_out = out
            io = self.io
            for n, io_name in self.outputs:
                io.write(io_name, bool(out >> (n - 1) & 1))
