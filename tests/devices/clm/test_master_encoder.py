"""Master encoder 1 of the CLM on the simulated plant: a measuring wheel on the [material] line
wired as ``device.master_encoder_1`` (C000-C003 L5474-5531, V011 L1365, Status 47 L7175-7193,
VEO 5 L2880-2893, AEO L1442-1468). Decisions: src/axisline/devices/clm/master_encoder.py and
override.py 11-13."""

from __future__ import annotations

from fractions import Fraction
from pathlib import Path

import pytest

from axisline.configerrors import ConfigError
from axisline.devices.clm.status import status_body
from axisline.machine import Machine

from .clmrig import roll_feed_text, with_parameters, run_to as run

EXAMPLES = Path(__file__).resolve().parents[3] / "examples"
COUNT_MM = 200 / (4 * 1250)  # C002 200 mm per revolution / (4 x C000 1250 lines)
QUANTUM = COUNT_MM / (32 * 0.002)  # one count in the 32-cycle average, mm/s


def machine(tmp_path: Path, program: str, speeds: list[tuple[float, float]], params: dict[str, str] | None = None,
            wire: str = "wheel", kind: str = "wheel") -> Machine:
    """examples/roll_feed_clm.toml with a [material] line (speed changes at 3000 mm/s^2) and a
    [[master]] wheel of 1250 lines x4 on 200 mm (C000 01250, C002 0200.00000)."""
    prg = tmp_path / "test.prg"
    prg.write_text(program)
    par_text = (EXAMPLES / "clm" / "roll_feed.par").read_text()
    (tmp_path / "test.par").write_text(with_parameters(par_text, {"C002": "0200.00000", **(params or {})}))
    text = roll_feed_text(prg, tmp_path / "test.par")
    text = text.replace("start_at = 0.1 ", f'master_encoder_1 = "{wire}"\nstart_at = 0.1 ')
    text += "\n[material]\nspeed = 0.0\n"
    for t, v in speeds:
        text += f"[[material.profile]]\ntime = {t}\nspeed = {v}\nacceleration = 3000.0\n"
    if kind == "wheel":
        text += '\n[[master]]\nname = "wheel"\nkind = "wheel"\n[master.wheel]\nlines_per_revolution = 1250\ncircumference = 200.0\nmultiplier = 4\n'
    else:
        text += '\n[[master]]\nname = "wheel"\nkind = "virtual"\n'
    path = tmp_path / "m.toml"
    path.write_text(text)
    return Machine.from_file(path)


def test_v011_and_status_47_follow_the_line(tmp_path):
    """master_encoder.py decisions 1, 4, 5: V011 (IU/s, L1365) and Status 47 (1/min, ``Xs47_0_...``,
    L7183) are the 32-cycle average (L7191) of the wheel's counts x C002 / (4 x C000)."""
    m = machine(tmp_path, "0000 JMP 0000\n", [(0.2, 300.0), (1.0, 450.0)])
    rt = m.device.rt
    run(m, 0.9)
    assert m.device.memory.variables[11] / 1e6 == pytest.approx(300.0, abs=QUANTUM)
    assert status_body(rt, 47, []) == "47 0 +0090.00 "  # 300 mm/s on a 200 mm wheel = 90 1/min
    run(m, 1.8)
    assert m.device.memory.variables[11] / 1e6 == pytest.approx(450.0, abs=QUANTUM)
    assert status_body(rt, 47, [])[:13] in ("47 0 +0135.00", "47 0 +0134.99", "47 0 +0135.01")


def test_position_is_exact_counts_times_c002(tmp_path):
    """Decisions 1, 2: the position is an exact Fraction of the integer counts; FAK 5 scales C002."""
    m = machine(tmp_path, "0000 WAI 00.500\n0001 FAK 5 1.234500\n0002 JMP 0002\n", [(0.0, 300.0)])
    me = m.device.rt.master_encoder
    run(m, 0.4)
    assert me.position == Fraction(me.counts) * Fraction(200, 5000)
    wheel = m.material.position if hasattr(m, "material") else None
    if wheel is not None:
        assert abs(float(me.position) - wheel) <= 300.0 * m.period + COUNT_MM * 1.01  # sampled a cycle back
    run(m, 1.0)
    assert me.position == Fraction(me.counts) * Fraction(200, 5000) * Fraction(12345, 10000)


def test_direction_digit_turns_the_count(tmp_path):
    """Decision 3: C001's direction digit 1 negates master encoder 1."""
    m = machine(tmp_path, "0000 JMP 0000\n", [(0.0, 300.0)], {"C001": "0 0 00 0 1 0"})
    run(m, 0.5)
    assert m.device.memory.variables[11] / 1e6 == pytest.approx(-300.0, abs=QUANTUM)


def test_veo5_scales_the_feed_with_the_line(tmp_path):
    """override.py decision 12, Fig. 5-33 (L2884): 999 x |V011| / Ax06 -> the feed runs at the
    line speed (x 0.999) and follows its change."""
    m = machine(tmp_path, "0000 VEO 1 5 0 000 0\n0001 POI 1 +100000.000 999\n0002 JMP 0002\n", [(0.2, 300.0), (1.2, 450.0)])
    run(m, 1.1)
    ax = m.axis("feed")
    assert ax.actual_velocity == pytest.approx(0.999 * 300.0, abs=1.0)
    run(m, 2.0)
    assert ax.actual_velocity == pytest.approx(0.999 * 450.0, abs=1.0)
    assert m.device.rt.modes.fault_error is None


def test_veo5_above_125_percent_is_4d(tmp_path):
    """Decision 12 (L2889-2891): above Ax06 the feed is capped at Ax06; beyond 1.25 x Ax06 it is
    fault 4D "Max. Override A1"."""
    m = machine(tmp_path, "0000 VEO 1 5 0 000 0\n0001 POI 1 +100000.000 999\n0002 JMP 0002\n", [(0.2, 550.0), (1.5, 700.0)])
    run(m, 1.4)
    rt = m.device.rt
    assert rt.modes.fault_error is None
    assert m.axis("feed").actual_velocity == pytest.approx(500.0, abs=1.0)
    run(m, 2.0)
    assert rt.modes.fault_error is not None and rt.modes.fault_error.code == "4D"


def test_aeo_acceleration_follows_the_line(tmp_path):
    """Decision 13, Fig. 5-5 (L1458-1466): Ax09 x V011^2 / Ax06^2 x 500 / 1000, not below the
    minimum 100 per mille of Ax09; AEO 1 0 1 ends it."""
    m = machine(tmp_path, "0000 AEO 1 1 1 500 100\n0001 WAI 01.500\n0002 AEO 1 0 1 500 100\n0003 JMP 0003\n", [(0.3, 300.0)])
    axis = m.device.rt.axes[1]
    a09 = axis.ax09_acceleration
    run(m, 0.2)
    assert axis.acceleration == pytest.approx(a09 * 0.1)  # line standing: the minimum (L1468)
    run(m, 1.2)
    v = m.device.memory.variables[11] / 1e6
    assert axis.acceleration == pytest.approx(a09 * v * v / 500.0**2 * 0.5)
    assert axis.acceleration == pytest.approx(a09 * 0.36 * 0.5, rel=0.01)
    run(m, 1.8)
    assert axis.aeo_acceleration is None and axis.acceleration == a09


def test_master_encoder_1_must_be_a_wheel(tmp_path):
    with pytest.raises(ConfigError, match="master_encoder_1"):
        machine(tmp_path, "0000 JMP 0000\n", [(0.0, 100.0)], kind="virtual")


def test_travel_is_the_float_of_the_exact_scale(tmp_path):
    """Decisions 1, 2: the wheel's travel in a cycle (what the measuring wheel mode adds, L4615) is
    float(counts x scale) exactly - worked out from the scale's numerator and denominator, which
    follow FAK 5 as the scale does (a FAK 5 changes it from the next read on)."""
    m = machine(tmp_path, "0000 WAI 00.100\n0001 FAK 5 1.234567\n0002 JMP 0002\n", [(0.0, 300.0)], {"C002": "0199.99999"})
    me = m.device.rt.master_encoder
    run(m, 0.05)
    before = me.scale
    assert before == Fraction(19999999, 100000) / 5000
    for n in (1, -1, 7, 12345, -987654321, 2**40 + 3):
        assert me.travel(n) == float(n * before)
    run(m, 0.5)
    assert me.scale == before * Fraction(1234567, 10**6)
    for n in (1, -1, 7, 12345, -987654321, 2**40 + 3):
        assert me.travel(n) == float(n * me.scale)
