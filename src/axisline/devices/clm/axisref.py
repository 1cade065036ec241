"""The reference side of a CLM axis: rotary table arithmetic, SAC, RTM and homing (part 3).

Split from `axis` by what the code does: `ClmAxis` positions and monitors, this mixin keeps
the axis' coordinate frame (the exact rotary-table IUT and its modulo targets, the SAC shift,
the homed state and the running homing). The decisions are in `axis`' docstring (20-24).
"""

from __future__ import annotations

from fractions import Fraction
from typing import Any

from axisline.motion.axis import AxisState

from .errors import ClmError, axis_fault
from .operands import Operand
from .parameters import ParameterSet

__all__ = ["AxisReferences"]

_MILLI = 1000  # program lengths are 1/1000 IU


def _f(x: Any) -> Fraction:
    return Fraction(str(x)) if not isinstance(x, (int, Fraction)) else Fraction(x)


class AxisReferences:
    """Mixed into `ClmAxis` (its attributes: axis, number, image, _factor, _homed, ...)."""

    # the ClmAxis attributes this side uses
    axis: Any
    number: int
    _factor: Fraction
    _homed: bool

    def _configure_table_and_homing(self, params: ParameterSet, feed: Fraction) -> None:
        """Rotary table, SAC frame and homing parameters (decisions 20-24); Parameter mode ends
        the reference and the Homed output (L3715-3721)."""
        a = f"A{self.number}"
        self._motion = params.motion_type(self.number)
        self._controlled = params.encoder_type(self.number) == 3
        p19 = params.get(a + "19")
        pulses = int(p19.number("pulses")) or 1
        self._increment = feed / (4 * pulses)  # IU per encoder increment, exact
        self.iut: Fraction | None = None
        if self._motion == 2:
            base = _f(params.get(a + "01").number("feed_constant"))
            self.iut = base * int(p19.number("revolutions")) if self._absolute else base  # Fig. 7-6 / 7-8
        self._ax05_shortest = int(params.get(a + "05").number("direction")) == 1
        self._shortest = self._ax05_shortest
        p23, p24 = params.get(a + "23"), params.get(a + "24")
        self._homing_in: Operand = p23["homing_input"]
        self._home_switch: Operand = p23["home_switch_input"]
        self._homed_out: Operand = p24["homed_output"]
        self._homing_sign = -1 if p24["search_direction"] == "-" else 1
        self._homing_per_mille = int(p24.number("search_velocity"))
        self._homing_type = int(p24.number("homing_type"))
        # what `_homing_tick` looks at every cycle: the Homing input, option 5's passive reference
        self._homing_input_used = not self._homing_in.unset
        self._passive = self._homing_type == 4 and not self._home_switch.unset
        self._homing_inputs = self._passive or self._homing_input_used
        self._ax25 = _f(params.get(a + "25").number("homing_offset"))
        self._homing_proc: Any = None
        self._homing_input_was = 1  # a rising edge needs a 0 first
        self._switch_was: bool | None = None  # option 5: the home switch at the last cycle
        if getattr(self, "_sac_shift", 0):
            self.set_actual(self.axis.actual_position - float(self._sac_shift))
        self._sac_shift = Fraction(0)
        if getattr(self, "_ran", False):  # leaving Parameter mode (a fresh axis is not homed anyway;
            self._homed = False           # a test may declare it homed before the power-on cycle)
        self._homed_output(0)


    # ------------------------------------------------------------------ rotary table, SAC, homing (part 3)

    @property
    def motion_type(self) -> int:
        """Ax00: 0 rotary, 1 linear, 2 rotary table."""
        return self._motion

    def _table_goal(self, target: int) -> Fraction:
        """The unwrapped exact goal of a POA on the rotary table (decisions 20, 21)."""
        n, iut = self.number, self.iut
        assert iut is not None
        backwards = target < 0 and not self._shortest
        value = Fraction(-target if backwards else target, _MILLI) * self._factor
        if value < 0:
            raise ClmError(axis_fault(0x10, n), f"rotary table target {float(value):.3f} is negative: 0..IUT = {float(iut):.3f} (L3603)")
        if value > iut:
            raise ClmError(axis_fault(0x11, n), f"rotary table target {float(value):.3f} is beyond IUT = {float(iut):.3f} (L3603)")
        base = self._base()
        here = base % iut
        if self._shortest:
            ahead = (value - here) % iut
            step = ahead - iut if ahead > iut / 2 else ahead
        elif backwards:
            step = -((here - value) % iut)
        else:
            step = (value - here) % iut
        return base + step

    @property
    def position(self) -> float:
        """The actual position as the CLM shows it (Vx00): modulo IUT on a rotary table."""
        p = self.axis.actual_position
        return p if self.iut is None else p % float(self.iut)

    @property
    def table_target(self) -> Fraction | None:
        """The programmed target modulo IUT (exact) on a rotary table, else the target."""
        t = self._target
        return t if t is None or self.iut is None else t % self.iut

    @property
    def shortest_way(self) -> bool:
        """The rotary table mode now in force (Ax05 / RTM)."""
        return self._shortest

    def set_table_mode(self, mode: int) -> None:
        """RTM: 0 Ax05, 1 shortest, 2 programmed direction, > 2 unchanged (decision 22)."""
        if self._motion != 2:
            return
        if not self.homed:
            raise ClmError(axis_fault(0x08, self.number), f"RTM on axis {self.number}: the rotary table is not homed (L2482)")
        if mode == 0:
            self._shortest = self._ax05_shortest
        elif mode in (1, 2):
            self._shortest = mode == 1

    def set_counter(self, mode: int, value: int) -> None:
        """SAC a m value (value in 1/1000 IU), per motion type (decision 23)."""
        n = self.number
        if mode not in (0, 1, 9) or self._controlled:
            raise ClmError("1B", f"SAC mode {mode} on axis {n}" + (" (Ax20: controlled axis)" if self._controlled else ": modes 0, 1, 9"))
        v = Fraction(value, _MILLI)
        if not self.homed:
            if mode == 9:
                return
            if self._motion != 0:
                kind = "linear axis" if self._motion == 1 else "rotary table"
                raise ClmError(axis_fault(0x08, n), f"SAC {mode} cannot home a {kind} (Figs. 5-23/5-24): axis {n} not homed")
            self._shift(v - Fraction(self.axis.actual_position))
            self._sac_shift = Fraction(0)
            self._homed = True
            self._homed_output(1)
            return
        if mode == 9:
            if self._motion == 0:
                self._shift(-Fraction(self.axis.actual_position))
                self._sac_shift = Fraction(0)
                self._homed = False
            return
        target = self._base()
        new = v if mode == 0 else self._sac_shift + v - target
        self._shift(new - self._sac_shift)
        self._sac_shift = new

    def _shift(self, delta: Fraction) -> None:
        """Move the coordinate system by `delta` (no motion); the exact target moves with it."""
        if delta == 0:
            return
        self.axis.set_position(float(delta), relative=True)
        if self._target is not None:
            self._target = self._target + delta
        self.loop.resync()

    @property
    def frame_shift(self) -> Fraction:
        """SAC's shift against the initial frame (decision 23); restart keeps targets in the initial frame."""
        return self._sac_shift

    @property
    def homing(self) -> bool:
        """A homing (HOM or the Homing input) is running."""
        return self._homing_proc is not None

    def start_homing(self) -> None:
        """HOM / the Homing input: start the Ax24 homing option (decision 24, homing.py)."""
        n = self.number
        if self._absolute:
            raise ClmError(axis_fault(0x12, n), f"HOM on axis {n}: an absolute encoder needs no homing (L2006-2008)")
        if self._homing_type == 4:
            raise ClmError(axis_fault(0x12, n), f"HOM on axis {n}: Ax24 type 4 is passive homing, flying cutoff only (L4739)")
        ax = self.axis
        if not (self._drive_on and ax.powered) or not self.motion_done:
            raise ClmError(axis_fault(0x12, n), f"HOM on axis {n}: the drive must be enabled and at rest (L2010)")
        from .homing import ClmHoming

        switch = self._home_switch
        image = self.image
        cam = (lambda: False) if switch.unset else (lambda: bool(image.get(switch)))
        proc = ClmHoming(option=self._homing_type + 1, cam=cam, marker=self.marker, direction=self._homing_sign,
                         v1=float(self._vmax * self._homing_per_mille / 1000), accel=self.acceleration,
                         increment=float(self._increment), cycle_s=self.nc_cycle_s, revolution=float(self._feed),
                         offset=self._ax25, kernel_axis=ax, on_reference=self.loop.resync)
        cmd = ax.home(proc)
        if cmd.error:
            raise ClmError(axis_fault(0x12, n), f"HOM on axis {n}: {cmd.error_text}")
        self._homing_proc = proc
        self._homed = False
        self._target = None
        self._sac_shift = Fraction(0)  # homing makes the initial frame
        self._homed_output(0)

    @property
    def marker(self) -> Any:
        """The marker pulse input (the plant encoder's index); a test may replace it."""
        m = getattr(self, "_marker", None)
        if m is None:
            from .homing import EncoderMarker

            m = self._marker = EncoderMarker(self.machine.units[self.axis_name])
        return m

    @marker.setter
    def marker(self, value: Any) -> None:
        self._marker = value

    def _abort_homing(self) -> bool:
        """Stop, Immediate Stop, a mode change: a running homing ends (L3770-3775)."""
        if self._homing_proc is None:
            return False
        self._homing_proc = None
        ax = self.axis
        if ax.state is AxisState.HOMING:
            ax.stop(self.deceleration)
            ax.stop_release()
        self._target = None
        return True

    def _homing_tick(self, mode: str) -> ClmError | None:
        """The Homing input's rising edge in Manual; completion / failure of a running homing;
        option 5's passive reference."""
        err = None
        if self._passive:
            self._passive_homing(mode)
        if self._homing_input_used:
            now = self.image.get(self._homing_in)
            if now and not self._homing_input_was and mode == "manual" and self._homing_proc is None and not self._fault:
                try:
                    self.start_homing()
                except ClmError as e:
                    err = e
            self._homing_input_was = now
        proc = self._homing_proc
        if proc is None:
            return err
        ax = self.axis
        if proc.error is not None:
            self._homing_proc = None
            return ClmError(axis_fault(proc.error.offset, self.number), str(proc.error))
        if ax.state is AxisState.HOMING:
            return None
        self._homing_proc = None
        if ax.state is AxisState.ERROR_STOP:
            return ClmError(axis_fault(0x12, self.number), ax.error_text)
        if proc.phase == proc._DONE:
            self._homed = True
            self._homed_output(1)
            if self._blocked:
                self._start()
        return None

    def _passive_homing(self, mode: str) -> None:
        """Option 5 (L3797-3803, homing.py decision 9): homed where the axis leaves the home switch moving
        forward (Jog Forward in Manual, the synchronized carriage in Automatic) or reaches it
        moving in reverse (Jog Reverse, Manual); that point gets -Ax25 like options 3/4."""
        on = bool(self.image.get(self._home_switch))
        was, self._switch_was = self._switch_was, on
        if was is None or on == was or self._homed or not self._drive_on:
            return
        velocity = self.axis.command_velocity
        if (was and velocity > 0.0 and mode in ("manual", "automatic")) or (on and velocity < 0.0 and mode == "manual"):
            self.set_actual(float(-self._ax25))
            self._homed = True
            self._homed_output(1)

    def _homed_output(self, value: int) -> None:
        out = getattr(self, "_homed_out", None)
        if out is not None and not out.unset:
            self.image.set(out, value)
