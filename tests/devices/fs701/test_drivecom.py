"""FS701 serial protocol: Drivecom (ISO 1745) framing, BCC, NAK without change, streaming, addressing.

The FS701 manual has no example telegram (spec fs701.md §6 [GAP]); the byte strings below follow
the framing documented in drivecom.py, built by hand from the control characters.
"""

from __future__ import annotations

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from axisline.devices.fs701.drivecom import (
    ACK,
    EOT,
    ETX,
    NAK,
    STX,
    DrivecomClient,
    DrivecomEndpoint,
    DrivecomError,
    bcc,
    build_read,
    build_reply,
    build_write,
    encode_address,
    parse_reply,
)
from axisline.devices.fs701.registers import REGISTERS, RegisterMap


def snapshot(m: RegisterMap) -> dict:
    return {r.code: m.read(r.code) for r in REGISTERS} | {"stores": m.store_count}


@pytest.fixture
def unit():
    m = RegisterMap()
    return m, DrivecomEndpoint(m)


# ---- telegrams byte for byte -----------------------------------------------------------------


def test_bcc_is_the_xor_after_stx_through_etx():
    # motrona's published reply example (AX345 manual): STX ":1" "-180" ETX BCC = 02 3A 31 2D 31 38 30 03 1C
    assert bcc(bytes.fromhex("3A 31 2D 31 38 30 03")) == 0x1C
    assert bcc(b"") == 0


def test_read_request_and_reply_bytes(unit):
    m, ep = unit
    req = build_read(11, 0x0000)
    assert req == bytes.fromhex("04 31 31 30 30 30 30 05")  # EOT "11" "0000" ENQ
    reply = ep.feed(req)
    assert reply == bytes.fromhex("02 30 30 30 30 31 30 30 30 03 02")  # STX "0000" "1000" ETX BCC
    assert reply == build_reply(0x0000, "1000")
    m.params.sync_rate = -1.25
    assert ep.feed(bytes.fromhex("04 31 31 30 31 30 35 05")) == bytes([STX]) + b"0105-125" + bytes([ETX, 0x1C])
    assert parse_reply(ep.feed(build_read(11, 0x0105))).value == -125
    # lower-case hex is accepted, the reply uses upper case
    m.params.ser_data_format = 6
    assert ep.feed(b"\x0411" + b"02c7" + b"\x05") == build_reply(0x02C7, "6")


def test_write_telegram_bytes_and_ack(unit):
    m, ep = unit
    w = build_write(11, 0x0105, -125)
    assert w == bytes.fromhex("04 31 31 02 30 31 30 35 2D 31 32 35 03 1C")  # EOT "11" STX "0105" "-125" ETX BCC
    assert ep.feed(w) == bytes([ACK])
    assert m.params.sync_rate == -1.25
    assert ep.feed(build_write(11, 0x0105, "1.50")) == bytes([ACK])  # decimal point with the register's decimals
    assert m.params.sync_rate == 1.5
    assert ep.feed(build_write(11, 0x0901, 1)) == bytes([ACK])  # single command: Start / Stop
    assert m.status.serial_commands == 0b10


def test_nak_cases_leave_every_register_unchanged(unit):
    m, ep = unit
    before = snapshot(m)
    good = build_write(11, 0x0000, 2500)
    bad_bcc = good[:-1] + bytes([good[-1] ^ 0x01])
    body = b"0000" + b"25" + bytes([0x06]) + b"00" + bytes([ETX])  # control character in the data
    cases = {
        "bad bcc": bad_bcc,
        "unknown register": build_write(11, 0x01A0, 0),
        "unknown 0x090E": build_write(11, 0x090E, 1),
        "out of range": build_write(11, 0x0000, 0),
        "out of range 2": build_write(11, 0x0105, 1000),
        "zero digit address value": build_write(11, 0x02C5, 20),
        "read only": build_write(11, 0x0800, 1),
        "wrong decimals": build_write(11, 0x0105, "1.5"),
        "not a number": build_write(11, 0x0000, "12a"),
        "empty data": b"\x0411\x02" + b"0000" + bytes([ETX]) + bytes([bcc(b"0000" + bytes([ETX]))]),
        "bad code chars": b"\x0411\x02" + b"00G0" + b"5" + bytes([ETX]) + bytes([bcc(b"00G05" + bytes([ETX]))]),
        "control char": b"\x0411\x02" + body + bytes([bcc(body)]),
        "too long data": build_write(11, 0x0000, "1" * 16)[:-2] + b"1" * 20,
        "adjust with enable": None,
        "read unknown": build_read(11, 0x0B06),
        "read 090E": build_read(11, 0x090E),
        "read short code": b"\x0411" + b"000" + b"\x05",
        "read long code": b"\x0411" + b"00000" + b"\x05",
        "read bad char": b"\x0411" + b"0G00" + b"\x05",
    }
    m.status.hardware_commands = 1  # Control Enable ON
    before = snapshot(m)
    cases["adjust with enable"] = build_write(11, 0x091E, 1)
    for name, telegram in cases.items():
        assert ep.feed(telegram) == bytes([NAK]), name
        assert snapshot(m) == before, name
        ep.reset()
    # after all that, the unit still answers normally
    assert ep.feed(good) == bytes([ACK]) and m.params.cutting_length == 2500


def test_writes_can_be_disabled():
    m = RegisterMap()
    ep = DrivecomEndpoint(m, writes_allowed=False)
    assert ep.feed(build_write(11, 0x0000, 2500)) == bytes([NAK]) and m.params.cutting_length == 1000
    assert ep.feed(build_read(11, 0x0000)) == build_reply(0, "1000")
    ep.writes_allowed = lambda: True
    assert ep.feed(build_write(11, 0x0000, 2500)) == bytes([ACK])


# ---- streaming --------------------------------------------------------------------------------


def test_partial_telegrams_across_calls(unit):
    m, ep = unit
    w = build_write(11, 0x0000, 2500)
    assert [ep.feed(w[i : i + 1]) for i in range(len(w))] == [b""] * (len(w) - 1) + [bytes([ACK])]
    r = build_read(11, 0x0000)
    assert ep.feed(r[:3]) == b"" and ep.feed(r[3:]) == build_reply(0, "2500")


def test_several_telegrams_and_garbage_in_one_call(unit):
    m, ep = unit
    stream = b"\xff noise \x02\x03" + build_read(11, 0x0000) + b"\x06\x15xx" + build_write(11, 0x0001, 777) + b"zz"
    stream += build_read(11, 0x0001)
    assert ep.feed(stream) == build_reply(0, "1000") + bytes([ACK]) + build_reply(1, "777")


def test_eot_restarts_and_reset_drops_a_partial_telegram(unit):
    m, ep = unit
    w = build_write(11, 0x0000, 2500)
    assert ep.feed(w[:7] + build_read(11, 0x0000)) == build_reply(0, "1000")  # abandoned write
    assert m.params.cutting_length == 1000
    ep.feed(w[:7])
    ep.reset()  # inter-character time-out
    assert ep.feed(w[7:]) == b"" and m.params.cutting_length == 1000


@settings(max_examples=60)
@given(st.lists(st.integers(min_value=1, max_value=12), min_size=1, max_size=40))
def test_any_chunking_gives_the_same_answers(cuts):
    stream = (
        build_read(11, 0x0100)
        + b"junk"
        + build_write(11, 0x0105, -300)
        + build_write(12, 0x0000, 5)
        + build_write(11, 0x0000, 0)
        + build_read(11, 0x0105)
    )
    whole_map = RegisterMap()
    expected = DrivecomEndpoint(whole_map).feed(stream)
    m = RegisterMap()
    ep = DrivecomEndpoint(m)
    out, i, k = b"", 0, 0
    while i < len(stream):
        n = cuts[k % len(cuts)]
        out += ep.feed(stream[i : i + n])
        i, k = i + n, k + 1
    assert out == expected == build_reply(0x0100, "1000") + bytes([ACK, NAK]) + build_reply(0x0105, "-300")
    assert snapshot(m) == snapshot(whole_map)


@settings(max_examples=60)
@given(st.binary(max_size=200).map(lambda b: bytes(x for x in b if x != EOT)))
def test_garbage_without_eot_is_ignored(noise):
    m = RegisterMap()
    ep = DrivecomEndpoint(m)
    before = snapshot(m)
    assert ep.feed(noise) == b""
    assert snapshot(m) == before
    assert ep.feed(build_read(11, 0x0000)) == build_reply(0, "1000")


# ---- addressing -------------------------------------------------------------------------------


def test_wrong_address_is_ignored(unit):
    m, ep = unit
    assert ep.feed(build_read(12, 0x0000)) == b""
    assert ep.feed(build_write(99, 0x0000, 2500)) == b"" and m.params.cutting_length == 1000
    bad = build_write(12, 0x0000, 2500)
    assert ep.feed(bad[:-1] + bytes([bad[-1] ^ 1])) == b""  # not ours: no NAK either
    assert ep.feed(b"\x0412" + b"00G0" + b"\x05") == b""
    assert ep.ignored == 4 and ep.telegrams == 0


def test_a_foreign_bcc_equal_to_eot_does_not_start_a_telegram(unit):
    m, ep = unit
    value = next(v for v in range(10_000) if bcc(b"0000" + str(v).encode() + bytes([ETX])) == EOT)
    foreign = build_write(12, 0x0000, value)
    assert foreign[-1] == EOT
    # if the BCC were taken as EOT, "11" "0000" ENQ would be answered
    assert ep.feed(foreign + b"11" + b"0000" + b"\x05") == b""


def test_broadcast_writes_execute_silently_and_broadcast_reads_are_ignored(unit):
    m, ep = unit
    assert ep.feed(build_write(0, 0x0000, 2000, broadcast=True)) == b"" and m.params.cutting_length == 2000
    assert ep.feed(build_write(10, 0x0000, 3000, broadcast=True)) == b"" and m.params.cutting_length == 3000
    assert ep.feed(build_write(1, 0x0000, 4000, broadcast=True)) == b"" and m.params.cutting_length == 4000
    assert ep.feed(build_write(20, 0x0000, 5000, broadcast=True)) == b"" and m.params.cutting_length == 4000
    assert ep.feed(b"\x0400" + b"0000" + b"\x05") == b""
    assert ep.feed(build_write(0, 0x0000, 0, broadcast=True)) == b"" and m.params.cutting_length == 4000


def test_address_follows_the_register_when_not_fixed():
    m = RegisterMap()
    ep = DrivecomEndpoint(m, address=None)
    assert ep.address == 11
    assert ep.feed(build_write(11, 0x02C5, 23)) == bytes([ACK])  # acknowledged under the old address
    assert ep.feed(build_read(11, 0x02C5)) == b""
    assert ep.feed(build_read(23, 0x02C5)) == build_reply(0x02C5, "23")
    assert DrivecomEndpoint(m, address=45).address == 45
    for bad in (10, 20, 0, 100, 5):
        with pytest.raises(DrivecomError):
            DrivecomEndpoint(m, address=bad)


# ---- client side ------------------------------------------------------------------------------


def test_client_round_trip(unit):
    m, ep = unit
    c = DrivecomClient(ep.feed)
    assert c.read(0x0000) == 1000
    c.write(0x0105, "-2.50")
    assert c.read(0x0105) == -250 and c.read_text(0x0105) == "-250"
    with pytest.raises(DrivecomError, match="NAK"):
        c.write(0x0000, 0)
    with pytest.raises(DrivecomError, match="NAK"):
        c.read(0x0B06)
    assert m.params.cutting_length == 1000


def test_reply_parsing_and_builders():
    assert parse_reply(bytes([ACK])).kind == "ack" and parse_reply(bytes([NAK])).kind == "nak"
    r = parse_reply(bytes.fromhex("02 30 31 30 35 2D 31 32 35 03 1C"))
    assert (r.kind, r.code, r.text, r.value) == ("data", 0x0105, "-125", -125)
    with pytest.raises(DrivecomError, match="BCC"):
        parse_reply(bytes.fromhex("02 30 31 30 35 2D 31 32 35 03 1D"))
    with pytest.raises(DrivecomError):
        parse_reply(b"\x02\x03")
    with pytest.raises(DrivecomError):
        parse_reply(bytes([ACK])).value
    assert encode_address(11) == b"11" and encode_address(0, broadcast=True) == b"00"
    with pytest.raises(DrivecomError):
        encode_address(20)
    with pytest.raises(DrivecomError):
        build_write(11, 0x0000, "1\x03")
    with pytest.raises(DrivecomError):
        build_read(11, 0x10000)


def test_sessions_frame_apart_on_one_unit(unit):
    # one connection's telegram is its own: a write cut off before its BCC cannot take the next
    # client's EOT as the BCC (and swallow its read)
    m, ep = unit
    a, b = ep.session(), ep.session()
    w = build_write(11, 0x0000, 2500)
    assert a.feed(w[:-1]) == b""
    assert b.feed(build_read(11, 0x0000)) == build_reply(0, "1000")
    assert a.feed(w[-1:]) == bytes([ACK]) and m.params.cutting_length == 2500  # the same unit
    assert ep.telegrams == 2 and ep.feed(build_read(11, 0x0000)) == build_reply(0, "2500")
