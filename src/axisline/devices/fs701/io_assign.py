"""FS701 command inputs, output signals and their assignment to hardware terminals.

Source: manual §4.1.1 (inputs), §4.1.2 (outputs), §4.1.3 (IO Definition card), §11 (command and
output tables); spec fs701.md §3.1, §3.2, §7 E24.

Data: `INPUT_FUNCTIONS` (bit of the command words 0x0B00..0x0B03, serial code 0x0900+bit, type,
default hardware input) and `OUTPUT_SIGNALS` (bit of 0x0B04, serial code 0x0A00+bit, default
hardware output).

`IOAssignment` is the IO Definition card: which hardware inputs In1..In16 (X6 "Cont.In") switch
which input functions, and which output signals drive which hardware outputs Out1..Out8 (X7
"Cont.Out"). It is a relation, not a one-to-one map:

* one hardware input may switch several functions "in parallel" (§4.1.3);
* several output signals on one hardware output are OR'd (§4.1.3);
* axisline also lets one function listen to several inputs (OR'd) and one signal drive several
  outputs (see Decisions); `is_manual_compatible()` says whether a real unit's card can hold it.

Every function is also switchable by the serial link and by CAN; the effective command is the
OR of the three sources (§4.1.1: "All input signals follow a logical OR conjunction").

Decisions (spec line -> choice -> why):

* spec §3.1 "Print Mark ... In15 (fixed), no serial code": Print Mark is fixed to In15 (an
  attempt to move it is refused). It has no serial or CAN bit. Bit 14 of the command words is
  the gap in the §11 command table where Print Mark is listed, so bit 14 of 0x0B00 (hardware
  commands) and 0x0B03 (all commands) shows the Print Mark level (In15) for diagnostics; bit 14
  of 0x0B01/0x0B02 is always 0 and serial code 0x090E does not exist.
* spec §3.12 [DERIVED] "0x0B00 Hardware Commands": the word holds function bits after the
  assignment (same layout as 0x0B01/0x0B02), not raw terminal levels, so that
  All Commands = HW | Serial | CAN holds bit by bit.
* Adjust Program and Test Program (bits 30, 31) are "Ser./Bus" only: a hardware assignment is
  refused.
* One hardware terminal per function / per signal is what the card's drop-down allows; axisline
  accepts several (inputs OR'd, outputs all driven) because it is a strict superset and the
  machine files ask for it; `is_manual_compatible()` reports whether a unit could hold it.
* Active-low: the manual has no per-terminal inversion, only edge selection for two functions
  ("Edge Sense" for Cut completed, "Printmark Edge" for Print Mark), which `Edges.triggered`
  applies. axisline adds an optional per-terminal inversion (`inverted_inputs`,
  `inverted_outputs`, default none) for wiring with NC contacts; a unit cannot hold it.
* "Cut Test-Length" is listed as static with a pulse behaviour ("a short HIGH pulse only ...
  one single cut of the test length"): type STATIC_OR_PULSE; the latch is the cut cycle's job.
* The assignment has no serial codes (it "is stored to EEPROM when leaving this register
  card"): it is not in the register map; it is part of the EEPROM image and of parameter files.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import dataclass

__all__ = [
    "HW_INPUTS",
    "HW_OUTPUTS",
    "PRINT_MARK_INPUT",
    "SignalType",
    "InputFunction",
    "OutputSignal",
    "INPUT_FUNCTIONS",
    "OUTPUT_SIGNALS",
    "input_function",
    "output_signal",
    "COMMAND_BASE",
    "OUTPUT_BASE",
    "SERIAL_COMMAND_MASK",
    "IOAssignmentError",
    "IOAssignment",
    "Edges",
    "EdgeDetector",
    "bit_names",
]

HW_INPUTS = 16  # In1..In16 on X6 "Cont.In"
HW_OUTPUTS = 8  # Out1..Out8 on X7 "Cont.Out"
PRINT_MARK_INPUT = 15  # "Print Mark — In 15 (fix)"
COMMAND_BASE = 0x0900  # single command n at 0x0900 + n
OUTPUT_BASE = 0x0A00  # single output n at 0x0A00 + n


class SignalType:
    STATIC = "static"  # level
    RISING = "rising edge"  # dynamic
    EDGE_SENSE = "edge per Edge Sense"  # Cut completed: register 0x0107
    PRINTMARK_EDGE = "edge per Printmark Edge"  # Print Mark: register 0x0113
    STATIC_OR_PULSE = "static or pulse"  # Cut Test-Length
    SERIAL_ONLY = "Ser./Bus"  # Adjust / Test Program
    UNUSED = "not in use"


@dataclass(frozen=True, slots=True)
class InputFunction:
    bit: int  # bit in 0x0B00..0x0B03 (Print Mark: 14, hardware only)
    name: str  # manual name (§11 command table)
    attr: str
    type: str
    code: int | None  # serial code of the single command (None: Print Mark)
    default_input: int | None  # IO Definition screenshot (§4.1.3)
    description: str
    aliases: tuple[str, ...] = ()

    @property
    def in_use(self) -> bool:
        return self.type != SignalType.UNUSED

    @property
    def assignable(self) -> bool:
        """May the function be put on a hardware input (Adjust/Test: no; Print Mark: only In15)."""
        return self.type != SignalType.SERIAL_ONLY

    @property
    def serial(self) -> bool:
        """Has a serial/CAN bit."""
        return self.code is not None

    @property
    def mask(self) -> int:
        return 1 << self.bit


@dataclass(frozen=True, slots=True)
class OutputSignal:
    bit: int  # bit of 0x0B04 "Output Status"
    name: str
    attr: str
    code: int  # serial code of the single output
    default_output: int | None
    description: str
    aliases: tuple[str, ...] = ()

    @property
    def in_use(self) -> bool:
        return not self.name.startswith("(")

    @property
    def mask(self) -> int:
        return 1 << self.bit


def _in(bit: int, name: str, attr: str, kind: str, default: int | None, text: str, aliases: tuple[str, ...] = ()):
    return InputFunction(bit, name, attr, kind, COMMAND_BASE + bit, default, text, aliases)


S, R = SignalType.STATIC, SignalType.RISING

# fmt: off
INPUT_FUNCTIONS: tuple[InputFunction, ...] = (
    _in(0, "Control Enable", "control_enable", S, 1,
        "OFF: controller disabled, analogue outputs 0, counters held in reset, errors cleared; ON: enabled."),
    _in(1, "Start / Stop", "start_stop", S, 2,
        "OFF: carriage held at home (closed loop), jog and immediate cut allowed; ON: automatic cutting."),
    _in(2, "Select VirMaster", "select_virmaster", S, 3,
        "ON: the virtual master replaces Encoder1; changes only while Start/Stop is LOW.",
        ("select_virt_master", "select_virtual_master")),
    _in(3, "Run Virt. Master", "run_virt_master", S, 4,
        "Ramps the virtual master up (LOW->HIGH) or down (HIGH->LOW) with Ramp Vir. Master.",
        ("run_virtual_master",)),
    _in(4, "Immediate Cut", "immediate_cut", R, 5,
        "Starts a cutting cycle now, independent of the actual length; counts as waste."),
    _in(5, "Cut completed", "cut_completed", SignalType.EDGE_SENSE, 6,
        "The edge selected by Edge Sense ends the synchronous phase and starts the return."),
    _in(6, "Cut Test-Length", "cut_test_length", SignalType.STATIC_OR_PULSE, 7,
        "ON: cut Test Cut. Length; a short pulse: one test-length cut in the next cycle."),
    _in(7, "Clear Error", "clear_error", R, 8, "Resets error states and clears the error messages."),
    _in(8, "Set Zero Pos.", "set_zero_pos", S, 9,
        "Holds the carriage position counter at zero (Start/Stop LOW only); the falling edge fixes Zero.",
        ("set_zero_position",)),
    _in(9, "Jog forward", "jog_forward", S, 10, "Jogs the carriage forward (Stop state only)."),
    _in(10, "Jog reverse", "jog_reverse", S, 11, "Jogs the carriage backward (Stop state only)."),
    _in(11, "Decr. Batch Cou.", "decr_batch_cou", R, 12,
        "Batch counter - 1 and waste counter + 1.", ("decrement_batch_counter",)),
    _in(12, "Start Gap", "start_gap", S, 13, "Starts the gap action after the cut (Gap function)."),
    _in(13, "Teach Printmark", "teach_printmark", S, 14,
        "Teaches the print-mark position set point and locates the print-mark window."),
    InputFunction(14, "Print Mark", "print_mark", SignalType.PRINTMARK_EDGE, None, PRINT_MARK_INPUT,
                  "Print-mark sensor input, edge per Printmark Edge; fixed to In15, no serial code.",
                  ("printmark",)),
    _in(15, "(Command 15)", "command_15", SignalType.UNUSED, 16, "Not in use."),
    _in(16, "Reset Diff.Cou.", "reset_diff_cou", S, None,
        "ON: differential error counter held at zero, PI loop off (open loop).",
        ("reset_differential_counter",)),
    _in(17, "Reset Batch Cou.", "reset_batch_cou", S, None, "ON: batch counter := 0.",
        ("reset_batch_counter",)),
    _in(18, "Sync Mode Enable", "sync_mode_enable", S, None,
        "ON: the control mode of register Sync Mode during the synchronous phase (ask motrona)."),
    *(_in(n, f"(Command {n})", f"command_{n}", SignalType.UNUSED, None, "Not in use.") for n in range(19, 29)),
    _in(29, "Store to EEProm", "store_to_eeprom", R, None,
        "Rising edge: stores all actual registers and parameters to the EEPROM."),
    _in(30, "Adjust Program", "adjust_program", SignalType.SERIAL_ONLY, None,
        "Switches to the Adjust program (Control Enable must be OFF); serial / bus only."),
    _in(31, "Test Program", "test_program", SignalType.SERIAL_ONLY, None,
        "Switches to the Test program (Control Enable must be OFF); serial / bus only."),
)


def _out(bit: int, name: str, attr: str, default: int | None, text: str, aliases: tuple[str, ...] = ()):
    return OutputSignal(bit, name, attr, OUTPUT_BASE + bit, default, text, aliases)


OUTPUT_SIGNALS: tuple[OutputSignal, ...] = (
    _out(0, "Ready", "ready", 1, "Unit ready after power-up, initialisation and self-test."),
    _out(1, "Ready to cut", "ready_to_cut", 2,
         "Carriage at the cutting position and synchronous; LOW again after 'Cut completed'."),
    _out(2, "Home", "home", 3, "Carriage inside the Home Window."),
    _out(3, "Alarm", "alarm", 4, "Carriage beyond Alarm Position in forward motion (no stop, no error)."),
    _out(4, "Length Pulses", "length_pulses", 5, "One pulse per Length per Pulse of forward line motion, duty 1:1."),
    _out(5, "Gap Completed", "gap_completed", 6, "Gap done; waiting for 'Cut completed'."),
    _out(6, "Master Reverse", "master_reverse", 7,
         "Line moved back more than Master Rev. Limit; reset by forward motion or Clear Error."),
    _out(7, "Error", "error", 8, "An error is present (see status.ERRORS)."),
    _out(8, "Master in motion", "master_in_motion", None, "Encoder1 speed above Zero Speed Master."),
    _out(9, "Vir.M. in motion", "vir_m_in_motion", None, "Virtual master speed above Zero Speed Vir. Ma.",
         ("virtual_master_in_motion",)),
    _out(10, "No Printmark", "no_printmark", None, "Missing Printmarks sheets without a mark in the window."),
    _out(11, "Printmark Window", "printmark_window", None, "Window open (always ON when the window is disabled)."),
    _out(12, "Virt. Printmark", "virt_printmark", None, "A virtual print mark is to be cut."),
    _out(13, "Max. Correction", "max_correction", None, "Proportional correction at the Max. Correction limit."),
    _out(14, "Printm. Teached", "printm_teached", None, "Print-mark position set point taught.",
         ("printmark_teached",)),
    *(_out(n, f"(Output {n})", f"output_{n}", None, "Not in use.") for n in range(15, 32)),
)
# fmt: on

_FUNCS: dict[str, InputFunction] = {}
for _f in INPUT_FUNCTIONS:
    for _n in (_f.attr, *_f.aliases):
        _FUNCS[_n] = _f
_SIGS: dict[str, OutputSignal] = {}
for _s in OUTPUT_SIGNALS:
    for _n in (_s.attr, *_s.aliases):
        _SIGS[_n] = _s
_FUNC_BY_BIT = {f.bit: f for f in INPUT_FUNCTIONS}
_SIG_BY_BIT = {s.bit: s for s in OUTPUT_SIGNALS}

#: bits a serial (or CAN) master can set in 0x0B01 / 0x0B02: every bit but Print Mark's 14
SERIAL_COMMAND_MASK = sum(f.mask for f in INPUT_FUNCTIONS if f.serial)


class IOAssignmentError(ValueError):
    """A function, signal or terminal the IO Definition card does not accept."""


def input_function(key: "str | int") -> InputFunction:
    """Input function by attribute name / alias or by bit number."""
    found = _FUNC_BY_BIT.get(key) if isinstance(key, int) and not isinstance(key, bool) else _FUNCS.get(key)  # type: ignore[arg-type]
    if found is None:
        raise IOAssignmentError(f"no FS701 input function {key!r} (known: {', '.join(f.attr for f in INPUT_FUNCTIONS)})")
    return found


def output_signal(key: "str | int") -> OutputSignal:
    """Output signal by attribute name / alias or by bit number."""
    found = _SIG_BY_BIT.get(key) if isinstance(key, int) and not isinstance(key, bool) else _SIGS.get(key)  # type: ignore[arg-type]
    if found is None:
        raise IOAssignmentError(f"no FS701 output signal {key!r} (known: {', '.join(s.attr for s in OUTPUT_SIGNALS)})")
    return found


def bit_names(word: int, kind: str) -> list[str]:
    """Attribute names of the set bits of a command word ("commands") or output word ("outputs")."""
    table = _FUNC_BY_BIT if kind == "commands" else _SIG_BY_BIT if kind == "outputs" else None
    if table is None:
        raise ValueError(f"kind must be 'commands' or 'outputs', not {kind!r}")
    return [table[b].attr for b in range(32) if word >> b & 1 and b in table]


def _terminals(value: "int | Iterable[int] | None", limit: int, what: str, owner: str) -> frozenset[int]:
    if value is None:
        return frozenset()
    items = [value] if isinstance(value, int) else list(value)
    for n in items:
        if isinstance(n, bool) or not isinstance(n, int) or not 1 <= n <= limit:
            raise IOAssignmentError(f"{owner}: hardware {what} {n!r} is outside 1..{limit}")
    return frozenset(items)


class IOAssignment:
    """The IO Definition card (plus axisline's optional inversions); validated on every change.

    inputs:  function attr -> hardware inputs (1..16) that switch it
    outputs: signal attr   -> hardware outputs (1..8) it drives
    """

    __slots__ = ("_inputs", "_outputs", "_inv_in", "_inv_out")

    def __init__(
        self,
        inputs: Mapping[str, "int | Iterable[int] | None"] | None = None,
        outputs: Mapping[str, "int | Iterable[int] | None"] | None = None,
        *,
        inverted_inputs: Iterable[int] = (),
        inverted_outputs: Iterable[int] = (),
    ) -> None:
        self._inputs: dict[str, frozenset[int]] = {f.attr: frozenset() for f in INPUT_FUNCTIONS}
        self._inputs["print_mark"] = frozenset({PRINT_MARK_INPUT})
        self._outputs: dict[str, frozenset[int]] = {s.attr: frozenset() for s in OUTPUT_SIGNALS}
        self._inv_in = _terminals(list(inverted_inputs), HW_INPUTS, "input", "inverted_inputs")
        self._inv_out = _terminals(list(inverted_outputs), HW_OUTPUTS, "output", "inverted_outputs")
        staged_in = {k: self._check_input(k, v) for k, v in (inputs or {}).items()}
        staged_out = {k: self._check_output(k, v) for k, v in (outputs or {}).items()}
        self._inputs.update(staged_in)
        self._outputs.update(staged_out)

    @classmethod
    def default(cls) -> "IOAssignment":
        """The factory assignment of the §4.1.3 screenshot (spec §7 E24)."""
        return cls(
            {f.attr: f.default_input for f in INPUT_FUNCTIONS if f.default_input is not None},
            {s.attr: s.default_output for s in OUTPUT_SIGNALS if s.default_output is not None},
        )

    # ---- validation -------------------------------------------------------------------------
    @staticmethod
    def _check_input(key: str, value: "int | Iterable[int] | None") -> frozenset[int]:
        f = input_function(key)
        terms = _terminals(value, HW_INPUTS, "input", f"input function {f.attr!r}")
        if not f.assignable and terms:
            raise IOAssignmentError(f"input function {f.attr!r} ({f.name}) is serial/bus only; no hardware input allowed")
        if f.attr == "print_mark" and terms != {PRINT_MARK_INPUT}:
            raise IOAssignmentError(
                f"input function 'print_mark' is fixed to In{PRINT_MARK_INPUT}; got {sorted(terms) or 'none'}"
            )
        return terms

    @staticmethod
    def _check_output(key: str, value: "int | Iterable[int] | None") -> frozenset[int]:
        s = output_signal(key)
        return _terminals(value, HW_OUTPUTS, "output", f"output signal {s.attr!r}")

    # ---- editing (each call is all-or-nothing) ------------------------------------------------
    def assign_input(self, function: str, inputs: "int | Iterable[int] | None") -> None:
        """Set the hardware inputs of a function (replaces the previous ones; None = no input)."""
        terms = self._check_input(function, inputs)
        self._inputs[input_function(function).attr] = terms

    def assign_output(self, signal: str, outputs: "int | Iterable[int] | None") -> None:
        terms = self._check_output(signal, outputs)
        self._outputs[output_signal(signal).attr] = terms

    def set_inverted_inputs(self, inputs: Iterable[int]) -> None:
        self._inv_in = _terminals(list(inputs), HW_INPUTS, "input", "inverted_inputs")

    def set_inverted_outputs(self, outputs: Iterable[int]) -> None:
        self._inv_out = _terminals(list(outputs), HW_OUTPUTS, "output", "inverted_outputs")

    # ---- queries ----------------------------------------------------------------------------
    def inputs_of(self, function: str) -> frozenset[int]:
        return self._inputs[input_function(function).attr]

    def outputs_of(self, signal: str) -> frozenset[int]:
        return self._outputs[output_signal(signal).attr]

    def functions_of_input(self, terminal: int) -> list[str]:
        _terminals(terminal, HW_INPUTS, "input", "functions_of_input")
        return [f.attr for f in INPUT_FUNCTIONS if terminal in self._inputs[f.attr]]

    def signals_of_output(self, terminal: int) -> list[str]:
        _terminals(terminal, HW_OUTPUTS, "output", "signals_of_output")
        return [s.attr for s in OUTPUT_SIGNALS if terminal in self._outputs[s.attr]]

    @property
    def inverted_inputs(self) -> frozenset[int]:
        return self._inv_in

    @property
    def inverted_outputs(self) -> frozenset[int]:
        return self._inv_out

    def is_manual_compatible(self) -> bool:
        """Could a real unit's IO Definition card hold this (one terminal per entry, no inversion)?"""
        return (
            all(len(t) <= 1 for t in self._inputs.values())
            and all(len(t) <= 1 for t in self._outputs.values())
            and not self._inv_in
            and not self._inv_out
        )

    # ---- evaluation (one call per cycle; no allocation beyond ints) ---------------------------
    def hardware_command_word(self, terminal_levels: int) -> int:
        """Word 0x0B00 from the electrical levels of In1..In16 (bit 0 = In1).

        A function is ON when any of its inputs is active (after inversion); bit 14 shows the
        Print Mark level on In15.
        """
        active = terminal_levels ^ self._inv_mask_in()
        word = 0
        for f in INPUT_FUNCTIONS:
            for t in self._inputs[f.attr]:
                if active >> (t - 1) & 1:
                    word |= f.mask
                    break
        return word

    def printmark_level(self, terminal_levels: int) -> bool:
        """Level of the Print Mark input (In15, after inversion)."""
        return bool((terminal_levels ^ self._inv_mask_in()) >> (PRINT_MARK_INPUT - 1) & 1)

    def hardware_output_levels(self, output_status: int) -> int:
        """Electrical levels of Out1..Out8 (bit 0 = Out1) from word 0x0B04: OR of the signals."""
        levels = 0
        for s in OUTPUT_SIGNALS:
            if output_status & s.mask:
                for t in self._outputs[s.attr]:
                    levels |= 1 << (t - 1)
        return levels ^ self._inv_mask_out()

    def _inv_mask_in(self) -> int:
        return sum(1 << (t - 1) for t in self._inv_in)

    def _inv_mask_out(self) -> int:
        return sum(1 << (t - 1) for t in self._inv_out)

    # ---- copies, comparison, serialisation ----------------------------------------------------
    def assign(self, other: "IOAssignment") -> None:
        """Take every entry of `other` in place (holders of this object see the change)."""
        self._inputs = dict(other._inputs)
        self._outputs = dict(other._outputs)
        self._inv_in = other._inv_in
        self._inv_out = other._inv_out

    def copy(self) -> "IOAssignment":
        new = IOAssignment.__new__(IOAssignment)
        new._inputs = dict(self._inputs)
        new._outputs = dict(self._outputs)
        new._inv_in = self._inv_in
        new._inv_out = self._inv_out
        return new

    def as_dict(self) -> dict[str, object]:
        """{"inputs": {function: [terminals]}, "outputs": {...}, "inverted_inputs": [...], ...}
        with every function and signal (empty list = not assigned)."""
        return {
            "inputs": {k: sorted(v) for k, v in self._inputs.items()},
            "outputs": {k: sorted(v) for k, v in self._outputs.items()},
            "inverted_inputs": sorted(self._inv_in),
            "inverted_outputs": sorted(self._inv_out),
        }

    @classmethod
    def from_dict(cls, data: Mapping[str, object]) -> "IOAssignment":
        unknown = set(data) - {"inputs", "outputs", "inverted_inputs", "inverted_outputs"}
        if unknown:
            raise IOAssignmentError(f"unknown I/O assignment keys {sorted(unknown)}")
        return cls(
            data.get("inputs") or {},  # type: ignore[arg-type]
            data.get("outputs") or {},  # type: ignore[arg-type]
            inverted_inputs=data.get("inverted_inputs") or (),  # type: ignore[arg-type]
            inverted_outputs=data.get("inverted_outputs") or (),  # type: ignore[arg-type]
        )

    def diff(self, other: "IOAssignment") -> list[str]:
        """Human-readable differences."""
        out: list[str] = []
        for k, v in self._inputs.items():
            if other._inputs[k] != v:
                out.append(f"input {k}: {sorted(v)} != {sorted(other._inputs[k])}")
        for k, v in self._outputs.items():
            if other._outputs[k] != v:
                out.append(f"output {k}: {sorted(v)} != {sorted(other._outputs[k])}")
        if self._inv_in != other._inv_in:
            out.append(f"inverted_inputs: {sorted(self._inv_in)} != {sorted(other._inv_in)}")
        if self._inv_out != other._inv_out:
            out.append(f"inverted_outputs: {sorted(self._inv_out)} != {sorted(other._inv_out)}")
        return out

    def __eq__(self, other: object) -> bool:
        return (
            isinstance(other, IOAssignment)
            and self._inputs == other._inputs
            and self._outputs == other._outputs
            and self._inv_in == other._inv_in
            and self._inv_out == other._inv_out
        )

    __hash__ = None  # type: ignore[assignment]

    def __repr__(self) -> str:
        ins = ", ".join(f"{k}={sorted(v)}" for k, v in self._inputs.items() if v)
        outs = ", ".join(f"{k}={sorted(v)}" for k, v in self._outputs.items() if v)
        return f"IOAssignment(inputs: {ins}; outputs: {outs})"


@dataclass(frozen=True, slots=True)
class Edges:
    """Edges of a command word between two cycles."""

    rising: int
    falling: int
    level: int

    def triggered(self, function: str, *, edge_sense: int = 0, printmark_edge: int = 0) -> bool:
        """Did the function's active edge occur? Static functions never trigger (read `level`).

        Cut completed uses register Edge Sense (0 rising, 1 falling); Print Mark uses
        Printmark Edge (0 rising, 1 falling).
        """
        f = input_function(function)
        if f.type == SignalType.EDGE_SENSE:
            return bool((self.falling if edge_sense else self.rising) & f.mask)
        if f.type == SignalType.PRINTMARK_EDGE:
            return bool((self.falling if printmark_edge else self.rising) & f.mask)
        if f.type == SignalType.RISING:
            return bool(self.rising & f.mask)
        return False

    def on(self, function: str) -> bool:
        return bool(self.level & input_function(function).mask)


class EdgeDetector:
    """Edge detection on a 32-bit command word (All Commands 0x0B03), one `update` per cycle."""

    __slots__ = ("_last",)

    def __init__(self, initial: int = 0) -> None:
        self._last = initial

    @property
    def last(self) -> int:
        """The word of the last `update` (or `reset`)."""
        return self._last

    def update(self, word: int) -> Edges:
        last, self._last = self._last, word
        return Edges(word & ~last, last & ~word, word)

    def reset(self, word: int = 0) -> None:
        self._last = word
