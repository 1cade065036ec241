"""Where the CLM's system inputs and outputs are (spec §2, §6.2, §6.3; the table in `modes`):
their operands, and the bytes and bit masks the mode machine reads and writes every NC cycle,
located once in the process image (`image.ProcessImage.locate`) instead of per access."""

from __future__ import annotations

from typing import NamedTuple

from .image import ProcessImage
from .operands import Operand

__all__ = ["PARAMETER", "AUTOMATIC", "ESTOP", "START", "IMMEDIATE_STOP", "CLEAR", "RESTART", "RESTART_FIELDBUS", "ENABLE", "JOG",
           "Q_MANUAL", "Q_AUTOMATIC", "Q_PARAMETER", "Q_ERROR", "Q_RUN_TASK", "Q_INHIBIT", "Q_RESTART", "EdgeBytes",
           "SystemOutputs", "system_outputs"]


def _i(text: str) -> Operand:
    area, rest = text[0], text[1:].split(".")
    return Operand(area, int(rest[0]), int(rest[1]), int(rest[2]) if len(rest) > 2 else None)


PARAMETER, AUTOMATIC, ESTOP, START, IMMEDIATE_STOP, CLEAR = (_i(t) for t in ("I0.00.0", "I0.00.1", "I0.00.2", "I0.00.3", "I0.00.4", "I0.00.7"))
RESTART, RESTART_FIELDBUS = _i("I0.01.6"), _i("I2.01.6")  # X3/15 and the control word's bit 14 (L5920, L7619)
ENABLE = {1: _i("I0.00.5"), 2: _i("I0.00.6"), 3: _i("I0.02.0"), 4: _i("I0.02.3")}
JOG = {1: (_i("I0.01.0"), _i("I0.01.1")), 2: (_i("I0.01.2"), _i("I0.01.3")), 3: (_i("I0.02.1"), _i("I0.02.2")), 4: (_i("I0.02.4"), _i("I0.02.5"))}
Q_MANUAL, Q_AUTOMATIC, Q_PARAMETER, Q_ERROR, Q_RUN_TASK, Q_INHIBIT = (_i(t) for t in ("Q0.00.0", "Q0.00.1", "Q0.00.2", "Q0.00.5", "Q0.01.1", "Q0.01.5"))
Q_RESTART = _i("Q0.01.0")  # X4/9 Restart possible; no status-word bit (Q2.01.0 is reserved, L6068)
_Q0 = (Operand("Q", 0, 0), Operand("Q", 0, 1))
_STATUS_WORD = (Operand("Q", 2, 0), Operand("Q", 2, 1))


class EdgeBytes(NamedTuple):
    """Where the edge inputs are: External Clear and Start in I0.00, Re-Start in I0.01 (X3) and
    I2.01 (the fieldbus control word); the bytes and each input's bit mask."""

    system: int
    clear: int
    start: int
    restart_x3: int
    restart: int
    restart_dp: int
    restart_fieldbus: int

    @classmethod
    def of(cls, places: dict[Operand, tuple[int, int, int]]) -> EdgeBytes:
        (ca, cs, _), (sa, ss, _) = places[CLEAR], places[START]
        (ra, rs, _), (fa, fs, _) = places[RESTART], places[RESTART_FIELDBUS]
        if ca != sa:
            raise AssertionError("External Clear and Start are bits of I0.00")
        return cls(ca, 1 << cs, 1 << ss, ra, 1 << rs, fa, 1 << fs)


class SystemOutputs(NamedTuple):
    """The system outputs as bit masks of their two bytes Q0.00 / Q0.01 and the status word's."""

    at0: int
    keep0: int  # the bits of Q0.00 that are not system outputs
    mode_bits: dict[str, int]
    ok: int
    at1: int
    keep1: int
    run: int
    restart: int
    word0: int
    word1: int
    word1_keep: int  # Q2.01 without its reserved bit 0


def system_outputs() -> SystemOutputs:
    def place(op: Operand) -> tuple[int, int]:
        at, shift, _ = ProcessImage.locate(op)
        return at, 1 << shift

    (at0, manual), (_, automatic), (_, parameter), (_, ok) = (place(op) for op in (Q_MANUAL, Q_AUTOMATIC, Q_PARAMETER, Q_ERROR))
    (at1, run), (_, restart) = place(Q_RUN_TASK), place(Q_RESTART)
    if {place(op)[0] for op in (Q_MANUAL, Q_AUTOMATIC, Q_PARAMETER, Q_ERROR)} != {at0} or place(Q_RESTART)[0] != at1:
        raise AssertionError("the system outputs are bits of Q0.00 and Q0.01")
    word0, word1 = (ProcessImage.locate(op)[0] for op in _STATUS_WORD)
    reserved_at, reserved = place(Operand("Q", 2, 1, 0))
    if (ProcessImage.locate(_Q0[0])[0], ProcessImage.locate(_Q0[1])[0], reserved_at) != (at0, at1, word1):
        raise AssertionError("the status word mirrors Q0.00 and Q0.01")
    return SystemOutputs(at0, 0xFF & ~(manual | automatic | parameter | ok), {"manual": manual, "automatic": automatic, "parameter": parameter},
                          ok, at1, 0xFF & ~(run | restart), run, restart, word0, word1, 0xFF & ~reserved)
