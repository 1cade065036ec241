"""ClmAxis on a real Machine with the simulated plant: a servo slide on the +-10 V path.

The rig: 10 mm feed constant, 3000 RPM at 10 V (500 mm/s full speed, Ax06 = 500), Kv = 1,
Ax08 = 2000 mm/s², the amplifier scaled like Ax12 (50 mm/s per volt, 2 ms velocity loop), an
encoder of 1000 increments/mm, NC cycle 2 ms. Each machine cycle the CLM axis ticks in LOGIC
(as the NC runtime does), before the set points.
"""

from __future__ import annotations

from fractions import Fraction

import pytest

from axisline.config import parse_machine
from axisline.devices.clm.axis import DRIVE_OUTPUTS, ClmAxis
from axisline.devices.clm.errors import ClmError
from axisline.devices.clm.image import ProcessImage
from axisline.devices.clm.operands import parse_operand
from axisline.devices.clm.parameters import ParameterSet
from axisline.kernel import Stage
from axisline.machine import Machine
from axisline.motion.axis import AxisState

T = 0.002
BASE = {
    "A100": "1 0 0 0 1",  # linear, normal feed axis
    "A101": "0010.00000",  # 10 mm per revolution
    "A106": "000500.000",  # = possible Vmax 3000 / 60 x 10
    "A107": "000100.000",
    "A108": "002000",
    "A109": "000 000",
    "A111": "01.00 0",
    "A112": "03000 10.0",
    "A114": "0 010 00.00.0",  # window 10 % of 3000 x 10 / 1000 = 3 mm
    "A127": "Q1.00.2 0000.100",
}


class Rig:
    def __init__(self, params: dict[str, str] | None = None, *, drive: dict | None = None, encoder: dict | None = None,
                 mode: str = "automatic", number: int = 1, axes: int = 1) -> None:
        d = {"type": "servo", "command": "analog", "time_constant": 0.002, "velocity_per_volt": 50.0}
        d.update(drive or {})
        e = {"lines_per_unit": 250.0, "multiplier": 4}
        e.update(encoder or {})
        data = {
            "machine": {"cycle_us": int(T * 1e6), "duration": 30.0},
            "axis": [{"name": f"ax{n}", "unit": "mm", "counts_per_unit": 1000.0, "v_max": 1000.0, "a_max": 100000.0,
                      "following_error_limit": 1000.0, "drive": d, "encoder": e} for n in range(1, axes + 1)],
            "trace": {"enabled": False},
        }
        self.m = Machine(parse_machine(data, "clm_axis_test.toml"))
        self.ps = ParameterSet()
        for pid, value in {**BASE, **(params or {})}.items():
            self.ps.set(pid.replace("A1", f"A{number}", 1) if pid.startswith("A1") else pid, value)
        self.image = ProcessImage()
        self.ax = ClmAxis(number, self.m, f"ax{number}", self.ps, self.image, T)
        self.mode, self.enable, self.estop = mode, True, True
        self.errors: list[ClmError] = []
        self.m.scheduler.add_task("clm", self._tick, Stage.LOGIC)

    def _tick(self, cycle: int) -> None:
        err = self.ax.tick(self.mode, self.enable, self.estop)
        if err is not None:
            self.errors.append(err)

    def run(self, seconds: float) -> None:
        self.m.scheduler.run(round(seconds / T))

    def run_until(self, predicate, seconds: float = 10.0) -> int:
        """Cycles run until predicate() holds (checked after each cycle); fails after `seconds`."""
        for n in range(1, round(seconds / T) + 1):
            self.m.scheduler.run_cycle()
            if predicate():
                return n
        raise AssertionError(f"not within {seconds} s: {self.ax!r}")

    def trace(self, seconds: float, *names: str) -> list[tuple[float, ...]]:
        rows = []
        for _ in range(round(seconds / T)):
            self.m.scheduler.run_cycle()
            rows.append(tuple(getattr(self.ax.axis, n) for n in names))
        return rows

    def out(self, text: str) -> int:
        return self.image.get(parse_operand(text, bit=True))

    def settle(self) -> None:
        self.run_until(lambda: self.ax.in_position)


def started(**kw) -> Rig:
    rig = Rig(**kw)
    rig.run(0.01)
    return rig


# --------------------------------------------------------------------------- positioning


@pytest.mark.parametrize("per_mille", [999, 600, 100])
def test_poi_reaches_target_at_per_mille_of_ax06(per_mille):
    """POI (L2280-2298) at vvv per mille of Ax06: 999 = 99.9 % (PBK text L2230, errata §3.2);
    the axis ends at the target within Ax27 (L4774)."""
    rig = started()
    rig.ax.position_incremental(200_000, per_mille)
    rows = rig.trace(4.5, "command_velocity")
    assert max(v for (v,) in rows) == pytest.approx(per_mille / 1000 * 500.0, rel=1e-9)
    assert rig.ax.motion_done and rig.ax.in_position
    assert rig.ax.command_position == 200.0 and rig.ax.actual_position == pytest.approx(200.0, abs=0.01)
    assert rig.errors == []


def test_poi_is_additive_to_the_running_target():
    """L2287-2291: "The drive unit traverses the distance: -100 +200 = +100" (POI then PSI)."""
    rig = started()
    rig.ax.position_incremental(-100_000, 999)
    rig.run(0.01)
    rig.ax.position_incremental(200_000, 999)
    rows = rig.trace(2.0, "command_position")
    assert min(p for (p,) in rows) > -100.0  # the first target was extended, never reached
    assert rig.ax.target == 100.0 and rig.ax.command_position == 100.0


def test_poa_examples_move_to_the_absolute_position():
    """POA (L2244-2260): from -100 to +200 is 300 forward; from +400 to +200 is 200 backward."""
    rig = started()
    rig.ax.homed = True
    rig.ax.set_actual(-100.0)
    rig.ax.position_absolute(200_000, 999)
    rig.settle()
    assert rig.ax.command_position == 200.0
    rig.ax.set_actual(400.0)
    rig.ax.position_absolute(200_000, 999)
    rows = rig.trace(2.0, "command_velocity")
    assert min(v for (v,) in rows) < 0.0 and rig.ax.command_position == 200.0


def test_poa_errors_48_50_51():
    """POA needs a reference, else "Not homed" (L2265, code 48); a target beyond Ax03 / Ax04 is
    "Target Pos < Lim" / "> Lim" (L4298, spec §7.2: 50 / 51), checked on target x FAK (L1927)."""
    rig = started(params={"A103": "-000100.000", "A104": "+000300.000"})
    with pytest.raises(ClmError) as e:
        rig.ax.position_absolute(10_000, 999)
    assert e.value.code == "48"
    rig.ax.homed = True
    with pytest.raises(ClmError) as e:
        rig.ax.position_absolute(-100_001, 999)
    assert e.value.code == "50"
    with pytest.raises(ClmError) as e:
        rig.ax.position_absolute(300_001, 999)
    assert e.value.code == "51"
    rig.ax.set_factor(2_000_000)
    with pytest.raises(ClmError) as e:
        rig.ax.position_absolute(150_001, 999)  # x 2.000000 = 300.002
    assert e.value.code == "51"
    rig.ax.position_absolute(150_000, 999)  # = 300.000: on the limit is allowed
    assert rig.ax.target == 300.0
    # an absolute encoder is a reference of its own (L2265)
    rig2 = started(params={"A120": "0 1 12 1"})
    rig2.ax.position_absolute(10_000, 999)
    assert rig2.ax.target == 10.0


def test_axis_2_uses_its_own_parameters_and_codes():
    """Axis codes per axis (spec §7.2: 78 = Axis 2 not Homed); B000 enables axis 2 (L4158)."""
    rig = Rig(params={"B000": "1 0 0"}, number=2, axes=2)
    with pytest.raises(ClmError) as e:
        rig.ax.position_absolute(10_000, 999)
    assert e.value.code == "78"


def test_acc_changes_the_ramp():
    """ACC (L1405-1431, Fig. 5-3): 999 = 99.9 % of Ax08 (errata §3.2), 500 = 50 %; 000 = Ax08
    as in Ax09 (L4412). New values apply to the following moves; a move already running keeps
    its ramp (L1454). Mode change / error: back to Ax09 (L1413)."""
    rig = started()
    rig.ax.set_acceleration(999, 999)
    rig.ax.position_incremental(200_000, 999)
    rows = rig.trace(0.01, "command_acceleration")
    assert max(a for (a,) in rows) == pytest.approx(1998.0)
    rig.ax.set_acceleration(500, 999)  # while moving: the running move keeps 1998
    rows = rig.trace(2.0, "command_acceleration")
    assert min(a for (a,) in rows) == pytest.approx(-1998.0)
    rig.settle()
    rig.ax.position_incremental(300_000, 999)  # PSI at 50 % acceleration
    rows = rig.trace(3.0, "command_acceleration")
    assert max(a for (a,) in rows) == pytest.approx(1000.0)
    assert min(a for (a,) in rows) == pytest.approx(-1998.0)
    rig.ax.set_acceleration(0, 250)
    assert rig.ax.acceleration == 2000.0 and rig.ax.deceleration == 500.0
    rig.ax.reset_defaults()
    assert rig.ax.acceleration == 2000.0 and rig.ax.deceleration == 2000.0  # Ax09 000 000 = Ax08


def test_ax10_jerk_time_rounded_up_to_a_power_of_two_cycles():
    """Ax10 (L4424-4430): jerk constant x 1000 / cycle (ms) = 2^n, rounded up: 10 ms at 2 ms is
    5 cycles -> 8 cycles = 16 ms for the acceleration to build up."""
    rig = started(params={"A110": "0.010"})
    rig.ax.position_incremental(200_000, 999)
    rows = rig.trace(0.05, "command_acceleration")
    first_full = next(i for i, (a,) in enumerate(rows) if a >= 2000.0 - 1e-6)
    assert first_full == 7  # rows[k] is the set point at (k + 1) x 2 ms: full at 16 ms
    assert 0.0 < rows[3][0] < rows[6][0] < 2000.0
    rig.settle()
    assert rig.ax.command_position == 200.0


def test_fak_scales_the_next_positionings():
    """FAK (L1913-1945, Fig. 5-13): PSI 100 = 100, after FAK 1.234500 = 123.45, after FAK
    1.000300 = 100.03, exactly; a move in progress keeps its length (L1931)."""
    rig = started()
    start = Fraction(0)
    for factor, length in ((1_000_000, "100"), (1_234_500, "123.45"), (1_000_300, "100.03")):
        rig.ax.set_factor(factor)
        rig.ax.position_incremental(100_000, 999)
        rig.settle()
        assert rig.ax.exact_target == start + Fraction(length)
        start = rig.ax.exact_target
    assert start == Fraction("323.48") and rig.ax.command_position == pytest.approx(323.48, abs=1e-12)
    rig.ax.position_incremental(100_000, 999)
    rig.run(0.05)
    rig.ax.set_factor(2_000_000)  # the running move is not affected
    rig.settle()
    assert rig.ax.exact_target == Fraction("423.51")  # 1.000300 still in force


def test_pbk_discards_the_rest_and_poi_adds_to_the_stop_point():
    """PBK example (L2223-2230): CON 1 1 +999, WAI 2 s, PBK 1, POI 1 +50 100: "the axis still
    moves over the deceleration distance from V = 99.9 % to V = 0 plus 50 IU ... a continuous
    transition from V = 99.9 % to V = 10 %"; PBK also discards a positioning's rest (L2219)."""
    rig = started()
    rig.ax.continuous(True, 999)
    rig.run(2.0)
    p0, v0 = rig.ax.command_position, rig.ax.axis.command_velocity
    assert v0 == pytest.approx(499.5)
    rig.ax.stop_motion()
    stop = rig.ax.target
    assert stop == pytest.approx(p0 + v0 * v0 / (2 * 2000.0), abs=v0 * T)
    rig.run(T)
    rig.ax.position_incremental(50_000, 100)
    rows = rig.trace(5.0, "command_velocity")
    moving = [v for (v,) in rows if v > 0.0]
    assert min(moving[: len(moving) // 2]) == pytest.approx(50.0)  # 99.9 % -> 10 %, never 0
    assert rig.ax.command_position == pytest.approx(stop + 50.0, abs=1e-9)
    # PBK during a POI: the remaining travel is ignored
    rig.ax.position_incremental(400_000, 999)
    rig.run(0.3)
    rig.ax.stop_motion()
    rig.settle()
    assert rig.ax.command_position < stop + 50.0 + 400.0 - 50.0
    assert rig.ax.target == rig.ax.command_position and rig.ax.remaining_distance == pytest.approx(0.0, abs=0.1)


def test_immediate_stop_and_resume_lose_no_dimension():
    """Immediate Stop (L5879) / JST (L2077): decelerate with the programmed deceleration, the
    remaining travel is stored and executed first after the next start: no loss of dimensions."""
    rig = started()
    rig.ax.position_incremental(300_000, 999)
    rig.run(0.2)
    rig.ax.immediate_stop()
    rig.run(1.0)
    assert rig.ax.axis.command_velocity == 0.0 and not rig.ax.motion_done and not rig.ax.in_position
    rest = rig.ax.remaining_distance
    assert 50.0 < rest < 300.0
    rig.ax.resume()
    rig.settle()
    assert rig.ax.command_position == 300.0 and rig.ax.target == 300.0
    # CON is switched off by JST / Immediate Stop, not kept (L2077)
    rig.ax.continuous(True, 500)
    rig.run(0.5)
    rig.ax.immediate_stop()
    rig.run_until(lambda: rig.ax.motion_done)
    rig.ax.resume()
    rig.run(0.2)
    assert rig.ax.axis.command_velocity == 0.0


def test_move_waits_for_drive_enable():
    """Without Drive Enable nothing moves (Inhibit Operation, L5918): the positioning starts
    when the drive is enabled."""
    rig = started(mode="manual")
    rig.enable = False
    rig.run(0.01)
    rig.ax.position_incremental(20_000, 999)
    rig.run(0.2)
    assert rig.ax.actual_position == pytest.approx(0.0, abs=0.01) and not rig.ax.in_position
    rig.enable = True
    rig.settle()
    assert rig.ax.command_position == 20.0


# --------------------------------------------------------------------------- the loop


@pytest.mark.parametrize("kv", ["01.00", "02.00"])
def test_steady_lag_follows_the_kv_formula(kv):
    """Kv = 1 gives 1 mm of lag at 1 m/min (L4461; errata §1.1: v[IU/s] = Kv x 1000/60 x lag).
    At 600 per mille of 500 mm/s = 18 m/min: 18 mm / Kv. The command voltage is v / (Ax12 RPM /
    60 x Ax01) x Ax12 volts (L4473-4482): 300 / 500 x 10 V = 6 V."""
    rig = started(params={"A111": f"{kv} 0"})
    rig.ax.continuous(True, 600)
    rig.run(1.5)
    k = float(kv)
    assert rig.ax.lag == pytest.approx(18.0 / k, abs=0.01)
    assert rig.ax.volts == pytest.approx(6.0, abs=0.002)
    assert rig.ax.actual_velocity == pytest.approx(300.0, rel=1e-3)
    assert rig.ax.rpm == pytest.approx(1800.0, rel=1e-3)  # 300 mm/s / 10 mm x 60
    assert rig.errors == []


@pytest.mark.parametrize("feedforward", [1, 3])
def test_feed_forward_removes_the_steady_lag(feedforward):
    """Ax11 feedforward 1 = on, 3 = on with the average of 4 values (L4443-4447): the set-point
    velocity goes straight to the drive, no lag is needed at constant speed."""
    rig = started(params={"A111": f"01.00 {feedforward}"})
    rig.ax.continuous(True, 600)
    rig.run(1.5)
    assert abs(rig.ax.lag) < 0.02


def test_excess_lag_when_the_drive_cannot_follow():
    """Ax14 (L4518-4532): window = 10 % of 3000 RPM x 10 mm / (1000 x Kv) = 3 mm; a drive that
    runs at most 200 mm/s under a 499.5 mm/s set point is "Excess Pos Lag" 43 (spec §7.2);
    Drive Enable goes off at once (spec §7.1) and the homed state is lost (errata §3.8)."""
    rig = started(drive={"max_velocity": 200.0})
    rig.ax.homed = True
    rig.ax.position_incremental(400_000, 999)
    rig.run_until(lambda: bool(rig.errors), 2.0)
    assert [e.code for e in rig.errors] == ["43"]
    assert rig.ax.window == pytest.approx(3.0)
    assert not rig.ax.drive_enabled and rig.ax.axis.state is AxisState.DISABLED
    assert rig.out("Q0.00.3") == 0 and rig.out("Q0.00.4") == 0
    assert not rig.ax.homed
    rig.run(0.5)
    assert len(rig.errors) == 1 and not rig.ax.drive_enabled  # latched until cleared
    rig.ax.clear_fault()
    rig.run(0.01)
    assert rig.ax.drive_enabled


def test_runaway_with_a_reversed_encoder():
    """"Drive Runaway" (L4520) with a wrong direction (spec §5.2 causes): the encoder counts
    backwards, the loop drives away: 42."""
    rig = started(encoder={"direction": -1})
    rig.ax.position_incremental(100_000, 500)
    rig.run_until(lambda: bool(rig.errors), 2.0)
    assert [e.code for e in rig.errors] == ["42"]


def test_ax21_turns_a_reversed_encoder_round():
    """Ax21 (decision 27, L8731): the encoder counting backwards (the runaway above) is set
    right with the first digit: the feed reaches its target, the plant encoder counting down."""
    rig = started(encoder={"direction": -1}, params={"A121": "1 0 0"})
    rig.ax.position_incremental(100_000, 500)
    rig.run_until(lambda: rig.ax.in_position, 3.0)
    assert rig.errors == []
    assert rig.ax.actual_position == pytest.approx(100.0, abs=0.1)
    unit = rig.m.units["ax1"]
    assert unit.drive.position == pytest.approx(100.0, abs=0.1)  # the slide moved forward
    assert unit.encoder.counts < 0  # while its encoder counted down (mounted the other way)


def test_ax21_output_alone_runs_away():
    """Ax21 (decision 27): a turned output on a correctly wired axis is the manual's runaway
    cause 1 (L4565 "Ax21 'Direction' conflicts with the encoder wiring or the command value"): 42."""
    rig = started(params={"A121": "0 1 0"})
    rig.ax.position_incremental(100_000, 500)
    rig.run_until(lambda: bool(rig.errors), 2.0)
    assert [e.code for e in rig.errors] == ["42"]


def test_ax21_both_reverse_the_motion():
    """Ax21 "1 1 0" (decision 27, "Designated directions can be combined"): the program's +100
    moves the slide 100 backwards, and the CLM reads +100 there."""
    rig = started(params={"A121": "1 1 0"})
    rig.ax.position_incremental(100_000, 500)
    rig.run_until(lambda: rig.ax.in_position, 3.0)
    assert rig.errors == []
    assert rig.ax.actual_position == pytest.approx(100.0, abs=0.1)
    assert rig.m.units["ax1"].drive.position == pytest.approx(-100.0, abs=0.1)


def test_ax14_output_instead_of_the_message():
    """Ax14 mode 1 (L4504, L4512): messages off, the output "Position error > Max. allowable
    deviation" is set instead."""
    rig = started(params={"A114": "1 010 Q1.00.5"}, drive={"max_velocity": 200.0})
    rig.ax.position_incremental(400_000, 999)
    rig.run_until(lambda: rig.out("Q1.00.5") == 1, 2.0)
    assert rig.errors == [] and rig.ax.drive_enabled


def test_cpl_clears_the_lag():
    """CPL (L1794-1800): the position lag is set to zero once: set point := actual."""
    rig = started(drive={"max_velocity": 100.0}, params={"A114": "1 010 00.00.0"})
    rig.ax.position_incremental(100_000, 999)
    rig.run(0.3)
    assert rig.ax.lag > 20.0
    rig.ax.clear_lag()
    assert rig.ax.lag == 0.0 and rig.ax.target == rig.ax.actual_position
    rig.run(0.5)
    assert abs(rig.ax.lag) < 0.5 and rig.errors == []


# --------------------------------------------------------------------------- outputs, enable


def test_in_position_per_ax27():
    """PSA (L2307-2320): in position when the target is reached within the switching threshold
    Ax27; the output programmed in Ax27 follows (L4769-4774). While the set point still runs the
    move is not complete (L2328), even with the actual position inside the threshold."""
    rig = started(params={"A127": "Q1.00.2 0020.000"})
    rig.ax.position_incremental(100_000, 999)
    seen = []
    for _ in range(round(1.0 / T)):
        near = abs(100.0 - rig.ax.actual_position) <= 20.0
        state = (near, rig.ax.motion_done, rig.ax.in_position)
        rig.m.scheduler.run_cycle()  # the tick writes the output from the state the cycle starts with
        seen.append((*state, rig.out("Q1.00.2")))
    assert any(near and not done for near, done, _, _ in seen)
    assert all(inpos == (near and done) and out == inpos for near, done, inpos, out in seen)
    assert seen[-1][2]
    # a tight threshold: in position only once the actual is within 0.1 mm
    rig2 = started()
    rig2.ax.position_incremental(100_000, 999)
    rig2.run_until(lambda: rig2.ax.motion_done)
    assert not rig2.ax.in_position  # the lag is still being pulled in
    rig2.settle()
    assert abs(100.0 - rig2.ax.actual_position) <= 0.1
    rig2.run(T)
    assert rig2.out("Q1.00.2") == 1


def test_drive_enable_and_brake_with_200_ms_delay():
    """Drive Enable in Manual/Automatic with E-Stop and Enable Axis x (L6027-6033); the brake
    is released 200 ms after Drive Enable (L6058) and applied at once with it (L6060); axis 1
    Q0.00.3 / Q0.00.4 (spec §6.3)."""
    rig = Rig(mode="parameter")
    rig.run(0.1)
    assert (rig.out("Q0.00.3"), rig.out("Q0.00.4")) == (0, 0) and not rig.ax.axis.powered
    rig.mode = "manual"
    rig.run(T)
    assert (rig.out("Q0.00.3"), rig.out("Q0.00.4")) == (1, 0) and rig.ax.axis.powered
    rig.run(0.2 - T)  # 99 cycles = 198 ms after the enable
    assert rig.out("Q0.00.4") == 0
    rig.run(T)  # 200 ms
    assert rig.out("Q0.00.4") == 1
    rig.enable = False
    rig.run(T)
    assert (rig.out("Q0.00.3"), rig.out("Q0.00.4")) == (0, 0) and not rig.ax.axis.powered
    rig.enable = True
    rig.run(0.1)
    rig.estop = False
    rig.run(T)
    assert (rig.out("Q0.00.3"), rig.out("Q0.00.4")) == (0, 0)
    rig.estop = True
    rig.run(0.3)
    rig.ax.fault_stop()
    assert (rig.out("Q0.00.3"), rig.out("Q0.00.4")) == (0, 0)
    assert rig.errors == []


def test_drive_outputs_of_axes_2_to_4():
    """Spec §6.3 / L6010-6052: Q0.00.6/Q0.00.7, Q0.01.6/Q0.02.0, Q0.01.7/Q0.02.1."""
    assert [(str(e), str(b)) for e, b in DRIVE_OUTPUTS.values()] == [
        ("Q0.00.3", "Q0.00.4"), ("Q0.00.6", "Q0.00.7"), ("Q0.01.6", "Q0.02.0"), ("Q0.01.7", "Q0.02.1")]
    rig = Rig(params={"B000": "1 0 0"}, number=2, axes=2, mode="manual")
    rig.run(0.21)
    assert (rig.out("Q0.00.6"), rig.out("Q0.00.7"), rig.out("Q0.00.3")) == (1, 1, 0)


def test_automatic_without_enable_is_40():
    """L6039: "In Automatic Mode, Drive Enable must be present for activated axes (at all times
    for Axis 1) ... Otherwise, the error message 'Drive not ready'" (40)."""
    rig = started()
    rig.enable = False
    rig.run(T)
    assert [e.code for e in rig.errors] == ["40"]
    rig.mode = "manual"
    rig.ax.clear_fault()
    rig.run(0.1)
    assert len(rig.errors) == 1  # Manual: no fault, the drive is just off


def test_jog_at_ax07_stops_at_the_limit():
    """Jog forward/reverse at Ax07 in Manual (L5901-5916); homed, the jog key becomes inactive at
    the travel limit (L4294, L4330); not homed there are no limits (L4292 "only in Absolute Mode")."""
    rig = started(mode="manual", params={"A104": "+000050.000", "A103": "-000010.000"})
    rig.ax.homed = True
    rows = []
    for _ in range(round(1.0 / T)):
        rig.ax.jog(1)
        rig.m.scheduler.run_cycle()
        rows.append(rig.ax.axis.command_velocity)
    assert max(rows) == pytest.approx(100.0) and rig.ax.command_position == 50.0
    rig.ax.jog(1)
    rig.run(0.2)
    assert rig.ax.command_position == 50.0  # dead at the limit
    rig.ax.jog(0)
    rig.ax.jog(-1)
    rig.run(0.2)
    rig.ax.jog(0)
    rig.run_until(lambda: rig.ax.motion_done)
    assert 20.0 < rig.ax.command_position < 50.0
    rig.ax.homed = False
    rig.ax.jog(1)
    rig.run(0.8)
    assert rig.ax.command_position > 50.0
    rig.ax.jog(0)
    rig.run_until(lambda: rig.ax.motion_done)
    assert rig.ax.axis.state is AxisState.STANDSTILL


def test_jog_zero_does_not_stop_a_program_move():
    """The jog keys released (jog(0) every cycle) leave a Task 3 positioning alone."""
    rig = started(mode="manual")
    rig.ax.position_incremental(100_000, 999)
    for _ in range(round(1.0 / T)):
        rig.ax.jog(0)
        rig.m.scheduler.run_cycle()
    assert rig.ax.command_position == 100.0


def test_travel_limit_fault_in_automatic():
    """Automatic, homed: actual > Ax04 is "Max Travel Lmt" 47 (L4332); CON in the homed state
    must mind Ax03/Ax04 (L1717)."""
    rig = started(params={"A104": "+000020.000"})
    rig.ax.homed = True
    rig.ax.continuous(True, 200)
    rig.run_until(lambda: bool(rig.errors), 2.0)
    assert [e.code for e in rig.errors] == ["47"]
    assert 20.0 < rig.ax.actual_position < 21.0


def test_reset_defaults_on_mode_change():
    """Mode change / error: ACC -> Ax09 (L1413), FAK -> 1 (L1933), CON off (L1721), the kept rest
    dropped (errata §3.8)."""
    rig = started()
    rig.ax.set_acceleration(100, 100)
    rig.ax.set_factor(2_000_000)
    rig.ax.position_incremental(100_000, 999)
    rig.run(0.1)
    rig.ax.immediate_stop()
    rig.run(0.5)
    rig.ax.reset_defaults()
    assert rig.ax.acceleration == 2000.0 and rig.ax.remaining_distance == pytest.approx(0.0, abs=0.05)
    rig.ax.resume()
    rig.run(0.5)
    assert rig.ax.command_position < 100.0 and rig.ax.motion_done
    rig.ax.continuous(True, 100)
    rig.run(0.2)
    rig.ax.reset_defaults()
    rig.run_until(lambda: rig.ax.motion_done)
    assert rig.ax.axis.state is AxisState.STANDSTILL


def test_pbk_stop_point_with_the_ax10_jerk():
    """PBK brakes "using the current deceleration value" (L2219) with the Ax10 jerk (L4428): the
    stop point the next POI adds to is where the set point really stops."""
    rig = started(params={"A110": "0.050"})
    rig.ax.set_acceleration(999, 400)
    rig.ax.continuous(True, 700)
    rig.run(0.3)  # still accelerating
    rig.ax.stop_motion()
    stop = rig.ax.target
    rig.run_until(lambda: rig.ax.motion_done)
    assert rig.ax.command_position == pytest.approx(stop, abs=1e-9)
    assert rig.ax.axis.state is AxisState.STANDSTILL
