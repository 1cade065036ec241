"""The CLM's analog inputs AE1-AE4 as the firmware reads them: Status 45 / 49 (L7157-7229),
V007-V010 (L1361-1364), B017's averaging (L5220-5233) and the override it feeds (L3266-3280).
Decisions: src/axisline/devices/clm/analog.py."""

from __future__ import annotations

from pathlib import Path

import pytest

from axisline.devices.clm.analog import averaging_values
from axisline.devices.clm.telegram import checksum
from axisline.machine import Machine

from .clmrig import roll_feed_text, with_parameters

EXAMPLES = Path(__file__).resolve().parents[3] / "examples"


def machine(tmp_path: Path, program: str, volts: dict[str, float], params: dict[str, str] | None = None) -> Machine:
    """examples/roll_feed_clm.toml with [device.analog_inputs] `volts`."""
    prg = tmp_path / "test.prg"
    prg.write_text(program)
    par_text = (EXAMPLES / "clm" / "roll_feed.par").read_text()
    (tmp_path / "test.par").write_text(with_parameters(par_text, params or {}))
    text = roll_feed_text(prg, tmp_path / "test.par")
    text += "\n[device.analog_inputs]\n" + "".join(f"{k} = {v}\n" for k, v in volts.items())
    path = tmp_path / "m.toml"
    path.write_text(text)
    return Machine.from_file(path)


def run(m: Machine, cycles: int) -> None:
    for _ in range(cycles):
        m.scheduler.run_cycle()


def reply(body: str) -> bytes:
    """The CLM's status reply ``X<blank><body>$hh CR LF`` (RS232 station: a blank)."""
    text = "X " + body
    return f"{text}${checksum(text)}\r\n".encode("ascii")


def status(m: Machine, number: int) -> bytes:
    return m.device.byte_endpoint().feed(f"? X  {number} \r\n".encode("ascii"))


def test_status_49_and_45_in_millivolts(tmp_path):
    """Decisions 1, 3 (L7157-7229 ``Xs49_+12345_+12345_$hh``): the voltage in mV through the
    12-bit converter (1.234 V is 253 steps of 4.883 mV = 1235 mV); 49 is AE1, AE2 and 45 AE3, AE4;
    without averaging or override a new voltage is read when asked."""
    m = machine(tmp_path, "0000 JMP 0000\n", {"AE1": 5.0, "AE2": -2.5, "AE3": 1.234, "AE4": 10.0})
    run(m, 5)
    assert status(m, 49) == reply("49 +05000 -02500 ")
    assert status(m, 45) == reply("45 +01235 +10000 ")
    # Fig. 9-12 by hand: the bytes of "X 49 +05000 -02500 " sum to 0x389, 0x03 + 0x89 = 0x8C, -> $74
    assert status(m, 49).endswith(b"$74\r\n")
    m.device.analog.set_input("AE1", 7.5)
    assert status(m, 49) == reply("49 +07500 -02500 ")


def test_v007_to_v010_standardized(tmp_path):
    """Decision 1 (L1361 "standardized to +/- 1"): V007-V010 = volts / 10, also in a program and
    over the interface."""
    m = machine(tmp_path, "0000 SET V600 = +V007\n0001 JMP 0001\n", {"AE1": 5.0, "AE2": -2.5, "AE4": 10.0})
    run(m, 100)
    v = m.device.memory.variables
    assert (v[7], v[8], v[9], v[10]) == (500_000, -250_000, 0, 1_000_000)
    assert v[600] == 500_000
    body = "007 +00000000.500000 "
    assert m.device.byte_endpoint().feed(b"? V007\r\n") == f"V {body}${checksum('V ' + body)}\r\n".encode()


def test_averaging_digit_table():
    """Decision 2 (L5220-5231, the printed column shifted one row): 0 none, 1 = 8 ... 9 = 2048."""
    assert [averaging_values(d) for d in range(10)] == [1, 8, 16, 32, 64, 128, 256, 512, 1024, 2048]
    with pytest.raises(ValueError, match="allowed 0"):
        averaging_values(10)


def test_averaging_digit_1_is_8_values(tmp_path):
    """Decision 2: B017 averaging 1 = the mean of the last 8 values, one per NC cycle: a step of
    0 -> 10 V reads 1.25, 2.5, ... 10 V in Status 49 over 8 cycles, then stays."""
    m = machine(tmp_path, "0000 JMP 0000\n", {"AE1": 0.0}, params={"B017": "1 0 0 0 0 0"})
    run(m, 20)
    assert status(m, 49) == reply("49 +00000 +00000 ")
    m.device.analog.set_input("AE1", 10.0)
    seen = []
    for _ in range(10):
        run(m, 1)
        seen.append(status(m, 49))
    assert seen == [reply(f"49 +{min(k, 8) * 1250:05d} +00000 ") for k in range(1, 11)]
    assert m.device.memory.variables[7] == 1_000_000


def test_averaging_digit_4_on_v008(tmp_path):
    """Decision 2: digit 4 = 64 values: a steady input reads its value from the start (the window
    starts full); 32 cycles after a step 2.5 V -> 5 V the mean is half way, after 63 one step of
    2.5 V / 64 short, after 64 the new value."""
    m = machine(tmp_path, "0000 JMP 0000\n", {"AE2": 2.5}, params={"B017": "4 0 0 0 0 0"})
    run(m, 2)
    v = m.device.memory.variables
    assert v[8] == 250_000
    m.device.analog.set_input("AE2", 5.0)
    run(m, 32)
    assert v[8] == 375_000
    run(m, 31)
    assert v[8] == round(500_000 - 250_000 / 64)
    run(m, 1)
    assert v[8] == 500_000


def test_averaged_value_drives_the_override(tmp_path):
    """Decision 2 with B017's override on AE1 (Fig. 7-2): averaging 7 = 512 values (1.024 s at
    2 ms): a step 10 V -> 5 V moves the feed's speed from 499.5 mm/s to 249.75 mm/s over 1.024 s
    (half way at 0.512 s: 7.5 V = 374.6 mm/s); without averaging it follows at once."""
    program = "0000 POI 1 +001500.000 999\n0001 JMP 0001\n"
    m = machine(tmp_path, program, {"AE1": 10.0}, params={"B017": "7 1 0 0 0 0"})
    run(m, 250)  # start at 0.1 s, at full speed by 0.5 s
    assert m.axis("feed").actual_velocity == pytest.approx(499.5, rel=0.01)
    m.device.analog.set_input("AE1", 5.0)
    run(m, 256)
    assert m.axis("feed").actual_velocity == pytest.approx(374.6, rel=0.02)
    run(m, 300)
    assert m.axis("feed").actual_velocity == pytest.approx(249.75, rel=0.01)
    assert status(m, 49) == reply("49 +05000 +00000 ")
    m0 = machine(tmp_path, program, {"AE1": 10.0}, params={"B017": "0 1 0 0 0 0"})
    run(m0, 250)
    m0.device.analog.set_input("AE1", 5.0)
    run(m0, 50)  # 0.1 s: the ramp down (5000 mm/s^2) is done
    assert m0.axis("feed").actual_velocity == pytest.approx(249.75, rel=0.01)
