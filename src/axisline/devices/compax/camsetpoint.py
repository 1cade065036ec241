"""COMPAX XX70 cam operation, part 3 of 4: the slave's set point of the cycle (compax.md §1.3,
§2.4, §2.7.2; manual §4.1): the curve value at the master position with the curve offset,
blended while coupling / decoupling, its speed (with the P68 filter) and acceleration, and the
software limits P11 / P12. `camop.CamOperation.tick` calls `_compute` once per cycle; the axis
takes the result through `CamIO.sample`.

Decisions (numbered as in camop.py; each has a test in tests/devices/compax/test_camop*.py or
the test named):

* D19 P68 "Filter for external speed feed forward; 0: filter switched off", % 0 ... 550, VP
  (compax.md §2.1 "numerical differentiation; optional filter P68", §3 P68 "Only use filter P68,
  if quantization noises can be heard due to low resolution in the master channel. Otherwise,
  set to 0 to reduce the tracking error to a minimum"; the filter type is [GAP]): a first-order
  low-pass (PT1, backward Euler) on the speed feed-forward only, time constant T_f = P68 % of
  the 1 ms cycle (100 % = 1 ms, 550 % = 5.5 ms); the position set point and the acceleration
  feed-forward are not filtered (so the filter costs tracking accuracy, as the manual warns).
  The filter starts from the feed-forward the slave had (0 at LOOP) and reads the valid P68
  every cycle. Tests: test_p68_filters_the_speed_feed_forward_only, test_p68_0_is_off.
* D15 Software limits (§2.4): in normal mode with P11/P12 set, a set point beyond a limit
  stops the slave (ramp), interrupts the cam operation, blocks master counting and reports
  E25; supervision resumes once the slave is back inside. Test: test_software_limit_e25.
* D24 Acceleration set point (§1.3 "The position set points taken from the curve are
  differentiated", the differentiation's filter is [GAP]; issue 16): position and speed set
  points stay the device's per-cycle values (the speed with P68), but the acceleration, which
  only the trace and its jerk show, is the cam law a = F''·U'^2 + F'·U'' with F'' the set
  points' second difference (`PointTable.set_point_acceleration`) and U', U'' from a tracking
  observer of the counted master increments (`motion.master_observer`): a double difference
  of whole increments per 1 ms gave +-7e4 deg/s^2 of noise on the example's knife. The
  observer takes the master at the speed of the first whole cycle counted after the enabling
  (a gated count starts at the encoder's speed). Test:
  tests/test_plots_first_hour.py::test_compax_knife_acceleration_is_the_cam_law_not_count_noise.
* D25 The acceleration set point every cycle (issue 18: "share the segment, or compute the
  acceleration only when it is traced"): shared, computed every cycle with the position and
  speed from one interval search (`PointTable.eval_with_acceleration`, the same numbers as
  `eval` and `set_point_acceleration`): the axis' command acceleration is not only a trace
  channel, the machine's stop sequence waits for it to be 0 (`Machine.at_rest_after_stop`), so
  leaving it out when not traced would change when a stopped run ends. Test: tests/motion/test_cam.py::
  test_eval_with_acceleration_is_eval_and_set_point_acceleration_in_one_search.
"""

from __future__ import annotations

from axisline.devices.compax import E_POSITION_INVALID
from axisline.devices.compax.camcommands import CamCommands
from axisline.devices.compax.camio import CamState
from axisline.motion.camsync import smooth_step

__all__ = ["CamSetPoint"]


class CamSetPoint(CamCommands):
    """The set point of the cam operation's cycle (see the module docstring)."""

    def _compute(self, u: float) -> None:
        state = self.state
        curve = self.curve
        assert curve is not None
        k = self._k36
        base = self._base if self.loop_active else self.offset
        if state is CamState.IDLE:
            f = curve.table.eval(u)[0]
            self._set_point = base + k * f
            self._s45 = 1000.0 * f
            return
        f, df, ddf = curve.table.eval_with_acceleration(u)  # one interval search for all three
        chain = self.chain
        inv = 1.0 / chain.scaled_cycle
        Ud = chain.velocity * inv  # master cycles / s
        # the acceleration: the cam law with the observed master (motion.master_observer)
        obs = self._master_obs
        Ud_a = obs.velocity * inv
        Udd_a = obs.acceleration * inv
        c = base + k * f
        dc = k * df
        ddc = k * ddf
        self._set_point = c
        self._s45 = 1000.0 * f
        if state is CamState.SYNC or state is CamState.WAIT_DECOUPLE:
            p, dp, ddp = c, dc, ddc
        elif state is CamState.COUPLING or state is CamState.DECOUPLING:
            length = self._U1 - self._U0
            h, dh, ddh = smooth_step((self._U - self._U0) / length)
            dh /= length
            ddh /= length * length
            if state is CamState.COUPLING:
                d = c - self._s0
                p = self._s0 + d * h
                dp = dc * h + d * dh
                ddp = ddc * h + 2.0 * dc * dh + d * ddh
            else:
                d = self._stop - c
                p = c + d * h
                dp = dc - dc * h + d * dh
                ddp = ddc - ddc * h - 2.0 * dc * dh + d * ddh
        else:
            p, dp, ddp = self._hold, 0.0, 0.0
        self._p = p - self._R
        v = dp * Ud
        pv = self._pv
        p68 = float(pv[68])
        if p68 > 0.0:
            # D19: P68, first-order low-pass on the speed feed-forward, T_f = P68 % of 1 ms
            tf = p68 / 100.0 * 1e-3
            v = self._v + (v - self._v) * (self.period / (self.period + tf))
        self._v = v
        self._a = ddp * Ud_a * Ud_a + dp * Udd_a
        if int(pv[93]) == 1:  # the software limits supervise in normal mode only
            self._check_limits()

    def _check_limits(self) -> None:
        """D15: software limits P11/P12 in normal mode during cam operation (E25)."""
        if int(self._pv[93]) != 1:
            return
        high = float(self._pv[11])
        low = float(self._pv[12])
        if high >= 4_000_000 and low <= -4_000_000:
            return
        p = self._p
        inside = low <= p <= high
        if self._limit_suspended:
            if inside:
                self._limit_suspended = False
            return
        if not inside and self.state is not CamState.IDLE:
            self.last_error = E_POSITION_INVALID
            self._p = max(low, min(high, p))
            self._leave()
            self.chain.block()
            self._limit_suspended = True
            self.axis.halt()
