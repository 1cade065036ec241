"""COMPAX XX70 cam operation: the cam controller that drives a slave `Axis` from a curve of
the cam memory (compax.md §2.1, §2.7 ... §2.19, Appendix A; manual §4.1, §8 ... §21).

    op = CamOperation(axis, params, curves, encoder=enc, inputs={"I13": False, ...})
    op.setc(1); op.setm(0.0); op.loop(10)              # curve commands (between cycles)
    every 1 ms cycle:  op.tick(cycle)                   # BEFORE axis.update_setpoint(cycle)
                       axis.update_setpoint(cycle); axis.position_loop(actual)
    op.output(16), op.status(44), op.s(48), ...

The operation never integrates physics. LOOP hands the slave to the kernel as a sync source
(`Axis.start_sync(op)`): each cycle `tick` computes the set point (position, velocity and
acceleration from the curve and the master's motion) and `sample` returns it, so the
axis' position loop, following-error watch (E10) and traces stay the kernel's. POSR CAM is
an ordinary positioning (`Axis.move_absolute`), STOP / BREAK a braking ramp (`Axis.halt`).

Master: `masterchain.MasterChain` (P30, P31, P35, P39, P98, P143, P179; I16), advanced in
`tick`; the curve sees the master as a fraction u of the master cycle, 0 <= u < 1.
Curve: the set points F_0 ... F_{N-1} (fractions of S_T) equidistant over the master cycle
and interpolated linearly (§1.2, §2.7.2 [DERIVED]); the curve value in slave units is
c(u) = P36 · S_T · F(u). The largest fraction 0x7FFFFF (0.9999999) is the full slave cycle.

Frames
------
The device frame is the axis frame (S1 = the axis' actual position). Inside one LOOP the
operation works in an "absolute" frame that starts equal to the device frame at LOOP;
reset mode (P93 = 3) keeps the actual value between curve start and end by shifting the
device frame against it by R (device = absolute - R): at every master-cycle wrap while the
slave follows an open curve, set and actual position are counted back by the curve's
travel per cycle Δ = P36·S_T·(F_last - F_first) (`Axis.set_position(-Δ, relative=True)`,
the following error is unchanged). The curve offset ("base", SETS / automatic curve
adjustment) is the slave position of curve value 0 in the current master cycle; while the
slave follows an open curve it grows by Δ per cycle (normal and endless mode: the absolute
reference is kept, §2.14 normal mode).

Parameters: ``params[n]`` is read as the valid value. The operation tells the parameter
object (``params.accept(event)`` when it has one, devices/compax/parameters.py) when the
triggered acceptances happen: "SETC" (P34, P36), "LOOP" (P32, P33) and "CYCLE" at every
forward master-cycle wrap (the curve zero point: P36, P32, P33 = 10 ... 12), and reads the
values after the event. The triggered transfer of P35 (P30 >= 10) is done by the master
chain, so ``params.synchronous`` is left False. The label synchronisation (label.py) gets the
same events.

Reset-mode wraps re-start the axis' sync (`Axis.start_sync`) right after the frame shift, so
the axis' sync frame always equals the device frame and nothing accumulates in float.

States (Appendix A): IDLE (positioning controller) -> LOOP -> READY ("curve ready", the
slave stands) -> coupling (WAIT_COUPLE for M_E, COUPLING blend) -> SYNC (O16 = 1) ->
decoupling (WAIT_DECOUPLE for M_A, DECOUPLING blend) -> READY, or IDLE when the LOOP has
been carried out (loop counter 0) or P34 bit 1 is set. STOP / BREAK / an axis error: IDLE.

Coupling and decoupling profiles (docs/decisions.md S1): blends in the master domain with
the 5th-order smooth step of motion.camsync, coupling s = s0 + (curve - s0)·h over
[U_E, U_S], decoupling s = curve + (S_0 - curve)·h over [U_A, U_B] (U = master cycles since
LOOP): position, speed and acceleration continuous at both ends.

Decisions (the spec's [AMBIGUOUS]/[GAP]/[CONFLICT] points that concern this file; the manual
wins over the spec; each has a test in tests/devices/compax/test_camop*.py):

* D1 Curve shape (§2.7.2 [DERIVED]): set point k at k·M_T/(N-1), linear interpolation; the
  fraction 0x7FFFFF (>= 8388607/2^23) is read as exactly 1.0 = S_T, so an open curve from 0
  to 0.9999999 moves exactly S_T per cycle (§2.20 advice, §6.2). Test: test_curve_*.
* D3 P34 = 0 (M_E "insignificant"): coupling starts at the I13 edge and is synchronous at
  the next M_S (the spec's figure-only cells [GAP] for M_E = M_S != 0 and M_E < M_S at
  P34 = 0); M_E = M_S = 0: automatic curve adjustment at once, also with a negative master.
  P34 = 1: M_E = M_S = 0 adjusts at the next cycle start, M_E = M_S != 0 adjusts at M_E
  (speed leap, no position jump), M_E < M_S waits for M_E and blends to M_S. An automatic
  curve adjustment at a master position (cycle start, M_E) aligns the curve at exactly that
  position, so a master that has already moved past it shows as the manual's speed leap.
  M_S below M_E lies in the next master cycle (S1). Decoupling mirrors it (M_A, M_B, S_0);
  "stop jerkily" holds the set point where the curve is at that moment (S_0 ignored for
  M_A = M_B, as the manual says for M_A = M_B = 0). Tests: test_camop_coupling.py.
* D4 Recognition of M_E / M_A (§2.11 note "A very small coupling position ... may not be
  recognised"): a position P > 0 is recognised when the master is sampled at >= P after a
  sample below P in the same master cycle, as the device does; P = 0 is the cycle start
  (the wrap) and always recognised. Test: test_small_coupling_position_jumped_over_waits.
* D5 I13 edges: a rising edge while the slave is not at standstill (during a decoupling
  movement) is ignored ("Coupling ... can only occur if the slave is at a standstill when the
  coupling procedure is activated"); I13 = 1 when LOOP is given counts as an edge (the
  manual's procedures give LOOP and I13 = 1 in either order); a rising edge while still
  waiting for M_A cancels the decoupling; I13 = 0 while waiting for M_E cancels the
  coupling; I13 = 0 during the coupling movement decouples once the slave is synchronous.
  A coupling (decoupling) that needs a rising master waits while S46 = 1. Test:
  test_i13_edge_rules.
* D6 LOOP counting (§2.8): a loop counts at the master-cycle wrap when the slave was
  synchronous (O16 = 1) during the whole cycle; the counter reaching 0 triggers the
  decoupling at that wrap (for an immediate stop the slave stops at the curve end value of
  the cycle). LOOP 0: S48 = -8388608, the LOOP ends only by STOP / BREAK (or P34 bit 1);
  I13 still couples and decouples. Tests: test_loop_*.
* D7 Standstill position S_0 (§2.7.2 "Value range ±S_T", §8.2.1): S_0·S_T·P36 relative to
  the curve offset of the master cycle in which the braking position M_B is reached (a
  negative S_0 retracts behind the curve start, the manual's "retraction"). Exception S_0 =
  S_T: after the decoupling the standing slave counts as position 0 of the next curve cycle
  (the offset advances by Δ; reset mode counts the actual value back by Δ), so the next
  coupling continues forward ("Coupling from 0"). Test: test_s0_equal_st_*.
* D9 P36 (§3.1 footnote 5) is taken at SETC and at every master-cycle wrap ("curve zero
  point"); the cycle just finished still adds its travel with the old factor. P34 is taken
  at SETC ("VP & SETC"). Test: test_p36_taken_at_the_curve_zero_point.
* D14 Curve linking (§2.14, §7 X14/X15): a SETC + LOOP given during cam operation with
  P210 = 1 takes over at the wrap where the running LOOP's counter reaches 0, if it was given
  at least LINK_LEAD_CYCLES (10 ms) before; the new curve's value 0 is put on the old curve's
  end value (normal mode; a curve starting != 0 jumps, as the manual warns); reset mode counts
  back by the old curve's travel; the new curve's first cycle counts as a whole one. P34 bit 2
  without a waiting curve stops the slave at the end of the master cycle; without bit 2 a
  waiting curve takes over all the same (the decoupling parameters are 0 for linking). A link
  given later than 10 ms before the end is not a link: the running LOOP ends as it would
  alone, and the linked SETC + LOOP then start as a new LOOP (coupling per I13 and P34, so the
  partial first cycle is not counted). A linking SETC does not disable the master counting
  (§15.3.1) and makes P34 ("VP & SETC") valid for the linked curve. Tests: test_camop_linking.py;
  the jump onto a curve not starting at 0 (manual §15.3.4 "Attention! In curves that do not
  begin at 0 ... a set point jump"): test_curve_linking_to_a_curve_not_starting_at_0_jumps.

The set point (D15, D19, D24, D25) is in camsetpoint.py, the commands (D8, D10, D11, D17, D20,
D21, D23, D26) in camcommands.py, the I/O image, the auxiliary outputs and the status values
(D2, D12, D13, D16, D18, D22) in camio.py.
"""

from __future__ import annotations

import math
from typing import Any

from axisline.devices.compax import E_TRACKING
from axisline.devices.compax.camio import (
    _FOLLOWING,
    _SYNCHRONOUS,
    _UNWIRED,
    E_NOT_AVAILABLE,
    LINK_LEAD_CYCLES,
    LOOP0_S48,
    CamState,
    analog_volts,
)
from axisline.devices.compax.camsetpoint import CamSetPoint
from axisline.devices.compax.preparedcurve import PreparedCurve
from axisline.motion.axis import AxisState

__all__ = [
    "CamOperation",
    "CamState",
    "E_NOT_AVAILABLE",
    "LINK_LEAD_CYCLES",
    "LOOP0_S48",
    "PreparedCurve",
    "analog_volts",
]


def _next_crossing(U: float, pos: float) -> float:
    """First cycle coordinate > U whose place in the cycle is pos (0 <= pos < 1)."""
    k = math.floor(U)
    X = k + pos
    if X <= U + 1e-12:
        X += 1.0
    return X


class CamOperation(CamSetPoint):
    """The cam controller on a slave axis; see the module docstring.

    axis: the slave `Axis` (powered). params: the COMPAX parameters, ``params[n]`` gives the
    valid value of Pn (missing: the manual's default). curves: the cam memory (an object with
    ``curve(n)``, or a mapping number -> record; None / missing: E17). encoder: the master
    encoder (``counts``), not needed with the internal time base. inputs: "I12" ... "I16" ->
    bool or callable returning bool (read every tick). master: a `MasterChain` to use
    (default: one built from params and encoder).
    """

    # ================================================================== per cycle

    def tick(
        self,
        cycle: int,
        *,
        i14_edges: Any = None,
        i16_latch: int | None = None,
        zero_pulse: int | None = None,
    ) -> None:
        """One cycle of device logic, before `axis.update_setpoint(cycle)`."""
        self._cycle = cycle
        self.activated = True
        ax = self.axis
        chain = self.chain
        inputs = self.inputs
        if "I2" in inputs:  # Shift I2 (I1 + I2): machine datum travel (D21)
            shift = self.input("I1") and self.input("I2")
            if shift and not self._shift_i2:
                self.posa_home()
            self._shift_i2 = shift
        if self._home_pending:
            self._start_home()
        i13 = inputs.get("I13", False)  # (input(), inline: the inputs are read every cycle)
        i13 = bool(i13() if callable(i13) else i13)
        rise13 = i13 and not self._i13
        fall13 = self._i13 and not i13
        self._i13 = i13
        if self._release:
            self._release = False
            if not self.loop_active and ax.state is AxisState.SYNCHRONIZED_MOTION:
                ax.end_sync()
        self._i12_check()
        if self.loop_active and ax.state is not AxisState.SYNCHRONIZED_MOTION:
            # the axis left the cam (following error E10, a fault, a stop from elsewhere)
            if ax.state is AxisState.ERROR_STOP and ax.error_id == 0x40:
                self.last_error = E_TRACKING
            self._leave()
        state = self.state
        chain.synchronous = state is CamState.SYNC or state is CamState.WAIT_DECOUPLE
        u_prev = chain.fraction
        counting = chain.counting
        i16 = inputs.get("I16", False)
        i16 = bool(i16() if callable(i16) else i16)
        wraps = chain.update(cycle, i16, i16_latch=i16_latch, zero_pulse=zero_pulse)
        if self._master_obs_start and chain.counting:
            self._master_obs.start(chain.delta)  # the first whole cycle counted: the encoder's speed
        else:
            self._master_obs.update(chain.delta)
        self._master_obs_start = chain.counting and not counting  # (the enabling cycle counts from the latch)
        u = chain.fraction
        label = self.label
        if label is not None:
            label.measure(u_prev, wraps, i14_edges, u)
        if self.curve is None:
            self._outputs_idle()
            return
        if wraps:
            while wraps > 0:
                self._on_wrap(+1)
                wraps -= 1
            while wraps < 0:
                self._on_wrap(-1)
                wraps += 1
            u = chain.fraction  # a curve transfer at the wrap changes the master cycle
        self._U = self._K + u
        if self.loop_active:
            self._cycle_counter = self._U - self._loop_U0
            self._state_machine(u, rise13, fall13)
        if label is not None and label.mode != 0:
            step = label.step(self._U)  # (reads the master again: a LOOP ended above may change M_T)
            if step and self.loop_active:
                self._base += step  # slave related correction (P33 = 2) added to the slave channel
        self._compute(u)
        self._outputs(u)

    def _i12_check(self) -> None:
        """I12 enables the output stage outside cam operation and positioning (§2.17)."""
        level = self.inputs.get("I12", _UNWIRED)
        if level is _UNWIRED:
            return
        level = bool(level() if callable(level) else level)
        if level == self._i12:
            return
        ax = self.axis
        if self.loop_active or ax.state not in (AxisState.STANDSTILL, AxisState.DISABLED):
            return  # "I12, during a positioning process, ... also when the LOOP command is active is not evaluated"
        self._i12 = level
        ax.power(level)

    # ------------------------------------------------------------------ master-cycle wrap

    def _on_wrap(self, direction: int) -> None:
        state = self.state
        curve = self.curve
        assert curve is not None
        if direction > 0:
            self._K += 1
            self._event("CYCLE")  # end of the curve cycle: P32, P33 (10...12), P36 (curve zero point)
            if self.loop_active:
                terminated = False
                if state in _FOLLOWING:
                    self._base += self._delta
                    if int(self._pv[93]) == 3:
                        self._shift_frame(self._delta)
                if state in _SYNCHRONOUS:
                    if self._whole and self.loop_m > 0 and self.loop_counter > 0:
                        self.loop_counter -= 1  # D6: a whole cycle synchronous
                        terminated = self.loop_counter == 0
                    self._whole = True
                else:
                    self._whole = False
                self._accept_p36_at_zero()
                if state in (CamState.WAIT_COUPLE, CamState.WAIT_DECOUPLE):
                    self._seen_below = False
                    if self._wait_pos == 0.0:
                        self._reached(float(self._K))
                if terminated:
                    self._terminate()
            else:
                self._accept_p36_at_zero()
        else:
            self._K -= 1
            if self.loop_active and state in _FOLLOWING:
                self._base -= self._delta
                if int(self._pv[93]) == 3:
                    self._shift_frame(-self._delta)
            self._whole = False
            self._seen_below = False

    def _accept_p36_at_zero(self) -> None:
        if float(self._pv[36]) != self.p36:
            self._accept_p36()  # D9: "accepted at the next curve zero point"

    def _shift_frame(self, amount: float) -> None:
        """Reset mode: count set and actual position back by `amount` (device = absolute - R)."""
        if amount == 0.0:
            return
        self._R += amount
        ax = self.axis
        ax.set_position(-amount, relative=True)
        if ax.state is AxisState.SYNCHRONIZED_MOTION:
            self._sync_cmd = ax.start_sync(self)  # the sync frame starts at the new frame (no double shift)

    # ------------------------------------------------------------------ state machine

    def _state_machine(self, u: float, rise13: bool, fall13: bool) -> None:
        if self.state is CamState.SYNC and not (rise13 or fall13 or self._decouple_after_coupling):
            return  # synchronous without an I13 edge: nothing to change (the cycle of a running cam)
        self._complete()
        state = self.state
        if rise13:
            if state is CamState.READY:
                self._couple_pending = True
            elif state is CamState.WAIT_DECOUPLE and not self._wait_terminated:
                self.state = state = CamState.SYNC  # D5: coupling again cancels the pending decoupling
            elif state is CamState.COUPLING:
                self._decouple_after_coupling = False
            # during a decoupling movement: ignored (D5)
        if fall13:
            self._couple_pending = False
            if state is CamState.WAIT_COUPLE:
                self.state = state = CamState.READY
            elif state is CamState.COUPLING:
                self._decouple_after_coupling = True
            elif state is CamState.SYNC:
                self._start_decoupling(u, terminated=False)
                state = self.state
        if state is CamState.READY and self._couple_pending:
            self._start_coupling(u)
            state = self.state
        if state in (CamState.WAIT_COUPLE, CamState.WAIT_DECOUPLE):
            pos = self._wait_pos
            if pos > 0.0:
                if u < pos:
                    self._seen_below = True
                elif self._seen_below and self.chain.s46 == 0:
                    self._reached(self._K + pos)
        self._complete()

    def _complete(self) -> None:
        """Blends that have reached their end; a decoupling that waited for the coupling's end."""
        state = self.state
        if state is CamState.COUPLING and self._U >= self._U1:
            self._synchronous(whole=False)
            state = self.state
        elif state is CamState.DECOUPLING and self._U >= self._U1:
            self._hold = self._stop
            self._decoupled()
            state = self.state
        if state is CamState.SYNC and self._decouple_after_coupling:
            self._decouple_after_coupling = False
            if not self._i13:
                self._start_decoupling(self._U - self._K, terminated=False)

    def _start_coupling(self, u: float) -> None:
        curve = self.curve
        assert curve is not None
        me, ms = curve.me, curve.ms
        bit0 = self.p34 & 1
        if not bit0 and me == 0.0 and ms == 0.0:
            # automatic curve adjustment: the slave does not travel; also with a negative master
            f, _ = self._f(u)
            self._base = self._hold - self._k36 * f
            self._synchronous(whole=u == 0.0)
            return
        if self.chain.s46 != 0:
            return  # coupling only with a rising master; stays pending (D5)
        self._couple_pending = False
        if not bit0:
            self._s0 = self._hold
            self._U0 = self._U
            self._U1 = _next_crossing(self._U, ms)
            self.state = CamState.COUPLING
            return
        self._wait_pos = me
        self._seen_below = u < me
        self._wait_terminated = False
        self.state = CamState.WAIT_COUPLE

    def _reached(self, U: float) -> None:
        """The master reached the awaited coupling (M_E) or decoupling (M_A) position at U."""
        curve = self.curve
        assert curve is not None
        u_at = U - math.floor(U)
        if self.state is CamState.WAIT_COUPLE:
            if curve.me == curve.ms:
                f, _ = self._f(u_at)
                self._base = self._hold - self._k36 * f  # automatic curve compensation at M_E (speed leap)
                self._synchronous(whole=u_at == 0.0)
            else:
                span = (curve.ms - curve.me) % 1.0 or 1.0
                self._s0 = self._hold
                self._U0 = U
                self._U1 = U + span
                self.state = CamState.COUPLING
        elif self.state is CamState.WAIT_DECOUPLE:
            if curve.ma == curve.mb:
                f, _ = self._f(u_at)
                self._hold = self._base + self._k36 * f  # "stop jerkily" where the curve is at M_A
                self._decoupled()
            else:
                span = (curve.mb - curve.ma) % 1.0 or 1.0
                self._begin_decoupling_blend(U, U + span)

    def _synchronous(self, whole: bool) -> None:
        self.state = CamState.SYNC
        self._whole = whole
        self._couple_pending = False

    def _start_decoupling(self, u: float, terminated: bool, at: float | None = None) -> None:
        """I13 = 0 (or the loop counter reached 0 at U = `at`): decouple per P34, M_A, M_B."""
        curve = self.curve
        assert curve is not None
        ma, mb = curve.ma, curve.mb
        bit0 = self.p34 & 1
        if terminated or self.p34 & 2:
            self._finish = True
        U_now = self._U if at is None else at
        if not bit0:
            if ma == 0.0 and mb == 0.0:
                # stop immediately (speed leap; S_0 not taken into account), also with a negative master
                f, _ = self._f(U_now - math.floor(U_now) if at is None else 0.0)
                self._hold = self._base + self._k36 * f
                self._decoupled()
                return
            self._begin_decoupling_blend(U_now, _next_crossing(U_now, mb))
            return
        self._wait_pos = ma
        self._seen_below = (U_now - math.floor(U_now)) < ma
        self._wait_terminated = terminated
        self.state = CamState.WAIT_DECOUPLE
        if ma == 0.0 and at is not None:
            self._reached(at)  # the counter ended at the cycle start = M_A

    def _begin_decoupling_blend(self, U0: float, U1: float) -> None:
        curve = self.curve
        assert curve is not None
        k_now = self._K
        k_stop = math.ceil(U1) - 1  # the master cycle in which M_B is reached (D7)
        self._stop_base = self._base + (k_stop - k_now) * self._delta
        self._stop = self._stop_base + curve.s0 * curve.slave_cycle * self.p36
        self._U0 = U0
        self._U1 = U1
        self.state = CamState.DECOUPLING

    def _decoupled(self) -> None:
        """The slave stands (at _hold): READY again, or the LOOP is over."""
        curve = self.curve
        assert curve is not None
        if self.state is CamState.DECOUPLING and curve.s0 == 1.0 and curve.open:
            # D7 exception S_0 = S_T: the slave counts as 0 of the next curve cycle
            target = self._stop_base + self._delta
            shift = target - self._base
            self._base = target
            if shift and int(self._pv[93]) == 3:
                self._shift_frame(shift)
        self.state = CamState.READY
        self._whole = False
        if self._finish:
            self._finish_loop()

    def _terminate(self) -> None:
        """The loop counter reached 0 at this wrap (U = K)."""
        link = self._link
        if link is not None and self._cycle - link[2] >= LINK_LEAD_CYCLES:
            self._transfer(link)
            return
        curve = self.curve
        assert curve is not None
        U = float(self._K)
        if self.p34 & 4:
            # leave the curve at the end of the master cycle, independent of the coupling parameters
            self._hold = self._base + self._k36 * curve.f_first
            self._finish = True
            self._decoupled()
            return
        self._start_decoupling(0.0, terminated=True, at=U)

    def _transfer(self, link: tuple[PreparedCurve, int, int]) -> None:
        """Curve linking (D14): the next curve starts now, its value 0 on the old curve's end value."""
        new, m, _ = link
        old = self.curve
        assert old is not None
        s_end = self._base + self._k36 * old.f_first  # = the old curve's end value (base already advanced)
        self._link = None
        self.curve = new
        self.chain.set_cycle(new.master_cycle)
        self.p34 = self._next_p34
        self._accept_p36()
        self._base = s_end
        self.loop_m = m
        self.loop_counter = m
        self._whole = True
        self._event("LOOP")

    def _finish_loop(self) -> None:
        """The LOOP has been carried out: back to the positioning controller.

        The slave stands at the hold position this cycle; the axis' sync ends at the next
        tick (from rest, so the halt of `end_sync` does not move it). A linked LOOP that came
        too late for the transfer (D14) starts now as a new LOOP from the standing slave."""
        link = self._link
        self._p, self._v, self._a = self._hold - self._R, 0.0, 0.0
        self._leave()
        self._release = True
        if link is not None:
            curve, m, _ = link
            self.curve = curve
            self.chain.set_cycle(curve.master_cycle)
            self.p34 = self._next_p34
            self._accept_p36()
            self.aligned = True
            self.loop(m)
