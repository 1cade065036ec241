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
* D2 Units of S44/S45/S50...S52 (§0 [CONFLICT] % vs ‰): per mille (§20); SETM in %.
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
* D8 LOOP start point (§2.8, §11.1.1): without SETS / POSR CAM since the last LOOP / SETC the
  slave position is folded into the slave cycle [0, S_T·P36) by counting set and actual
  position back by n·S_T·P36, and the curve offset is 0 (curve start = slave zero).
  Test: test_loop_folds_the_slave_into_the_slave_cycle.
* D9 P36 (§3.1 footnote 5) is taken at SETC and at every master-cycle wrap ("curve zero
  point"); the cycle just finished still adds its travel with the old factor. P34 is taken
  at SETC ("VP & SETC"). Test: test_p36_taken_at_the_curve_zero_point.
* D10 Endless mode (P93 = 2, §2.1): POSR CAM sets the actual position to 0 and moves to the
  curve value (a relative move by S47); in cam operation endless mode follows like normal
  mode. P93 = 4 (speed control) refuses LOOP (E_NOT_AVAILABLE). Test: test_endless_posr_cam.
* D11 Commands during cam operation (§11.2 "the LOOP-command is still active and COMPAX does
  not carry out any commands"): SETC/SETM/SETS/POSR CAM/LOOP are refused with
  E_NOT_AVAILABLE (107), except SETC + LOOP with P210 = 1 (curve linking, §2.14); a second
  linked LOOP while one waits is refused ("the second positioning command is rejected").
  SETM/SETS/POSR CAM without a selected curve have no effect ("only becomes efficient
  after a curve has been selected"), except SETM 0.
* D12 Auxiliary functions (§2.12): the outputs follow the set points only while synchronous
  (O16 = 1); at LOOP with I15 = 0 the masked outputs take P37 at once; leaving synchronous
  operation freezes them. O14 is the label error when P33 != 0. The analogue channels are
  interpolated whenever a curve is selected (independent of I15) and scaled 10 V / 128 LSB
  at gain 100 (§2.12 [DERIVED]). Tests: test_camop_aux.py.
* D13 O15 (§2.18 "actualized at each movement"): updated every cycle from the axis'
  following error against P79.
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
* D17 Operation parameters as arguments (§2.8 "SETC .P40, SETM .P40, LOOP .P40"): the string
  ".P40" ... ".P49" stands for the valid value of that parameter. Test:
  test_operation_parameters_as_arguments.
* D18 D/A monitor (§2.12 signals 20 ... 24): 22 = the master position in the cycle (M_T ≙
  100 mV), 23 = the curve value S45 (S_T ≙ 100 mV), 24 = S41 (20000 min⁻¹ ≙ 10 V), times the
  gain, limited to ±10 V. Tests: test_da_monitor_* (§7 X8).
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
* D16 S47 is the curve set point (curve offset + curve value, device frame) also while
  coupling / decoupling; S45 the curve value in per mille of S_T·P36 (plus the slave-related
  label correction); S2 is the m of the last LOOP in cam operation, else the set point.
* D20 Machine datum before cam operation (§2.4 "When limit supervision is activated in normal
  mode after "Power on", normal operation is only initiated once the machine datum has been
  reached. This also applies for the time between the activation of the machine datum travel
  until the machine datum is reached."; the manual does not say how the datum is reached nor
  which error a refused command gives [GAP]): while P11/P12 supervise (P93 = 1 and not both
  switched off, ±4 000 000) LOOP and POSR CAM are refused with E_NOT_AVAILABLE (107, S30)
  until the slave axis' homing has finished (`Axis.homed`) since power on; the datum travel is
  POSA HOME (`posa_home`, ASCII "POSA HOME", Shift I2) or any axis homing; during the travel
  (HOMING) the datum counts as not reached. Reset mode (P93 = 3, "supervision ineffective as the
  datum is never reached"), endless mode and switched-off limits need no datum. The travel is
  `homing` (a `HomingProcedure`, default `DirectHoming(0)`: the datum where the slave stands,
  for a rig without a reference switch). Tests: test_limit_supervision_in_normal_mode_needs_the_
  machine_datum, test_datum_not_reached_during_the_datum_travel,
  test_no_datum_needed_without_supervision (test_camop_datum.py).
* D21 POSA HOME / Shift I2 during cam operation (§2.11 "Exception: If the curve commands are
  specified via an interface (not as a set command), COMPAX also reacts during the cam
  operation to the command "POSA HOME" or Shift I2"): given over the interface (ASCII line
  "POSA HOME", blanks ignored; `posa_home()`) or by Shift I2 (inputs I1 = Shift and I2 both 1,
  rising edge, the COMPAX standard assignment [DERIVED]; read only when "I2" is wired) the LOOP
  is left (O16 = 0, the outputs freeze as on STOP), the slave brakes on its ramp and the datum
  travel starts at standstill. As a set command (`posa_home(interface=False)`) it is refused
  during cam operation like the other commands (D11, E_NOT_AVAILABLE). Tests:
  test_posa_home_during_cam_operation_over_the_interface,
  test_posa_home_as_a_set_command_is_refused_during_cam_operation,
  test_shift_i2_during_cam_operation_starts_the_datum_travel.
* D22 D/A monitor at power on (manual §13.2 "During the activation (after "Power-On") the
  analogous output is 10V."): `da_monitor` gives +10 V for every signal and gain from power on
  (construction) until the first device cycle (`tick`), the end of the activation in axisline
  (its length on the device is not given [GAP]). Test:
  test_da_monitor_is_10v_during_the_activation_after_power_on.
* D23 HEDA not modelled (§2.6 "Process coupling via HEDA (option A1/A3)"): reason: a hardware
  option (SSI bus, ±2.5 µs time-slice synchronisation, data blocks of a second COMPAX, E76 ...
  E78 transmission errors) with no second device in axisline to send the process value; a
  partial model (another axis' data block, the 2 ms delay at P188 > 0) would give results the
  bus cannot be checked against. A HEDA master (P188 != 0, or P243 bit 1 "passive slave")
  refuses LOOP with E_NOT_AVAILABLE (107); P31 = 9 with P188 = 0 stays the static I16 enable
  of the encoder / time base. Test: test_heda_master_is_not_modelled.
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
"""

from __future__ import annotations

import math
from enum import Enum
from typing import Any

from axisline.devices.compax import E_CURVE_NOT_PRESENT, E_POSITION_INVALID, E_TRACKING, CompaxError
from axisline.devices.compax.masterchain import MasterChain, param
from axisline.motion.axis import Axis, AxisState, MotionCommand
from axisline.devices.compax.preparedcurve import PreparedCurve
from axisline.motion.camsync import smooth_step
from axisline.motion.camswitch import AuxTrack
from axisline.motion.homing import DirectHoming, HomingProcedure
from axisline.motion.master_observer import MasterObserver

__all__ = [
    "CamOperation",
    "CamState",
    "LINK_LEAD_CYCLES",
    "LOOP0_S48",
    "PreparedCurve",
    "analog_volts",
]

E_VALUE = 103
E_NOT_AVAILABLE = 107

#: §2.19 "At a cyclical travel with "LOOP 0" S48 = -8388608".
LOOP0_S48 = -8388608
#: §2.14 "A processing time of ca. 10ms is required ... ca. 10ms before the start of the next curve."
LINK_LEAD_CYCLES = 10


class CamState(Enum):
    IDLE = "idle"  # not in cam operation (positioning controller)
    READY = "curve ready"  # LOOP active, slave standing, waiting for I13
    WAIT_COUPLE = "waiting for the coupling position"
    COUPLING = "coupling"
    SYNC = "synchronous"
    WAIT_DECOUPLE = "waiting for the decoupling position"
    DECOUPLING = "decoupling"


_FOLLOWING = (CamState.COUPLING, CamState.SYNC, CamState.WAIT_DECOUPLE, CamState.DECOUPLING)
_SYNCHRONOUS = (CamState.SYNC, CamState.WAIT_DECOUPLE)


def analog_volts(value: float, gain: float = 100.0) -> float:
    """An analogue aux value (signed byte units) as D/A volts: 100 % = 128 LSB = 0.1 V · gain,
    limited to ±10 V (§2.12: signals 20/21 "100% ≙ 100mV" at gain 1; P71 = 100: 127 ≙ 10 V)."""
    volts = value / 128.0 * 0.1 * gain
    return max(-10.0, min(10.0, volts))


def _lookup(curves: Any, number: int) -> Any:
    """A curve record of the cam memory, or None (E17). A cam memory's own CompaxError passes."""
    for name in ("curve", "get_curve", "read_curve"):
        fn = getattr(curves, name, None)
        if callable(fn):
            try:
                return fn(number)
            except CompaxError:
                raise
            except (KeyError, IndexError, LookupError, ValueError):
                return None
    if callable(curves) and not hasattr(curves, "__getitem__"):
        try:
            return curves(number)
        except (KeyError, IndexError, LookupError, ValueError):
            return None
    try:
        return curves[number]
    except (KeyError, IndexError, LookupError, TypeError):
        return None


def _operand(params: Any, value: Any) -> Any:
    """A command argument, or an operation parameter ".P40" ... ".P49" (§2.8: "SETC .P40")."""
    if isinstance(value, str):
        text = value.strip().upper()
        if text.startswith(".P") and text[2:].isdigit() and 40 <= int(text[2:]) <= 49:
            return param(params, int(text[2:]))
        raise CompaxError(f"argument {value!r} not allowed: a number or an operation parameter .P40 ... .P49",
                          code=E_VALUE, field="argument", value=value, allowed="number, .P40 ... .P49")
    return value


def _next_crossing(U: float, pos: float) -> float:
    """First cycle coordinate > U whose place in the cycle is pos (0 <= pos < 1)."""
    k = math.floor(U)
    X = k + pos
    if X <= U + 1e-12:
        X += 1.0
    return X


class CamOperation:
    """The cam controller on a slave axis; see the module docstring.

    axis: the slave `Axis` (powered). params: the COMPAX parameters, ``params[n]`` gives the
    valid value of Pn (missing: the manual's default). curves: the cam memory (an object with
    ``curve(n)``, or a mapping number -> record; None / missing: E17). encoder: the master
    encoder (``counts``), not needed with the internal time base. inputs: "I12" ... "I16" ->
    bool or callable returning bool (read every tick). master: a `MasterChain` to use
    (default: one built from params and encoder).
    """

    def __init__(
        self,
        axis: Axis,
        params: Any,
        curves: Any,
        *,
        encoder: Any = None,
        inputs: dict[str, Any] | None = None,
        master: MasterChain | None = None,
        label: Any = None,
        homing: HomingProcedure | None = None,
    ) -> None:
        self.axis = axis
        #: the machine datum travel of POSA HOME / Shift I2 (D20; default: the datum where the slave stands)
        self.homing: HomingProcedure = homing if homing is not None else DirectHoming(0.0)
        self._home_pending = False
        self.home_command: MotionCommand | None = None
        self._shift_i2 = False
        #: False from power on until the first cycle ("During the activation ... 10V", D22)
        self.activated = False
        self.params = params
        self.curves = curves
        self.period = axis.period
        self.chain = master if master is not None else MasterChain(params, encoder, axis.period)
        self.inputs: dict[str, Any] = inputs if inputs is not None else {}
        self.state = CamState.IDLE
        self.curve: PreparedCurve | None = None
        self.p36 = float(param(params, 36))
        self.p34 = int(param(params, 34))
        self._k36 = 0.0  # P36 · S_T
        self._delta = 0.0  # slave travel per master cycle Δ
        self.offset = 0.0  # curve offset in the device frame (outside LOOP), SETS
        self.aligned = False  # SETS / POSR CAM given since the last LOOP / SETC
        # LOOP
        self.loop_active = False
        self.loop_m = 0
        self.loop_counter = 0
        self._finish = False  # the LOOP ends after the running decoupling
        self._whole = False  # synchronous since the start of this master cycle
        self._K = 0  # master-cycle wraps since LOOP
        self._U = 0.0  # master position in cycles since LOOP (K + u)
        self._loop_U0 = 0.0
        self._cycle_counter = 0.0  # S13/S14 code 33
        # frames (absolute = device + R inside a LOOP)
        self._base = 0.0  # curve offset, absolute frame
        self._R = 0.0
        # hold / blends (absolute frame)
        self._hold = 0.0
        self._s0 = 0.0
        self._U0 = 0.0
        self._U1 = 1.0
        self._stop = 0.0
        self._stop_base = 0.0  # curve offset of the braking cycle (S_0 = S_T exception)
        self._wait_pos = 0.0
        self._seen_below = False
        self._wait_terminated = False  # the pending decoupling comes from the loop counter
        self._couple_pending = False
        self._decouple_after_coupling = False
        self._i13 = False
        # linking
        self._next_curve: PreparedCurve | None = None
        self._link: tuple[PreparedCurve, int, int] | None = None  # curve, m, cycle given
        self._next_p34 = 0
        self._release = False  # end the axis' sync at the next tick (the LOOP is over)
        # I/O and status
        self.out = 0  # output image, bit n-1 = On
        self.last_error = 0
        self._limit_suspended = False
        self.posr_target = 0.0  # S49
        self._p = self._v = self._a = 0.0
        # the acceleration set point's master speed/acceleration: observed, not differenced (issue 16)
        self._master_obs = MasterObserver(self.period)
        self._master_obs_start = False  # counting was enabled in the last cycle
        self._set_point = 0.0  # S47 (absolute frame)
        self._s45 = 0.0
        self._cycle = 0
        self._sync_cmd: MotionCommand | None = None
        self._aux_key: tuple[int, int, int] | None = None
        self._aux: AuxTrack | None = None
        self.label = label
        if label is not None and hasattr(label, "attach"):
            label.attach(self)
        self._i12: bool | None = None

    # ================================================================== inputs / outputs

    def input(self, name: str) -> bool:
        value = self.inputs.get(name, False)
        return bool(value() if callable(value) else value)

    def output(self, n: int) -> bool:
        """Output On (1 ... 16)."""
        return bool(self.out >> (n - 1) & 1)

    def _set_out(self, n: int, on: bool) -> None:
        bit = 1 << (n - 1)
        self.out = (self.out | bit) if on else (self.out & ~bit)

    @property
    def aux_byte(self) -> int:
        """O7 ... O14 as the byte of the aux functions (bit 0 = O7)."""
        return self.out >> 6 & 0xFF

    def set_output(self, n: int, on: bool) -> None:
        """OUTPUT On (standard command): O7...O12 outside cam operation only (§2.12); O13/O14 never."""
        if n in (13, 14) or n in (15, 16):
            raise CompaxError(f"OUTPUT O{n} not allowed: O13 ... O16 are not available by OUTPUT (§2.12)",
                              code=E_NOT_AVAILABLE, field="OUTPUT", value=n, allowed="O1 ... O12")
        if self.loop_active and 7 <= n <= 12:
            raise CompaxError(f"OUTPUT O{n} not allowed during cam operation", code=E_NOT_AVAILABLE,
                              field="OUTPUT", value=n, allowed="outside cam operation")
        if not 1 <= n <= 12:
            raise CompaxError(f"OUTPUT O{n} not allowed", code=E_VALUE, field="OUTPUT", value=n, allowed="1 ... 12")
        self._set_out(n, on)

    # ================================================================== curve helpers

    def _f(self, u: float) -> tuple[float, float]:
        """(F(u), dF/du) of the selected curve."""
        s, ds, _, _ = self.curve.table.eval(u)  # type: ignore[union-attr]
        return s, ds

    def _ddf(self, u: float) -> float:
        """d2F/du2 of the set points (PointTable.set_point_acceleration), for the acceleration."""
        return self.curve.table.set_point_acceleration(u)  # type: ignore[union-attr]

    def _accept_p36(self) -> None:
        self.p36 = float(param(self.params, 36))
        curve = self.curve
        if curve is not None:
            self._k36 = self.p36 * curve.slave_cycle
            self._delta = self._k36 * (curve.f_last - curve.f_first)

    def curve_value(self) -> float:
        """The curve value at the current master position, device frame, with the curve offset
        (what SETS aligns to and POSR CAM travels to)."""
        if self.curve is None:
            return self.axis.command_position
        f, _ = self._f(self.chain.fraction)
        if self.loop_active:
            return self._base + self._k36 * f - self._R
        return self.offset + self._k36 * f

    # ================================================================== commands

    def _busy(self, command: str) -> CompaxError:
        return CompaxError(
            f"{command} not allowed while the LOOP command is active (cam operation, §11.2)",
            code=E_NOT_AVAILABLE, field=command, allowed="outside cam operation",
        )

    def limits_supervised(self) -> bool:
        """§2.4: P11/P12 supervise (normal mode P93 = 1, not both switched off)."""
        if int(param(self.params, 93)) != 1:
            return False
        return not (float(param(self.params, 11)) >= 4_000_000 and float(param(self.params, 12)) <= -4_000_000)

    @property
    def datum_reached(self) -> bool:
        """The machine datum has been reached since power on (the axis' homing has finished, D20)."""
        return bool(getattr(self.axis, "homed", False))

    def _datum_check(self, command: str) -> None:
        """D20 (§2.4): with limit supervision in normal mode, cam operation only after the datum."""
        if self.limits_supervised() and not self.datum_reached:
            self.last_error = E_NOT_AVAILABLE
            raise CompaxError(
                f"{command} not allowed: software end limits P11/P12 supervise in normal mode (P93 = 1) and the "
                "machine datum has not been reached since power on (POSA HOME first, §2.4)",
                code=E_NOT_AVAILABLE, field=command, allowed="after the machine datum (POSA HOME)",
            )

    def _heda_check(self) -> None:
        """D23: a HEDA master (slave input quantity P188 > 0, passive HEDA slave P243 bit 1) is not modelled."""
        p188 = int(param(self.params, 188))
        p243 = int(param(self.params, 243))
        if p188 != 0 or p243 & 2:
            self.last_error = E_NOT_AVAILABLE
            raise CompaxError(
                f"LOOP not allowed: the HEDA master (P188 = {p188}, P243 = {p243}, option A1/A3, §2.6) is not "
                "modelled by axisline; use the encoder (P30 = 0) or the internal time base (P30 = 1)",
                code=E_NOT_AVAILABLE, field="P188", value=p188, allowed="P188 = 0, P243 bit 1 = 0",
            )

    def posa_home(self, *, interface: bool = True) -> MotionCommand | None:
        """POSA HOME: machine datum travel (`self.homing`). During cam operation only when given over
        the interface (§2.11 "Exception ... POSA HOME or Shift I2", D21): the LOOP is left, the slave
        brakes (ramp) and the datum travel starts at standstill; a set command (interface=False) is
        refused there like the other commands (§11.2)."""
        ax = self.axis
        if self.loop_active:
            if not interface:
                raise self._busy("POSA HOME")
            self._leave()
            self._release = False
            ax.halt()
        self._home_pending = True
        self.home_command = None
        ax.homed = False  # "the time between the activation of the machine datum travel until ... reached"
        self._start_home()
        return self.home_command

    def _start_home(self) -> None:
        ax = self.axis
        if self._home_pending and ax.state is AxisState.STANDSTILL:
            self._home_pending = False
            self.home_command = ax.home(self.homing)

    def setc(self, n: int) -> None:
        """SETC n: select curve n (E17 if it is not in the cam memory)."""
        n = _operand(self.params, n)
        if isinstance(n, float) and n.is_integer():
            n = int(n)
        if isinstance(n, bool) or not isinstance(n, int):
            raise CompaxError(f"SETC {n!r} not allowed: a curve number", code=E_VALUE, field="SETC", value=n)
        linking = self.loop_active
        if linking and int(param(self.params, 210)) != 1:
            raise self._busy("SETC")
        try:
            record = _lookup(self.curves, n)
        except CompaxError as e:  # the cam memory's own E17 (or another refusal)
            self.last_error = e.code or E_CURVE_NOT_PRESENT
            raise
        if record is None:
            self.last_error = E_CURVE_NOT_PRESENT
            raise CompaxError(f"SETC {n}: curve {n} is not present in the cam memory (E17)",
                              code=E_CURVE_NOT_PRESENT, field="SETC", value=n)
        curve = PreparedCurve(record)
        curve.number = n
        self.chain.select_curve(curve.master_cycle, linking=linking)
        if linking:
            self._next_curve = curve  # curve linking: takes over with the next LOOP (§2.14)
            self._event("SETC")
            self._next_p34 = int(param(self.params, 34))  # "VP & SETC"
            return
        self._event("SETC")  # P34 ("VP & SETC") and P36 become valid now
        self.curve = curve
        self.p34 = int(param(self.params, 34))
        self._accept_p36()
        self.offset = 0.0
        self.aligned = False

    def setm(self, percent: float) -> None:
        """SETM x: master position := x % of the master cycle."""
        percent = _operand(self.params, percent)
        if self.loop_active:
            raise self._busy("SETM")
        if self.curve is None and float(percent) != 0.0:
            return  # "only becomes efficient after a curve has been selected. Exception: SETM 0"
        self.chain.setm(percent)
        if self.label is not None:
            self.label.interrupt()  # "SETM interrupts a current master related label synchronization!"

    def sets(self) -> None:
        """SETS: shift the curve so that it runs through the slave's position (no motion)."""
        if self.loop_active:
            raise self._busy("SETS")
        if self.curve is None:
            return
        f, _ = self._f(self.chain.fraction)
        self.offset = self.axis.command_position - self._k36 * f
        self.aligned = True

    def posr_cam(self, velocity: float | None = None, acceleration: float | None = None) -> MotionCommand | None:
        """POSR CAM: a normal positioning to the curve value of the actual master position.

        Endless mode (P93 = 2, D10): the actual position is set to 0 first, so the slave moves
        by the curve set point."""
        if self.loop_active:
            raise self._busy("POSR CAM")
        if self.curve is None:
            return None
        self._datum_check("POSR CAM")
        target = self.curve_value()
        self.posr_target = target
        self.aligned = True
        if int(param(self.params, 93)) == 2:
            self.axis.set_position(0.0)
        return self.axis.move_absolute(target, velocity, acceleration, acceleration)  # ACCEL: both ramps

    def loop(self, m: int) -> None:
        """LOOP m: activate the cam operation, m curve travels (0: endless)."""
        m = _operand(self.params, m)
        if isinstance(m, float) and m.is_integer():
            m = int(m)
        if isinstance(m, bool) or not isinstance(m, int) or not 0 <= m <= 65000:
            raise CompaxError(f"LOOP {m!r} not allowed: 0 ... 65000", code=E_VALUE, field="LOOP", value=m,
                              allowed="0 ... 65000")
        if self.loop_active:
            if int(param(self.params, 210)) == 1 and self._next_curve is not None and self._link is None:
                if m == 0:
                    raise CompaxError("LOOP 0 cannot be linked (§2.14: only curves with a pre-defined number of cycles)",
                                      code=E_VALUE, field="LOOP", value=m, allowed="1 ... 65000 for a linked curve")
                self._link = (self._next_curve, m, self._cycle)
                self._next_curve = None
                return
            raise self._busy("LOOP")
        if self.curve is None:
            return  # "only becomes efficient after a curve has been selected"
        if int(param(self.params, 93)) == 4:
            raise CompaxError("LOOP not allowed in speed control mode (P93 = 4)", code=E_NOT_AVAILABLE,
                              field="P93", value=4, allowed="1, 2, 3")
        self._heda_check()
        self._datum_check("LOOP")
        ax = self.axis
        held = self._release and ax.state is AxisState.SYNCHRONIZED_MOTION  # the LOOP just ended, slave at rest
        self._release = False
        if ax.state is not AxisState.STANDSTILL and not held:
            raise CompaxError(
                f"LOOP not allowed: the slave must be at standstill (axis {ax.state.value})",
                code=E_NOT_AVAILABLE, field="LOOP", value=m, allowed="slave at standstill",
            )
        curve = self.curve
        self._event("LOOP")  # P32, P33 become valid with LOOP
        if self.aligned:
            base = self.offset
        else:
            # D8: fold the slave position into the slave cycle, curve start = slave zero
            length = abs(self._k36) if self._k36 != 0.0 else abs(curve.slave_cycle)
            lo = min(0.0, self._k36)
            if length > 0.0:
                n = math.floor((ax.command_position - lo) / length)
                if n != 0:
                    ax.set_position(-n * length, relative=True)
            base = 0.0
        self.aligned = False
        self.loop_active = True
        self.loop_m = m
        self.loop_counter = m
        self._finish = False
        self._R = 0.0
        self._base = base
        self._hold = ax.command_position
        self._K = 0
        self._U = self._loop_U0 = self.chain.fraction
        self._cycle_counter = 0.0
        self._whole = False
        self._link = None
        self._next_curve = None
        self._p, self._v, self._a = self._hold, 0.0, 0.0
        self.state = CamState.READY
        self._decouple_after_coupling = False
        self._i13 = self.input("I13")
        self._couple_pending = self._i13  # D5: I13 already 1 counts as the edge
        self._sync_cmd = ax.start_sync(self)
        if not self.input("I15") and curve.aux is not None:
            self._aux_reset()

    def stop(self, deceleration: float | None = None) -> MotionCommand:
        """STOP / BREAK / EMERGENCY-STOP: interrupt the cam operation, brake to standstill (§2.11)."""
        if self.loop_active:
            self._leave()
        return self.axis.halt(deceleration)

    brk = stop

    @property
    def link_pending(self) -> bool:
        """A linked SETC + LOOP waits for the end of the running LOOP (curve linking, D14)."""
        return self._link is not None

    @property
    def next_curve_selected(self) -> bool:
        """A SETC during cam operation has selected the next curve; its LOOP is still to come."""
        return self._next_curve is not None

    @property
    def datum_travel_pending(self) -> bool:
        """POSA HOME was given; the datum travel starts when the slave stands."""
        return self._home_pending

    def _event(self, name: str) -> None:
        """Tell the parameter object and the label synchronisation about an acceptance event."""
        hook = getattr(self.params, "accept", None)
        if callable(hook):
            try:
                hook(name)
            except Exception:  # pragma: no cover - a parameter object without this event
                pass
        if self.label is not None:
            self.label.event(name)

    # ================================================================== sync source

    def sample(self, cycle: int) -> tuple[float, float, float]:
        """Set point of the cycle for the axis (computed in `tick`)."""
        return self._p, self._v, self._a

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
        if "I2" in self.inputs:  # Shift I2 (I1 + I2): machine datum travel (D21)
            shift = self.input("I1") and self.input("I2")
            if shift and not self._shift_i2:
                self.posa_home()
            self._shift_i2 = shift
        self._start_home()
        i13 = self.input("I13")
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
        chain.synchronous = self.state in _SYNCHRONOUS
        u_prev = chain.fraction
        counting = chain.counting
        wraps = chain.update(cycle, self.input("I16"), i16_latch=i16_latch, zero_pulse=zero_pulse)
        if self._master_obs_start and chain.counting:
            self._master_obs.start(chain.delta)  # the first whole cycle counted: the encoder's speed
        else:
            self._master_obs.update(chain.delta)
        self._master_obs_start = chain.counting and not counting  # (the enabling cycle counts from the latch)
        if self.label is not None:
            self.label.measure(u_prev, wraps, i14_edges)
        if self.curve is None:
            self._outputs_idle()
            return
        while wraps > 0:
            self._on_wrap(+1)
            wraps -= 1
        while wraps < 0:
            self._on_wrap(-1)
            wraps += 1
        u = chain.fraction
        self._U = self._K + u
        if self.loop_active:
            self._cycle_counter = self._U - self._loop_U0
            self._state_machine(u, rise13, fall13)
        if self.label is not None:
            step = self.label.step(self._U)
            if step and self.loop_active:
                self._base += step  # slave related correction (P33 = 2) added to the slave channel
        self._compute(u)
        self._outputs(u)

    def _i12_check(self) -> None:
        """I12 enables the output stage outside cam operation and positioning (§2.17)."""
        if "I12" not in self.inputs:
            return
        level = self.input("I12")
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
                    if int(param(self.params, 93)) == 3:
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
                if int(param(self.params, 93)) == 3:
                    self._shift_frame(-self._delta)
            self._whole = False
            self._seen_below = False

    def _accept_p36_at_zero(self) -> None:
        if float(param(self.params, 36)) != self.p36:
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
            if shift and int(param(self.params, 93)) == 3:
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

    def _leave(self) -> None:
        """Leave cam operation (LOOP done, STOP, error): device-frame curve offset kept."""
        self.offset = self._base - self._R
        self._R = 0.0
        self.loop_active = False
        self.state = CamState.IDLE
        self._link = None
        self._next_curve = None
        self._finish = False
        self._couple_pending = False
        self._set_out(16, False)

    # ------------------------------------------------------------------ set point

    def _compute(self, u: float) -> None:
        state = self.state
        curve = self.curve
        assert curve is not None
        f, df = self._f(u)
        k = self._k36
        chain = self.chain
        inv = 1.0 / chain.scaled_cycle
        Ud = chain.velocity * inv  # master cycles / s
        # the acceleration: the cam law with the observed master (motion.master_observer)
        Ud_a = self._master_obs.velocity * inv
        Udd_a = self._master_obs.acceleration * inv
        base = self._base if self.loop_active else self.offset
        c = base + k * f
        dc = k * df
        ddc = k * self._ddf(u) if state is not CamState.IDLE else 0.0
        self._set_point = c
        self._s45 = 1000.0 * f
        if state is CamState.IDLE:
            return
        if state in _SYNCHRONOUS:
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
        p68 = float(param(self.params, 68))
        if p68 > 0.0:
            # D19: P68, first-order low-pass on the speed feed-forward, T_f = P68 % of 1 ms
            tf = p68 / 100.0 * 1e-3
            v = self._v + (v - self._v) * (self.period / (self.period + tf))
        self._v = v
        self._a = ddp * Ud_a * Ud_a + dp * Udd_a
        self._check_limits()

    def _check_limits(self) -> None:
        """D15: software limits P11/P12 in normal mode during cam operation (E25)."""
        if int(param(self.params, 93)) != 1:
            return
        high = float(param(self.params, 11))
        low = float(param(self.params, 12))
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

    # ------------------------------------------------------------------ outputs

    def _aux_reset(self) -> None:
        """P37 on the masked outputs (I15 = 0 at LOOP)."""
        self._write_aux(self._aux_track(), None, enabled=False)

    def _aux_track(self) -> AuxTrack | None:
        """The aux track of the curve with mask P38 and reset value P37 (rebuilt when they change)."""
        curve = self.curve
        if curve is None or curve.aux is None:
            return None
        mask = (int(param(self.params, 38)) >> 6) & 0xFF
        if int(param(self.params, 33)) % 10 != 0:
            mask &= 0x7F  # O14 is the label error while label synchronisation is on
        reset = (int(param(self.params, 37)) >> 6) & 0xFF
        key = (id(curve), mask, reset)
        if key != self._aux_key:
            self._aux_key = key
            self._aux = AuxTrack(curve.aux.bits_per_point, mask=mask, reset_value=reset)
        return self._aux

    def _write_aux(self, track: AuxTrack | None, point: int | None, enabled: bool) -> None:
        if track is None:
            return
        prev = self.aux_byte
        if point is None:
            byte = (prev & ~track.mask & 0xFF) | (track.reset_value & track.mask)
        else:
            byte = track.outputs(point, prev, enabled)
        self.out = (self.out & ~(0xFF << 6)) | (byte << 6)

    def _outputs(self, u: float) -> None:
        state = self.state
        if state in _SYNCHRONOUS:
            track = self._aux_track()
            if track is not None:
                enabled = self.input("I15")
                self._write_aux(track, self.curve.table.last_point_passed(u), enabled)  # type: ignore[union-attr]
        if self.label is not None and self.label.active:
            self._set_out(14, self.label.o14)
        self._set_out(15, abs(self.axis.following_error) <= float(param(self.params, 79)))
        self._set_out(16, state in _SYNCHRONOUS)

    def _outputs_idle(self) -> None:
        self._set_out(15, abs(self.axis.following_error) <= float(param(self.params, 79)))
        self._set_out(16, False)

    # ================================================================== status

    def analog(self, channel: int) -> float:
        """Analogue aux function `channel` (0/1) at the master position, signed-byte units."""
        curve = self.curve
        if curve is None or curve.analog[channel] is None:
            return 0.0
        return curve.analog[channel].eval(self.chain.fraction)[0]  # type: ignore[union-attr]

    def da_monitor(self, signal: int, gain: float = 1.0) -> float:
        """D/A monitor output of the cam signals 20 ... 24 in volts (§2.12, limited to ±10 V):
        20/21 analogue aux 0/1 (100 % = 128 LSB ≙ 100 mV), 22 scaled master position (M_T ≙ 100 mV),
        23 scaled slave position (S_T ≙ 100 mV), 24 master speed (20000 min⁻¹ ≙ 10 V), each times
        the gain (P71/P72 for the D1 option)."""
        if not self.activated:
            return 10.0  # D22: "During the activation (after "Power-On") the analogous output is 10V."
        curve = self.curve
        if signal in (20, 21):
            return analog_volts(self.analog(signal - 20), gain)
        if signal == 22:
            volts = 0.1 * self.chain.fraction
        elif signal == 23:
            volts = 0.1 * (self._s45 / 1000.0) if curve is not None else 0.0
        elif signal == 24:
            volts = 10.0 * self.chain.s41 / 20000.0
        else:
            raise CompaxError(f"D/A signal {signal} not a cam signal (20 ... 24)", code=E_VALUE, field="signal",
                              value=signal, allowed="20 ... 24")
        return max(-10.0, min(10.0, volts * gain))

    @property
    def set_point(self) -> float:
        """S47: slave set point from the curve interpolation, device frame."""
        return self._set_point - (self._R if self.loop_active else 0.0)

    def status(self, n: int) -> float:
        """Status value Sn (S1, S2, S13, S14, S30, S41 ... S52)."""
        ax = self.axis
        chain = self.chain
        if n == 1:
            return ax.actual_position
        if n == 2:
            return float(self.loop_m) if self.loop_active else ax.command_position
        if n in (13, 14):
            return self._indicator(int(param(self.params, 233 if n == 13 else 234)))
        if n == 30:
            return float(self.last_error)
        if n == 41:
            return chain.s41
        if n == 42:
            return chain.s42
        if n == 43:
            return float(self.curve.number) if self.curve is not None else 0.0
        if n == 44:
            return chain.s44
        if n == 45:
            return self._s45
        if n == 46:
            return float(chain.s46)
        if n == 47:
            return self.set_point
        if n == 48:
            if self.loop_m == 0:
                return float(LOOP0_S48) if self.loop_active else 0.0
            return float(self.loop_counter)
        if n == 49:
            return self.posr_target
        if n in (50, 51, 52):
            return self.label.status(n) if self.label is not None else 0.0
        raise CompaxError(f"status S{n} not available", code=105, field="S", value=n)

    s = status

    def _indicator(self, code: int) -> float:
        """Optimizing indicators (§2.19): 31 function pointer, 32 normalized correction factor,
        33 cycle counter, 37 encoder frequency [increments/ms]."""
        if code == 33:
            return self._cycle_counter
        if code == 37:
            return self.chain.encoder_frequency
        if code in (31, 32) and self.label is not None:
            return self.label.indicator(code)
        return 0.0
