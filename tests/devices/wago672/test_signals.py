"""The consumed signals as the tick reads them (signals.py) and the opcode constants the compiled
tick uses (opcodes.py)."""

from __future__ import annotations

import pytest

from axisline.devices.wago672.bits import Bit, BitTable
from axisline.devices.wago672.config_table import ConfigTable
from axisline.devices.wago672.opcodes import Opcode
from axisline.devices.wago672.program import Cmd
from axisline.devices.wago672.signals import SIGNAL_BITS, SIGNALS, Signals


@pytest.mark.parametrize("index", range(len(SIGNALS)))
def test_each_bit_of_the_word_sets_exactly_its_own_signal(index: int) -> None:
    s = Signals(1 << index, True)
    high = [name for name, value in s.as_dict().items() if value]
    assert high == [SIGNALS[index][0]]


def test_before_the_first_tick_every_signal_is_0() -> None:
    s = Signals()
    assert not s.known
    assert not any(s.as_dict().values())


def test_a_word_wider_than_the_signals_is_refused() -> None:
    with pytest.raises(ValueError, match="beyond the 28 signals"):
        Signals(1 << 28)


def test_signals_follow_the_links_of_the_bit_table() -> None:
    # default links: Stop1_N reads Input1 (DI1), LimitSwitch_Pos reads Input5 (manual §4.5)
    bits = BitTable(ConfigTable())
    group = bits.group(SIGNAL_BITS)
    bits.put(Bit.Input1, True)
    s = Signals(bits.word(group), True)
    assert s.stop1_n and not s.ls_pos
    bits.put(Bit.Input1, False)
    bits.put(Bit.Input5, True)
    s = Signals(bits.word(group), True)
    assert s.ls_pos and not s.stop1_n
    # the word is what `values` reads, bit by bit
    assert [bool(bits.word(group) >> i & 1) for i in range(len(SIGNALS))] == list(bits.values(group))


def test_move_opcodes_are_the_run_program_commands() -> None:
    names = [n for n in vars(Opcode) if n.isupper()]
    assert len(names) == 23
    for name in names:
        assert getattr(Opcode, name) == Cmd[name].value, name
