"""The FS701 flying shear's device view: its register cards, status words, errors and cut table.

Everything is read from the unit's own register map (`devices/fs701/registers.py`): the
parameter blocks with the §11 ranges and units (`parameters.py`), the process values, the
command / output / error words decoded with the names of the I/O card (`io_assign.py`) and of
§6 (`status.py`), and the cuts measured on the plant (`report/cuts.py` records).

A write goes through `RegisterMap.write_value`, the checked path the Drivecom and Modbus writes
take (`write_text` / `write_many` end in the same `_checked`): a refused value raises the
unit's own message and changes nothing; an accepted one acts as a serial write does
(personality decision D3: next cycle, the encoder scales at the next Control Enable OFF).

Decisions:
 1. Issue 17 "diagnostics with acknowledge" and manual §6 (spec fs701.md L696: "activate input
    Clear Error or switch off Control Enable or press the Reset button ... or cycle the power"):
    the HMI's acknowledge is the "Clear Error" command (bit 7) as a PC sends it: the serial
    command bit is set at one cycle boundary and released at the next one, so the cut cycle sees
    one rising edge, exactly as from the serial link. Control Enable OFF would drop the carriage
    out of closed loop, the Reset button is behind the connector plate, a power cycle loses the
    RAM parameters: none of them is what an operator's "acknowledge" means. While Clear Error is
    already held ON (an input or a client's serial bit) no edge can be made: nothing is changed
    and the answer says so. Errors whose cause persists (05) come back at once, as §6 says.
    Test: tests/hmi/test_device_views.py::test_fs701_acknowledge_clears_error_02.
 2. Issue 17 "parameters ... with range and unit and validation": rows are named by the
    parameter's snake_case attribute (parameters.py decision "Attribute names"), which is also
    what the write takes (aliases and the manual's names are accepted, as `parameter()` does);
    values are engineering values (1.5 for Sync Rate 1.50 %), not the raw register integers,
    because that is what the OS5.1 card shows. Test: test_fs701_write_in_range_and_refused.
"""

from __future__ import annotations

from typing import Any

from axisline.devices.fs701.io_assign import COMMAND_BASE, INPUT_FUNCTIONS, OUTPUT_SIGNALS
from axisline.devices.fs701.parameters import BLOCKS, PARAMETERS, UnknownParameterError, parameter
from axisline.devices.fs701.registers import RegisterError
from axisline.devices.fs701.status import ERRORS, PROCESS_VALUES, STATUS_WORDS

from . import _sections as s

__all__ = ["view", "write", "acknowledge"]

_CLEAR_ERROR_BIT = 7  # "Clear Error", single command 0x0907 (§4.1.1)
_COMMAND_NAMES = {f.bit: f.name for f in INPUT_FUNCTIONS}
_OUTPUT_NAMES = {o.bit: o.name for o in OUTPUT_SIGNALS}
_ERROR_NAMES = {n: f"Error {n:02d}: {e.name}" for n, e in ERRORS.items()}
_BY_BLOCK = {key: [p for p in PARAMETERS if p.block == key] for key in BLOCKS}


def view(device: Any) -> dict[str, Any]:
    device.refresh_status()  # process values and words from the cutter, as a protocol read does (D5)
    regs = device.registers
    st = regs.status
    params = device.params
    # (keyed on the values, not on params.version: the counters are stored at every status refresh)
    key = tuple(params.as_dict(raw=True).values())
    sections: list[dict[str, Any]] = list(s.cached(device, "parameters", key, lambda: _cards(regs)))
    process = [s.row(pv.attr, f"#{pv.number:02d} {pv.name}", regs.read(pv.code), pv.unit) for pv in PROCESS_VALUES if not pv.reserved]
    sections.append(s.parameters("Process data (0x0800..)", process))
    words = []
    for w in STATUS_WORDS:
        names = _ERROR_NAMES if w.bits == "errors" else _OUTPUT_NAMES if w.bits == "outputs" else _COMMAND_NAMES
        words.append(s.word(f"{w.name} (0x{w.code:04X})", st.word(w.code), names))
    sections.append(s.bits("Commands, outputs and errors (0x0B00..0x0B05)", words))
    errors = st.error_status
    sections.append(s.diagnostics("Errors (§6)", [(f"{n:02d}", e.message, bool(errors >> n & 1)) for n, e in ERRORS.items()]))
    lu = device.unit.config.unit
    sections.append(s.cut_table(f"Cuts (the last {s.MAX_ROWS})", [r.as_dict() for r in device.meter.records[-s.MAX_ROWS:]], lu))
    c = device.cutter
    job = device.job
    lines = [
        f"Control state: {c.control_state.name}   Cut state: {c.cut_state.name}",
        f"Batch counter: {c.batch_counter}   Waste counter: {c.waste_counter}",
        f"Batch job: {job.state if job is not None else 'none'}" + (f", {job.counted} counted" if job is not None else ""),
        f"Cuts measured: {len(device.meter.records)} on the {device.measured_on}",
    ]
    if device.commissioning.ran:
        lines.append(f"Adjust program: {'ok' if device.commissioning.ok else 'FAILED'} "
                     f"(Ana-Out Offset 2 = {device.settings.ana_out_offset_2}, Gain 2 = {device.settings.ana_out_gain_2})")
    sections.append(s.text("State", lines))
    return {"title": f"motrona FS701 flying shear (carriage {device.config.carriage!r})", "sections": sections}


def write(device: Any, name: str, value: Any) -> tuple[Any, Any]:
    try:
        p = parameter(name)
    except UnknownParameterError:
        raise ValueError(f"name: {name!r} is not an FS701 parameter (the rows of the parameter cards name them, "
                         f"e.g. 'cutting_length')") from None
    regs = device.registers
    old = regs.read_value(p.code)
    try:
        regs.write_value(p.code, value)  # the serial / Modbus write's check: range, resolution, refusal
    except RegisterError as e:  # (RegisterRangeError is a ValueError; a refused command is not)
        raise ValueError(str(e)) from None
    return old, regs.read_value(p.code)


def _cards(regs: Any) -> list[dict[str, Any]]:
    """The parameter cards (blocks) with the values of the register map."""
    sections = []
    for key, block in BLOCKS.items():
        rows = [
            s.row(p.attr, f"{p.name} (0x{p.code:04X})", regs.read_value(p.code), p.unit, p.minimum_value, p.maximum_value,
                  True, **({"choices": {str(k): v for k, v in p.choices.items()}} if p.choices else {}))
            for p in _BY_BLOCK[key]
        ]
        if rows:
            sections.append(s.parameters(f"{block.title} ({block.section})", rows))
    return sections


def acknowledge(device: Any) -> str:
    """Decision 1: one rising edge of Clear Error from the serial side."""
    device.refresh_status()
    regs = device.registers
    st = regs.status
    active = [ERRORS[n].message for n in ERRORS if st.error_status >> n & 1]
    mask = 1 << _CLEAR_ERROR_BIT
    if st.all_commands & mask:
        return "FS701: Clear Error is held ON (input or serial command): release it to acknowledge" if active else ""
    regs.write(COMMAND_BASE + _CLEAR_ERROR_BIT, 1)  # the register side clears the status image now
    machine = device.machine
    machine.commands.submit_at(machine.clock.cycle + 1, _release_clear_error, regs)  # the cutter saw the edge
    return f"FS701 Clear Error: {', '.join(active)}" if active else ""


def _release_clear_error(regs: Any) -> None:
    if regs.status.serial_commands >> _CLEAR_ERROR_BIT & 1:
        regs.write(COMMAND_BASE + _CLEAR_ERROR_BIT, 0)


def faults(device: Any) -> dict[str, str]:
    """The active errors (§6), cheap enough for serve's look every 10 ms: the event log's faults."""
    errors = device.registers.status.error_status
    return {f"FS701 error {n:02d}": e.message for n, e in ERRORS.items() if errors >> n & 1}
