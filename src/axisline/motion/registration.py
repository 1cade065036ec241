"""Registration to print marks and labels: capture, window, correction, missing marks, mark queue.

The generic parts both registration personalities build on (a flying cut-off that cuts at print
marks, a cam controller that keeps labels in phase with its curve). Device parameter names stay
in the devices; every behaviour they need is a combination of the pieces here:

:class:`ChannelMotion`, :class:`MarkCapture`
    Where the master and the slave were when a mark passed the sensor. The sensor edge carries a
    sub-cycle moment (absolute time or fraction of the cycle); positions are interpolated between
    the cycle's start and end (linearly, or exactly for constant acceleration when velocities are
    known), the sensor's dead time is taken back and a fixed sensor-to-tool distance added.

:class:`MarkWindow`
    The expected mark position (cyclic with a cycle length, or linear with a pitch) and a window
    of +-half_width around it. Marks outside are ignored and counted; "teach" takes a mark as the
    new expected position; the start-up may accept marks without the window. A window that passes
    without a mark yields a substitute mark and counts a miss; ``missing_alarm_after``
    consecutive misses set the alarm, the next good mark clears it.

:class:`Correction`
    The correction ``measured - expected`` distributed smoothly: limited per mark, limited per
    cycle, optionally only inside a master range (spread over it in proportion to master travel).

:class:`Registration`
    Window + correction glued together for the usual per-cycle loop, with master-side or
    slave-side application.

:class:`MarkQueue`
    Marks between the sensor and the tool, first in first out, in a preallocated ring buffer;
    each becomes due when the tool reaches it; overflow is reported, never silently dropped;
    virtual marks fill the gap at start; only every n-th mark starts a product.

Sign conventions
----------------
*Deviation* (also called the measured correction) is ``measured - expected``: positive when the
mark came late in the measuring frame (the frame had already run past the expected position).
Cyclic deviations are wrapped into ``(-cycle/2, cycle/2]``.

Marks must be measured in the frame the correction acts on (the corrected master seen by the
slave, or the slave position including its correction). Then each new mark already shows what
the earlier corrections achieved, so a new deviation *replaces* the correction still pending
instead of adding to it; that is what keeps registration free of overshoot.

:attr:`Correction.offset` is ``-(correction applied so far)``: the amount to **add** to the
measuring frame so that the next mark lands on its expected position. For master-side
correction add it to the master position the slave follows; for slave-side correction add it to
the slave set point when the slave moves the tool. When the corrected channel instead *carries*
the material (a feed roll whose curve position is the measuring frame), moving the set point
forward makes marks arrive *earlier* in the curve, so subtract it there.

Per-cycle path: no containers are built (the queue is a preallocated numpy ring buffer); the
objects returned per mark are small named tuples.
"""

from __future__ import annotations

from axisline.motion.mark_capture import CapturedMark, ChannelMotion, MarkCapture
from axisline.motion.mark_correction import Correction
from axisline.motion.mark_queue import MarkKind, MarkQueue, QueuedMark
from axisline.motion.mark_window import MarkVerdict, MarkWindow
from axisline.motion.registration_common import Side, Startup, Substitute, expected_at_sensor, phase, wrap

__all__ = [
    "CapturedMark",
    "ChannelMotion",
    "Correction",
    "MarkCapture",
    "MarkKind",
    "MarkQueue",
    "MarkVerdict",
    "MarkWindow",
    "QueuedMark",
    "Registration",
    "Side",
    "Startup",
    "Substitute",
    "expected_at_sensor",
    "phase",
    "wrap",
]


class Registration:
    """A window and a correction working together, applied on the master or the slave side.

    Per cycle: :meth:`mark` for each captured mark (in the measuring frame, i.e. including the
    correction), then :meth:`step` with the frame position at the cycle end. An accepted mark's
    deviation becomes the pending correction; a taught mark cancels it (the reference changed);
    ignored marks and substitutes never steer the correction (they carry no measurement), so a
    correction in progress runs on.

    ``side`` says where the offset goes: ``"master"`` (the master position the slave follows,
    :meth:`master_for_slave`) or ``"slave"`` (the slave set point, :meth:`slave_set_point`).
    """

    __slots__ = ("window", "correction", "side")

    def __init__(self, window: MarkWindow, correction: Correction, *, side: Side = "master") -> None:
        if side not in ("master", "slave"):
            raise ValueError(f"side must be 'master' or 'slave', got {side!r}")
        self.window = window
        self.correction = correction
        self.side = side

    @property
    def offset(self) -> float:
        return self.correction.offset

    def mark(self, position: float) -> MarkVerdict:
        verdict = self.window.mark(position)
        if verdict is MarkVerdict.ACCEPTED or verdict is MarkVerdict.STARTUP:
            self.correction.set(self.window.deviation)
        elif verdict is MarkVerdict.TAUGHT:
            self.correction.cancel()
        return verdict

    def step(self, position: float, master_phase: float | None = None) -> float:
        """End of a cycle: window bookkeeping at frame ``position``, then this cycle's share of
        the correction. Returns the offset."""
        self.window.update(position)
        return self.correction.step(master_phase)

    def master_for_slave(self, master: float) -> float:
        """Master position the slave follows (corrected when the side is the master)."""
        return master + self.correction.offset if self.side == "master" else master

    def slave_set_point(self, set_point: float) -> float:
        """Slave set point (corrected when the side is the slave)."""
        return set_point + self.correction.offset if self.side == "slave" else set_point
