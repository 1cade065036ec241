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

from axisline.motion.axis import AxisState

from .cut_settings import CutterSettings, s_ramp_limits
from .cut_states import (
    _SYNC_STATES,
    S_RAMP_PEAK_FACTOR,
    ControlState,
    CutKind,
    CutState,
    FS701Error,
)
from .cutter_io import CutRecord, CutRecorder, CutterInputs, CutterOutputs
from .cutter_motion import CutterMotion

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


class Cutter(CutterMotion):
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

    # ------------------------------------------------------------------ convenience

    @property
    def return_speed_used(self) -> float:
        """Peak return speed of the last return plan, LU/min."""
        return self._ret_speed * 60.0
