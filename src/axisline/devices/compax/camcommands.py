"""COMPAX XX70 cam operation, part 2 of 4: the curve commands SETC, SETM, SETS, POSR CAM, LOOP,
STOP / BREAK and POSA HOME (compax.md §2.4, §2.8, §2.11, §2.14; manual §11, §15).

    op.setc(1); op.setm(0.0); op.sets(); op.posr_cam(); op.loop(10); op.stop(); op.posa_home()

A command is given between cycles; what it starts runs in `camop.CamOperation.tick`. A refused
command raises `CompaxError` with the device's code (E17 curve missing, 103 value, 107 not
available now) and changes nothing.

Decisions (numbered as in camop.py; each has a test in tests/devices/compax/test_camop*.py):

* D8 LOOP start point (§2.8, §11.1.1): without SETS / POSR CAM since the last LOOP / SETC the
  slave position is folded into the slave cycle [0, S_T·P36) by counting set and actual
  position back by n·S_T·P36, and the curve offset is 0 (curve start = slave zero).
  Test: test_loop_folds_the_slave_into_the_slave_cycle.
* D10 Endless mode (P93 = 2, §2.1): POSR CAM sets the actual position to 0 and moves to the
  curve value (a relative move by S47); in cam operation endless mode follows like normal
  mode. P93 = 4 (speed control) refuses LOOP (E_NOT_AVAILABLE). Test: test_endless_posr_cam.
* D11 Commands during cam operation (§11.2 "the LOOP-command is still active and COMPAX does
  not carry out any commands"): SETC/SETM/SETS/POSR CAM/LOOP are refused with
  E_NOT_AVAILABLE (107), except SETC + LOOP with P210 = 1 (curve linking, §2.14); a second
  linked LOOP while one waits is refused ("the second positioning command is rejected").
  SETM/SETS/POSR CAM without a selected curve have no effect ("only becomes efficient
  after a curve has been selected"), except SETM 0.
* D17 Operation parameters as arguments (§2.8 "SETC .P40, SETM .P40, LOOP .P40"): the string
  ".P40" ... ".P49" stands for the valid value of that parameter. Test:
  test_operation_parameters_as_arguments.
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
* D23 HEDA not modelled (§2.6 "Process coupling via HEDA (option A1/A3)"): reason: a hardware
  option (SSI bus, ±2.5 µs time-slice synchronisation, data blocks of a second COMPAX, E76 ...
  E78 transmission errors) with no second device in axisline to send the process value; a
  partial model (another axis' data block, the 2 ms delay at P188 > 0) would give results the
  bus cannot be checked against. A HEDA master (P188 != 0, or P243 bit 1 "passive slave")
  refuses LOOP with E_NOT_AVAILABLE (107); P31 = 9 with P188 = 0 stays the static I16 enable
  of the encoder / time base. Test: test_heda_master_is_not_modelled.
* D26 A curve prepared once per state of the valid copy (issue 18: "values computed once per
  configuration change"): SETC reads the curve from the cam memory's valid copy, which only VF
  changes (`CamMemory.valid_version`); a curve read and prepared (table, aux track, analogue
  channels) since the last VF is taken again as a copy, so curve linking, which selects the same
  few curves every master cycle, does not decode the memory each time. Each SETC still gives a
  new curve object. Test: test_setc_reads_the_valid_copy_as_it_is_after_each_vf
  (test_camop_integration.py).
"""

from __future__ import annotations

import copy
import math
from typing import Any

from axisline.devices.compax import E_CURVE_NOT_PRESENT, CompaxError
from axisline.devices.compax.camio import E_NOT_AVAILABLE, E_VALUE, CamIO, CamState
from axisline.devices.compax.masterchain import param
from axisline.devices.compax.preparedcurve import PreparedCurve
from axisline.motion.axis import AxisState, MotionCommand

__all__ = ["CamCommands"]


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


class CamCommands(CamIO):
    """The curve commands of the cam operation (see the module docstring)."""

    def _busy(self, command: str) -> CompaxError:
        return CompaxError(
            f"{command} not allowed while the LOOP command is active (cam operation, §11.2)",
            code=E_NOT_AVAILABLE, field=command, allowed="outside cam operation",
        )

    def limits_supervised(self) -> bool:
        """§2.4: P11/P12 supervise (normal mode P93 = 1, not both switched off)."""
        if int(self._pv[93]) != 1:
            return False
        return not (float(self._pv[11]) >= 4_000_000 and float(self._pv[12]) <= -4_000_000)

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
        p188 = int(self._pv[188])
        p243 = int(self._pv[243])
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
        return self._start_home()

    def _start_home(self) -> MotionCommand | None:
        """The datum travel, once the slave stands (POSA HOME pending): its command, else None."""
        ax = self.axis
        if self._home_pending and ax.state is AxisState.STANDSTILL:
            self._home_pending = False
            cmd = self.home_command = ax.home(self.homing)
            return cmd
        return None

    def setc(self, n: Any) -> None:
        """SETC n: select curve n (E17 if it is not in the cam memory); n: a number or ".P40" ... ".P49"."""
        n = _operand(self.params, n)
        if isinstance(n, float) and n.is_integer():
            n = int(n)
        if isinstance(n, bool) or not isinstance(n, int):
            raise CompaxError(f"SETC {n!r} not allowed: a curve number", code=E_VALUE, field="SETC", value=n)
        linking = self.loop_active
        if linking and int(self._pv[210]) != 1:
            raise self._busy("SETC")
        curve = self._prepared_curve(n)
        self.chain.select_curve(curve.master_cycle, linking=linking)
        if linking:
            self._next_curve = curve  # curve linking: takes over with the next LOOP (§2.14)
            self._event("SETC")
            self._next_p34 = int(self._pv[34])  # "VP & SETC"
            return
        self._event("SETC")  # P34 ("VP & SETC") and P36 become valid now
        self.curve = curve
        self.p34 = int(self._pv[34])
        self._accept_p36()
        self.offset = 0.0
        self.aligned = False

    def _prepared_curve(self, n: int) -> PreparedCurve:
        """Curve n of the cam memory made ready for the cam operation (E17 if it is absent).

        A cam memory that numbers the states of its valid copy (`CamMemory.valid_version`,
        changed by VF) has each curve read and prepared once per state: a SETC of a curve
        prepared since the last VF takes a copy of it (a new object, as every SETC gives one;
        curve linking selects the same few curves again and again)."""
        version = getattr(self.curves, "valid_version", None)
        known = self._prepared.get(n)
        if known is not None and version is not None and known[0] == version:
            return copy.copy(known[1])
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
        if isinstance(version, int):
            self._prepared[n] = (version, curve)
        return curve

    def setm(self, percent: Any) -> None:
        """SETM x: master position := x % of the master cycle; x: a number or ".P40" ... ".P49"."""
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
        if int(self._pv[93]) == 2:
            self.axis.set_position(0.0)
        return self.axis.move_absolute(target, velocity, acceleration, acceleration)  # ACCEL: both ramps

    def loop(self, m: Any) -> None:
        """LOOP m: activate the cam operation, m curve travels (0: endless); m: a number or ".P40" ... ".P49"."""
        m = _operand(self.params, m)
        if isinstance(m, float) and m.is_integer():
            m = int(m)
        if isinstance(m, bool) or not isinstance(m, int) or not 0 <= m <= 65000:
            raise CompaxError(f"LOOP {m!r} not allowed: 0 ... 65000", code=E_VALUE, field="LOOP", value=m,
                              allowed="0 ... 65000")
        if self.loop_active:
            if int(self._pv[210]) == 1 and self._next_curve is not None and self._link is None:
                if m == 0:
                    raise CompaxError("LOOP 0 cannot be linked (§2.14: only curves with a pre-defined number of cycles)",
                                      code=E_VALUE, field="LOOP", value=m, allowed="1 ... 65000 for a linked curve")
                self._link = (self._next_curve, m, self._cycle)
                self._next_curve = None
                return
            raise self._busy("LOOP")
        if self.curve is None:
            return  # "only becomes efficient after a curve has been selected"
        if int(self._pv[93]) == 4:
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

    def brk(self, deceleration: float | None = None) -> MotionCommand:
        """BREAK: as STOP (§2.11)."""
        return self.stop(deceleration)

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
