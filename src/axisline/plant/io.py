"""The I/O image: named digital bits and analog channels as the controller sees them.

Inputs follow PLC practice: the plant (or a test) sets the physical value at any time with
``set_input``; :meth:`DigitalIO.sample` copies it into the image once per cycle, and the
controller reads only the image, so every read in a cycle sees the same value and edges are
"since the last cycle". Forcing (commissioning) overrides a physical input or a written
output until released.
"""

from __future__ import annotations

import math
from collections.abc import Iterable

__all__ = ["AnalogIO", "DigitalIO"]


def _check_names(inputs: Iterable[str], outputs: Iterable[str]) -> tuple[list[str], list[str]]:
    ins, outs = list(inputs), list(outputs)
    seen: set[str] = set()
    for name in ins + outs:
        if not name or not isinstance(name, str):
            raise ValueError(f"I/O names must be non-empty strings, got {name!r}")
        if name in seen:
            raise ValueError(f"I/O name {name!r} is used twice")
        seen.add(name)
    return ins, outs


class DigitalIO:
    """Named digital inputs and outputs with a per-cycle image, edge detection and forcing."""

    def __init__(self, inputs: Iterable[str] = (), outputs: Iterable[str] = ()) -> None:
        ins, outs = _check_names(inputs, outputs)
        self.inputs: tuple[str, ...] = tuple(ins)
        self.outputs: tuple[str, ...] = tuple(outs)
        self._physical: dict[str, bool] = dict.fromkeys(ins, False)
        self._image: dict[str, bool] = dict.fromkeys(ins, False)
        self._previous: dict[str, bool] = dict.fromkeys(ins, False)
        self._written: dict[str, bool] = dict.fromkeys(outs, False)
        self._output_previous: dict[str, bool] = dict.fromkeys(outs, False)
        self._forced: dict[str, bool] = {}

    def _check(self, name: str, table: dict[str, bool], kind: str) -> None:
        if name not in table:
            raise KeyError(f"unknown digital {kind} {name!r}")

    # -- inputs --------------------------------------------------------------------------------

    def set_input(self, name: str, value: bool) -> None:
        """Set the physical level of an input (seen by the controller from the next sample)."""
        self._check(name, self._physical, "input")
        self._physical[name] = bool(value)

    def sample(self) -> None:
        """Copy the physical inputs (or their forced values) into the image; once per cycle.

        Also remembers the outputs as they were, so output edges are per cycle as well.
        """
        forced = self._forced
        image = self._image
        previous = self._previous
        for name, value in self._physical.items():
            previous[name] = image[name]
            image[name] = forced.get(name, value)
        written = self._written
        output_previous = self._output_previous
        for name, level in written.items():  # output() without its name check: the names are ours
            output_previous[name] = forced.get(name, level)

    def read(self, name: str) -> bool:
        """Input value in this cycle's image, or an output's effective value."""
        if name in self._image:
            return self._image[name]
        self._check(name, self._written, "input or output")
        return self.output(name)

    def rising(self, name: str) -> bool:
        """Input went from 0 to 1 between the last two samples."""
        self._check(name, self._image, "input")
        return self._image[name] and not self._previous[name]

    def falling(self, name: str) -> bool:
        """Input went from 1 to 0 between the last two samples."""
        self._check(name, self._image, "input")
        return self._previous[name] and not self._image[name]

    # -- outputs -------------------------------------------------------------------------------

    def write(self, name: str, value: bool) -> None:
        """Controller sets an output."""
        self._check(name, self._written, "output")
        self._written[name] = bool(value)

    def output(self, name: str) -> bool:
        """Output level the plant sees: the forced value if forced, else the written one."""
        self._check(name, self._written, "output")
        return self._forced.get(name, self._written[name])

    def output_rising(self, name: str) -> bool:
        """Output is 1 now and was 0 at the last sample."""
        return self.output(name) and not self._output_previous[name]

    def output_falling(self, name: str) -> bool:
        """Output is 0 now and was 1 at the last sample."""
        return self._output_previous[name] and not self.output(name)

    # -- forcing -------------------------------------------------------------------------------

    def force(self, name: str, value: bool) -> None:
        """Override an input or output until :meth:`release` (inputs: from the next sample)."""
        if name not in self._physical:
            self._check(name, self._written, "input or output")
        self._forced[name] = bool(value)

    def release(self, name: str) -> None:
        """End forcing of ``name`` (no error if it was not forced)."""
        self._forced.pop(name, None)

    def is_forced(self, name: str) -> bool:
        return name in self._forced

    @property
    def forced(self) -> dict[str, bool]:
        """Copy of the forced values."""
        return dict(self._forced)

    def snapshot(self) -> dict[str, bool]:
        """Every input (image) and output (effective) by name, for traces and the HMI."""
        values = dict(self._image)
        for name in self._written:
            values[name] = self.output(name)
        return values


class AnalogIO:
    """Named analog channels in volts, clamped to +-``limit`` and optionally quantised.

    With ``input_bits``/``output_bits`` a value is rounded to the converter's step
    ``2 * limit / 2**bits`` (e.g. 12-bit inputs, 14-bit outputs over +-10 V).
    """

    def __init__(
        self,
        inputs: Iterable[str] = (),
        outputs: Iterable[str] = (),
        *,
        limit: float = 10.0,
        input_bits: int | None = None,
        output_bits: int | None = None,
    ) -> None:
        if not limit > 0.0:
            raise ValueError("limit must be > 0")
        ins, outs = _check_names(inputs, outputs)
        self.inputs: tuple[str, ...] = tuple(ins)
        self.outputs: tuple[str, ...] = tuple(outs)
        self.limit = float(limit)
        self._in_step = 2.0 * limit / (1 << input_bits) if input_bits else 0.0
        self._out_step = 2.0 * limit / (1 << output_bits) if output_bits else 0.0
        self._physical: dict[str, float] = dict.fromkeys(ins, 0.0)
        self._image: dict[str, float] = dict.fromkeys(ins, 0.0)
        self._written: dict[str, float] = dict.fromkeys(outs, 0.0)
        self._forced: dict[str, float] = {}

    def _convert(self, volts: float, step: float) -> float:
        if math.isnan(volts):
            raise ValueError("analog value is NaN")
        v = min(self.limit, max(-self.limit, float(volts)))
        if step:
            v = min(self.limit, max(-self.limit, round(v / step) * step))
        return v

    def set_input(self, name: str, volts: float) -> None:
        """Set the physical voltage at an input (clamped to the converter range)."""
        if name not in self._physical:
            raise KeyError(f"unknown analog input {name!r}")
        self._physical[name] = min(self.limit, max(-self.limit, float(volts)))

    def sample(self) -> None:
        """Convert the inputs into the image; once per cycle."""
        for name, volts in self._physical.items():
            self._image[name] = self._convert(self._forced.get(name, volts), self._in_step)

    def read(self, name: str) -> float:
        """Input voltage in this cycle's image, or an output's effective voltage."""
        if name in self._image:
            return self._image[name]
        return self.output(name)

    def write(self, name: str, volts: float) -> float:
        """Controller sets an output; returns the voltage actually produced (clamped)."""
        if name not in self._written:
            raise KeyError(f"unknown analog output {name!r}")
        value = self._convert(volts, self._out_step)
        self._written[name] = value
        return value

    def output(self, name: str) -> float:
        """Output voltage the plant sees: forced value if forced, else the written one."""
        if name not in self._written:
            raise KeyError(f"unknown analog output {name!r}")
        if name in self._forced:
            return self._convert(self._forced[name], self._out_step)
        return self._written[name]

    def force(self, name: str, volts: float) -> None:
        if name not in self._physical and name not in self._written:
            raise KeyError(f"unknown analog channel {name!r}")
        self._forced[name] = float(volts)

    def release(self, name: str) -> None:
        self._forced.pop(name, None)

    def is_forced(self, name: str) -> bool:
        return name in self._forced
