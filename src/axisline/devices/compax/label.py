"""COMPAX XX70 online label synchronisation (compax.md §2.13, §2.14 P32/P33 acceptance, §2.18 O14;
manual §14, §15.3.2, §19.2, §20, §21).

    label = LabelSync()
    op = CamOperation(axis, params, curves, encoder=enc, inputs=inputs, label=label)
    op.tick(cycle, i14_edges=sensor_edges)      # the label input's edges of the cycle
    label.on_label = lambda s51, s52: ...       # each accepted label (S51, S52 in per mille)
    label.corrected                             # correction applied so far (fraction of the cycle)

The label sensor is on I14. The device polls I14 every 100 µs; an edge from the plant (with its
exact moment in the 1 ms cycle) is seen at the next 100 µs poll, and the label value is the
master (P33 = 1) or slave (P33 = 2) position at that poll, interpolated between the cycle's
start and end. Positions are fractions of the cycle (S50 ... S52 in per mille):

    master related:  frame = master position (S44), reference M_ref = M_M - |P32|
    slave related:   frame = slave position in the curve (S45), reference S_ref = S_M - |P32|
                     (cycles added until the result lies in 0 ... cycle, §14.2)

A label is accepted inside the window ref ± M_f (the first measurement after the label
synchronisation is enabled is taken without the window); its deviation F_k = label - ref
(S52 = S51 - S50, wrapped into half a cycle either way) becomes the pending correction
(`motion.registration.Correction`: a new label replaces what is still pending, because it is
measured in the corrected frame), limited per P180 and spread over the master range M_k1 ...
M_k2 (wrapping past the cycle end when M_k1 > M_k2; equal: the whole cycle). Master related,
the correction is injected into the master position integrator (before the curve, the master
chain); slave related, it is added to the slave channel after the curve (the curve offset).

Decisions (spec line -> choice, why); each has a test in tests/devices/compax/test_camop_label.py:

* L1 Sign of the correction (§2.13 [DERIVED] "Sign convention ... not stated — choose so that
  the next label lands on S50"): master related, -F_k is added to the master position (a
  label seen late means the master count ran ahead of the product); slave related, +F_k·S_T
  is added to the slave set point (a label seen late in the curve needs the slave, which
  carries the product, to feed more). With a constant slip the next label lands on the
  reference. Tests: test_master_related_label_converges, test_slave_related_label_converges.
* L2 Stuck-high I14 (§2.13 "If I14 remains on "1", a label signal is recognised cyclically at
  the window start ... a drift in the positive master direction of M_f per cycle"): I14 is
  evaluated only inside the window once the window applies; I14 = 1 at the window start is a
  rising edge there. Test: test_stuck_high_i14_drifts_by_the_window_per_cycle (§7 X10).
* L3 O14 (§2.18 [CONFLICT] §14.3 "reset to 1 when the next window is reached" vs §19.2 "remains
  at 0 until the next label is recognised"): §19.2, the output's own description: O14 = 0 from
  the end of a window without a label until a label is recognised; 0 after power on until
  the first label. Test: test_o14_label_missing.
* L4 P180 (§2.13 table, §7 X11): P180 = 0 or >= 100: the first label is corrected in full
  wherever it is, then only labels inside the window; 0 < P180 <= M_f (in % of the cycle):
  labels are taken without the window until one lies inside it (start-up), every correction
  limited to P180 % of the cycle; P180 > M_f: the same start-up, then no P180 limit (the
  window limits). Tests: test_p180_examples.
* L5 "When the corrections are allocated, it is ensured that the corrections are terminated in
  the next label window" (§2.13): a label's correction replaces the rest of the previous one
  (the registration rule), so a correction never runs on past the next accepted label.
* L6 100 µs sampling (§1.4, §2.17 "The label impulse has to be longer than 100µs"): an edge at
  fraction f of the cycle is seen at the poll ceil(10·f)/10; a pulse whose rising and falling
  edge fall before the same poll is not seen. Test: test_label_timing_error (§7 X9).
* L7 P32 / P33 acceptance (§2.14, §15.3.2): both are taken at LOOP; P33 = 10 ... 12 and P32 also
  at the end of every curve cycle; P33 = 0 ... 2 only at LOOP. A change of the mode (or its
  first enabling) restarts the first measurement without the window (§2.13). SETM stops a
  master related correction in progress and restarts the first measurement ("SETM interrupts
  a current master related label synchronization!"). Master related synchronisation runs
  while the master is counted (also before LOOP); slave related only while synchronous
  (O16 = 1), its pending correction is dropped when the slave leaves synchronous operation.
* L8 Window size (§2.13 "Restriction: M_f <= 0.3 * M_T"): a larger window is limited to 0.3.
* L10 Slave related setup P31 = "2" (detailed procedure) vs "4" (summary) (§2.13 [CONFLICT]):
  both are accepted; each enables the master counting with the first reference pulse on I16
  after SETC (they differ only in what a later SETC does with I16 = 1, masterchain MC4/MC5).
  Test: test_slave_related_setup_with_p31_2_or_4.
* L9 S13/S14 code 31 "function pointer" ([GAP]: values not given): 0 off, 1 first measurement
  (no window), 2 start-up (until a label lies in the window), 3 window, +10 while a correction
  is in progress. Code 32 runs 0 ... 1000 per mille over a correction.
* L11 Master related distribution over M_k1 ... M_k2 (§2.13 "positive or negative correction
  pulses into the integrator for the master position"; "it is ensured that the corrections are
  terminated in the next label window"): the pulses move the master the range is measured in, so
  the correction is spread over the rest of the range measured in the uncorrected master travel
  (from the corrected position when the label is taken; `Correction(in_phase=True)`). A
  correction larger than the rest of the range makes the master run at most
  (1 + F_k / rest) times its speed, never a jump. Tests: test_early_label_large_correction_is_no_jump,
  test_correction_in_phase_spreads_over_uncorrected_travel.
"""

from __future__ import annotations

import math
from typing import Any, Callable

from axisline.devices.compax.camio import CamState
from axisline.devices.compax.masterchain import param
from axisline.motion.registration import Correction, phase, wrap

__all__ = ["LabelSync", "POLL_PER_CYCLE", "poll_fraction"]

#: I14 is polled every 100 µs: 10 polls per 1 ms cycle (§1.4).
POLL_PER_CYCLE = 10
_MAX_WINDOW = 0.3


def poll_fraction(fraction: float, polls: int = POLL_PER_CYCLE) -> float:
    """The fraction of the cycle at which a poll every 1/polls of the cycle sees an edge at `fraction`."""
    return min(1.0, max(0.0, math.ceil(fraction * polls - 1e-9) / polls))


def _edges(edges: Any) -> list[tuple[float, bool]]:
    out = []
    for e in edges:
        if isinstance(e, tuple):
            f, rising = float(e[0]), bool(e[1]) if len(e) > 1 else True
        else:
            f, rising = float(e.fraction), bool(getattr(e, "rising", True))
        out.append((f, rising))
    out.sort(key=lambda x: x[0])
    return out


class LabelSync:
    """Label synchronisation of one cam operation; see the module docstring."""

    def __init__(self) -> None:
        self.op: Any = None
        self.mode = 0  # accepted P33 % 10: 0 off, 1 master related, 2 slave related
        self.p33 = 0
        self.p32 = 0.0
        self.level = False  # I14 as last seen
        self.o14 = False  # "After Power on, O14 is initially at 0."
        self.ref = 0.0
        self.window = 0.0
        self.s51 = 0.0
        self.s52 = 0.0
        self.correction = Correction()
        self._first = True  # the next label is taken without the window
        self._until_inside = False
        self._limit_after = math.inf  # per-mark limit once the window applies
        self._X = 0.0  # frame position (cycles, unwrapped) at the end of the last cycle
        self._have_X = False
        self._window_n = 0  # index of the current window (centre n + ref)
        self._seen = False
        self._in_window = False
        self._total = 0.0  # size of the correction in progress (for indicator 32)
        self._was_active = False
        self._range: tuple[float, float] | None = None  # (M_k1, M_k2) of the correction
        #: called with (S51, S52) in per mille for each label accepted (ignored ones are not
        #: reported: outside the window, a second label in it)
        self.on_label: Callable[[float, float], None] | None = None
        #: correction applied since construction (fraction of the cycle, same sign as the
        #: deviation; never reset, so a reader can take differences across restarts)
        self.corrected = 0.0

    # ------------------------------------------------------------------ wiring

    def attach(self, op: Any) -> None:
        self.op = op

    @property
    def active(self) -> bool:
        """Label synchronisation switched on (P33 != 0): O14 is the label error."""
        return self.mode != 0

    def _running(self) -> bool:
        op = self.op
        if self.mode == 1:
            return bool(op.chain.counting)
        if self.mode == 2:
            state = op.state
            return state is CamState.SYNC or state is CamState.WAIT_DECOUPLE
        return False

    # ------------------------------------------------------------------ acceptance (L7)

    def event(self, name: str) -> None:
        op = self.op
        if op is None:
            return
        if name == "LOOP":
            self._take_p33(int(param(op.params, 33)))
            self.p32 = float(param(op.params, 32))
            self._reference()
        elif name == "CYCLE":
            value = int(param(op.params, 33))
            if value >= 10 or self.p33 >= 10:
                if value >= 10:
                    self._take_p33(value)
                self.p32 = float(param(op.params, 32))
            self._reference()
        elif name == "SETC":
            self._reference()

    def _take_p33(self, value: int) -> None:
        mode = value % 10
        if mode not in (0, 1, 2):
            mode = 0
        self.p33 = value
        if mode != self.mode:
            self.mode = mode
            self._restart()

    def _limited(self) -> bool:
        p180 = float(param(self.op.params, 180)) if self.op is not None else 0.0
        return 0.0 < p180 < 100.0

    def _restart(self) -> None:
        """First measurement without the window (§2.13); limits per P180 (L4)."""
        self._first = True
        self._until_inside = self._limited()
        self._have_X = False
        self._seen = False
        self._in_window = False
        self.correction.reset()
        self._total = 0.0
        self._setup_correction()

    def interrupt(self) -> None:
        """SETM: stop a master related correction in progress and start over (L7)."""
        if self.mode == 1:
            self._restart()

    def _reference(self) -> None:
        op = self.op
        curve = op.curve if op is not None else None
        if curve is None:
            return
        cycle = curve.master_cycle if self.mode != 2 else curve.slave_cycle
        distance = abs(self.p32) / cycle if cycle else 0.0
        self.ref = phase(curve.label_set_point - distance, 1.0)  # M_ref = M_M - |P32| (+ cycles)
        self.window = min(max(0.0, curve.label_window), _MAX_WINDOW)
        self._setup_correction()

    def _setup_correction(self) -> None:
        op = self.op
        curve = op.curve if op is not None else None
        p180 = float(param(op.params, 180)) if op is not None else 0.0
        limit = p180 / 100.0
        if p180 <= 0.0 or p180 >= 100.0:
            per_mark, self._limit_after = None, math.inf
        else:
            self._limit_after = limit if limit <= self.window else math.inf
            per_mark = limit if not self._windowing() else self._limit_after
        k1 = curve.k1 if curve is not None else 0.0
        k2 = curve.k2 if curve is not None else 0.0
        c = self.correction
        if self._range != (k1, k2):
            # a new range: a new distributor that keeps what is pending and applied
            self._range = (k1, k2)
            new = Correction(max_per_mark=per_mark, enable_from=k1, enable_to=k2, master_cycle=1.0, spread=True)
            new.pending, new.applied, new.requested = c.pending, c.applied, c.requested
            self.correction = c = new
        c.max_per_mark = math.inf if per_mark is None else per_mark
        if self._windowing():
            c.max_per_mark = self._limit_after

    # ------------------------------------------------------------------ per cycle

    def _frame(self, u: float) -> float:
        """Position in the measuring frame (fraction of the cycle): master u, or the curve F(u)."""
        if self.mode == 2:
            return self.op._f(u)[0]
        return u

    def measure(self, u_prev: float, wraps: int, edges: Any, u: float | None = None) -> None:
        """The label input of the cycle that ended now (called after the master update; `u`: the
        master position now, ``op.chain.fraction``, when the caller has it)."""
        op = self.op
        if op is None or op.curve is None:
            return
        running = self.mode != 0 and self._running()
        if not running:
            if self._was_active and self.mode == 2:
                self.correction.cancel()  # slave related: switched off during decoupling (L7)
            self._was_active = False
            self._have_X = False
            self._track_level(edges)
            return
        self._was_active = True
        if u is None:
            u = op.chain.fraction
        if self.mode == 2:  # `_frame`, inline
            f0, f1 = op._f(u_prev)[0], op._f(u)[0]
        else:
            f0, f1 = u_prev, u
        if not self._have_X:
            self._X = f0
            self._have_X = True
            self._place(f0)
            self._seen = self._in_window  # a window entered in its middle is not held against the line
        X0 = self._X
        X1 = X0 + wrap(f1 - f0, 1.0)
        if edges is None:
            level = op.input("I14")
            events = [(1.0, level)] if level != self.level else []
        else:
            events = []
            for f, rising in _edges(edges):
                fp = poll_fraction(f)
                if events and events[-1][0] == fp and events[-1][1] != rising:
                    events.pop()  # a pulse shorter than the poll: not seen (L6)
                    continue
                events.append((fp, rising))
        for fp, rising in events:
            X = X0 + (X1 - X0) * fp
            self._windows_until(X)
            if rising and not self.level:
                self.level = True
                self._label(X)
            elif not rising:
                self.level = False
        self._windows_until(X1)
        self._X = X1

    def _track_level(self, edges: Any) -> None:
        if edges is None:
            if self.op is not None:
                self.level = self.op.input("I14")
            return
        for _, rising in _edges(edges):
            self.level = rising

    def _place(self, X: float) -> None:
        """Current window: the first whose end is not behind X (window n: n + ref ± M_f)."""
        w = self.window
        self._window_n = math.ceil(X - self.ref - w)
        self._in_window = X >= self._window_n + self.ref - w

    def _windowing(self) -> bool:
        return not self._first and not self._until_inside

    def _windows_until(self, X: float) -> None:
        """Open and close the windows the frame passes up to X (only once the window applies)."""
        if not self._windowing() or self.window <= 0.0:
            return
        w = self.window
        while True:
            centre = self._window_n + self.ref
            if not self._in_window:
                start = centre - w
                if X < start:
                    return
                self._in_window = True
                self._seen = False
                if self.level:
                    self._label(start)  # I14 already 1 at the window start: a rising edge there (L2)
            end = centre + w
            if X <= end:
                return
            if not self._seen:
                self.o14 = False  # label missing (L3)
            self._in_window = False
            self._window_n += 1

    def _label(self, X: float) -> None:
        """A rising edge of I14 at frame position X."""
        deviation = wrap(X - self.ref, 1.0)
        inside = abs(deviation) <= self.window
        if self._windowing():
            if not self._in_window or self._seen:
                return  # outside the window (or a second label in it): ignored
            self._seen = True
        else:
            if self._until_inside and inside:
                self._until_inside = False
            self._first = False
            if not self._until_inside:
                self.correction.max_per_mark = self._limit_after
                # the window applies from here: the window of this label has had its label
                self._place(X)
                self._seen = self._in_window
        self.o14 = True
        self.s51 = 1000.0 * phase(X, 1.0)
        self.s52 = 1000.0 * deviation
        self._total = self.correction.set(deviation)
        if self.on_label is not None:
            self.on_label(self.s51, self.s52)

    def step(self, U: float) -> float:
        """This cycle's share of the correction; returns the slave set-point change (units)."""
        op = self.op
        if op is None or op.curve is None or self.mode == 0:
            return 0.0
        if not self._running():
            return 0.0
        before = self.correction.applied
        # L11: master related, the correction moves the master it is spread over
        self.correction.in_phase = self.mode == 1
        self.correction.step(op.chain.fraction)
        amount = self.correction.applied - before  # same sign as the deviation
        if amount == 0.0:
            return 0.0
        self.corrected += amount
        if self.mode == 1:
            # L1: into the master integrator; the frame (the master position) shows it next cycle
            op.chain.inject(-amount * op.chain.scaled_cycle)
            return 0.0
        # slave related: the slave feeds more; the labels then arrive earlier in the curve
        return amount * op.curve.slave_cycle * op.p36

    # ------------------------------------------------------------------ status

    def status(self, n: int) -> float:
        if n == 50:
            return 1000.0 * self.reference_now()
        if n == 51:
            return self.s51
        return self.s52

    def reference_now(self) -> float:
        """S50 from the valid P32 / P33 and the selected curve ("S50 changes with P32 and with the
        selected curve; S50 must therefore be read out after each change", §14.6.1)."""
        op = self.op
        curve = op.curve if op is not None else None
        if curve is None:
            return self.ref
        slave = int(param(op.params, 33)) % 10 == 2
        cycle = curve.slave_cycle if slave else curve.master_cycle
        distance = abs(float(param(op.params, 32))) / cycle if cycle else 0.0
        return phase(curve.label_set_point - distance, 1.0)

    def indicator(self, code: int) -> float:
        pending = self.correction.pending
        if code == 32:
            total = self._total
            if total == 0.0:
                return 0.0
            return 1000.0 * (1.0 - pending / total)
        if self.mode == 0:
            return 0.0
        state = 1 if self._first else (2 if self._until_inside else 3)
        return float(state + (10 if pending else 0))
