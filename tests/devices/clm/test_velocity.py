"""CLM velocity functions on the simulated plant (roll feed: Vmax 500 mm/s, 5000 mm/s², Kv 10):
VCC (L2808-2859), VEO (L2861-2944), the §7.3 override tables (L3251-3360), AEO (L1442-1468).
Decisions: src/axisline/devices/clm/override.py."""

from __future__ import annotations

import pytest

from axisline.devices.clm.errors import ClmError
from axisline.devices.clm.operands import parse_operand
from axisline.devices.clm.override import (
    GRAY_PERCENT, aeo_acceleration, analog_factor, binary_factor, gray_factor, gray_step, veo_master_override,
)

from .manual_examples import PROGRAM_LISTINGS
from .test_manual_plant import machine


def listing(name: str) -> str:
    """A manual listing as a program: comment-only and empty rows dropped."""
    entry = next(e for e in PROGRAM_LISTINGS if e["name"] == name)
    rows = []
    for row in entry["text"].splitlines():
        cells = [c.strip() for c in row.split("\t")]
        if not cells[0] or len(cells) < 2 or not cells[1]:
            continue
        fields = " ".join(c for c in cells[1:] if c and not c.startswith("- "))
        rows.append(f"{cells[0]} {fields}")
    return "\n".join(rows) + "\n"


def profile(m, seconds: float, until=None) -> list[tuple[float, float]]:
    """(actual position, actual velocity) every cycle."""
    out = []
    for _ in range(round(seconds / m.period)):
        m.scheduler.run_cycle()
        ax = m.axis("feed")
        out.append((ax.actual_position, ax.actual_velocity))
        if until is not None and until(out):
            break
    return out


def v_at(samples, position: float) -> float:
    """The velocity when the axis first passes `position`."""
    return next(v for p, v in samples if p >= position)


def set_inputs(m, byte: int) -> None:
    m.device.memory.image.set(parse_operand("I1.01", bit=False), byte)


# -- the tables of §7.3 -----------------------------------------------------------------------

GRAY_ROWS = [  # L3297-3316: I1.01.4 I1.01.5 I1.01.6 I1.01.7 -> %
    ((0, 0, 0, 0), 0), ((1, 0, 0, 0), 1), ((1, 1, 0, 0), 2), ((0, 1, 0, 0), 4), ((0, 1, 1, 0), 6),
    ((1, 1, 1, 0), 8), ((1, 0, 1, 0), 10), ((0, 0, 1, 0), 20), ((0, 0, 1, 1), 30), ((1, 0, 1, 1), 40),
    ((1, 1, 1, 1), 50), ((0, 1, 1, 1), 60), ((0, 1, 0, 1), 70), ((1, 1, 0, 1), 80), ((1, 0, 0, 1), 90),
    ((0, 0, 0, 1), 100),
]


def test_gray_table_is_the_manual_table():
    """L3297-3316, errata §3.2: the 16 rows are the reflected Gray code of the steps 0..15."""
    for n, (bits, percent) in enumerate(GRAY_ROWS):
        code = sum(b << i for i, b in enumerate(bits))
        assert code == n ^ (n >> 1) and gray_step(code) == n
        assert gray_factor(code) * 100 == percent == GRAY_PERCENT[n]


def test_binary_and_analog_factors():
    """Fig. 7-4 (L3356): sum / 255; Fig. 7-2 (L3277): 0-10 V -> 0-1."""
    assert binary_factor(0b10000000) == pytest.approx(128 / 255)
    assert binary_factor(0xFF) == 1 and binary_factor(0) == 0
    assert analog_factor(5.0) == 0.5 and analog_factor(10.0) == 1.0 and analog_factor(-3.0) == 0.0


def test_master_encoder_formulas():
    """Fig. 5-33 (L2884) and Fig. 5-5 (L1458-1466)."""
    assert veo_master_override(250.0, 500.0, 2.0) == 1.0
    assert aeo_acceleration(5000.0, 250.0, 500.0, 999, 100.0) == pytest.approx(5000 * 0.25 * 0.999)
    assert aeo_acceleration(5000.0, 10.0, 500.0, 500, 100.0) == 100.0  # not below the minimum (L1468)


# -- the overrides on the plant ----------------------------------------------------------------


def test_gray_example_on_the_plant(tmp_path):
    """L3320-3342: A106 500, PSI 1 +001000.000 500 -> 250 mm/s; with B017 Gray and
    I1.01.4 = I1.01.5 = 1 (2 %): 0.02 x 250 = 5 mm/s."""
    m = machine(tmp_path, listing("gray_override_psi"), params={"B017": "0 6 0 0 0 0"})
    set_inputs(m, 0b0011_0000)
    samples = profile(m, 1.5)
    assert samples[-1][1] == pytest.approx(5.0, rel=0.02)
    m2 = machine(tmp_path, listing("gray_override_psi"))  # without the override: 250 mm/s
    assert profile(m2, 1.0)[-1][1] == pytest.approx(250.0, rel=0.01)


def test_binary_override_on_the_plant(tmp_path):
    """Only I1.01.7 (128): 128/255 of 499.5 mm/s; the override follows the inputs while moving."""
    m = machine(tmp_path, "0000 POI 1 +001000.000 999\n0001 JMP 0001\n", params={"B017": "0 5 0 0 0 0"})
    set_inputs(m, 0b1000_0000)
    assert profile(m, 0.5)[-1][1] == pytest.approx(499.5 * 128 / 255, rel=0.01)
    set_inputs(m, 0xFF)
    assert profile(m, 0.3)[-1][1] == pytest.approx(499.5, rel=0.01)


def test_analog_override_on_the_plant(tmp_path):
    """Fig. 7-1/7-2: 5 V on AE1 (device.analog_inputs) -> F = 0.5; 2.5 V while moving -> 0.25."""
    m = machine(tmp_path, "0000 POI 1 +001000.000 999\n0001 JMP 0001\n", params={"B017": "0 1 0 0 0 0"})
    m.device.analog.set_input("AE1", 5.0)
    assert profile(m, 0.5)[-1][1] == pytest.approx(249.75, rel=0.01)
    m.device.analog.set_input("AE1", 2.5)
    assert profile(m, 0.3)[-1][1] == pytest.approx(124.875, rel=0.01)


def test_zero_override_stands_still(tmp_path):
    """Decision 7: 0 % brakes the positioning to a crawl; it goes on when the override rises."""
    m = machine(tmp_path, "0000 POI 1 +000300.000 999\n0001 JMP 0001\n", params={"B017": "0 6 0 0 0 0"})
    set_inputs(m, 0b1000_0000)  # Gray 0001 -> step 15 = 100 %
    profile(m, 0.3)
    set_inputs(m, 0)
    samples = profile(m, 0.5)
    stopped_at = samples[-1][0]
    assert abs(stopped_at - samples[-50][0]) < 0.01  # 0.1 s: still
    assert 0 < stopped_at < 300
    set_inputs(m, 0b1000_0000)
    profile(m, 1.5)
    assert m.axis("feed").actual_position == pytest.approx(300.0, abs=0.1)


# -- VEO ---------------------------------------------------------------------------------------


@pytest.mark.parametrize("program, marker, expected", [
    ("A", 0x40, (499.5, 400, 300, 200, 100)),  # Fig. 5-34: unaffected
    ("B", 0x20, (350, 350, 300, 200, 100)),  # Fig. 5-35: limited to 70 % of Vmax
    ("C", 0x60, (249.75, 200, 150, 100, 50)),  # Fig. 5-36: x 0.5
])
def test_veo_example_programs_a_b_c(tmp_path, program, marker, expected):
    """L2910-2927: program selection on M2.02, VEO 1 4 1 vvv f, POI 100 and VCC 35/50/65/80."""
    m = machine(tmp_path, listing("veo_examples"))
    m.device.memory.image.set(parse_operand("M2.02", bit=False), marker)
    samples = profile(m, 3.0, until=lambda s: s[-1][0] > 99.9)
    got = [v_at(samples, p) for p in (30, 48, 63, 77, 92)]
    assert got == pytest.approx(expected, rel=0.03), got


def test_veo_priority_and_cancel(tmp_path):
    """L2872: a VEO replaces B017 (binary 255 = 100 % here); VEO s = 0 cancels it (B017 again);
    L2876: a change of mode cancels it."""
    program = ("0000 VEO 1 4 1 200 0\n0001 POI 1 +002000.000 999\n0002 WAI 00.500\n"
               "0003 VEO 1 0 0 000 0\n0004 WAI 00.500\n0005 VEO 1 4 1 200 0\n0006 JMP 0006\n")
    m = machine(tmp_path, program, params={"B017": "0 5 0 0 0 0"})
    set_inputs(m, 0x7F)  # 127/255
    assert profile(m, 0.45)[-1][1] == pytest.approx(99.9, rel=0.01)  # 20 % of 499.5, not 127/255
    assert profile(m, 0.5)[-1][1] == pytest.approx(499.5 * 127 / 255, rel=0.01)
    profile(m, 0.2)
    vf = m.device.rt.velocity
    assert 1 in vf.veo
    m.device.rt.modes.mode = "manual"  # (as the mode inputs do)
    vf.tick()
    assert vf.veo == {}


def test_veo_sources_1_to_3(tmp_path):
    """Decision 6: VEO s 1 analog input of the axis, 2 binary, 3 Gray, as a limit of Vmax (f = 1)."""
    m = machine(tmp_path, "0000 VEO 1 3 0 000 1\n0001 POI 1 +001000.000 999\n0002 JMP 0002\n")
    set_inputs(m, 0b1111_0000)  # Gray 1111 = 50 % -> limit 250 mm/s
    assert profile(m, 0.5)[-1][1] == pytest.approx(250.0, rel=0.01)


# -- VCC ---------------------------------------------------------------------------------------


def test_vcc_mode0_example(tmp_path):
    """Fig. 5-31 (L2826-2832): POI 100 at 999 from 0; after 50 -> 25 %, 75 -> 50 %, 90 -> 10 %;
    the velocity changes where the drive has traversed the distance (decision 8). Ax08 =
    10000 mm/s² (5000 would still be braking at 75: 499.5 -> 125 takes 23 mm)."""
    m = machine(tmp_path, listing("vcc_mode0_fig5_31"), params={"A108": "010000", "A114": "0 030 00.00.0"})
    samples = profile(m, 2.5, until=lambda s: s[-1][0] > 99.9)
    assert v_at(samples, 45) == pytest.approx(499.5, rel=0.01)
    assert v_at(samples, 50) > 400  # not before the switching distance
    assert [v_at(samples, p) for p in (70, 86, 97)] == pytest.approx((125, 250, 50), rel=0.03)
    samples = profile(m, 3.0, until=lambda s: s[-1][0] > 199.9)  # JMP 0000: the next 100 IU likewise
    assert [v_at(samples, p) for p in (170, 186, 197)] == pytest.approx((125, 250, 50), rel=0.03)


def test_vcc_mode1_example(tmp_path):
    """Fig. 5-32 (L2851-2856): from +100 (homed), POA 300; 50 % reached at +200, 10 % at +280."""
    program = "0000 POA 1 +000100.000 999\n0001 PSA 1 +000100.000 999\n" + "\n".join(
        f"{int(r[:4]) + 2:04d}{r[4:]}" for r in listing("vcc_mode1_fig5_32").splitlines()) + "\n"
    m = machine(tmp_path, program, params={"A108": "010000", "A114": "0 030 00.00.0"})
    profile(m, 0.05)  # (power-up; the axis is homed as the example assumes, before Start)
    m.device.rt.axes[1].homed = True
    samples = profile(m, 4.0, until=lambda s: s[-1][0] > 299.9)
    for p, v in ((200.0, 250.0), (280.0, 50.0)):
        after = [w for q, w in samples if p <= q <= p + 2.0]  # (the loop's transient: a mean)
        assert sum(after) / len(after) == pytest.approx(v, rel=0.08)
        assert v_at(samples, p - 2.0) > 1.15 * v  # not reached long before


def test_vcc_mode0_skipped_beyond_the_move(tmp_path):
    """L2822: a VCC distance not smaller than the positioning is not executed."""
    m = machine(tmp_path, "0000 POI 1 +000100.000 999\n0001 VCC 1 +000100.000 100 0 0\n0002 AEA Q1.00.6 1\n0003 JMP 0003\n")
    samples = profile(m, 0.2)
    assert m.device.rt.tasks[0].pc >= 2 and samples[-1][1] > 300


def test_vcc_errors(tmp_path):
    """Decision 10: mode 1 without a reference is 48; a negative point on a rotary table 1E."""
    m = machine(tmp_path, "0000 POI 1 +000100.000 999\n0001 VCC 1 +000050.000 100 1 1\n0002 JMP 0002\n")
    profile(m, 0.2)
    assert m.device.rt.modes.fault_error.code == "48"
    vf = m.device.rt.velocity
    axis = m.device.rt.axes[1]
    axis.homed = True
    m.device.memory.parameters.set("A100", "0 0 0 0 2")
    assert m.device.memory.parameters.motion_type(1) == 2
    with pytest.raises(ClmError) as e:
        vf.vcc_start(axis, -10_000, 100, 1)
    assert e.value.code == "1E"


def test_veo5_and_aeo_without_master(tmp_path):
    """Decision 11: without master encoder 1 in use, VEO 5 and AEO proceed at once (L2880, L1450)."""
    m = machine(tmp_path, "0000 VEO 1 5 0 500 0\n0001 AEO 1 1 1 500 100\n0002 POI 1 +000100.000 999\n0003 JMP 0003\n")
    samples = profile(m, 0.5)
    assert m.device.rt.modes.fault_error is None
    assert max(v for _, v in samples) == pytest.approx(499.5, rel=0.01)
