"""Reference runs in every mode of wago.md §2.4 (manual §3.11.1.5, §3.11.3.1) with simulated switches.

Plant: reference switch (Input2) active for 2000 <= x <= 4000, positive limit switch (Input5)
for x >= 10000, negative limit switch (Input6) for x <= -10000 (microsteps, plant frame).
SetupSpeed 5000 -> 10000 microsteps/s, SetupAcceleration 4000 -> 100000 microsteps/s^2:
the reference edge is latched within one cycle, i.e. 10 microsteps.
"""

from __future__ import annotations

import pytest

from axisline.devices.wago672.bits import Bit
from axisline.devices.wago672.image import C1, C3, S1, S2

from .rig import Rig

REF_LO, REF_HI, LIM = 2000, 4000, 10000


def rig(x0: float, mode: int, ref_switch: bool = True, **values) -> Rig:
    values.setdefault("SetupSpeed", 5000)
    values.setdefault("SetupAcceleration", 4000)
    r = Rig(Reference_Mode=mode, **values)
    r.enable()
    # the machine stands at x0 when the module powers up, and counts from 0 there
    r.plant = lambda: r.axis.command_position - r.axis.position_offset + x0
    if ref_switch:
        r.inputs["Input2"] = lambda: REF_LO <= r.plant() <= REF_HI
    r.inputs["Input5"] = lambda: r.plant() >= LIM
    r.inputs["Input6"] = lambda: r.plant() <= -LIM
    r.select(C1.M_Reference)
    return r


def run(r: Rig, direction: int, limit: int = 20000) -> None:
    r.c3 = C3.Direction_Pos if direction > 0 else C3.Direction_Neg
    r.start()
    assert r.has(S2.Busy) and not r.has(S2.Reference_OK) and not r.has(S2.On_Target)
    r.until(lambda: r.has(S2.Reference_OK), limit)
    assert not r.has(S2.Busy) and r.has(S2.On_Target) and r.has(S2.StandStill)
    assert r.error == 0


def latched_at(r: Rig, edge: float, offset: int = 0) -> None:
    """The reported position is Reference_Offset at the edge plus the braking distance."""
    braking = r.plant() - edge
    assert abs(braking) > 50, "the drive brakes after the edge"
    assert abs((braking + offset) - r.position) <= 11, (r.plant(), r.position)


@pytest.mark.parametrize("x0", [8000, -8000], ids=["from_positive_range", "from_negative_range"])
def test_r1_positive_end_start_negative(x0):
    r = rig(x0, mode=0b10)
    run(r, -1)
    latched_at(r, REF_HI)
    assert r.plant() > REF_HI, "the positive end is approached moving positive"


def test_r1_from_the_limit_switch_does_not_move_and_sets_err_range():
    r = rig(-10500, mode=0b10)
    r.c3 = C3.Direction_Neg
    r.start()
    r.step(20)
    assert r.error == 0 and r.plant() == -10500
    assert not r.has(S2.Busy) and not r.has(S2.Reference_OK)
    assert r.dev.bits.read(Bit.Err_Range_Neg) and r.dev.bits.read(Bit.Err_Range)


@pytest.mark.parametrize("x0", [8000, -8000, 3000], ids=["from_positive_range", "from_negative_range", "from_reference_switch"])
def test_r2_negative_end_start_negative(x0):
    r = rig(x0, mode=0b00)
    r.record = True
    run(r, -1)
    latched_at(r, REF_LO)
    assert r.plant() < REF_LO
    if x0 == 3000:
        # on the reference switch the module first moves the other way until the switch is free
        assert max(p for _, p, _ in r.trace) + x0 > REF_HI


@pytest.mark.parametrize("x0", [-5000, 6000], ids=["from_below", "from_positive_range_switch_behind"])
def test_r3_positive_end_start_positive(x0):
    r = rig(x0, mode=0b10)
    r.record = True
    run(r, +1)
    latched_at(r, REF_HI)
    if x0 == 6000:
        # the limit switch reverses the search (Fig. 3.11.1-11)
        assert max(p for _, p, _ in r.trace) + x0 >= LIM


def test_r5_negative_end_start_positive():
    r = rig(-5000, mode=0b00)
    run(r, +1)
    latched_at(r, REF_LO)
    assert r.plant() < REF_LO


def test_reference_offset_is_the_value_at_the_edge():
    r = rig(8000, mode=0b10, Reference_Offset=-250)
    run(r, -1)
    latched_at(r, REF_HI, offset=-250)


def test_reference_switch_not_found_between_the_limit_switches_is_1451():
    r = rig(0, mode=0, ref_switch=False)
    r.c3 = C3.Direction_Pos
    r.start()
    r.until(lambda: r.error != 0, 20000)
    assert r.error == 1451 and not r.has(S2.Reference_OK) and not r.has(S2.Busy)


@pytest.mark.parametrize("x0", [0, 10500], ids=["from_positive_range", "from_positive_limit_switch"])
def test_r4_limit_switch_negative(x0):
    r = rig(x0, mode=0b01)
    run(r, -1)
    latched_at(r, -LIM)
    assert r.dev.bits.read(Bit.LimitSwitch_Neg), "the drive ends on the limit switch"


def test_r6_limit_switch_positive_then_special_mode():
    r = rig(0, mode=0b01)
    run(r, +1)
    latched_at(r, LIM)
    # special mode: on the positive limit switch the drive may leave it in another mode (negative only)
    r.select(C1.M_Positioning)
    r.move(5000, 5000, r.position - 3000)
    assert r.error == 0
    r.move(5000, 5000, r.position + 2000)
    assert r.error == 0


def test_positioning_at_a_limit_switch_without_special_mode_is_1931():
    r = rig(-10500, mode=0)
    r.select(C1.M_Positioning)
    r.positioning(5000, 5000, 1000)
    r.c1 |= C1.Start
    r.step()
    assert r.error == 1931


def test_reference_run_without_direction_is_1431_and_with_both_does_not_move():
    r = rig(0, mode=0)
    r.c3 = 0
    r.c1 |= C1.Start
    r.step()
    assert r.error == 1431
    r = rig(0, mode=0)
    r.c3 = C3.Direction_Pos | C3.Direction_Neg
    r.start()
    r.step(10)
    assert r.error == 0 and r.dev.velocity_steps == 0.0 and not r.has(S2.Busy)


def test_setup_speed_zero_is_1453():
    r = rig(0, mode=0, SetupSpeed=0)
    r.c3 = C3.Direction_Pos
    r.c1 |= C1.Start
    r.step()
    assert r.error == 1453


def test_restart_during_a_run_initiates_it_again():
    r = rig(8000, mode=0b00)
    r.c3 = C3.Direction_Neg
    r.start()
    r.step(200)
    r.start()  # a new rising edge: "The reference run is newly initiated"
    assert r.has(S1.Start_ACK) is False and r.has(S2.Busy)
    r.until(lambda: r.has(S2.Reference_OK), 20000)
    latched_at(r, REF_LO)


def test_stop2_n_during_the_run_ends_it_without_reference():
    r = rig(8000, mode=0b00)
    r.c3 = C3.Direction_Neg
    r.start()
    r.step(100)
    r.c1 &= ~C1.Stop2_N
    r.until(lambda: not r.has(S1.Stop_N_ACK), 2000)
    assert not r.has(S2.Reference_OK) and not r.has(S2.Busy) and r.error == 0
    r.c1 |= C1.Stop2_N
    r.step()
    assert r.has(S1.Stop_N_ACK)
