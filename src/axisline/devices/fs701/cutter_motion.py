"""The FS701 cutter's motions: a layer of `Cutter` over `CutterBase` (cutter_state.py lists
the layers; cutter.py describes the cut cycle and lists the decisions).
"""

from __future__ import annotations

import math

from axisline.motion.profiles import Limits, Profile, State, plan, plan_velocity

from .cut_settings import approach_geometry, return_profile, s_ramp_limits, v_return_max
from .cut_states import (
    _BIG,
    _V_EPS,
    _WASTE,
    RETURN_REPLAN_FRACTION,
    RETURN_TARGET_FRACTION,
    CutKind,
    CutState,
    FS701Error,
)
from .cutter_state import CutInfo, CutterBase

__all__ = ["CutterMotion"]


class CutterMotion(CutterBase):
    """The cutter's motions: starting a cut and its targets, jog, the set point of each state,
    deceleration and the return (a layer of `Cutter` over `CutterBase`, cutter.py)."""

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
