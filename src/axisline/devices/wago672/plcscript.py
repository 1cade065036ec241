"""Runs the `[[device.plc]]` steps (plc.py) on the coupler, one PLC cycle per K-bus tick.

Its own module, apart from the steps' pydantic model, because it runs every cycle of
`axisline run` and is compiled (compiled_modules.txt): pydantic models stay interpreted.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any

from axisline.devices.wago672.coupler import Coupler
from axisline.devices.wago672.errors import describe
from axisline.devices.wago672.image import IMAGE_SIZE, OFFSET_C1, OFFSET_C2, OFFSET_C3, OFFSET_D0
from axisline.devices.wago672.plc import _S2_ERROR, OUTPUT_BITS, STATUS_BITS, PlcStep

__all__ = ["PlcScript", "error_text"]


def _status_text(image: bytes) -> str:
    return (f"S1=0x{image[OFFSET_C1]:02x} S2=0x{image[OFFSET_C2]:02x} S3=0x{image[OFFSET_C3]:02x}")


class PlcScript:
    """Runs the `[[device.plc]]` steps on a coupler, one PLC cycle per K-bus tick.

    `error_text(module)`: the module's error as text for a failure message (the PLC would
    read it with DIAG_RD_ERROR through the mailbox). Time is counted in cycles (`period` s
    each): the script never reads the wall clock."""

    def __init__(self, steps: Sequence[PlcStep], coupler: Coupler, period: float,
                 error_text: Callable[[int], str] | None = None) -> None:
        self.steps = list(steps)
        self.coupler = coupler
        self.period = period
        self.error_text = error_text or (lambda module: "")
        n = len(coupler.modules)
        self.images = [bytearray(IMAGE_SIZE) for _ in range(n)]  # the PLC's output area
        self.index = 0  # the step running (len(steps): all done)
        self.started = False
        self.failed: str | None = None
        #: the failed step for the headline: step number, label and a short reason
        self.failure: dict[str, Any] | None = None
        self.log: list[dict[str, Any]] = []  # one entry per step done: step, name, t_start, t_done
        self._start_cycle = 0
        # each step's wait as (image offset, mask, level), checked every cycle
        self._waits = [tuple((STATUS_BITS[n][0], STATUS_BITS[n][1], want) for n, want in step.wait.items()) for step in self.steps]
        self._area: bytes | None = None  # the output area as written (None: changed since)

    @property
    def done(self) -> bool:
        """All steps done, or one failed: the PLC's job is over."""
        return self.failed is not None or self.index >= len(self.steps)

    @property
    def steps_done(self) -> int:
        return len(self.log)

    def _apply(self, step: PlcStep) -> None:
        self._area = None
        image = self.images[step.module]
        for name in step.set:
            offset, mask = OUTPUT_BITS[name]
            image[offset] |= mask
        for name in step.clear:
            offset, mask = OUTPUT_BITS[name]
            image[offset] &= ~mask & 0xFF
        if step.velocity is not None:
            image[OFFSET_D0 : OFFSET_D0 + 2] = step.velocity.to_bytes(2, "little", signed=True)
        if step.acceleration is not None:
            image[OFFSET_D0 + 2 : OFFSET_D0 + 4] = step.acceleration.to_bytes(2, "little", signed=True)
        if step.target is not None:
            image[OFFSET_D0 + 4 : OFFSET_D0 + 7] = (step.target & 0xFFFFFF).to_bytes(3, "little")

    def _begin(self, cycle: int) -> None:
        self._start_cycle = cycle
        self._apply(self.steps[self.index])

    def tick(self, cycle: int) -> None:
        """One PLC cycle: check the running step on the last inputs, advance, write the outputs."""
        if not self.steps:
            return
        if not self.started:
            self.started = True
            self._begin(cycle)
        while not self.done and self._check(cycle):
            step = self.steps[self.index]
            self.log.append({
                "step": self.index + 1,
                "name": step.name,
                "module": step.module,
                "writes": step.writes(),
                "t_start": round(self._start_cycle * self.period, 6),
                "t_done": round(cycle * self.period, 6),
            })
            self.index += 1
            if self.index < len(self.steps):
                self._begin(cycle)
            break  # the next step's writes go out now; its condition is checked from the next cycle
        if self._area is None:
            self._area = b"".join(bytes(i) for i in self.images)
        self.coupler.write_images(self._area)  # all registers from 0, as one FC16

    def _check(self, cycle: int) -> bool:
        """True when the running step is done; sets `failed` on a timeout or the module's Error."""
        step = self.steps[self.index]
        inputs = self.coupler.inputs(step.module)
        elapsed = (cycle - self._start_cycle) * self.period
        if elapsed + 1e-9 < step.wait_s or cycle == self._start_cycle:
            return False
        for offset, mask, want in self._waits[self.index]:
            if (inputs[offset] & mask != 0) != want:
                break
        else:
            return True  # every bit of `wait` has its level
        if inputs[OFFSET_C2] & _S2_ERROR and "Error" not in step.wait:
            text = self.error_text(step.module)
            self._fail(step, f"the module reports Error (S2.7): {text} ({_status_text(inputs)})", f"module Error {text.split(':')[0]}")
            return False
        if elapsed - step.wait_s > step.timeout_s + 1e-9:
            missing = [(n, want) for n, want in step.wait.items() if bool(inputs[STATUS_BITS[n][0]] & STATUS_BITS[n][1]) != want]
            want = ", ".join(f"{n} = {int(v)}" for n, v in step.wait.items())
            got = ", ".join(f"{n} = {int(not v)}" for n, v in missing)
            self._fail(step, f"waited {step.timeout_s:g} s (timeout_s) for {want}; the module shows {got} ({_status_text(inputs)})",
                       f"no {want} within {step.timeout_s:g} s")
        return False

    def _fail(self, step: PlcStep, detail: str, reason: str) -> None:
        self.failed = f"PLC {step.label(self.index)} (device.plc[{self.index}]), module {step.module}: {detail}"
        self.failure = {"step": self.index + 1, "label": step.label(self.index), "reason": reason}
        self._area = None
        stop = OUTPUT_BITS["Stop2_N"][1] | OUTPUT_BITS["Start"][1]
        for image in self.images:  # the fault reaction: brake with the STOP ramp, Enable kept
            image[OFFSET_C1] &= ~stop & 0xFF


def error_text(device: Any) -> str:
    """The module's error for a message: '1117 CI_SPEED2: ...', or 'no error code'."""
    code = device.errors.error
    return describe(code) if code else "no error code"
