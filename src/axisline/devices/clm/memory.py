"""The CLM's memory: variables, the I/O and marker image with each area's clear and retain
rules, and the battery-buffered part kept in a file.

Variables (§5.6, L1283-1400; spec §3.2): V000-V999, each ``+12345678.123456`` (kept as integer
millionths). V000-V599 are the system's: the CLM writes them (cycle counters, positions, ...),
a program writing one is fault 31, a serial write Status 01 error 23; V600-V999 are the user's.
SET may write V047, V048 and Vx00 while the axis is not homed (L2590).

Markers (spec §3.3): M2 (NC) is cleared on leaving Automatic, at power loss and on a fault; M3
is kept even at power loss; M4 (NC -> LT) is cleared at power loss; M5 (LT -> NC) and M6.20-39
on leaving Parameter mode, on a Logic Task fault and at power loss; M6.00-19 are kept. M0 / M1
are the system's markers. Outputs are cleared in Parameter mode (L3177) and on a fault as
B018 says.

Retained memory (§1.3, spec §1.3: "program instructions, parameters, Logic Task, variables
V600-V999, counters, M3, M6.00-19" are battery-buffered): `RetainedStore` keeps them in one
file, written atomically whenever one of them changed (at most once per NC cycle, at the
cycle's end), so a kill -9 at any moment leaves the last state the CLM had acknowledged or
executed, as the CLM's buffered RAM does through a power cut. The restart image of a running
program (`restart`, §7.11) is part of it (`ClmMemory.restart`, a JSON table kept by the runtime,
`restart_version` counting its changes): it changes only when the program changes state at an
instruction boundary or starts / stops (restart decision 10), not every cycle.
"""

from __future__ import annotations

import json
import os
from collections.abc import Callable
from pathlib import Path

from ...kernel import atomic_write_text
from .errors import ClmError, serial_code
from .fields import HOMING_SETTABLE, USER_VARIABLES, VARIABLE_MAX, format_variable, parse_variable_value
from .image import LAYOUT, ProcessImage
from .logic import logic_listing, read_logic_text
from .parameters import ParameterSet, read_parameter_text
from .program import Program
from .files import read_program_text

__all__ = ["ClmMemory", "RetainedStore", "Variables"]

VARIABLE_COUNT = 1000


class Variables:
    """V000-V999 as integer millionths; `version` counts changes of the user's V600-V999."""

    def __init__(self) -> None:
        self.values = [0] * VARIABLE_COUNT
        self.version = 0
        #: the CLM's live system variables (V000-V599), computed when read: the runtime's
        #: `system_value` (None: the stored value, e.g. V047 set while not homed)
        self.system: Callable[[int], int | None] | None = None

    def __getitem__(self, number: int) -> int:
        if number < USER_VARIABLES and self.system is not None:
            live = self.system(number)
            if live is not None:
                return live
        return self.values[number]

    def write(self, number: int, raw: int, *, by: str = "nc", homing_exempt: bool = False) -> None:
        """A write by a program (`by` 'nc': fault 31 for V000-V599) or over an interface
        ('serial': Status 01 error 23); values beyond +-99999999.999999 are fault 32."""
        if not 0 <= number < VARIABLE_COUNT:
            raise ClmError("1F" if by == "nc" else serial_code(23), f"V{number}: variables are V000-V999")
        if number < USER_VARIABLES and not (homing_exempt and number in HOMING_SETTABLE):
            if by == "nc":
                raise ClmError("31", f"V{number:03d} is a system variable: a program writes V600-V999", f"V{number:03d}")
            raise ClmError(serial_code(23), f"V{number:03d} is a system variable (read-only)", f"V{number:03d}")
        if not -VARIABLE_MAX <= raw <= VARIABLE_MAX:
            raise ClmError("32" if by == "nc" else serial_code(16), f"V{number:03d}: {raw / 1e6:.6f} is beyond +-99999999.999999", f"V{number:03d}")
        if self.values[number] != raw:
            self.values[number] = raw
            if number >= USER_VARIABLES:
                self.version += 1

    def set_system(self, number: int, raw: int) -> None:
        """The CLM's own write of a system variable (clamped to the variable format)."""
        self.values[number] = max(-VARIABLE_MAX, min(VARIABLE_MAX, raw))

    def user(self) -> dict[int, int]:
        """The user's variables that are not 0 (what a variables file holds)."""
        return {n: v for n, v in enumerate(self.values) if n >= USER_VARIABLES and v}

    def clear_user(self, first: int = USER_VARIABLES, last: int = VARIABLE_COUNT - 1) -> None:
        """``!sCCLVAR``: V600-V999 (or a range of them) to 0."""
        for n in range(max(first, USER_VARIABLES), min(last, VARIABLE_COUNT - 1) + 1):
            if self.values[n]:
                self.values[n] = 0
                self.version += 1


def _span(area: str, source: int, first: int = 0, last: int | None = None) -> slice:
    start, count = LAYOUT[(area, source)]
    end = count - 1 if last is None else last
    return slice(start + first, start + end + 1)


# the byte ranges of the image each event clears (spec §3.3)
_M2 = _span("M", 2)
_M4 = _span("M", 4)
_M5 = _span("M", 5)
_M6_CLEARED = _span("M", 6, 20, 39)
_OUTPUTS = (_span("Q", 0), _span("Q", 1), _span("Q", 2))
_RETAINED = (("M3", _span("M", 3)), ("M6", _span("M", 6, 0, 19)))


class ClmMemory:
    """Program, parameters, Logic Task, variables, image and counters of one CLM."""

    def __init__(self) -> None:
        self.program = Program()
        self.parameters = ParameterSet()
        self.logic: dict[int, str] = {}
        self.variables = Variables()
        self.image = ProcessImage()
        self.version = 0  # bumped by every change of the program, parameters or Logic Task
        #: the restart image as the memory file keeps it (restart.RestartImage.to_json), or None
        self.restart: dict[str, object] | None = None
        self.restart_version = 0

    # -- clear rules ---------------------------------------------------------------------

    def _zero(self, *spans: slice) -> None:
        data = self.image.data
        for s in spans:
            data[s] = bytes(s.stop - s.start)

    def leave_automatic(self) -> None:
        self._zero(_M2)

    def fault(self) -> None:
        self._zero(_M2)

    def leave_parameter_mode(self) -> None:
        self._zero(_M5, _M6_CLEARED)

    def logic_fault(self) -> None:
        self._zero(_M5, _M6_CLEARED)

    def clear_outputs(self) -> None:
        self._zero(*_OUTPUTS)

    def enter_parameter_mode(self) -> None:
        """"The outputs and non-retained marker flags are cleared" (L3177): M2, M4, M5, M6.20-39."""
        self._zero(*_OUTPUTS, _M2, _M4, _M5, _M6_CLEARED)

    def power_on(self) -> None:
        """After a (simulated) power cut: everything but the retained markers is 0 (in place:
        the axes and the Logic Task hold the image)."""
        data = self.image.data
        keep = [(s, bytes(data[s])) for _, s in _RETAINED]
        data[:] = bytes(len(data))
        for s, kept in keep:
            data[s] = kept

    # -- retained state ------------------------------------------------------------------

    def retained_key(self) -> tuple[object, ...]:
        """Cheap to compute every cycle; changes whenever `retained()` would."""
        data = self.image.data
        return (self.version, self.variables.version, self.restart_version, tuple(self.program.counters.items()), *(bytes(data[s]) for _, s in _RETAINED))

    def retained(self) -> dict[str, object]:
        return {
            "program": self.program.listing(comments=False),
            "counters": {str(n): c for n, c in sorted(self.program.counters.items())},
            "parameters": self.parameters.listing(),
            "logic": logic_listing(self.logic),
            "variables": {f"V{n:03d}": format_variable(v) for n, v in self.variables.user().items()},
            "markers": {name: bytes(self.image.data[s]).hex() for name, s in _RETAINED},
            **({} if self.restart is None else {"restart": self.restart}),
        }

    def restore(self, state: dict[str, object], source: str) -> None:
        """Load a retained state (all or nothing); ValueError names what is wrong."""
        program, findings = read_program_text(str(state.get("program", "")), source)
        params, pfind = read_parameter_text(str(state.get("parameters", "")), source)
        logic, lfind = read_logic_text(str(state.get("logic", "")), source)
        errors = [f for f in findings + pfind + lfind if f.is_error]
        if errors:
            raise ValueError(f"{source}: the retained memory does not load: {errors[0]}")
        counters = state.get("counters", {})
        variables = state.get("variables", {})
        markers = state.get("markers", {})
        if not isinstance(counters, dict) or not isinstance(variables, dict) or not isinstance(markers, dict):
            raise ValueError(f"{source}: counters, variables and markers must be tables")
        values = Variables()
        for key, text in variables.items():
            number = int(str(key).lstrip("V"))
            if not USER_VARIABLES <= number < VARIABLE_COUNT:
                raise ValueError(f"{source}: {key} is not a user variable")
            values.values[number] = parse_variable_value(str(text))
        for key, count in counters.items():
            n = int(key)
            if program[n].mnemonic not in ("COU", "BAC") or not isinstance(count, int) or count < 0:
                raise ValueError(f"{source}: counter {key} = {count!r} does not belong to a COU/BAC")
            program.counters[n] = count
        restart = state.get("restart")
        if restart is not None:
            from .restart import RestartImage  # (restart imports nothing of the memory)

            try:
                RestartImage.from_json(restart)
            except ValueError as e:
                raise ValueError(f"{source}: {e}") from None
        image = ProcessImage()
        for name, span in _RETAINED:
            data = bytes.fromhex(str(markers.get(name, "")))
            if data and len(data) != span.stop - span.start:
                raise ValueError(f"{source}: markers {name} hold {len(data)} bytes, not {span.stop - span.start}")
            if data:
                image.data[span] = data
        self.program, self.parameters, self.logic = program, params, logic
        self.variables = values
        self.restart = restart  # type: ignore[assignment]
        self.restart_version += 1
        self.image.data[:] = image.data  # in place: the axes, the Logic Task and the modes hold the image
        self.version += 1


class RetainedStore:
    """The battery-buffered memory in one JSON file, written atomically when it changed."""

    FORMAT = "axisline-clm-retained"
    MAX_BYTES = 8 << 20  # 3000 instructions, 200 parameters, 1000 LT lines: about 200 kB

    def __init__(self, path: str | os.PathLike[str]) -> None:
        self.path = Path(path)
        self._saved: tuple[object, ...] | None = None

    def exists(self) -> bool:
        return self.path.exists()

    def load(self, memory: ClmMemory) -> None:
        from axisline.configerrors import read_text

        try:
            doc = json.loads(read_text(self.path, self.MAX_BYTES))
        except (ValueError, RecursionError) as e:
            raise ValueError(f"{self.path}: not a CLM memory file ({e})") from None
        if not isinstance(doc, dict) or doc.get("format") != self.FORMAT or doc.get("version") != 1:
            raise ValueError(f"{self.path}: not a CLM memory file (format {self.FORMAT!r}, version 1)")
        memory.restore(doc, str(self.path))
        self._saved = memory.retained_key()

    def _text(self, memory: ClmMemory) -> str:
        return json.dumps({"format": self.FORMAT, "version": 1, **memory.retained()}, indent=1) + "\n"

    def save(self, memory: ClmMemory, *, force: bool = False) -> bool:
        """Write the retained memory if it changed since the last save; True if written.
        OSError when it cannot be written (the caller answers with its error)."""
        key = memory.retained_key()
        if key == self._saved and not force:
            return False
        self.path.parent.mkdir(parents=True, exist_ok=True)
        atomic_write_text(self.path, self._text(memory))
        self._saved = key
        return True
