"""The FS701 cutter in layers (cutter.py describes the cut cycle and lists the decisions):

    CutterBase (this file)   construction, read-outs, the SyncSource side, errors, monitors,
                             the time-domain plans
      <- CutterMotion        starting a cut and its targets, jog, the set point of each state,
                             deceleration and the return (cutter_motion.py)
      <- Cutter              the cycle, enable and disable (cutter.py)

A layer calls only what it or a lower layer defines (single inheritance: mypyc compiles it).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Callable

from axisline.motion.axis import Axis
from axisline.motion.profiles import Profile

from .cut_settings import CutterSettings
from .cut_states import (
    _OUT_OF_CYCLE,
    _SYNC_STATES,
    ControlState,
    CutKind,
    CutState,
    FS701Error,
)
from .cutter_io import CutterInputs, CutterOutputs
from .line_master import LineMaster
from .loop import PositionLoop

__all__ = ["CutInfo", "CutterBase"]


@dataclass
class CutInfo:
    """The cut being executed (or last executed)."""

    number: int  # running number since construction
    kind: CutKind
    target_mc: int  # master position (milli-counts) at which the cut point passes home
    piece_length: float  # LU, nominal length of the piece this cut ends (nan: unknown)
    ready_cycle: int = -1  # cycle Ready to Cut rose (-1: not yet)


class CutterBase:
    """The cutter's state: construction, read-outs, the SyncSource side, errors, monitors and the
    time-domain plans (the lowest layer of `Cutter`, cutter.py)."""

    def __init__(self, axis: Axis, settings: CutterSettings, *, line: Any = None, period: float | None = None) -> None:
        self.axis = axis
        self.settings = settings
        self.period = float(axis.period if period is None else period)
        self.inputs = CutterInputs()
        self.outputs = CutterOutputs()
        self.master = LineMaster(settings, self.period, line)
        self.loop = PositionLoop(settings, self.period)
        from .printmark import PrintMarkControl  # local: printmark imports this module's types

        self.printmarks = PrintMarkControl(self)
        self.errors = 0  # Error Status word (bits per FS701Error)
        self.control_state = ControlState.DISABLED
        self.cut_state = CutState.IDLE
        # set point of this cycle (axis frame, LU)
        self._p = float(axis.command_position)
        self._v = 0.0
        self._a = 0.0
        self._cycle = -1
        # positions (axis frame)
        self.zero = float(axis.actual_position)  # FS701 Zero (C13)
        self.home_position = self._p
        # line / length
        self._last_cut_mc = 0  # milli-counts of the last cut target (the grid the next target is on)
        self._counter_mc = 0  # reference of the Length Counter #0: the last cut point that passed home
        self._counter_pending: int | None = None  # a cut point on its way to home
        self._next_kind = CutKind.NORMAL
        self._test_latch = False
        self._late_pending = False  # C9: the next length target may be late (after Start etc.)
        self.current_cut: CutInfo | None = None
        self._cut_number = 0
        self._pending: CutInfo | None = None  # target chosen for the next approach
        # approach (master domain)
        self._ap_profile: Profile | None = None
        self._ap_start_mc = 0.0  # milli-counts
        self._ap_V = 0.0  # LU/s nominal
        self._ap_sync_mc = 0.0
        self._s_sync = 0.0  # carriage travel at sync (rel. home)
        self._R = 1.0
        # synchronous phase
        self._sync_cycle = 0
        self._window_count = 0
        self._gap_profile: tuple[float, float] | None = None  # (length, duration)
        self._gap_c0 = 0
        self._gap_offset = 0.0
        self._cut_completed_latched = False
        # time-domain plan (deceleration -> return, jog): up to two profiles
        self._t_profiles: list[Profile | None] = [None, None]
        self._t_c0 = 0
        self._ret_speed = 0.0
        self._ret_planned_speed = 0.0
        # edges
        self._prev_in = CutterInputs()
        self._first_tick = True
        # counters / monitors
        self.batch_counter = int(settings.batch_counter)
        self.waste_counter = int(settings.waste_counter)
        self._fwd_length = 0.0  # LU of forward motion (length pulses)
        self._rev_peak = 0.0
        self._lp_last: float | None = None  # master position of the last tick (length pulses)
        self.min_pos_error = 0.0
        self.max_pos_error = 0.0
        self.car_travel_dist = 0.0  # increments, forward excursion of the last cycle
        self.set_length_counter_consumed = False
        self.test_counter = 0  # #31: cycles of the Test program (status.py decision; personality sets it)
        self._jog_dir = 0
        self.feasible_next = True
        self.cut_log: list[CutInfo] = []  # every cut that reached Ready to Cut (for reports)
        self.on_cut: Callable[[CutInfo], None] | None = None
        self.outputs.ready = True  # §2.19: ready after power-up / self-test

    # ------------------------------------------------------------------ read-outs

    @property
    def line_speed(self) -> float:
        """Process value #2: line speed, LU/min (filtered over Sampling Time)."""
        return self.master.velocity * 60.0

    @property
    def master_frequency(self) -> float:
        """#1: line encoder frequency, Hz (increments/s)."""
        return self.master.velocity * self.settings.line_counts_per_lu

    @property
    def length_counter(self) -> int:
        """#0: material length counter (line increments since the last cut point passed home)."""
        return (self.master.counts * 1000 - self._counter_mc) // 1000

    @property
    def position_error(self) -> float:
        """#3: scheduled - actual carriage position, carriage increments (+: carriage lags)."""
        return self.loop.position_error

    @property
    def carriage_abs_pos(self) -> float:
        """#9: carriage position related to Zero, increments."""
        return (self.axis.actual_position - self.zero) * self.settings.cut_counts_per_lu

    @property
    def carriage_cut_pos(self) -> float:
        """#7: carriage position related to home, increments."""
        return (self.axis.actual_position - self.home_position) * self.settings.cut_counts_per_lu

    @property
    def act_cut_length(self) -> float:
        """#10: length of the piece being cut, line increments."""
        c = self.current_cut or self._pending
        if c is None or math.isnan(c.piece_length):
            return self.settings.cutting_length * self.settings.line_counts_per_lu
        return c.piece_length * self.settings.line_counts_per_lu

    @property
    def ready_to_cut(self) -> bool:
        return self.outputs.ready_to_cut

    @property
    def set_point(self) -> tuple[float, float, float]:
        return self._p, self._v, self._a

    def error_active(self, err: FS701Error) -> bool:
        return bool(self.errors >> int(err) & 1)

    def process_values(self) -> dict[int, float]:
        """Process data #0..#31 this module knows (printmark values from printmark.py)."""
        pv = {
            0: self.length_counter,
            1: self.master_frequency,
            2: self.line_speed,
            3: self.position_error,
            4: self.loop.feed_forward_value,
            5: self.loop.correction_value,
            6: self.loop.integral_value,
            7: self.carriage_cut_pos,
            8: self.car_travel_dist,
            9: self.carriage_abs_pos,
            10: self.act_cut_length,
            12: self.min_pos_error,
            13: self.max_pos_error,
            14: self.batch_counter,
            15: self.waste_counter,
            29: int(self.control_state),
            30: int(self.cut_state),
            31: self.test_counter,
        }
        # #11, #25..#28: unused slots, the status image keeps them 0 (status.py decision)
        pv.update(self.printmarks.process_values())
        return pv

    # ------------------------------------------------------------------ SyncSource

    def sample(self, cycle: int) -> tuple[float, float, float]:
        """The carriage set point of `cycle` (computed in tick)."""
        return self._p, self._v, self._a

    # ------------------------------------------------------------------ plant-facing helpers

    def print_mark_edge(self, edge: Any) -> None:
        """A Print Mark input edge of the cycle just simulated (plant Edge: fraction, rising)."""
        self.printmarks.edge(edge)

    def position_loop(self, actual_position: float, actual_velocity: float | None = None) -> float:
        """Stage 4: the axis' bookkeeping, then the FS701 PI loop -> Ana-Out 2 volts."""
        ax = self.axis
        ax.position_loop(actual_position, actual_velocity)
        if not ax.powered:
            return self.loop.off()
        sync_phase = self.cut_state in _SYNC_STATES
        return self.loop.update(
            ax.command_position,
            ax.command_velocity,
            ax.actual_position,
            reset=self.inputs.reset_diff_cou,
            sync_mode=self.inputs.sync_mode_enable and sync_phase,
            set_acceleration=ax.command_acceleration,
        )

    # ------------------------------------------------------------------ errors

    def _set_error(self, err: FS701Error) -> None:
        self.errors |= 1 << int(err)

    def _clear_errors(self) -> None:
        self.errors = 0
        self._late_pending = True  # C9/C3: the next length target may have passed meanwhile
        self.feasible_next = True

    # ------------------------------------------------------------------ monitors

    def _monitors(self) -> None:
        s = self.settings
        o = self.outputs
        m = self.master
        pos = m.position
        # length pulses (C21): forward motion only
        if self._lp_last is None:
            self._lp_last = pos
            self._rev_peak = pos
        d = pos - self._lp_last
        self._lp_last = pos
        if d > 0.0:
            self._fwd_length += d
        half = s.length_per_pulse / 2.0
        o.length_pulses = bool(int(math.floor(self._fwd_length / half + 1e-9)) % 2) if half > 0 else False
        # master reverse (C22)
        if pos >= self._rev_peak:
            self._rev_peak = pos
            o.master_reverse = False
        elif s.master_rev_limit > 0 and self._rev_peak - pos > s.master_rev_limit:
            o.master_reverse = True
        if s.master_rev_limit <= 0:
            o.master_reverse = False
        # motion detection (§2.18)
        enc = m.encoder_master
        v_enc = abs(enc.velocity) * 60.0 if enc is not None else 0.0
        o.master_in_motion = v_enc > s.zero_speed_master
        o.vir_m_in_motion = abs(m.virtual.velocity) * 60.0 > s.zero_speed_vir_ma

    def _limits_and_alarm(self) -> None:
        s = self.settings
        ax = self.axis
        if not ax._powered:
            return
        actual = ax._actual
        rel = actual - self.zero
        st = self.cut_state
        cycle_running = st not in _OUT_OF_CYCLE
        automatic = self.inputs.start_stop or cycle_running
        if automatic:
            self.outputs.alarm = rel >= s.alarm_position
            if rel <= s.minimum_position:
                self._set_error(FS701Error.LIMIT_SWITCH)
        else:
            self.outputs.alarm = False
        # forward excursion / position-error statistics
        if cycle_running:
            exc = (actual - self.home_position) * s.cut_counts_per_lu
            if exc > self.car_travel_dist:
                self.car_travel_dist = exc
        if self.outputs.ready_to_cut or st is CutState.READY_TO_CUT:
            e = self.position_error
            if e < self.min_pos_error:
                self.min_pos_error = e
            if e > self.max_pos_error:
                self.max_pos_error = e

    # ------------------------------------------------------------------ time-domain plans

    def _t_plan(self, first: Profile, second: Profile | None = None, *, from_this_cycle: bool = False) -> None:
        """Run a time-domain plan. Planned from the last cycle's set point (before this
        cycle's set point was made), its first sample is one cycle on; planned from this
        cycle's set point (`from_this_cycle`), this cycle samples its start."""
        self._t_profiles[0] = first
        self._t_profiles[1] = second
        self._t_c0 = self._cycle if from_this_cycle else self._cycle - 1

    def _t_sample(self, cycle: int) -> bool:
        """Sample the time plan; True while it runs (False: ended, set point at its end)."""
        p0 = self._t_profiles[0]
        assert p0 is not None
        t = (cycle - self._t_c0) * self.period
        if t < p0.duration:
            self._p, self._v, self._a, _ = p0.sample(t)
            return True
        p1 = self._t_profiles[1]
        if p1 is not None:
            t1 = t - p0.duration
            self._p, self._v, self._a, _ = p1.sample(t1)
            return t1 < p1.duration
        self._p, self._v, self._a, _ = p0.sample(t)
        return False
