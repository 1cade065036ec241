"""FS701 cut cycle: the flying shear / saw on a carriage axis, driven by the line master.

    settings = CutterSettings(cutting_length=10000, pulses_line_1000=2000, ...)   # manual names
    cutter = Cutter(axis, settings, line=line_encoder)     # an encoder, or an EncoderMaster
    each cycle c (period T):
        cutter.print_mark_edge(edge)            # plant edges of the cycle just simulated (mode 2/3)
        cutter.inputs.start_stop = True         # the command inputs (any time between cycles)
        cutter.tick(c)                          # BEFORE axis.update_setpoint(c)
        axis.update_setpoint(c)                 # samples the cutter (it is the axis' SyncSource)
        volts = cutter.position_loop(actual)    # Ana-Out 2 (loop.py), actual carriage LU
        drive.command_voltage(volts)
        cutter.outputs.ready_to_cut, cutter.errors, cutter.process values ...

The cutter never integrates physics. It owns the carriage set point: while Control Enable is
on, the carriage `Axis` is in SYNCHRONIZED_MOTION with the cutter as its sync source, and the
cutter produces every set point itself (holding, jog, the master-domain approach, synchronous
motion, gap, forward deceleration, return). The axis keeps its position loop bookkeeping
(actual position, following error); the FS701 PI loop with feed-forward and the +-10 V
output is loop.py (`Cutter.position_loop`).

Units: lengths in LU (the manual's "length units"), speeds in LU/min where the manual sets
them (parameters) and LU/s inside; the carriage axis' user unit is the LU (axis
counts_per_unit = Pulses Cut/1000 / 1000). Time is the integer cycle times the period.
Master positions are integer line increments; cut targets are integers in 1/1000 line
increment ("milli-counts": LU x Pulses Line/1000), so a batch of any length never drifts.

The cut cycle (spec §2.3)
-------------------------
Length mode (Cutting Mode 1): cut k targets the material point that passes the carriage home
position when the master reads T_k; T_{k+1} = T_k + (Cutting Length or Test Cut. Length) +
Tool Width. The carriage waits at home. The approach is planned in the MASTER domain (as
gear_in_position.GearInPos does, but with the FS701's own ramp): with V the filtered line speed when the
approach starts, R = 1 + Sync Rate/100 and v_s = R V,

    tau = (m - m_start) / V,   s(tau) = a ramp 0 -> v_s at Acceleration 1 (linear, or the
    S-ramp of the same duration whose peak acceleration is 1.25 x Acceleration 1),
    ramp time tau_a = v_s / a1, carriage travel s_sync = v_s tau_a / 2,
    m_sync = T_k + s_sync,  m_start = m_sync - V tau_a   (anticipation: m_start = T_k - V^2/2a1 at R = 1)

and from m_sync on the carriage is position-locked to the master: s = s_sync + R (m - m_sync).
Sampling the plan at the master position makes the carriage meet the cut point exactly even
when the line speed changes during the ramp (its real acceleration then scales with (m'/V)^2).
Synchron Time after m_sync, and the position error inside the Cut Window for Sync Samples
consecutive cycles, switch Ready to Cut on; Cut completed (edge per Edge Sense) ends the
synchronous phase: forward deceleration with Deceleration 1, then the return to home with
Acceleration 2 / Deceleration 2 at the lowest speed that is back in time for the next start
(at most Abs. Return Speed, or Rel. Return Speed x line speed).

Decisions (spec lines [AMBIGUOUS]/[GAP]/[CONFLICT]/[DERIVED] that concern the cut cycle;
each has a test in tests/devices/fs701/test_cutter*.py):
 C1 Ramp Form (spec §2.3.3 [GAP], §8 item 1): 0 (factory default) = S-ramp, 1..15 = linear
    ramp. The manual's intro says S-shape is the default "unless a linear ramp form has
    specifically been selected". The S-ramp is a trapezoidal-acceleration ramp with jerk
    phases of 20 % of the ramp time each: peak = 1.25 x setting, ramp time = dv / setting
    (spec suggestion), so the anticipation formula holds for both forms.
    Test: test_cutter.py::test_e3_s_ramp_peak_acceleration_is_1_25_times_the_setting (E3).
 C2 Anticipation (spec §2.3.2 [DERIVED], §8 item 2): master-domain plan above; with Sync
    Rate the ramp ends at v_s = R V and the anticipation is V tau_a - s_sync.
    Tests: test_e2_ramp_time_and_anticipation_distance, test_e2_simulated_approach_* (E2),
    test_cut_lands_on_target_at_constant_speed, test_cutter_line.py.
 C3 Error 02 / Home Window "Alarm state" (spec §2.3.6 [CONFLICT], §8 items 8): when the
    start point of a cut is reached while the carriage is not back home (return profile not
    finished, or the actual position outside the Home Window) the cut is NOT started
    (checked before any forward motion): Error 02 (error bit 2, Error output), the target is
    dropped, the carriage finishes its return and stands (manual §6: "remains in a closed-
    loop standstill position after termination of the current cut"). The Alarm output is
    NOT set by this (Alarm is the Alarm Position output). Clear Error resumes: the next cut
    is then "late" (see C9). Tests: test_error_02_is_checked_before_moving_and_clear_error_resumes,
    test_e19_one_metre_at_60_m_min_with_a_one_second_cut_is_not_possible (E19).
 C4 Self-optimising return (spec §2.3.5 [DERIVED]): v_ret_max = Abs. Return Speed if
    non-zero, else Rel. Return Speed x |line speed|, never below the reverse jog speed (so
    a carriage stopped with the line at standstill still comes home; E4 holds because the
    jog floor is below). The return uses the lowest speed that ends at home within 75 % of
    the time left to the next start point (at the current line speed), and is re-planned
    (faster) whenever the prediction passes 90 % of that time (line speeding up). With no next
    start known (Stop, line standing) it returns at half the maximum.
    Tests: test_return_speed_is_only_as_fast_as_needed, test_e4_return_speed_limits.
 C5 Cut Window unit (spec §3.4 [CONFLICT]): carriage encoder increments (manual text:
    "Setting is directly in number of increments of the carriage encoder"), compared with
    the position error (#3, scheduled - actual, increments). Test: test_cut_window_*.
 C6 Tool Width in length mode (spec §2.3.1 [DERIVED], §8 item 9): successive cut targets are
    L + Tool Width apart, so every piece has the nominal length L.
    Test: test_tool_width_spaces_the_targets_c6.
 C7 Immediate Cut (spec §2.3.7 [DERIVED]): accepted when the carriage is home (Stop or
    Start); the approach starts at once and the grid is re-referenced (next cut = immediate
    cut target + Cutting Length + Tool Width); Waste Counter + 1. An edge while a cycle runs
    is ignored (not latched: the operator sees nothing happen and can press again).
    Test: test_immediate_cut_*.
 C8 Cut Test Length (spec §2.3.8): the length of the next piece is fixed when its approach
    starts: Test Cut. Length if the input is HIGH then, or was HIGH at any time since the
    previous approach started (the "short pulse"); such cuts count as waste.
    Test: test_cut_test_length_pulse_gives_one_test_piece_c8.
 C9 Late first cut: when automatic operation (Start, Clear Error, Set Length Counter) finds
    the start point of the next length target already passed, the cut is made at once like
    an Immediate Cut (counted as waste, grid re-referenced) instead of an Error 02: the
    carriage is home, only the length is off. Test: test_late_first_cut_is_waste_c9.
 C10 Length counter at Start (spec §2.14, §8 item 13): Start keeps the material counted since
    the last cut (an Immediate Cut in Stop followed by Start gives a first piece of exactly
    the Cutting Length, manual §7.5) unless Set Length Cou (Ps) or (LU) is non-zero; then
    the counter is set to it and both registers are cleared. Precedence (spec §2.14 "Precedence
    if both are non-zero is unspecified", §8 item 13): Set Length Cou (Ps) wins. It is the
    exact value (line increments, no scaling through Pulses Line / 1000), the manual lists it
    first and describes the LU register "As above, but scaled in Length units", and a PLC that
    writes increments has computed the remainder from the counter itself. The LU value is
    discarded, not kept for a later Start ("set value only used one time" applies to the
    function, so a stale LU preset cannot surprise the operator at the next Start). Tests:
    test_set_length_counter_*, test_set_length_counter_ps_wins_over_lu_through_the_registers.
 C11 Stop during a cut cycle: a running cycle is completed (the blade may be in the material),
    then the carriage is held at home; no new automatic cycle starts.
    Test: test_stop_during_cycle_completes_it_c11.
 C12 Control Enable OFF: the axis power is switched off (analogue output 0 V), errors are
    cleared, the material length counter is held at 0 (the counters that count: length, sheet,
    FIFO). Batch/Waste counters and the carriage Zero are kept (Zero changes only at power-up
    and Set Zero Pos., manual §4.3.3). Test: test_control_enable_off_*.
 C13 Zero and limits: the cutter keeps the FS701 Zero as an offset in the axis frame
    (Carriage Abs.Pos #9 = axis position - zero); the axis frame itself is never shifted.
    Stop: jog stops exactly at Min/Max (unless Set Zero Pos. is HIGH, which holds the counter
    at 0 and so lifts the limits, §7.5); Start or an immediate cut: only Min (Error 03) and
    the Alarm output. Tests: test_cutter_misc.py::test_e8_* (E8),
    test_set_zero_position_holds_the_counter_and_lifts_the_limits_c13.
 C14 Jog ramps of 0 s (manual range 0..99) are a one-cycle step. Jog speeds and ramps are
    % of / s for Max. Line Speed (spec E22). Test: test_cutter_misc.py::test_e22_jog_speed_and_ramp.
 C15 Cut completed during a running gap is kept and acted on when the gap has ended (the gap
    must finish; manual: "Gap completed ... waits for the Cut completed signal").
    Test: test_cutter_misc.py::test_cut_completed_during_the_gap_waits_for_its_end_c15.
 C16 Gap motion (spec §2.13 [DERIVED]): a cycloidal displacement of +Gap Length over Gap Time
    on top of the synchronous set point (zero speed and acceleration at both ends; peak extra
    speed 2 x Gap Length / Gap Time); afterwards synchronous again, Gap Length ahead.
    Tests: test_cutter_misc.py::test_gap_moves_the_carriage_gap_length_ahead_of_the_material_c16,
    test_gap_is_unused_with_gap_length_0.
 C17 Ready to Cut / cut instant for accuracy checks: the cutter reports a cut when Ready to
    Cut rises; `CutRecorder` records a piece at the instant the caller's tool model says the
    blade passes the material (test_cutter_line.py: a fixed blade delay after Ready to Cut).
 C18 Virtual master speed quantisation (spec §2.8 [DERIVED], E21): floor to the 1/2048 step
    of Max. Line Speed. Ramp Vir. Master 0 s is a one-cycle step. Tests: test_cutter_misc.py::
    test_e21_virtual_line_speed_resolution, test_virtual_master_runs_the_cut_cycle_without_material.
 C19 Return floor when the line stands: see C4. Immediate Cut at line standstill is in sync
    at once (the approach is empty). Test: test_immediate_cut_at_line_standstill_is_synchronous_at_once_c19.
 C20 Encoder scaling (spec §2.1): "Pulses" are counter increments after the x1/x2/x4
    evaluation (Z-Distance "including multiple edge count"); kL = Pulses Line/1000 / 1000
    counts per LU. `line_lines_per_lu` gives the encoder lines for a plant encoder.
 C21 Length Pulses (spec §2.17 [DERIVED]): forward material motion only (reverse motion is
    not subtracted), output = floor(forward / (Length per Pulse / 2)) mod 2.
    Test: test_cutter_misc.py::test_e9_length_pulses_one_per_length_per_pulse_duty_1_to_1_c21 (E9).
 C22 Master Reverse (spec §2.15): set when the master is more than Master Rev. Limit behind
    its forward peak, reset when back at the peak or by Clear Error.
    Test: test_cutter_misc.py::test_master_reverse_output_c22.
 C23 Batch counter: every automatic cut that is not waste (length mode: Cutting Length cuts;
    print mark mode: every mark, substitute and additional cut) counts; Decr. Batch Cou.↑:
    batch - 1 (not below 0), waste + 1; Reset Batch Cou. (static) holds batch at 0.
    Tests: test_e25_decrement_batch_counter (E25), test_batch_counts_normal_cuts_*.
 C24 Control State #29 / Cut State #30 codes (spec §8 item 10 [GAP]): the enums ControlState and
    CutState below; Ready (§2.19) is HIGH from construction (no self-test to fail).
    Test: test_state_codes_and_process_values.
 C25 Motion detection (§2.18): Master in motion = |Encoder 1 speed| > Zero Speed Master;
    Vir. M. in motion = |virtual master speed| > Zero Speed Vir. Ma. (the manual's "Zero Freq.
    Master" in the output text is the register 0x0161). Test: test_motion_detection_outputs.
 C26 Set-point acceleration: the line's acceleration is the second difference of the line
    counts over ACC_WINDOW = 8 ms (LineMaster.acceleration; exact on a ramp, 8 ms late, its
    count noise bounded by 2 increments / W²); the virtual master's is its profile's. The
    window filter's own acceleration at the 1 ms Sampling Time is count noise (1 increment per
    ms² = 10^6 increments/s²). While synchronous the set point's acceleration is R x that; in
    the approach d²s/dtau² (m'/V)² + ds/dtau m''/V (the cam's curvature and its slope times the
    line's acceleration); the forward deceleration starts from a = 0. Only the acceleration
    feed-forward (loop.py L10, off by default) uses it; with it on, the set-point velocity
    also gets the measured line speed's lag made up (Sampling Time / 2 x acceleration), which
    the FS701 leaves in. Tests: test_feed_forward.py::test_the_line_acceleration_is_exact_on_a_ramp_and_one_window_late_c26,
    test_the_measured_line_speed_is_made_up_for_only_with_the_feed_forward,
    test_cutter_line.py (no overshoot at Cut completed).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Callable

from axisline.motion.axis import Axis, AxisState
from axisline.motion.profiles import Limits, Profile, State, plan, plan_velocity

from .cut_settings import CutterSettings, approach_geometry, return_profile, s_ramp_limits, v_return_max
from .cut_states import (
    _BIG,
    _OUT_OF_CYCLE,
    _SYNC_STATES,
    _V_EPS,
    _WASTE,
    RETURN_REPLAN_FRACTION,
    RETURN_TARGET_FRACTION,
    S_RAMP_PEAK_FACTOR,
    ControlState,
    CutKind,
    CutState,
    FS701Error,
)
from .cutter_io import CutRecord, CutRecorder, CutterInputs, CutterOutputs
from .line_master import LineMaster
from .loop import PositionLoop

__all__ = [
    "CutterSettings",
    "CutterInputs",
    "CutterOutputs",
    "Cutter",
    "CutKind",
    "CutState",
    "ControlState",
    "CutRecord",
    "CutRecorder",
    "FS701Error",
    "S_RAMP_PEAK_FACTOR",
    "s_ramp_limits",
]


@dataclass
class CutInfo:
    """The cut being executed (or last executed)."""

    number: int  # running number since construction
    kind: CutKind
    target_mc: int  # master position (milli-counts) at which the cut point passes home
    piece_length: float  # LU, nominal length of the piece this cut ends (nan: unknown)
    ready_cycle: int = -1  # cycle Ready to Cut rose (-1: not yet)


class Cutter:
    """The FS701 cut cycle (module docstring). It is the carriage axis' SyncSource.

    axis: the carriage Axis (user unit LU, counts_per_unit = Pulses Cut/1000 / 1000; its
    software limits off and its following-error limit generous: the FS701 has no
    following-error trip, it watches the Cut Window). settings: CutterSettings, read live
    every cycle (a change acts from the next cut on), except Pulses Line/1000, Dir. Counter 1
    and Sampling Time, which build the line master here: build a new Cutter after changing
    them (the unit, too, needs them set before it runs).
    line: the line encoder (anything with integer `counts`: an EncoderMaster is built with
    the Sampling Time filter), or a ready master (e.g. an EncoderMaster in LU); None: only the
    virtual master. period: cycle time in s (default: the axis').
    """

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

    # ------------------------------------------------------------------ per cycle

    def tick(self, cycle: int) -> None:
        """Inputs -> logic -> set point of `cycle`. Call before axis.update_setpoint(cycle)."""
        s = self.settings
        inp = self.inputs
        prev = self._prev_in
        self._cycle = cycle
        m = self.master
        # master source selection only in Stop (manual §4.1.1)
        if not inp.start_stop:
            m.select(inp.select_vir_master)
        m.run_virtual(inp.run_virt_master)
        m.update(cycle)
        if self._counter_pending is not None and m.counts * 1000 >= self._counter_pending:
            self._counter_mc = self._counter_pending
            self._counter_pending = None
        self.printmarks.advance(cycle)
        self._monitors()

        # Error 05 (persistent: comes back at once if not eliminated)
        if s.ratio_error:
            self._set_error(FS701Error.VALUE_RANGE)

        # Control Enable
        if not inp.control_enable:
            if prev.control_enable or self._first_tick:
                self._disable()
            # C12: the counters are held in reset while disabled
            self._last_cut_mc = self._counter_mc = m.counts * 1000
            self._finish_tick()
            return
        if not prev.control_enable or self._first_tick or not self.axis.powered:
            self._enable()
        elif self.axis.state is not AxisState.SYNCHRONIZED_MOTION:
            # the axis left the cutter's control (a following-error trip, another command):
            # hold everything until Clear Error re-enables it
            self.cut_state = CutState.IDLE
            if inp.clear_error and not prev.clear_error:
                self._enable()

        if inp.clear_error and not prev.clear_error:
            self._clear_errors()
            self.outputs.master_reverse = False
            self._rev_peak = self.master.position
            self.printmarks.clear_errors()
        if s.ratio_error:
            self._set_error(FS701Error.VALUE_RANGE)

        # counters inputs
        if inp.decr_batch_cou and not prev.decr_batch_cou:
            if self.batch_counter > 0:
                self.batch_counter -= 1
            self.waste_counter += 1
        if inp.reset_batch_cou:
            self.batch_counter = 0
        if inp.cut_test_length:
            self._test_latch = True

        # Start/Stop edge
        if inp.start_stop and not prev.start_stop:
            self._on_start()
        # Set Zero (Stop only): the counter is held at 0 while HIGH (C13)
        if inp.set_zero_pos and not inp.start_stop:
            self.zero = self.axis.actual_position

        st = self.cut_state
        if st in (CutState.HOME, CutState.JOG):
            self._home_logic(cycle)
        # cut completed edge
        cc_edge = (inp.cut_completed and not prev.cut_completed) if s.edge_sense == 0 else (
            prev.cut_completed and not inp.cut_completed
        )
        if cc_edge and self.cut_state in _SYNC_STATES:
            self._cut_completed_latched = True

        self._setpoint(cycle)
        self._limits_and_alarm()
        self._finish_tick()

    def _finish_tick(self) -> None:
        inp = self.inputs
        # the levels of this tick for the next one's edges (CutterInputs: plain fields only)
        self._prev_in.__dict__.update(inp.__dict__)
        self._first_tick = False
        o = self.outputs
        errors = self.errors
        ax = self.axis
        st = self.cut_state
        o.error = errors != 0
        o.max_correction = self.loop.at_max_correction
        d = ax._actual - self.home_position  # (Axis.actual_position / .powered, read directly: per cycle)
        o.home = (d if d >= 0.0 else -d) <= self.settings.home_window and ax._powered
        o.gap_completed = st is CutState.GAP_COMPLETED
        o.ready_to_cut = st in _SYNC_STATES
        self.printmarks.outputs(o)
        self.control_state = (
            ControlState.DISABLED
            if not inp.control_enable
            else ControlState.ERROR
            if errors
            else ControlState.AUTOMATIC
            if inp.start_stop
            else ControlState.STOP
        )

    # ------------------------------------------------------------------ enable / disable

    def _disable(self) -> None:
        ax = self.axis
        ax.power(False)
        self.errors = 0
        self.cut_state = CutState.IDLE
        self._ap_profile = None
        self._t_profiles[0] = self._t_profiles[1] = None
        self._gap_profile = None
        self._pending = None
        self._cut_completed_latched = False
        self._jog_dir = 0
        # counters held in reset (C12): the material counted since the last cut starts again
        self._last_cut_mc = self._counter_mc = self.master.counts * 1000
        self._counter_pending = None
        self.printmarks.reset()
        self.loop.reset()
        self._p = ax.actual_position
        self._v = self._a = 0.0

    def _enable(self) -> None:
        ax = self.axis
        if ax.state is AxisState.ERROR_STOP:
            ax.reset()
        ax.power(True)
        self._p = ax.command_position
        self._v = self._a = 0.0
        self.home_position = self._p
        self.cut_state = CutState.HOME
        self._last_cut_mc = self._counter_mc = self.master.counts * 1000
        self._counter_pending = None
        self._late_pending = True
        self.loop.reset()
        ax.start_sync(self)

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

    # ------------------------------------------------------------------ start / targets

    def _on_start(self) -> None:
        s = self.settings
        if self.cut_state in (CutState.HOME, CutState.JOG):
            self._end_jog_now()
            self.home_position = self._p  # manual §4.3.3: home = position at Start LOW->HIGH
        # Set Length Counter (C10)
        preset = 0
        if s.set_length_cou_ps:
            preset = int(s.set_length_cou_ps) * 1000
        elif s.set_length_cou_lu:
            preset = int(s.set_length_cou_lu) * int(s.pulses_line_1000)
        if s.set_length_cou_ps or s.set_length_cou_lu:
            self._last_cut_mc = self._counter_mc = self.master.counts * 1000 - preset
            self._counter_pending = None
            s.set_length_cou_ps = 0
            s.set_length_cou_lu = 0
            self.set_length_counter_consumed = True
        self._late_pending = True
        self.printmarks.on_start()

    def _piece_length_now(self) -> tuple[float, CutKind]:
        s = self.settings
        if self._test_latch or self.inputs.cut_test_length:
            return float(s.test_cut_length), CutKind.TEST
        return float(s.cutting_length), CutKind.NORMAL

    def _length_target_mc(self) -> int:
        """Master position (milli-counts) of the next length-mode cut (no allocation: per cycle)."""
        s = self.settings
        length = s.test_cut_length if (self._test_latch or self.inputs.cut_test_length) else s.cutting_length
        return self._last_cut_mc + int(round((length + s.tool_width) * s.pulses_line_1000))

    def _length_target(self) -> CutInfo:
        length, kind = self._piece_length_now()
        return CutInfo(self._cut_number + 1, kind, self._length_target_mc(), length)

    def _approach_geometry(self, V: float) -> tuple[Profile | None, float, float, float]:
        return approach_geometry(self.settings, V)

    def anticipation(self, line_speed_lu_s: float) -> float:
        """Anticipation distance (LU): the cut point is this far upstream of home at the start.

        Closed form (C2), the same for the linear ramp and the S-ramp of equal duration:
        tau_a = v_s/a1, master travel V tau_a, carriage travel v_s tau_a / 2."""
        V = line_speed_lu_s
        if V <= _V_EPS:
            return 0.0
        vs = self.settings.sync_ratio * V
        tau_a = vs / max(float(self.settings.acceleration_1), 1.0)  # (the register's minimum is 1)
        return V * tau_a - 0.5 * vs * tau_a

    def _start_mc(self, target_mc: float, V: float) -> float:
        """Master position (milli-counts) at which the approach to target_mc must start."""
        a = self.anticipation(V)
        return target_mc - a * self.settings.pulses_line_1000

    def _home_ok(self) -> bool:
        ax = self.axis
        return (
            self._t_profiles[0] is None
            and self.cut_state in (CutState.HOME, CutState.JOG)
            and self._jog_dir == 0
            and abs(ax.actual_position - self.home_position) <= self.settings.home_window
        )

    def _home_logic(self, cycle: int) -> None:
        inp, prev = self.inputs, self._prev_in
        s = self.settings
        # jog (Stop only)
        if not inp.start_stop:
            self._jog_logic()
        # immediate cut (Stop or Start), only from home (C7)
        if inp.immediate_cut and not prev.immediate_cut:
            if self.cut_state is CutState.HOME and self._t_profiles[0] is None and not self.errors:
                self._start_immediate(CutKind.IMMEDIATE)
                return
        if not inp.start_stop or self.errors:
            return
        if self.cut_state is not CutState.HOME:
            return
        V = self.master.velocity
        now_mc = self.master.counts * 1000
        if s.cutting_mode == 1:
            if V <= _V_EPS:
                return
            target_mc = self._length_target_mc()
            start = self._start_mc(target_mc, V)
            if now_mc < start:
                self._late_pending = False  # the start point is ahead: it will be met in time
                return
            late = now_mc - start > self._late_tolerance_mc(V)
            if late and self._late_pending:
                self._late_pending = False
                self._start_immediate(CutKind.LATE)  # C9
                return
            self._late_pending = False
            if not self._home_ok() or late:
                self._cut_not_possible(target_mc)
                return
            self._start_approach(self._length_target(), V)
        else:
            self.printmarks.home_logic(now_mc, V)

    def _late_tolerance_mc(self, V: float) -> float:
        """A start point passed by more than two cycles of line travel cannot be met any more."""
        return 2.0 * V * self.period * self.settings.pulses_line_1000

    def _cut_not_possible(self, target_mc: int) -> None:
        """C3: the carriage should start but is not back home: Error 02, the target is dropped."""
        self._set_error(FS701Error.CUT_NOT_POSSIBLE)
        if self.settings.cutting_mode == 1:
            self._last_cut_mc = target_mc
            self._counter_pending = target_mc  # the material keeps being measured from the dropped cut
        self._test_latch = False
        self.feasible_next = False

    def _check_start_while_returning(self) -> None:
        """C3: the next start point reached while the carriage is still out (automatic only)."""
        if not self.inputs.start_stop or self.errors:
            return
        V = self.master.velocity
        if V <= _V_EPS:
            return
        now_mc = self.master.counts * 1000
        if self.settings.cutting_mode == 1:
            target_mc = self._length_target_mc()
            if now_mc >= self._start_mc(target_mc, V):
                self._cut_not_possible(target_mc)
        else:
            self.printmarks.check_while_returning(now_mc, V)

    def _start_immediate(self, kind: CutKind) -> None:
        """Start a cycle now: the cut point is wherever the plan lands (C7, C9)."""
        s = self.settings
        V = max(self.master.velocity, 0.0)
        now_mc = self.master.counts * 1000
        antic = self.anticipation(V) if V > _V_EPS else 0.0
        target = int(round(now_mc + antic * s.pulses_line_1000))
        info = CutInfo(self._cut_number + 1, kind, target, math.nan)
        self._start_approach(info, V, exact_start=now_mc)

    def start_printmark_cut(self, info: CutInfo, V: float) -> None:
        """Used by printmark.py: start the approach to a FIFO target."""
        self._start_approach(info, V)

    def _start_approach(self, info: CutInfo, V: float, exact_start: float | None = None) -> None:
        s = self.settings
        self._cut_number = info.number
        self._end_jog_now()
        prof, tau_a, s_sync, dm = self._approach_geometry(V)
        kl_mc = s.pulses_line_1000  # milli-counts per LU
        self._R = s.sync_ratio
        self._ap_V = V
        self._s_sync = s_sync
        self._ap_sync_mc = info.target_mc + s_sync * kl_mc
        self._ap_start_mc = self._ap_sync_mc - dm * kl_mc if exact_start is None else float(exact_start)
        self._ap_profile = prof
        self.current_cut = info
        self._pending = None
        self.car_travel_dist = 0.0
        self._test_latch = False
        if s.cutting_mode == 1 or info.kind in _WASTE:
            # the grid reference: the next cut is measured from this one
            self._last_cut_mc = info.target_mc
        self._counter_pending = info.target_mc
        self.cut_state = CutState.ACCELERATION
        self._window_count = 0
        self._gap_profile = None
        self._gap_offset = 0.0
        self._cut_completed_latched = False

    # ------------------------------------------------------------------ jog

    def _jog_logic(self) -> None:
        inp = self.inputs
        s = self.settings
        want = 1 if inp.jog_forward and not inp.jog_reverse else -1 if inp.jog_reverse and not inp.jog_forward else 0
        if want == self._jog_dir:
            return
        if self._t_profiles[0] is not None and self._jog_dir == 0:
            return  # a return is still running: jog waits for it
        p, v = self._p, self._v
        if want == 0:
            _, _, dec = s.jog(self._jog_dir > 0, self.period)
            prof = plan_velocity("trapezoid", State(p, v, 0.0), 0.0, Limits(v=_BIG, a=dec, d=dec))
            self._t_plan(prof)
            self._jog_dir = 0
            return
        v_jog, acc, dec = s.jog(want > 0, self.period)
        limit_free = inp.set_zero_pos
        if limit_free:
            prof = plan_velocity("trapezoid", State(p, v, 0.0), want * v_jog, Limits(v=_BIG, a=acc, d=dec))
        else:
            lim = self.zero + (s.maximum_position if want > 0 else s.minimum_position)
            if (want > 0 and p >= lim) or (want < 0 and p <= lim):
                return  # at the limit: no motion in that direction
            prof = plan("trapezoid", State(p, v, 0.0), State(lim, 0.0), Limits(v=v_jog, a=acc, d=dec))
        self._t_plan(prof)
        self._jog_dir = want
        self.cut_state = CutState.JOG

    def _end_jog_now(self) -> None:
        if self.cut_state is CutState.JOG:
            self._t_profiles[0] = self._t_profiles[1] = None
            self._jog_dir = 0
            self._v = self._a = 0.0
            self.cut_state = CutState.HOME

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

    # ------------------------------------------------------------------ set point per state

    def _setpoint(self, cycle: int) -> None:
        st = self.cut_state
        if st is CutState.HOME or st is CutState.JOG:
            if self._t_profiles[0] is not None:
                if not self._t_sample(cycle):
                    self._t_profiles[0] = self._t_profiles[1] = None
                    self._v = self._a = 0.0
                    if st is CutState.JOG and self._jog_dir == 0:
                        self.cut_state = CutState.HOME
                        self.home_position = self._p  # manual: the new home after a jog
                    elif st is CutState.JOG:
                        # jog ran into a limit: stays jogging (held) until released
                        pass
            else:
                self._v = self._a = 0.0
                if st is CutState.JOG and self._jog_dir == 0:
                    self.cut_state = CutState.HOME
                    self.home_position = self._p
            return
        if st is CutState.ACCELERATION:
            self._approach_setpoint(cycle)
            return
        if st in (CutState.SYNCHRONOUS, CutState.READY_TO_CUT, CutState.GAP, CutState.GAP_COMPLETED):
            self._sync_setpoint(cycle)
            return
        if st in (CutState.DECELERATION, CutState.RETURN):
            self._return_setpoint(cycle)
            return
        # IDLE: nothing (axis unpowered)

    def _approach_setpoint(self, cycle: int) -> None:
        m = self.master
        x_mc = m.counts * 1000
        if x_mc >= self._ap_sync_mc or self._ap_profile is None:
            self.cut_state = CutState.SYNCHRONOUS
            self._sync_cycle = cycle
            self._sync_setpoint(cycle)
            return
        V = self._ap_V
        kl_mc = self.settings.pulses_line_1000
        tau = (x_mc - self._ap_start_mc) / (kl_mc * V)
        s, ds, dds, _ = self._ap_profile.sample(tau)
        k = m.velocity_now / V
        self._p = self.home_position + s
        self._v = ds * k
        # d²/dt² of s(x / V) with x the master's travel: the cam's curvature at the master's
        # speed plus its slope times the master's acceleration (loop.py L10 feeds it forward)
        self._a = dds * k * k + ds * m.acceleration / V

    def _sync_setpoint(self, cycle: int) -> None:
        s = self.settings
        m = self.master
        R = self._R
        kl_mc = s.pulses_line_1000
        p = self.home_position + self._s_sync + R * (m.counts * 1000 - self._ap_sync_mc) / kl_mc
        v = R * m.velocity_now
        a = R * m.acceleration
        st = self.cut_state
        # gap (C16): cycloidal extra displacement over Gap Time
        if st is CutState.GAP and self._gap_profile is not None:
            g_len, g_dur = self._gap_profile
            t = (cycle - self._gap_c0) * self.period
            if t >= g_dur:
                self._gap_offset = g_len
                self._gap_profile = None
                self.cut_state = st = CutState.GAP_COMPLETED
            else:
                u = t / g_dur
                w = 2.0 * math.pi
                p += g_len * (u - math.sin(w * u) / w)
                v += g_len / g_dur * (1.0 - math.cos(w * u))
                a += g_len / (g_dur * g_dur) * w * math.sin(w * u)
        p += self._gap_offset
        self._p, self._v, self._a = p, v, a
        if st is CutState.SYNCHRONOUS:
            # Ready to Cut: Synchron Time elapsed and the error inside the Cut Window for Sync Samples cycles
            elapsed_ms = (cycle - self._sync_cycle) * self.period * 1000.0
            if abs(self.position_error) <= s.cut_window:
                self._window_count += 1
            else:
                self._window_count = 0
            if elapsed_ms + 1e-9 >= s.synchron_time and self._window_count >= max(s.sync_samples, 1):
                self.cut_state = CutState.READY_TO_CUT
                self.min_pos_error = self.max_pos_error = self.position_error
                self._on_ready(cycle)
            return
        if st is CutState.READY_TO_CUT:
            if self.inputs.start_gap and s.gap_length > 0 and self._gap_offset == 0.0 and self._gap_profile is None:
                self._gap_profile = (float(s.gap_length), max(s.gap_time, 1) / 1000.0)
                self._gap_c0 = cycle  # this cycle's set point is the gap's start
                self.cut_state = CutState.GAP
                return
        if self._cut_completed_latched and st is not CutState.GAP:
            self._cut_completed_latched = False
            self._begin_return(cycle)

    def _on_ready(self, cycle: int) -> None:
        info = self.current_cut
        if info is None:
            return
        info.ready_cycle = cycle
        if info.kind in _WASTE:
            self.waste_counter += 1
        else:
            if not self.inputs.reset_batch_cou:
                self.batch_counter += 1
        self.cut_log.append(info)
        if self.on_cut is not None:
            self.on_cut(info)

    # ------------------------------------------------------------------ deceleration and return

    def _v_return_max(self) -> float:
        return v_return_max(self.settings, self.master.velocity)

    def _time_to_next_start(self) -> float:
        """Seconds until the next approach must start (inf: unknown / line stands)."""
        V = self.master.velocity
        if V <= _V_EPS or not self.inputs.start_stop:
            return math.inf
        s = self.settings
        target: float | None
        if s.cutting_mode == 1:
            target = self._length_target_mc()
        else:
            target = self.printmarks.next_target_mc()
            if target is None:
                return math.inf
        start = self._start_mc(target, V)
        return (start - self.master.counts * 1000) / (s.pulses_line_1000 * V)

    def _return_profile(self, p_from: float, v_r: float, state: State | None = None) -> Profile | None:
        start = state if state is not None else State(p_from, 0.0, 0.0)
        return return_profile(self.settings, start, self.home_position, v_r)

    @staticmethod
    def _return_time(dist: float, v: float, a2: float, d2: float) -> float:
        if v <= 0.0:
            return math.inf
        c = 0.5 / a2 + 0.5 / d2
        if dist <= c * v * v:  # triangle: the speed is never reached
            return 2.0 * math.sqrt(dist * c)
        return dist / v + c * v

    def _choose_return_speed(self, dist: float, t_avail: float) -> float:
        """C4: the lowest speed that is home within the target fraction of t_avail."""
        s = self.settings
        v_max = self._v_return_max()
        if dist <= 0.0:
            return v_max
        if math.isinf(t_avail):
            return min(v_max, max(v_max * 0.5, 1e-9)) if self.master.velocity > _V_EPS else v_max
        t = RETURN_TARGET_FRACTION * t_avail
        a2, d2 = float(s.acceleration_2), float(s.deceleration_2)
        c = 0.5 / a2 + 0.5 / d2
        disc = t * t - 4.0 * c * dist
        if t <= 0.0 or disc < 0.0:
            return v_max
        v = (t - math.sqrt(disc)) / (2.0 * c)
        return min(max(v, 1e-6), v_max)

    def _begin_return(self, cycle: int) -> None:
        s = self.settings
        p, v = self._p, self._v
        if v > _V_EPS:
            # from the synchronous speed; its acceleration (the line's, from quantised counts)
            # is left out: a jump of at most the line acceleration into the braking ramp
            shape, lim = s_ramp_limits(s.s_ramps, s.deceleration_1, v)
            dec = plan_velocity(shape, State(p, v, 0.0), 0.0, lim)
            t_dec = dec.duration
            p_stop = dec.target.p
        else:
            dec = None
            t_dec = 0.0
            p_stop = p
        dist = p_stop - self.home_position
        t_avail = self._time_to_next_start() - t_dec
        v_r = self._choose_return_speed(abs(dist), t_avail)
        ret = self._return_profile(p_stop, v_r)
        self._ret_speed = v_r
        self._ret_planned_speed = v_r
        # planned from this cycle's (synchronous) set point: no cycle is skipped
        if dec is None:
            if ret is None:
                self._arrive_home()
                return
            self._t_plan(ret, from_this_cycle=True)
            self.cut_state = CutState.RETURN
        else:
            self._t_plan(dec, ret, from_this_cycle=True)
            self.cut_state = CutState.DECELERATION
        self._sample_return(cycle)

    def _sample_return(self, cycle: int) -> None:
        running = self._t_sample(cycle)
        p0 = self._t_profiles[0]
        if self.cut_state is CutState.DECELERATION and p0 is not None:
            if (cycle - self._t_c0) * self.period >= p0.duration:
                self.cut_state = CutState.RETURN
        if not running:
            self._arrive_home()

    def _arrive_home(self) -> None:
        self._t_profiles[0] = self._t_profiles[1] = None
        self._p = self.home_position
        self._v = self._a = 0.0
        self.cut_state = CutState.HOME

    def _return_setpoint(self, cycle: int) -> None:
        if self.cut_state is CutState.RETURN:
            self._maybe_replan_return(cycle)
        self._check_start_while_returning()
        self._sample_return(cycle)

    def _maybe_replan_return(self, cycle: int) -> None:
        """C4: re-plan faster when the line speeds up and the return would end too late."""
        t_next = self._time_to_next_start()
        if math.isinf(t_next) or self._t_profiles[0] is None:
            return
        prof = self._t_profiles[1] if self._t_profiles[1] is not None else self._t_profiles[0]
        t0 = (self._t_profiles[0].duration if self._t_profiles[1] is not None else 0.0)
        t = (cycle - 1 - self._t_c0) * self.period - t0
        t_left = prof.duration - t
        v_max = self._v_return_max()
        if t_left <= RETURN_REPLAN_FRACTION * t_next or self._ret_speed >= v_max * (1 - 1e-9):
            return
        p, v, a = self._p, self._v, self._a
        dist = abs(p - self.home_position)
        v_new = max(self._choose_return_speed(dist, t_next), self._ret_speed * 1.05)
        v_new = min(v_new, v_max)
        if v_new <= self._ret_speed:
            return
        try:
            ret = self._return_profile(p, v_new, State(p, v, a))
        except ValueError:
            return
        if ret is None:
            return
        self._ret_speed = v_new
        self._t_plan(ret)

    # ------------------------------------------------------------------ convenience

    @property
    def return_speed_used(self) -> float:
        """Peak return speed of the last return plan, LU/min."""
        return self._ret_speed * 60.0
