"""Motor current per motion phase and the module's overcurrent model (manual §3.6.2, §4.1.4.3; wago.md §2.8).

The output stage drives the phase current as a percentage of the rated current Current
(addr 14, 0.1 A, peak) per motion phase: standstill (addr 15), acceleration (16), constant
speed (17), deceleration (18) and STOP mode (61); 0 % blocks the modulation.

"The module can supply a current of 150 % of the module's nominal current for a limited time
of up to 10 seconds. To protect the module, a simplified thermal model is calculated"
(§3.6.2.2). Its two published laws

    t_off  = 5 A / (I_OV - 5 A) * 5 s                  (time to shutdown at I_OV)
    t_cool = 4 * (I_OV - 5 A) / (5 A - I_re) * t_OV    (cooling at I_re after t_OV at I_OV)

are those of one integrator (wago.md §2.8 [DERIVED]): X += (I - 5 A) dt above 5 A, X -= (5 A - I)/4 dt
below (floor 0), shutdown with 1413 PARTMODL_CURRENT_TIME when X reaches 25 A*s. State
variable 21 reports X as 0 .. 255.
"""

from __future__ import annotations

import math
from enum import Enum

__all__ = ["CurrentPhase", "phase_current", "OvercurrentModel", "t_off", "t_cool", "MODULE_NOMINAL_A"]

MODULE_NOMINAL_A = 5.0  # module nominal (peak) current [A]
LOAD_LIMIT = MODULE_NOMINAL_A * 5.0  # 25 A*s: 2.5 A above nominal for 10 s


class CurrentPhase(Enum):
    """Phase of the motion that selects the current ratio."""

    OFF = "off"  # output stage off: no current
    STANDSTILL = "standstill"  # Current_Ratio_StandStill (15)
    RAMP_UP = "acceleration"  # Current_Ratio_RampUp (16)
    DRIVE = "constant speed"  # Current_Ratio_Drive (17)
    RAMP_DOWN = "deceleration"  # Current_Ratio_RampDown (18)
    STOP = "stop"  # Current_Ratio_Stop (61): braking by Stop1_N/Stop2_N/STOP


def phase_current(rated: int, ratio: int) -> float:
    """Peak phase current [A] = Current [0.1 A] / 10 * ratio [%] / 100."""
    return rated / 10.0 * ratio / 100.0


def t_off(i_ov: float) -> float:
    """Seconds until shutdown at the overcurrent i_ov > 5 A (§4.1.4.3)."""
    if i_ov <= MODULE_NOMINAL_A:
        return math.inf
    return MODULE_NOMINAL_A / (i_ov - MODULE_NOMINAL_A) * 5.0


def t_cool(i_ov: float, i_re: float, t_ov: float) -> float:
    """Cooling time at i_re < 5 A after t_ov seconds at i_ov (§4.1.4.3)."""
    return 4.0 * (i_ov - MODULE_NOMINAL_A) / (MODULE_NOMINAL_A - i_re) * t_ov


class OvercurrentModel:
    """The integrator of the simplified thermal model; `step` returns True when it trips."""

    __slots__ = ("load",)

    def __init__(self) -> None:
        self.load = 0.0  # A*s above the nominal current, net of cooling

    def step(self, current: float, dt: float) -> bool:
        if current > MODULE_NOMINAL_A:
            self.load += (current - MODULE_NOMINAL_A) * dt
        else:
            self.load = max(0.0, self.load - (MODULE_NOMINAL_A - current) / 4.0 * dt)
        return self.load >= LOAD_LIMIT * (1.0 - 1e-12)

    @property
    def state_variable(self) -> int:
        """Internal state variable 21: prior overcurrent load 0 .. 255 (255: error 1413)."""
        return min(255, int(255.0 * self.load / LOAD_LIMIT + 1e-9))

    def reset(self) -> None:
        self.load = 0.0
