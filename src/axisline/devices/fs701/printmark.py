"""FS701 print mark control: Cutting Mode 2 (cut to print marks) and 3 (with additional cuts).

Used by the Cutter (cutter.py); the pieces are the kernel's registration parts
(motion.registration):

    MarkCapture   the master position when the mark passed the sensor: the edge's sub-cycle
                  moment interpolated between the cycle's master positions, the Photocell
                  Delay taken back (p - v d), Photocell -> Cut added ("at the tool")
    MarkWindow    Printmark Window with teach, missing-mark counting and the substitute mark
                  ("cut with preset length when printmark is missing")
    MarkQueue     the cut-position FIFO of 64 between sensor and carriage (Error 04 on overflow)

Per cycle (Cutter.tick): `advance` after the master update processes the edges given since
the last tick (`edge`), closes the windows the master passed, and the cutter asks
`home_logic` whether the head of the FIFO must start its approach now.

Each good mark (accepted by the window, or any mark with the window off) counts for
Printm. per Length; every N-th (the first after Start) becomes the cut target

    T = x_sensor + Photocell->Cut - Printmark Offset          (LU of the master; x_sensor:
                                                              master position at the mark)

with Additional Cuts n (mode 3) preceded by T - (L1 + w), T - (L1 + L2 + 2w), ... (w = Tool
Width), all pushed in master order into the FIFO. The cut's piece length (for reports) is the
distance to the previous cut position less the Tool Width.

Decisions (spec [AMBIGUOUS]/[GAP]/[DERIVED] points of print mark operation; tests in
tests/devices/fs701/test_cutter_printmark.py):
 P1 Printmark Offset sign (spec §2.9 [AMBIGUOUS]): the manual's words: "A positive value moves
    the cut forward (leading the printmark)": forward is the line's direction, so the cut lies
    downstream of the mark and reaches the tool earlier: T = x + P2C - offset.
    `OFFSET_SIGN` (or one unit's `printmarks.offset_sign`) = -1 gives the other reading.
    Test: test_printmark_offset_moves_the_cut_forward_p1.
 P2 Printmark Window (spec §2.10 [AMBIGUOUS]): the setting is the FULL width (the window is
    +-W/2 around the expected mark, "a symmetric window"); the window is linear in the master
    position and follows the marks (next expected = last good mark + pitch), pitch = Cutting
    Length / Printm. per Length (the mark pitch; Cutting Length is the sheet). Before a teach
    the first mark places the window (self-locking); teach re-centres it (a mark seen while
    Teach is HIGH, or the master position at its falling edge). Output Printmark Window: the
    window is open (always HIGH with W = 0). Tests: test_window_with_teach_ignores_the_other_marks_p2,
    test_teach_at_standstill_takes_the_position_at_the_falling_edge_p2.
 P3 Missing marks (spec §2.10 [DERIVED]): with the window on, a window that passes without a
    mark yields a substitute mark one pitch after the last good mark or substitute (the cut
    "with preset length"), cut as a virtual mark (output Virt. Printmark during its cycle);
    Miss. Printm. Cou. (#19) counts consecutive misses; No Printmark is set when it reaches
    Missing Printmarks (0: never) and cleared by the next good mark or Clear Error. With the
    window off nothing is monitored. Tests: test_missing_mark_gives_a_substitute_cut_and_the_alarm_p3,
    test_missing_mark_monitoring_is_off_without_a_window.
 P4 Printm. per Length (spec §3.4 table shift): 1..99, 0 read as 1; the first good mark after
    Start cuts, then every N-th. Test: test_printmarks_per_length_cuts_every_nth_mark_p4.
 P5 Marks are registered in automatic operation only; Start clears the FIFO (and fills it with
    virtual marks when Virt. Printmarks = 1). The window and teach work in Stop too.
    Test: test_marks_are_registered_only_in_automatic_p5.
 P6 Virtual marks (spec §2.11 [DERIVED]): n = floor(Photocell->Cut / Cutting Length) marks as
    if they had passed the sensor Cutting Length apart before Start (the last one a sheet
    before the Start position); a virtual cut whose start point has already passed is dropped
    silently. Test: test_virtual_printmarks_at_start_p6.
 P7 Multiple cuts (spec §2.12 [GAP]): chronological order tail, L3, L2, L1 ending at the trigger
    mark ("(e) Add. Cut 1 Length = Trigger print mark"); each cut consumes Tool Width, so the
    tail shrinks (E11: 5000 pitch, L1 1000, w 10 -> pieces 3980 and 1000). Positions that
    would not lie after the previous cut position are skipped. The settings are read when the
    mark is registered (manual: changes act after the registered marks are cut).
    Test: test_e11_additional_cut_geometry_p7 (E11).
 P8 FIFO capacity (spec E10): one ring of 64 cut positions; a mark whose positions do not all
    fit is dropped and sets Error 04, so 64/32/21/16 marks fit with 0/1/2/3 additional cuts.
    Test: test_e10_fifo_capacity_64_32_21_16 (E10).
 P9 A real mark whose start point is passed while the carriage is not home, or is already
    passed when it reaches the head (Photocell -> Cut shorter than the anticipation), is
    Error 02 (dropped). Test: test_mark_too_close_to_the_tool_is_error_02_p9.
 P10 Printmark Status #20 [GAP]: bit 0 window on, 1 window open, 2 teach armed, 3 taught,
    4 No Printmark, 5 FIFO overflow. Test: test_printmark_status_and_process_values_p10.
"""

from __future__ import annotations

import math
from typing import Any

from axisline.motion.registration import ChannelMotion, MarkCapture, MarkKind, MarkQueue, MarkVerdict, MarkWindow

# cutter.py imports this module lazily (in Cutter.__init__), so this import is never circular
from .cut_states import _V_EPS, CutKind, CutState, FS701Error
from .cutter_state import CutInfo

__all__ = ["PrintMarkControl", "FIFO_CAPACITY"]

FIFO_CAPACITY = 64
_EDGE_BUFFER = 64  # print mark edges per cycle kept until the tick


#: P1: +1: a positive Printmark Offset moves the cut downstream of the mark (the default of
#: every PrintMarkControl.offset_sign; -1 gives the other reading)
OFFSET_SIGN = 1


class PrintMarkControl:
    """Print mark registration and the cut-position FIFO of one Cutter."""

    def __init__(self, cutter: Any) -> None:
        self.offset_sign = OFFSET_SIGN
        self.cutter = cutter
        self.period = cutter.period
        self.channel = ChannelMotion(0.0)
        self.capture = MarkCapture(self.channel, period=self.period)
        self.queue = MarkQueue(FIFO_CAPACITY)
        self._piece = [math.nan] * FIFO_CAPACITY  # nominal piece length per FIFO slot
        self._kind = [0] * FIFO_CAPACITY  # CutKind per FIFO slot
        # edges of the last simulated cycle, preallocated
        self._edge_f = [0.0] * _EDGE_BUFFER
        self._edge_r = [False] * _EDGE_BUFFER
        self._edges = 0
        self.window: MarkWindow | None = None
        self._window_w = -1.0
        self._window_pitch = -1.0
        self._mark_count = 0  # good marks since Start (Printm. per Length)
        self._last_pushed_mc: float | None = None
        self._teach_prev = False
        self._teach_mark = False
        self.taught = False
        self.overflow = False
        self.last_mark = math.nan  # master LU at the sensor
        self.last_delay_length = 0.0  # LU
        self.marks_seen = 0
        self.marks_ignored = 0
        self.virtual_cuts = 0
        self._channel_ready = False

    @property
    def marks_counted(self) -> int:
        """Good marks (and substitutes) since Start: the Printm. per Length count."""
        return self._mark_count

    # ------------------------------------------------------------------ settings-dependent parts

    def _pitch(self) -> float:
        s = self.cutter.settings
        n = max(int(s.printm_per_length), 1)
        return max(float(s.cutting_length), 1e-9) / n

    def _ensure_window(self) -> MarkWindow | None:
        s = self.cutter.settings
        w = float(s.printmark_window)
        if w <= 0.0:
            self.window = None
            self._window_w = w
            return None
        pitch = self._pitch()
        if self.window is None or w != self._window_w or pitch != self._window_pitch:
            half = min(w / 2.0, pitch / 2.0)
            pos = self.cutter.master.position
            self.window = MarkWindow(
                pos + pitch,
                half_width=half,
                pitch=pitch,
                follow_marks=True,
                startup="first",
                substitute="extrapolate",
                missing_alarm_after=int(s.missing_printmarks),
                position=pos,
            )
            self._window_w = w
            self._window_pitch = pitch
        return self.window

    # ------------------------------------------------------------------ inputs

    def edge(self, edge: Any) -> None:
        """A Print Mark input edge of the cycle just simulated (fraction 0..1, rising = level after)."""
        i = self._edges
        if i >= _EDGE_BUFFER:
            return  # more than 64 edges in one cycle: the input filter's limit
        self._edge_f[i] = float(edge.fraction)
        self._edge_r[i] = bool(edge.rising)
        self._edges = i + 1

    def reset(self) -> None:
        """Control Enable OFF: FIFO, counters and window start over."""
        self.queue.reset()
        self._mark_count = 0
        self._last_pushed_mc = None
        self.overflow = False
        self.window = None
        self._window_w = -1.0
        self._edges = 0

    def clear_errors(self) -> None:
        self.overflow = False
        self.queue.clear_overflow()
        if self.window is not None:
            self.window.alarm = False
            self.window.consecutive_missing = 0

    def on_start(self) -> None:
        """P5/P6: Start clears the FIFO; with Virt. Printmarks it is filled with virtual marks."""
        c = self.cutter
        s = c.settings
        self.queue.reset()
        self._mark_count = 0
        self._last_pushed_mc = None
        self.overflow = False
        if s.cutting_mode not in (2, 3) or not s.virt_printmarks:
            return
        spacing = float(s.cutting_length)
        if spacing <= 0.0:
            return
        n = math.floor(s.photocell_cut / spacing + 1e-9)
        x0 = c.master.position
        for k in range(n, 0, -1):
            self._register(x0 - k * spacing, CutKind.VIRTUAL, count=False)

    # ------------------------------------------------------------------ per cycle

    def advance(self, cycle: int) -> None:
        c = self.cutter
        s = c.settings
        m = c.master
        pos = m.position
        if not self._channel_ready:
            self.channel = ChannelMotion(pos)
            self.capture = MarkCapture(self.channel, period=self.period)
            self._channel_ready = True
        self.channel.advance(pos)
        mode_pm = s.cutting_mode in (2, 3)
        teach = c.inputs.teach_printmark
        if not mode_pm and not teach and not self._teach_prev and not self._edges:
            return  # length mode, no teach, no edge: nothing below would change anything
        cap = self.capture
        cap.sensor_delay = float(s.photocell_delay) / 1000.0
        cap.sensor_to_tool = float(s.photocell_cut)
        window = self._ensure_window() if mode_pm else None
        # Teach Printmark (P2)
        if teach and not self._teach_prev:
            self._teach_mark = False
            if window is not None:
                window.arm_teach()
            self.taught = False
        active_rising = s.printmark_edge == 0
        n = self._edges
        self._edges = 0
        for i in range(n):
            if self._edge_r[i] != active_rising:
                continue
            if not mode_pm:
                continue
            mark = cap.capture(self._edge_f[i])
            self.marks_seen += 1
            self.last_delay_length = mark.delay_length
            x = mark.master
            if window is not None:
                verdict = window.mark(x)
                if verdict is MarkVerdict.IGNORED:
                    self.marks_ignored += 1
                    continue
                if verdict is MarkVerdict.TAUGHT:
                    self.taught = True
            elif teach:
                self.taught = True
            if teach:
                self._teach_mark = True
            self.last_mark = x
            self._good_mark(x, virtual=False)
        if not teach and self._teach_prev and not self._teach_mark:
            # teach released without a mark: the position at the falling edge (line at standstill)
            if window is not None:
                window.teach(pos)
            self.taught = True
        self._teach_prev = teach
        if window is not None:
            sub = window.update(pos)
            if sub is not None:
                self._good_mark(sub, virtual=True)

    def _good_mark(self, x: float, *, virtual: bool) -> None:
        c = self.cutter
        s = c.settings
        if not c.inputs.start_stop:
            return  # P5: registered in automatic operation only
        n = max(int(s.printm_per_length), 1)
        k = self._mark_count
        self._mark_count = k + 1
        if k % n:
            return
        self._register(x, CutKind.VIRTUAL if virtual else CutKind.PRINTMARK, count=True)

    def _register(self, x: float, kind: Any, *, count: bool) -> None:
        """Cut positions of a mark captured at master x (LU): additional cuts first (P7)."""
        c = self.cutter
        s = c.settings
        pl = s.pulses_line_1000
        target = (x + s.photocell_cut - self.offset_sign * s.printmark_offset) * pl
        positions: list[tuple[float, Any]] = []
        if s.cutting_mode == 3 and s.additional_cuts > 0:
            lengths = (s.add_cut_1_length, s.add_cut_2_length, s.add_cut_3_length)[: int(s.additional_cuts)]
            w = float(s.tool_width)
            d = 0.0
            for L in lengths:
                d += float(L) + w
                positions.append((target - d * pl, CutKind.ADDITIONAL if kind is CutKind.PRINTMARK else kind))
            positions.reverse()
        positions.append((target, kind))
        last = self._last_pushed_mc
        positions = [(p, k) for p, k in positions if last is None or p > last]
        if not positions:
            return
        q = self.queue
        if q.capacity - len(q) < len(positions):
            # P8: the mark does not fit: Error 04, the mark is dropped
            self.overflow = True
            q.overflow = True
            c._set_error(FS701Error.PRINTMARK_BUFFER)
            return
        for p, k in positions:
            slot = q.write_index
            prev = self._last_pushed_mc
            self._piece[slot] = (p - prev) / pl - s.tool_width if prev is not None else math.nan
            self._kind[slot] = int(k)
            q.push(p, MarkKind.VIRTUAL if k is CutKind.VIRTUAL else MarkKind.REAL)
            self._last_pushed_mc = p

    # ------------------------------------------------------------------ cut scheduling

    def next_target_mc(self) -> float | None:
        """Head of the FIFO, or the earliest a mark at the sensor now could be cut."""
        q = self.queue
        if len(q):
            return q.head_position
        c = self.cutter
        s = c.settings
        return (c.master.position + s.photocell_cut - self.offset_sign * s.printmark_offset) * s.pulses_line_1000

    def _pop(self) -> tuple[float, int, float]:
        q = self.queue
        slot = q.read_index
        mark = q.pop()
        return mark.position, self._kind[slot], self._piece[slot]

    def home_logic(self, now_mc: int, V: float) -> None:
        """Carriage home in automatic print mark operation: start the head's approach when due."""
        c = self.cutter
        q = self.queue
        while len(q):
            if V <= _V_EPS:
                return
            target = q.head_position
            start = c._start_mc(target, V)
            if now_mc < start:
                return
            kind = CutKind(self._kind[q.read_index])
            late = now_mc - start > c._late_tolerance_mc(V)
            if late or not c._home_ok():
                self._pop()
                if kind is CutKind.VIRTUAL and late and c._home_ok():
                    continue  # P6: a virtual cut too close to the tool at Start: dropped silently
                c._cut_not_possible(int(round(target)))  # P9
                return
            p, k, piece = self._pop()
            info = CutInfo(c._cut_number + 1, CutKind(k), int(round(p)), piece)
            if info.kind is CutKind.VIRTUAL:
                self.virtual_cuts += 1
            c.start_printmark_cut(info, V)
            return

    def check_while_returning(self, now_mc: int, V: float) -> None:
        """The head's start point reached while the carriage is still out: Error 02 (P9)."""
        q = self.queue
        if not len(q):
            return
        c = self.cutter
        target = q.head_position
        if now_mc >= c._start_mc(target, V):
            self._pop()
            c._cut_not_possible(int(round(target)))

    # ------------------------------------------------------------------ outputs / process values

    def outputs(self, o: Any) -> None:
        c = self.cutter
        w = self.window
        o.printmark_window = True if w is None else w.window_open
        o.no_printmark = bool(w is not None and w.alarm and c.settings.missing_printmarks > 0)
        o.printm_teached = self.taught
        cur = c.current_cut
        o.virt_printmark = bool(
            cur is not None and cur.kind is CutKind.VIRTUAL and c.cut_state not in (CutState.HOME, CutState.IDLE, CutState.JOG)
        )

    def process_values(self) -> dict[int, float]:
        c = self.cutter
        s = c.settings
        kl = s.line_counts_per_lu
        w = self.window
        pos = c.master.position
        sheet = (pos - self.last_mark) * kl if not math.isnan(self.last_mark) else 0.0
        q = self.queue
        virtual = 0
        for i in range(len(q)):
            if self._kind[(q.read_index + i) % q.capacity] == CutKind.VIRTUAL:
                virtual += 1
        status = (
            (w is not None)
            | (bool(w is not None and w.window_open) << 1)
            | (bool(w is not None and w._teach_armed) << 2)
            | (self.taught << 3)
            | (bool(w is not None and w.alarm) << 4)
            | (self.overflow << 5)
        )
        return {
            16: sheet,
            17: self.last_delay_length * kl,
            18: self.last_mark * kl if not math.isnan(self.last_mark) else 0.0,
            19: w.consecutive_missing if w is not None else 0,
            20: status,
            21: virtual,
            22: q.write_index,
            23: q.read_index,
            24: len(q),
        }
