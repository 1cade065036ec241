"""The IDS01 decade switch on X6 (manual §7.8 L3659-3693, V015-V018 L1366-1369, B002 L5018-5040,
errors 12-15 L5327-5330 / L8418-8446) on the simulated roll feed (Vmax 500 mm/s).
Decisions: src/axisline/devices/clm/decade_switch.py (and serial.py decision 14)."""

from __future__ import annotations

from pathlib import Path

import pytest

from axisline.configerrors import ConfigError
from axisline.devices.clm.decade_switch import decode, encode, length_digits
from axisline.devices.clm.errors import ClmError
from axisline.devices.clm.telegram import checksum
from axisline.machine import Machine

from .clmrig import roll_feed_text, with_parameters, run_to as run
from .test_velocity import listing

EXAMPLES = Path(__file__).resolve().parents[3] / "examples"
IDS_ON_X6 = {"B002": "002400 1 0 8 1"}  # function digit 1: the decade switch (parameters.py decision 5)


def machine(tmp_path: Path, program: str, switch: str | None, params: dict[str, str] | None = None,
            automatic: bool | None = None) -> Machine:
    """examples/roll_feed_clm.toml with `switch` as the [device.decade_switch] table (None: no
    IDS01 connected). automatic given: I0.00.1 wired to the io input 'auto' (set_mode)."""
    prg = tmp_path / "test.prg"
    prg.write_text(program)
    par_text = (EXAMPLES / "clm" / "roll_feed.par").read_text()
    (tmp_path / "test.par").write_text(with_parameters(par_text, {**IDS_ON_X6, **(params or {})}))
    text = roll_feed_text(prg, tmp_path / "test.par")
    if automatic is not None:
        text = text.replace('inputs = ["press_top", "press_bottom"]', 'inputs = ["press_top", "press_bottom", "auto"]')
        text = text.replace('"I1.00.2" = true', '"I1.00.2" = true\n"I0.00.1" = "auto"')
    if switch is not None:
        text += "\n[device.decade_switch]\n" + switch
    path = tmp_path / "m.toml"
    path.write_text(text)
    m = Machine.from_file(path)
    if automatic is not None:
        set_mode(m, automatic)
    return m


def set_mode(m: Machine, automatic: bool) -> None:
    m.io.set_input("auto", automatic)


def var(m: Machine, n: int) -> float:
    return m.device.memory.variables[n] / 1e6


def fault(m: Machine) -> str | None:
    e = m.device.rt.modes.fault_error
    return None if e is None else e.code


def run_until_fault(m: Machine, until_s: float) -> float | None:
    """The simulated time of the NC cycle in which the first fault came, None if none by `until_s`."""
    while m.device.rt.cycle * m.period < until_s - 1e-9:
        m.scheduler.run_cycle()
        if fault(m) is not None:
            return round((m.device.rt.cycle - 1) * m.period, 6)
    return None


# -- the telegram and the digits ---------------------------------------------------------------


def test_digits_load_v015_to_v017(tmp_path):
    """Decision 1: the six length digits in V015 (5.1), V016 (4.2), V017 (3.3) (L1366-1368); V018
    = % x 10 (L1369). An IDS01.1-3 at 12.345 shows the digits 012345."""
    m = machine(tmp_path, "0000 JMP 0000\n", 'model = "IDS01.1-3"\nlength = 12.345\nvelocity = 7\n')
    run(m, 0.2)
    assert (var(m, 15), var(m, 16), var(m, 17), var(m, 18)) == (1234.5, 123.45, 12.345, 70.0)
    assert fault(m) is None
    assert length_digits(9999.99, "IDS01.1-2") == 999999 and length_digits(0.001, "IDS01.1-3") == 1


def test_telegram_round_trip_and_its_checks():
    """Decisions 2 and 4: LLLLLLVVhh CR LF with the CLM checksum (Fig. 9-12) over the digits; a
    bad telegram is 15 (too long), 14 (not digits / hex, too short), 13 (checksum)."""
    frame = encode(12345, 50)
    assert frame == b"01234550" + checksum("01234550").encode() + b"\r\n" and len(frame) == 12
    assert decode(frame) == (12345, 50)
    cases = {
        b"012345506B0\r\n": "15",
        b"01234A506B\r\n": "14",
        b"012345506G\r\n": "14",
        b"0123455\r\n": "14",
        b"012345506C\r\n": "13",
    }
    assert checksum("01234550") == "6B"
    for bad, code in cases.items():
        with pytest.raises(ClmError) as e:
            decode(bad)
        assert e.value.code == code, bad


# -- the manual's example on the plant ----------------------------------------------------------


def feeds(m: Machine, until_s: float) -> list[tuple[float, float]]:
    """Per feed (Q1.00.0 on, WAI 0.5 s, off): (position when Q1.00.0 goes off again, the axis
    settled; peak velocity of the feed)."""
    out, before, peak = [], False, 0.0
    while m.device.rt.cycle * m.period < until_s - 1e-9:
        m.scheduler.run_cycle()
        peak = max(peak, m.axis("feed").actual_velocity)
        now = m.io.output("press_valve")
        if before and not now:
            out.append((m.axis("feed").actual_position, peak))
            peak = 0.0
        before = now
    return out


def test_manual_example_feeds_from_the_switch(tmp_path):
    """L3677-3685: ``PSI 1 +V016 V018`` / AEA Q1.00.0 1 / WAI 00.500 / AEA 0 / JMP: an IDS01.1-2
    at 123.45 and 50 % feeds 123.45 at 500 per mille (250 mm/s of A106 = 500, decision 2; spec
    §10.33). At 1.4 s, while the second feed runs, the operator dials 200.00 and 80 %: that feed
    keeps its 123.45, the next ones take 200.00 at 400 mm/s (decision 3)."""
    switch = ('model = "IDS01.1-2"\nlength = 123.45\nvelocity = 50\n'
              "[[device.decade_switch.events]]\nat = 1.4\nlength = 200.0\nvelocity = 80\n")
    m = machine(tmp_path, listing("ids01_example"), switch)
    got = feeds(m, 4.5)
    assert fault(m) is None
    ends = [0.0] + [p for p, _ in got]
    lengths = [b - a for a, b in zip(ends, ends[1:])]
    assert lengths == pytest.approx([123.45, 123.45, 200.0, 200.0], abs=0.01)
    assert [v for _, v in got] == pytest.approx([250.0, 250.0, 400.0, 400.0], rel=0.05)
    assert (var(m, 16), var(m, 18)) == (200.0, 800.0)


# -- monitoring ---------------------------------------------------------------------------------


def test_break_is_12_in_automatic_only(tmp_path):
    """Decisions 4, 5 (L3675): a break in Automatic is fault 12 after 100 ms without a good
    telegram; in Manual nothing happens and V016 keeps the last value; Automatic selected while
    the cable is still broken faults at once; it returns after a Clear as long as the cause lasts,
    and a Clear after the cable is back lets the program start again."""
    switch = ('model = "IDS01.1-2"\nlength = 10.0\n[[device.decade_switch.events]]\nat = 1.0\nlink = "break"\n'
              "[[device.decade_switch.events]]\nat = 1.0\nlength = 20.0\n")
    m = machine(tmp_path, "0000 JMP 0000\n", switch, automatic=True)
    at = run_until_fault(m, 2.0)
    assert fault(m) == "12" and at is not None
    assert 1.05 < at <= 1.05 + m.period  # the last good telegram at 0.95 s (1.0 s is lost), then 100 ms
    assert var(m, 16) == 10.0  # nothing after the break was loaded
    assert not m.device.rt.modes.running

    m2 = machine(tmp_path, "0000 JMP 0000\n", switch, automatic=False)
    run(m2, 2.0)
    assert fault(m2) is None and var(m2, 16) == 10.0
    set_mode(m2, True)
    assert run_until_fault(m2, 2.1) is not None and fault(m2) == "12"
    m2.device.rt.modes.clear()
    run(m2, 2.2)
    assert fault(m2) == "12"  # the cause is still there


def test_cleared_after_the_cable_is_back(tmp_path):
    """Decision 4: with the link back (``link = "ok"``) a Clear ends fault 12 for good and the
    next Start runs the program from 0000 with the switch's value."""
    switch = ('model = "IDS01.1-2"\nlength = 10.0\n[[device.decade_switch.events]]\nat = 0.5\nlink = "break"\n'
              '[[device.decade_switch.events]]\nat = 1.0\nlink = "ok"\nlength = 30.0\n')
    m = machine(tmp_path, "0000 SET V600 = +V016\n0001 JMP 0001\n", switch)
    run(m, 0.9)
    assert fault(m) == "12"
    run(m, 1.2)
    m.device.rt.modes.clear()
    run(m, 1.3)
    assert fault(m) is None
    m.device.rt.modes.start()
    run(m, 1.4)
    assert fault(m) is None and var(m, 600) == 30.0


@pytest.mark.parametrize("link,code", [("checksum", "13"), ("format", "14"), ("too_long", "15")])
def test_checksum_format_and_length_errors(tmp_path, link, code):
    """Decisions 4, 5, 7: a telegram with a wrong checksum / a character that is no digit / too
    many characters is fault 13 / 14 / 15 in Automatic when it arrives (the next telegram after
    ``at``); in Manual it is dropped and the variables keep their value."""
    switch = (f'model = "IDS01.1-2"\nlength = 10.0\n[[device.decade_switch.events]]\nat = 0.52\nlink = "{link}"\n'
              "length = 20.0\n")
    m = machine(tmp_path, "0000 JMP 0000\n", switch, automatic=True)
    at = run_until_fault(m, 1.0)
    assert fault(m) == code and at == pytest.approx(0.55)  # the telegram completing at 0.55 s
    assert var(m, 16) == 10.0
    m2 = machine(tmp_path, "0000 JMP 0000\n", switch, automatic=False)
    run(m2, 1.0)
    assert fault(m2) is None and var(m2, 16) == 10.0
    assert m2.device.summary()["decade_switch"]["errors"][code] == 9  # 0.55 ... 0.95 s


def test_no_switch_connected_is_12(tmp_path):
    """Decision 4 (L3675 "no transmission"): B002 selects the IDS01 and nothing is connected."""
    m = machine(tmp_path, "0000 JMP 0000\n", None)
    at = run_until_fault(m, 1.0)
    assert fault(m) == "12" and at is not None and 0.1 < at <= 0.1 + m.period
    assert "no IDS01 connected" in m.device.rt.modes.fault_error.detail


def test_switch_not_read_without_b002(tmp_path):
    """Decision 6: with B002's function digit 0 (a data interface) the switch is not read."""
    m = machine(tmp_path, "0000 JMP 0000\n", 'model = "IDS01.1-2"\nlength = 10.0\nvelocity = 50\n',
                params={"B002": "019200 0 1 8 1"})
    run(m, 1.0)
    assert fault(m) is None and (var(m, 16), var(m, 18)) == (0.0, 0.0)


def test_bad_machine_file_is_refused(tmp_path):
    """Decision 1 and the schema: a length the model cannot show, a velocity beyond 99 %, an event
    that changes nothing: a ConfigError naming key, value and range."""
    bad = {
        'model = "IDS01.1-2"\nlength = 12.345\n': ["device.decade_switch.length = 12.345", "2 decimal places"],
        'model = "IDS01.1-3"\nlength = 1000.0\n': ["device.decade_switch.length = 1000.0", "0 ... 999.999"],
        'model = "IDS01.1-2"\n[[device.decade_switch.events]]\nat = 1.0\nlength = -1.0\n': ["events[0].length = -1.0"],
        'model = "IDS01.1-2"\nvelocity = 100\n': ["velocity"],
        'model = "IDS01.1-4"\n': ["model"],
        'model = "IDS01.1-2"\n[[device.decade_switch.events]]\nat = 1.0\n': ["length, velocity or link"],
    }
    for text, words in bad.items():
        with pytest.raises(ConfigError) as e:
            machine(tmp_path, "0000 JMP 0000\n", text)
        for w in words:
            assert w in str(e.value), (text, str(e.value))


# -- the serial endpoint ------------------------------------------------------------------------


def test_serial_endpoint_with_the_ids_on_x6(tmp_path, capsys):
    """serial.py decision 14 (L5028, L6329): X6 is the IDS01's; with X8 off nothing is answered
    (and stderr says why, once); with X8 a data interface (B004/B005) the endpoint is X8."""
    m = machine(tmp_path, "0000 JMP 0000\n", 'model = "IDS01.1-2"\nlength = 10.0\n')
    run(m, 0.1)
    ep = m.device.byte_endpoint()
    assert ep.feed(b"? X 53 \r\n") == b"" and ep.feed(b"? V016\r\n") == b""
    assert capsys.readouterr().err.count("X6 serves the IDS01") == 1
    m2 = machine(tmp_path, "0000 JMP 0000\n", 'model = "IDS01.1-2"\nlength = 10.0\n',
                 params={"B004": "009600 0 0 8 1", "B005": "0 1 00 0 000 000"})
    run(m2, 0.1)
    body = "016 +00000010.000000 "
    assert m2.device.byte_endpoint().feed(b"? V016\r\n") == f"V {body}${checksum('V ' + body)}\r\n".encode()


def test_example_machine_file():
    """examples/ids_feed_clm.toml: three feeds of 123.45, then 200.00 after the switch changes at
    3 s, fault 12 100 ms after the cable is pulled at 6 s (the last good telegram 5.95 s); the
    report says what came over the link."""
    m = Machine.from_file(EXAMPLES / "ids_feed_clm.toml")
    m.run()
    records = m.device.records
    targets = [r["target"] for r in records]
    steps = [b - a for a, b in zip([0.0] + targets, targets)]
    assert steps == pytest.approx([123.45] * 3 + [200.0] * 3)
    assert fault(m) == "12" and not m.device.rt.modes.running
    assert 6.05 < m.device.rt.cycle * m.period < 6.5
    report = m.device.report_markdown(m.device.summary(), [])
    assert "IDS01 decade switch on X6 (read)" in report and "errors 12: 1" in report
