"""The CLM's four analog inputs AE1-AE4 as the firmware reads them: 12-bit conversion, B017's
averaging, V007-V010 and Status 45 / 49 (manual L445, B017 L5216-5247, V007-V010 L1361-1364,
Status 45/49 L7157-7229; spec §5.3 B017, §8.5).

    analog = ClmAnalogInputs(io)        # io: an AnalogIO with AE1..AE4 (the machine file's volts)
    analog.configure(params)            # B017's averaging digit, on leaving Parameter mode
    analog.tick()                       # once per NC cycle when averaging or an override needs it
    analog.millivolts(1), analog.standardized(1), analog.volts(1)

One reading serves everything that uses an input: the override of B017 / VEO (override.py gets
`volts`), the variables V007-V010 and the status replies, so what a host reads in Status 49 is
what moves the axis.

Decisions (spec line -> choice, why)
------------------------------------
1. C-ANALOG-SCALE, spec §12 #15 (Status 45/49 scaling unspecified) and L6757/L7157/L7213 ("Voltage
   at analog inputs"): the field ``+12345`` is the voltage in mV with its sign (10 V = +10000,
   -2.5 V = -02500): five digits hold ±10 V at one mV, and the status is named a voltage. The
   value is that of the 12-bit converter (L445 "+/- 10 V (12-bit resolution)"): the volts are
   rounded to 20 V / 4096 = 4.883 mV steps (1.234 V reads +01235), full scale reaching ±10 V (the
   override's "0 - 1 corresponds to 0V - 10V", L3277, keeps 10 V = 100 %). V007-V010 are the same
   reading "standardized to +/- 1" (L1361), volts / 10. Tests:
   ``tests/devices/clm/test_analog_status.py::test_status_49_and_45_in_millivolts``,
   ``test_v007_to_v010_standardized``.
2. C-ANALOG-AVERAGING, L5220-5231 (the table's right column is shifted one row up: "0 = No
   averaging | 8 values ... 8 = | 2048, 9 = |"; spec line 1819): digit 0 = no averaging, 1-9 =
   the mean of the last 8, 16, 32, ..., 2048 values (2^(d+2)), one value per input per NC cycle
   (the firmware reads its inputs in the NC cycle; the manual gives no other rate), so 9 averages
   2048 cycles (4.1 s at 2 ms). The mean is exact (integer converter steps); when the averaging
   starts (power-on, leaving Parameter mode) its window is filled with the present reading, so a
   steady input reads its value at once and a step reaches the new value after exactly N cycles
   (linearly). The mean is what the override, V007-V010 and Status 45/49 see ("The values that
   have been read in can be queried via Status 45 or 49", L5233). B017's averaging digit is
   taken on leaving Parameter mode like every parameter. Tests: ``test_averaging_digit_table``,
   ``test_averaging_digit_1_is_8_values``, ``test_averaging_digit_4_on_v008``,
   ``test_averaged_value_drives_the_override``.
3. C-ANALOG-COST: without averaging nothing is done per NC cycle unless an override reads an
   input (override.py ``needs_analog``); a status or a V007-V010 read then converts the present
   voltage when it is asked. Test: ``test_status_49_and_45_in_millivolts`` (the reply follows a
   voltage set between two queries without any override).
"""

from __future__ import annotations

from typing import Any

__all__ = ["FULL_SCALE", "ClmAnalogInputs", "averaging_values"]

NAMES = ("AE1", "AE2", "AE3", "AE4")
FULL_SCALE = 2048  # converter steps for 10 V (12 bits over +-10 V, decision 1)
_MILLION = 1_000_000


def averaging_values(digit: int) -> int:
    """B017's averaging digit -> the number of values averaged (decision 2): 0 -> 1, 1 -> 8 ... 9 -> 2048."""
    if not 0 <= digit <= 9:
        raise ValueError(f"B017 averaging = {digit}: allowed 0 (none) .. 9 (2048 values)")
    return 1 if digit == 0 else 1 << (digit + 2)


def _steps(volts: float) -> int:
    return max(-FULL_SCALE, min(FULL_SCALE, round(volts * FULL_SCALE / 10.0)))


class ClmAnalogInputs:
    """AE1-AE4 through the 12-bit converter and B017's averaging (see the module docstring)."""

    def __init__(self, io: Any) -> None:
        self.io = io  # axisline.plant.io.AnalogIO with inputs AE1..AE4 (set_input: the voltage)
        self.window = 1
        self._rings: list[list[int]] = [[0], [0], [0], [0]]
        self._sums = [0, 0, 0, 0]
        self._at = 0
        self._fresh = False  # the window has to be filled with the present reading

    def configure(self, params: Any) -> None:
        """B017's averaging digit (decision 2); the window starts full with the present reading."""
        try:
            digit = int(params.get("B017")["analog_averaging"])
            self.window = averaging_values(digit)
        except (ValueError, KeyError, TypeError):
            self.window = 1  # an invalid B017 is fault 02 on leaving Parameter mode (parameters.py)
        self._fresh = True

    @property
    def averaging(self) -> bool:
        return self.window > 1

    def _read(self) -> list[int]:
        io = self.io
        io.sample()
        return [_steps(io.read(name)) for name in NAMES]

    def tick(self) -> None:
        """One value per input into the averaging window (decision 2)."""
        values = self._read()
        n = self.window
        if self._fresh or len(self._rings[0]) != n:
            self._rings = [[v] * n for v in values]
            self._sums = [v * n for v in values]
            self._at = 0
            self._fresh = False
            return
        at = self._at
        for i, v in enumerate(values):
            ring = self._rings[i]
            self._sums[i] += v - ring[at]
            ring[at] = v
        self._at = (at + 1) % n

    def _mean_steps(self, n: int) -> float:
        """Input `n` (1-4) in converter steps, averaged (decision 2) or read now (decision 3)."""
        if self.window == 1 or self._fresh:
            return float(self._read()[n - 1])
        return self._sums[n - 1] / self.window

    def volts(self, n: int) -> float:
        return self._mean_steps(n) * 10.0 / FULL_SCALE

    def all_volts(self) -> list[float]:
        """AE1..AE4 in volts as the override takes them (one conversion for the four)."""
        if self.window == 1 or self._fresh:
            return [v * 10.0 / FULL_SCALE for v in self._read()]
        return [s * 10.0 / (FULL_SCALE * self.window) for s in self._sums]

    def millivolts(self, n: int) -> int:
        """Status 45 / 49: mV (decision 1)."""
        return round(self._mean_steps(n) * 10_000 / FULL_SCALE)

    def standardized(self, n: int) -> int:
        """V007-V010: volts / 10 in millionths (decision 1)."""
        return round(self._mean_steps(n) * _MILLION / FULL_SCALE)
