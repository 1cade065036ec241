"""The measure of success for `make demo`: a cut-to-length line cutting 1 m pieces.

Simulated line: MaterialLine ramps up to 60 m/min, slows to 48 m/min and back during the batch,
then ramps down; a line encoder on the material (40 increments/mm); a carriage ServoDrive with
a first-order lag of a few ms and seeded commissioning errors (gain and offset of its ±10 V
input), commissioned first with the Adjust procedures (loop.py: tune_offset, tune_gain) as
manual §7 describes; then the FS701 cuts. LU = 0.1 mm, carriage encoder 20 increments/mm.

The cut instant (cutter.py C17): the shear's blade passes the material 20 ms after Ready to
Cut rises (the carriage is synchronous and inside the Cut Window then); the piece length is the
material between two such instants (material travel minus carriage travel), less Tool Width.

Stated accuracy (pieces whose two cuts both happened at constant line speed / any):
    constant speed: |error| <= 1 carriage increment (0.05 mm; the line's own quantisation is
                    0.025 mm per increment)
    otherwise:      |error| <= 2 carriage increments (0.1 mm; manual §9 expects 4..7
                    increments in practice, spec E18). The two cuts of such a piece happen at
                    different speeds, so the carriage's position error at the two cuts differs
                    (it is bounded by the Cut Window, 6 increments, when Ready to Cut rises).
Over seeds 0..19 and 701 the worst pieces were 0.35 (constant) and 1.6 increments (ramps).
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from axisline.devices.fs701.cutter import CutRecord
from axisline.devices.fs701.loop import tune_gain, tune_offset

from .test_cutter_rig import CutterRig, SpeedChange, demo_settings

# line speeds in LU/s (LU = 0.1 mm): 10000 = 60 m/min, accelerations 0.25 / 0.2 m/s^2
DEMO_PROFILE = (
    SpeedChange(0.0, 10000.0, 2500.0),
    SpeedChange(9.0, 8000.0, 2000.0),
    SpeedChange(14.0, 10000.0, 2500.0),
    SpeedChange(20.0, 0.0, 2500.0),
)
SEED = 701
CONSTANT_SPEED_TOLERANCE = 1.0  # carriage increments
RAMP_TOLERANCE = 2.0


def run_line(seed: int = SEED, seconds: float = 25.0) -> tuple[CutterRig, list[CutRecord], list[bool]]:
    """Commission, then run the batch. Returns the rig, the pieces (CutRecord, the first cut
    excluded: it has no previous cut) and per piece whether both its cuts happened at the same
    constant line speed."""
    rng = np.random.default_rng(seed)
    s = demo_settings()
    drive = dict(
        time_constant=float(rng.uniform(0.002, 0.004)),
        gain_factor=float(rng.uniform(0.92, 1.08)),
        offset_volts=float(rng.uniform(-0.03, 0.03)),
    )
    rig = CutterRig(s, line=list(DEMO_PROFILE), drive=drive)

    # manual §7: Adjust with the carriage disconnected (Control Enable LOW), then back to zero
    def counts() -> int:
        return rig.car_encoder.sample()

    off = tune_offset(s, rig.period, rig.drive, counts)
    gain = tune_gain(s, rig.period, rig.drive, counts)
    assert off.ok and gain.ok, (off, gain)
    rig.drive.reset(0.0)
    rig.drive.enable(False)
    rig.car_encoder.sample()

    speed_at_cut: list[float] = []  # line speed at the cut; nan while the line accelerates
    rec = rig.recorder
    original = rec.cut

    def cut(cycle, material_position, carriage_position):
        m = rig.material
        speed_at_cut.append(m.velocity if m.acceleration == 0.0 and m.velocity > 0.0 else math.nan)
        return original(cycle, material_position, carriage_position)

    rec.cut = cut  # type: ignore[method-assign]
    rig.enable()
    rig.start()
    rig.run(seconds)
    pieces = [r for r in rec.records if not math.isnan(r.actual_length)]
    # constant speed: both cuts of the piece at the same, constant line speed
    constant = [speed_at_cut[i] == speed_at_cut[i - 1] for i in range(1, len(speed_at_cut))]
    return rig, pieces, constant


def test_one_metre_pieces_on_a_line_with_speed_changes():
    rig, pieces, constant = run_line()
    c = rig.cutter
    assert c.errors == 0
    # the material of the whole run, cut into 1 m pieces (the last partial piece stays on the line)
    expected = int(rig.material.position // 10000) - 1
    assert len(pieces) >= expected - 1 and len(pieces) >= 15
    assert all(p.target_length == 10000.0 for p in pieces)
    assert sum(constant) >= 6 and not all(constant)
    for p, const in zip(pieces, constant):
        tol = CONSTANT_SPEED_TOLERANCE if const else RAMP_TOLERANCE
        assert abs(p.error_counts) <= tol, (p, const)
        assert abs(p.following_error) <= s_cut_window(rig)  # cut inside the Cut Window
    assert c.batch_counter == len(pieces) + 1 and c.waste_counter == 0
    # the per-cut record for the report
    r = pieces[0]
    assert {"target_length", "actual_length", "error_lu", "error_counts", "line_speed", "following_error"} <= {
        f.name for f in dataclasses.fields(r)
    }


def s_cut_window(rig: CutterRig) -> float:
    return float(rig.s.cut_window)


def test_position_error_stays_small_through_the_whole_cycle():
    """E17 (§7.5): during the whole cycle the position error should not exceed about 30."""
    s = demo_settings(acceleration_2=80000, deceleration_2=80000)
    rig = CutterRig(s, line_speed=10000.0, drive=dict(time_constant=0.003))
    rig.enable()
    rig.start()
    worst = 0.0
    for _ in range(4000):
        rig.step()
        worst = max(worst, abs(rig.cutter.position_error))
    assert len(rig.cutter.cut_log) >= 3 and worst <= 30.0
