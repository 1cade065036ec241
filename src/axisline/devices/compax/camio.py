"""COMPAX XX70 cam operation, part 1 of 4: its state, the I/O image, the auxiliary outputs and the
status values (compax.md §2.12, §2.18, §2.19; manual §13, §20). `camop.CamOperation` is the
cam controller (see camop.py); this module holds what it reads and writes besides the motion:

    op.input("I13"), op.output(16), op.aux_byte, op.set_output(9, True)
    op.status(44), op.s(48), op.analog(0), op.da_monitor(22), op.set_point

`CamIO` is the base of `camcommands.CamCommands` (the curve commands), `camsetpoint.CamSetPoint`
(the set point) and `camop.CamOperation` (the 1 ms cycle), in that order: one object, split by
what the code does.

Decisions (numbered as in camop.py; each has a test in tests/devices/compax/test_camop*.py):

* D2 Units of S44/S45/S50...S52 (§0 [CONFLICT] % vs ‰): per mille (§20); SETM in %.
* D12 Auxiliary functions (§2.12): the outputs follow the set points only while synchronous
  (O16 = 1); at LOOP with I15 = 0 the masked outputs take P37 at once; leaving synchronous
  operation freezes them. O14 is the label error when P33 != 0. The analogue channels are
  interpolated whenever a curve is selected (independent of I15) and scaled 10 V / 128 LSB
  at gain 100 (§2.12 [DERIVED]). Tests: test_camop_aux.py.
* D13 O15 (§2.18 "actualized at each movement"): updated every cycle from the axis'
  following error against P79.
* D16 S47 is the curve set point (curve offset + curve value, device frame) also while
  coupling / decoupling; S45 the curve value in per mille of S_T·P36 (plus the slave-related
  label correction); S2 is the m of the last LOOP in cam operation, else the set point.
* D18 D/A monitor (§2.12 signals 20 ... 24): 22 = the master position in the cycle (M_T ≙
  100 mV), 23 = the curve value S45 (S_T ≙ 100 mV), 24 = S41 (20000 min⁻¹ ≙ 10 V), times the
  gain, limited to ±10 V. Tests: test_da_monitor_* (§7 X8).
* D22 D/A monitor at power on (manual §13.2 "During the activation (after "Power-On") the
  analogous output is 10V."): `da_monitor` gives +10 V for every signal and gain from power on
  (construction) until the first device cycle (`tick`), the end of the activation in axisline
  (its length on the device is not given [GAP]). Test:
  test_da_monitor_is_10v_during_the_activation_after_power_on.
"""

from __future__ import annotations

from enum import Enum
from typing import Any

from axisline.devices.compax import CompaxError
from axisline.devices.compax.masterchain import MasterChain, param, valid_values
from axisline.devices.compax.preparedcurve import PreparedCurve
from axisline.motion.axis import Axis, MotionCommand
from axisline.motion.camswitch import AuxTrack
from axisline.motion.homing import DirectHoming, HomingProcedure
from axisline.motion.master_observer import MasterObserver

__all__ = ["CamIO", "CamState", "E_NOT_AVAILABLE", "E_VALUE", "LINK_LEAD_CYCLES", "LOOP0_S48", "analog_volts"]

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


_O14, _O15, _O16 = 1 << 13, 1 << 14, 1 << 15  # their bits in the output image (bit n-1 = On)
_AUX_MASK = 0xFF << 6  # P38's valences of O7 ... O14
_UNWIRED = object()  # an input missing from the wiring
_FOLLOWING = (CamState.COUPLING, CamState.SYNC, CamState.WAIT_DECOUPLE, CamState.DECOUPLING)
_SYNCHRONOUS = (CamState.SYNC, CamState.WAIT_DECOUPLE)


def analog_volts(value: float, gain: float = 100.0) -> float:
    """An analogue aux value (signed byte units) as D/A volts: 100 % = 128 LSB = 0.1 V · gain,
    limited to ±10 V (§2.12: signals 20/21 "100% ≙ 100mV" at gain 1; P71 = 100: 127 ≙ 10 V)."""
    volts = value / 128.0 * 0.1 * gain
    return max(-10.0, min(10.0, volts))


class CamIO:
    """The cam operation's state, inputs, outputs and status (see the module docstring and
    `camop.CamOperation`, the class to use)."""

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
        self._pv = valid_values(params)  # the valid values, read every cycle
        self.curves = curves
        self.period = axis.period
        self.chain = master if master is not None else MasterChain(params, encoder, axis.period)
        self.inputs: dict[str, Any] = inputs if inputs is not None else {}
        self.state = CamState.IDLE
        self.curve: PreparedCurve | None = None
        #: curves prepared by SETC: number -> (the cam memory's valid_version, curve)
        self._prepared: dict[int, tuple[int, PreparedCurve]] = {}
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
        self.p36 = float(self._pv[36])
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


    # ================================================================== outputs

    def _aux_reset(self) -> None:
        """P37 on the masked outputs (I15 = 0 at LOOP)."""
        self._write_aux(self._aux_track(), None, enabled=False)

    def _aux_track(self) -> AuxTrack | None:
        """The aux track of the curve with mask P38 and reset value P37 (rebuilt when they change)."""
        curve = self.curve
        if curve is None or curve.aux is None:
            return None
        mask = (int(self._pv[38]) >> 6) & 0xFF
        if int(self._pv[33]) % 10 != 0:
            mask &= 0x7F  # O14 is the label error while label synchronisation is on
        reset = (int(self._pv[37]) >> 6) & 0xFF
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
        synchronous = state is CamState.SYNC or state is CamState.WAIT_DECOUPLE
        if synchronous and int(self._pv[38]) & _AUX_MASK:  # P38 = 0 (the default): no output follows the curve
            track = self._aux_track()
            if track is not None:
                enabled = self.input("I15")
                self._write_aux(track, self.curve.table.last_point_passed(u), enabled)  # type: ignore[union-attr]
        out = self.out
        label = self.label
        if label is not None and label.mode != 0:  # O14: the label error (label.active)
            out = (out | _O14) if label.o14 else (out & ~_O14)
        out = (out | _O15) if abs(self.axis.following_error) <= float(self._pv[79]) else (out & ~_O15)
        self.out = (out | _O16) if synchronous else (out & ~_O16)

    def _outputs_idle(self) -> None:
        self._set_out(15, abs(self.axis.following_error) <= float(self._pv[79]))
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

    def s(self, n: int) -> float:
        """Status value Sn (`status`)."""
        return self.status(n)

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
