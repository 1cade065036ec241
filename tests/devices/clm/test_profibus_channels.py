"""The Profibus variable and service channels on their own (profibus_channels.py): the number
formats, the error numbers and codes, the serial session inside the service channel. The
manual's exchanges themselves go through Modbus TCP in test_profibus_modbus.py."""

from __future__ import annotations

import pytest

from axisline.devices.clm.memory import ClmMemory
from axisline.devices.clm.operands import parse_operand
from axisline.devices.clm.profibus import _ServiceSerial
from axisline.devices.clm.profibus_channels import (
    ServiceChannel, VariableChannel, from_long, long_words, to_long, words_long,
)

from .clmrig import Rig

HS, BIT14 = 0x8000, 0x4000
R, E, L, T, B = 0x1000, 0x2000, 0x0400, 0x0100, 0xB


def _words(data: bytes) -> list[int]:
    data = data.ljust(10, b"\0")
    return [data[k] << 8 | data[k + 1] for k in range(0, 10, 2)]


def _bytes(words: list[int]) -> bytes:
    return b"".join(bytes((w >> 8, w & 0xFF)) for w in words)


@pytest.mark.parametrize("raw, fmt, long", [
    (1_500_000, 0, 2), (-1_500_000, 0, -2), (1_499_999, 0, 1),  # integer, rounded (half away from zero)
    (1_999_999, 4, 1), (-1_999_999, 4, -1),  # integer, not rounded
    (12_345_678_500, 1, 12_345_679), (-1_000_499, 1, -1_000),  # fixed point 3, rounded
    (99_999_999, 2, 99_999_999), (-5, 2, -5),  # fixed point 6
])
def test_variable_formats_round_and_limit(raw, fmt, long):
    """L7759-7771 (channels decision 1): rounding per format; the long as two words, high first."""
    assert to_long(raw, fmt) == long
    assert words_long(*long_words(long)) == long


def test_variable_format_ranges():
    """L7767-7771: +-99999999 in every format: error 3 above, 4 below, on read and write."""
    with pytest.raises(ValueError) as e:
        to_long(100_000_000, 2)  # 100.000000 does not fit fixed point 6
    assert e.value.args[0] == 3
    with pytest.raises(ValueError) as e:
        to_long(-100_000_000_000, 1)
    assert e.value.args[0] == 4
    with pytest.raises(ValueError) as e:
        to_long(99_999_999_500_000, 0)  # rounds to 100000000
    assert e.value.args[0] == 3
    assert from_long(-12_345, 1) == -12_345_000 and from_long(7, 0) == 7_000_000
    with pytest.raises(ValueError) as e:
        from_long(100_000_000, 0)
    assert e.value.args[0] == 3


@pytest.mark.parametrize("control, error", [
    (HS | BIT14 | 600, 7),  # bit 14 set
    (HS | 1000, 0),  # number too large
    (HS | 3 << 10 | 600, 5),  # IEEE: not displayable
    (HS | 9 << 10 | 600, 2),  # unknown format
])
def test_variable_channel_errors(control, error):
    """L7773-7785 (channels decisions 2, 3): the error number in bits 10-13, bit 14 set, the
    number and handshake echoed; the data long is 0."""
    memory = ClmMemory()
    memory.variables.write(600, 5_000_000, by="serial")
    vc = VariableChannel(memory.variables)
    vc.exchange(control, 0, 0)
    assert vc.read_status == (control & (HS | 0x3FF)) | BIT14 | error << 10
    assert vc.words()[2:] == [0, 0]


def test_variable_write_then_read_same_exchange():
    """Channels decision 4: one exchange with both requests writes first, then reads."""
    memory = ClmMemory()
    vc = VariableChannel(memory.variables)
    vc.exchange(HS | 2 << 10 | 700, HS | 0 << 10 | 700, 42)
    assert memory.variables[700] == 42_000_000
    assert vc.read_status == HS | 2 << 10 | 700 and vc.data == 42_000_000
    vc.exchange(0 | 0 << 10 | 700, 0 | 4 << 10 | 701, -3)  # both toggled back
    assert memory.variables[701] == -3_000_000 and vc.data == 42 and vc.write_status == 4 << 10 | 701


def _service(program: str = "0000 NOP\n") -> tuple[Rig, ServiceChannel]:
    rig = Rig(program, mode="manual")
    rig.run()
    return rig, ServiceChannel(_ServiceSerial(rig.rt))


def _send(sc: ServiceChannel, control: int, data: bytes = b"") -> tuple[int, bytes]:
    sc.exchange([control, *_words(data)])
    words = sc.words()
    return words[0], _bytes(words[1:])[: words[0] >> 4 & 0xF]


def _query(sc: ServiceChannel, telegram: bytes) -> bytes:
    """Write `telegram` (one fragment), read the reply's fragments; each request toggles T."""
    t = 0 if sc.status & T else 1
    status, data = _send(sc, L | (T if t else 0) | len(telegram) << 4 | B, telegram)
    assert not status & E, data.hex()
    reply, t = b"", t ^ 1
    while True:
        status, data = _send(sc, R | L | (T if t else 0) | B)
        reply += data
        t ^= 1
        if status & L:
            return reply


def test_service_station_and_crlf_disregarded():
    """L7798 (channels decision 6): a station byte other than a blank, CR LF at the end and no
    checksum are taken; a CR inside the data is serial error 02."""
    _, sc = _service()
    assert _query(sc, b"?7N0000\r\n"[:9]) == b"# N0000 NOP   "
    status, data = _send(sc, L | 5 << 4 | B, b"? N\r0")
    assert status & E and data == bytes((0x01, 0x02))


def test_service_status_and_variable_replies():
    """The serial protocol inside: Status 53 and a variable read back, without $hh and CR LF."""
    rig, sc = _service()
    rig.rt.memory.variables.write(600, 250_000_000, by="serial")
    assert _query(sc, b"? V600 ") == b"V 600 +00000250.000000 "
    assert _query(sc, b"? X  53 ") == b"X 53 00 no error         "


def test_service_error_codes():
    """Fig. 10-30 (channels decision 8): format neither B nor F 0x008B, length above 10 0x008C,
    more than 128 collected bytes 0x0085; a read with nothing to read is an empty last
    fragment."""
    _, sc = _service()
    status, data = _send(sc, T | L | 2 << 4 | 0x5, b"? ")
    assert status == E | T | L | 2 << 4 | B and data == bytes((0x00, 0x8B))
    status, data = _send(sc, L | 12 << 4 | B, b"? N0000 ")
    assert status & E and data == bytes((0x00, 0x8C))
    t = 1
    for _ in range(12):  # 120 bytes, not the last fragment
        status, _ = _send(sc, (T if t else 0) | 10 << 4 | B, b"# N0000 NO")
        assert not status & E
        t ^= 1
    status, data = _send(sc, (T if t else 0) | 10 << 4 | B, b"# N0000 NO")
    assert status & E and data == bytes((0x00, 0x85))
    status, data = _send(sc, (0 if t else T) | R | L | B)
    assert status & L and not status & E and data == b""


def test_service_write_refused_without_allow_writes():
    """Serial decision 7 inside the channel: without --allow-writes a write telegram is refused
    with Status 01 error 18 (0x0112) and changes nothing."""
    rig = Rig("0000 WAI 01.000\n", mode="manual")
    rig.run()
    sc = ServiceChannel(_ServiceSerial(rig.rt, lambda: False))
    status, _ = _send(sc, T | 10 << 4 | B, b"# N0000 NO")
    assert not status & E
    status, data = _send(sc, L | 2 << 4 | B, b"P ")
    assert status & E and data == bytes((0x01, 18))
    assert rig.rt.memory.program[0].mnemonic == "WAI"


def test_variable_write_is_stored():
    """Channels decision 10: the write is saved before it is acknowledged; a save that fails
    undoes it and answers error 6."""
    memory = ClmMemory()
    saved = []
    vc = VariableChannel(memory.variables, lambda: saved.append(memory.variables[650]))
    vc.exchange(0, HS | 650, 5)
    assert saved == [5_000_000] and vc.write_status == HS | 650

    def broken():
        raise OSError(28, "No space left on device")

    vc = VariableChannel(memory.variables, broken)
    vc.exchange(0, HS | 650, 9)
    assert memory.variables[650] == 5_000_000
    assert vc.write_status == HS | BIT14 | 6 << 10 | 650


def test_no_fault_37_in_parameter_mode():
    """profibus.py decision 9: the watchdog expires in Parameter mode too (the words go to 0),
    but fault 37 is raised only outside it; in Manual it is."""
    from axisline.devices.clm.profibus import WD_EXPIRED, ClmProfibus

    rig = Rig("0000 NOP\n", params={"B008": "0 1 3 1 05"}, mode="manual")
    pb = ClmProfibus(rig.rt)
    pb.watchdog_ms = 10
    for _ in range(3):  # B008 taken: the control word is a system input
        pb.cycle(rig.rt.step)
    assert pb.settings.profibus == 1 and pb.settings.mode == 3
    rig.set_mode("parameter")
    pb.write_registers(6, [0, 0x00AA])
    for _ in range(8):
        pb.cycle(rig.rt.step)
    assert rig.rt.modes.mode == "parameter"
    assert pb.watchdog_status == WD_EXPIRED and rig.rt.modes.fault_error is None
    assert rig.rt.image.get(parse_operand("I2.02", bit=False)) == 0
    rig.set_mode("manual")
    pb.write_registers(6, [0])
    for _ in range(8):
        pb.cycle(rig.rt.step)
    assert rig.rt.modes.mode == "manual" and rig.fault == "37"
