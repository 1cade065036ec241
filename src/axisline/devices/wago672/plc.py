"""A scripted PLC for `axisline run`: `[[device.plc]]` steps on the coupler's process image.

On a real machine a PLC drives the 750-672 over the fieldbus: every PLC cycle it writes the
module's 12-byte output image and reads its input image (manual §3.7). `axisline serve` gets
that PLC from the network (Modbus TCP); `axisline run` has no network, so the machine file
may carry a stand-in: a list of steps in the module's own terms, run by this module.

    [[device.plc]]
    name = "enable"                          # optional: names the step in messages
    set = ["Reset_Quit", "Enable", "Stop2_N"]  # control bits to 1 (C0..C3, the manual's names)
    wait = { Ready = true, Stop_N_ACK = true, Reset = false }   # status bits (S0..S3) to wait for

    [[device.plc]]
    name = "move to 100 mm"
    clear = ["Reset_Quit"]                   # control bits to 0
    velocity = 25000                         # set-point words D0..D6, as the module takes them:
    acceleration = 10000                     #   velocity D0..D1, acceleration D2..D3,
    target = 256000                          #   target position D4..D6 (24 bit, position units)
    set = ["Start"]
    wait = ["Start_ACK"]                     # a list: these bits = 1
    timeout_s = 2.0                          # default 10 s

    [[device.plc]]
    wait_s = 1.5                             # a time: wait this long (then for `wait`, if any)

A step's writes (set, clear, the set-point words) reach the output image at once; the step is
done at the first PLC cycle on which `wait_s` has elapsed and every bit of `wait` has its level
in the input image the module returned; then the next step's writes follow in that cycle. A
step without `wait` and `wait_s` lasts one PLC cycle (the module sees its writes once before
the next step changes them again: a Start pulse is `set = ["Start"]` then `clear = ["Start"]`).
`module` (default 0) picks the module of `[[device.modules]]` the step writes and waits on.

The PLC cycle is the coupler's 1 ms tick: the script reads the inputs of the last K-bus cycle,
then writes the whole output area (one FC16 write, as a PLC's cyclic exchange), which feeds the
fieldbus watchdog; after the last step it goes on writing its last image (the PLC keeps running).

A step fails the run (a fault naming the step, `axisline run` exits 1) when its `wait` does not
hold within `timeout_s` after `wait_s`, or when the module reports Error (S2.7) while the step
waits for anything but Error itself - as a PLC program would stop on the module's Error bit.
The PLC's fault reaction then: Start and Stop2_N to 0 on every module (Enable kept), so a
moving drive brakes with its STOP ramp (Acceleration_Stop_Fast) and the run ends at rest.

Decisions (spec line -> choice, why):

1. wago.md §3.3-3.5 (bit tables of C0..C3 / S0..S3) -> the step vocabulary is exactly the bit
   names of image.py, which are the manual's (Enable, Stop2_N, Start, M_Positioning ...,
   Ready, Stop_N_ACK, Start_ACK, On_Target, Reference_OK ...). Stop1_N is not an image bit (it is
   DI1, Input1, wired in `device.modules.inputs`); naming it gets that explanation. A wrong
   name is a config error naming step, field and the allowed names (test_plc_script.py
   test_bad_bit_name_in_set_names_step_field_and_the_allowed_bits, test_stop1_n_is_explained_as_input1).
2. wago.md §3.6 (D0..D6 per mode) -> `velocity`, `acceleration`, `target` write the words at
   their single-positioning offsets, which speed control and referencing share; they are
   checked against the field's encoding (16 bit signed, 24 bit signed), not against the mode's
   rules (velocity 1..25000 ...): those are the module's, which answers with its own error code
   on Start, as on a real module (test_plc_script.py
   test_setpoint_out_of_encoding_is_a_config_error_naming_the_range,
   test_module_error_fails_the_step_with_the_module_error_code).
3. Not in the manual (the PLC is the user's) -> two masters: the script runs only on the
   simulated clock (`axisline run`). Under `serve` (wall clock) the Modbus client is the PLC and
   the script is not run; the personality says so on stderr once (test_plc_script.py
   test_serve_does_not_run_the_script; test_serve.py
   test_serve_says_on_the_console_when_the_watchdog_trips_and_does_not_run_the_script).
4. Not in the manual -> a failed step is the PLC program's fault: Start and Stop2_N go to 0 on
   every module (Enable kept), so the drive brakes with its STOP ramp, as §3.7.2 asks for a
   stop ("When closing down with a stop ramp, Stop2_N must be used"), and the run ends at rest
   instead of a drive left running into machine.duration (test_plc_script.py
   test_a_failed_step_brakes_a_moving_drive_with_the_stop_ramp).
"""

from __future__ import annotations

import difflib
import math
from enum import IntFlag
from collections.abc import Sequence
from typing import Any

from pydantic import BaseModel, ConfigDict, Field, StrictBool, field_validator, model_validator
from pydantic_core import PydanticCustomError

from axisline.devices.wago672.image import (
    INT24_MAX,
    INT24_MIN,
    OFFSET_C0,
    OFFSET_C1,
    OFFSET_C2,
    OFFSET_C3,
    C0,
    C1,
    C2,
    C3,
    S0,
    S1,
    S2,
    S3,
)

__all__ = ["OUTPUT_BITS", "STATUS_BITS", "PlcStep"]


def _bits(*flags: tuple[int, type[IntFlag]]) -> dict[str, tuple[int, int]]:
    out: dict[str, tuple[int, int]] = {}
    for offset, flag in flags:
        for member in flag:
            out[str(member.name)] = (offset, int(member))
    return out


#: control bits of the output image: name -> (byte offset, mask); C0's MBX is the mailbox switch
OUTPUT_BITS = _bits((OFFSET_C0, C0), (OFFSET_C1, C1), (OFFSET_C2, C2), (OFFSET_C3, C3))
#: status bits of the input image: name -> (byte offset, mask)
STATUS_BITS = _bits((OFFSET_C0, S0), (OFFSET_C1, S1), (OFFSET_C2, S2), (OFFSET_C3, S3))
_S2_ERROR = int(S2.Error)

_HINTS = {
    "stop1_n": "Stop1_N is Input1 (DI1), not an image bit: wire it in device.modules.inputs (Input1 = true); "
               "the image's stop bit is Stop2_N",
}


def _bad_name(name: Any, table: dict[str, tuple[int, int]], what: str) -> PydanticCustomError:
    hint = _HINTS.get(str(name).lower())
    if hint is None:
        lowered = {k.lower(): k for k in table}
        close = difflib.get_close_matches(str(name).lower(), list(lowered), n=1, cutoff=0.6)
        hint = f"did you mean {lowered[close[0]]}?" if close else ""
    hint = f"; {hint}" if hint else ""
    text = f"{str(name)[:64]!r} is not a {what}{hint} ({what}s: {', '.join(table)})"
    return PydanticCustomError("plc_bit", text.replace("{", "{{").replace("}", "}}"))


def _check_names(names: Sequence[str], table: dict[str, tuple[int, int]], what: str) -> None:
    for n in names:
        if n not in table:
            raise _bad_name(n, table, what)


class PlcStep(BaseModel):
    """One step of the `[[device.plc]]` script (see the module docstring)."""

    model_config = ConfigDict(extra="forbid")

    name: str | None = Field(None, min_length=1, max_length=80, description="names the step in messages and the report")
    module: int = Field(0, ge=0, le=15, description="the module (index in device.modules) the step writes and waits on")
    set: list[str] = Field(default_factory=list, max_length=40, description="control bits to 1 (C0..C3, the manual's names)")
    clear: list[str] = Field(default_factory=list, max_length=40, description="control bits to 0")
    velocity: int | None = Field(None, ge=-32768, le=32767, description="set-point word D0..D1 (positioning: 1..25000; speed control: signed)")
    acceleration: int | None = Field(None, ge=-32768, le=32767, description="set-point word D2..D3 (1..32767)")
    target: int | None = Field(None, ge=INT24_MIN, le=INT24_MAX, description="target position D4..D6 (24 bit, the module's position units)")
    wait: dict[str, StrictBool] = Field(
        default_factory=dict, description="status bits to wait for: {On_Target = true, Busy = false}, or a list of bits = 1"
    )
    wait_s: float = Field(0.0, ge=0.0, le=3600.0, description="wait this long first, s")
    timeout_s: float = Field(10.0, gt=0.0, le=3600.0, description="longest wait for `wait` after wait_s, s")

    @field_validator("set", "clear", mode="before")
    @classmethod
    def _one_name(cls, names: Any) -> Any:
        return [names] if isinstance(names, str) else names  # set = "Start" is set = ["Start"]

    @field_validator("wait", mode="before")
    @classmethod
    def _wait_form(cls, wait: Any) -> Any:
        if isinstance(wait, str):
            wait = [wait]
        if isinstance(wait, list):  # a list: these bits = 1
            if not all(isinstance(n, str) for n in wait):
                raise PydanticCustomError("plc_wait", "a list of status bit names, or a table such as {On_Target = true, Busy = false}")
            return dict.fromkeys(wait, True)
        if not isinstance(wait, dict):
            raise PydanticCustomError("plc_wait", "a table such as {On_Target = true, Busy = false}, or a list of status bit names")
        return wait

    @field_validator("set", "clear")
    @classmethod
    def _control_bits(cls, names: list[str]) -> list[str]:
        _check_names(names, OUTPUT_BITS, "control bit")
        return names

    @field_validator("wait")
    @classmethod
    def _status_bits(cls, wait: dict[str, bool]) -> dict[str, bool]:
        _check_names(list(wait), STATUS_BITS, "status bit")
        return wait

    @field_validator("wait_s", "timeout_s")
    @classmethod
    def _finite(cls, v: float) -> float:
        if not math.isfinite(v):
            raise ValueError("must be a finite number of seconds")
        return v

    @model_validator(mode="after")
    def _consistent(self) -> "PlcStep":
        both = [n for n in self.set if n in self.clear]
        if both:
            raise ValueError(f"{', '.join(both)} both in set and clear: a step sets a bit or clears it")
        return self

    def label(self, index: int) -> str:
        """'step 3 "move to 100 mm"' (1-based, as a user counts the tables)."""
        return f"step {index + 1}" + (f" {self.name!r}" if self.name else "")

    def writes(self) -> str:
        parts = [f"{n}=1" for n in self.set] + [f"{n}=0" for n in self.clear]
        for field in ("velocity", "acceleration", "target"):
            v = getattr(self, field)
            if v is not None:
                parts.append(f"{field}={v}")
        return " ".join(parts)
