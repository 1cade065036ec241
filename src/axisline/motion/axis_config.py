"""The axis' configuration (pydantic) and the sync-source protocol.

Separate from axis.py, which may be compiled (mypyc, compiled_modules.txt): a compiled module
can define neither a pydantic model nor a runtime-checkable Protocol. axis.py re-exports both.
"""

from __future__ import annotations

from typing import Literal, Protocol, runtime_checkable

from pydantic import BaseModel, ConfigDict, Field, model_validator

__all__ = ["AxisConfig", "SyncSource"]


@runtime_checkable
class SyncSource(Protocol):
    """A master-related set point (gear, cam, sync): axis-frame (p, v, a) of a cycle."""

    def sample(self, cycle: int) -> tuple[float, float, float]: ...


# ------------------------------------------------------------------------ configuration


class AxisConfig(BaseModel):
    """One axis of the machine file (flat; drive and encoder tables live beside it)."""

    model_config = ConfigDict(extra="forbid", allow_inf_nan=False)

    name: str = Field(min_length=1, description="Axis name as shown on the HMI and in traces.")
    kind: Literal["linear", "modulo"] = Field(
        default="linear", description="linear: unbounded travel; modulo: position wraps into [0, modulo_period)."
    )
    modulo_period: float | None = Field(
        default=None, gt=0, description="Period of a modulo axis in user units (e.g. 360 deg); only for kind = 'modulo'."
    )
    unit: str = Field(min_length=1, description="User unit of positions, e.g. 'mm' or 'deg'.")
    counts_per_unit: float = Field(gt=0, description="Scale: encoder counts per user unit.")
    v_max: float = Field(gt=0, description="Maximum velocity, user units/s; commands above it are clamped.")
    a_max: float = Field(gt=0, description="Maximum acceleration, user units/s^2.")
    d_max: float | None = Field(
        default=None, gt=0, description="Maximum deceleration, user units/s^2 (None: same as a_max)."
    )
    j_max: float | None = Field(
        default=None, gt=0, description="Maximum jerk, user units/s^3 (None: no jerk limit, trapezoid profiles)."
    )
    shape: Literal["trapezoid", "jerk", "sin2"] | None = Field(
        default=None,
        description="Profile shape: constant acceleration, linear acceleration ramps (jerk limited) or sin^2 "
        "ramps. None: 'jerk' if j_max is given, else 'trapezoid'.",
    )
    error_deceleration: float | None = Field(
        default=None, gt=0, description="Deceleration of the error stop (ERROR_STOP), user units/s^2 (None: d_max)."
    )
    sw_limits_enabled: bool = Field(default=False, description="Watch the software limits (linear axes only).")
    sw_limit_low: float = Field(default=0.0, description="Lower software limit, user units.")
    sw_limit_high: float = Field(default=0.0, description="Upper software limit, user units.")
    kv: float = Field(default=30.0, ge=0, le=10000, description="Position-loop gain Kv, 1/s (velocity per following error).")
    velocity_feed_forward: float = Field(
        default=1.0, ge=0, le=1.2, description="Velocity feed-forward factor (1.0 = full set-point velocity)."
    )
    following_error_limit: float = Field(
        gt=0, description="|set point - actual| above this trips ERROR_STOP while powered, user units."
    )
    in_position_window: float | None = Field(
        default=None, ge=0, description="At rest and |following error| within this: in position (None: limit/10)."
    )
    jog_velocity: float | None = Field(default=None, gt=0, description="Jog speed, user units/s (None: v_max/10).")
    jog_acceleration: float | None = Field(
        default=None, gt=0, description="Jog acceleration and deceleration, user units/s^2 (None: a_max)."
    )

    @model_validator(mode="after")
    def _consistent(self) -> AxisConfig:
        # Resolve the "None: same as ..." defaults here so every reader sees numbers.
        if self.d_max is None:
            self.d_max = self.a_max
        if self.shape is None:
            self.shape = "jerk" if self.j_max is not None else "trapezoid"
        if self.error_deceleration is None:
            self.error_deceleration = self.d_max
        if self.in_position_window is None:
            self.in_position_window = self.following_error_limit / 10.0
        if self.jog_velocity is None:
            self.jog_velocity = self.v_max / 10.0
        if self.jog_acceleration is None:
            self.jog_acceleration = self.a_max
        if self.kind == "modulo":
            if self.modulo_period is None:
                raise ValueError("modulo_period is required for kind = 'modulo'")
            if self.sw_limits_enabled:
                raise ValueError("sw_limits_enabled: software limits do not apply to a modulo axis")
        elif self.modulo_period is not None:
            raise ValueError("modulo_period is only used by kind = 'modulo' (this axis is linear)")
        if self.shape != "trapezoid" and self.j_max is None:
            raise ValueError(f"shape = {self.shape!r} needs j_max")
        if self.sw_limits_enabled and not self.sw_limit_low < self.sw_limit_high:
            raise ValueError(
                f"sw_limit_low = {self.sw_limit_low:g} must be below sw_limit_high = {self.sw_limit_high:g}"
            )
        if self.jog_velocity > self.v_max:
            raise ValueError(f"jog_velocity = {self.jog_velocity:g} exceeds v_max = {self.v_max:g}")
        if self.jog_acceleration > max(self.a_max, self.d_max):
            raise ValueError(f"jog_acceleration = {self.jog_acceleration:g} exceeds a_max = {self.a_max:g}")
        return self
