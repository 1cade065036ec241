"""Restart (manual §7.11, L3819-3857; RSV L2435-2466; B016 L5204-5214; Re-Start L5920-5927;
Restart possible L6066-6074): the decisions of src/axisline/devices/clm/restart.py on the
runtime (power loss and the plant: test_restart_power.py)."""

from __future__ import annotations

from fractions import Fraction

from axisline.devices.clm.errors import ClmError

from .clmrig import FakeAxis, Rig
from .manual_examples import PROGRAM_LISTINGS

def listing(name: str) -> str:
    """A listing of manual_examples (its instruction rows, heading rows left out)."""
    text = next(e["text"] for e in PROGRAM_LISTINGS if e.get("name") == name)
    return "\n".join(line for line in text.split("\n") if line[:4].isdigit()) + "\n"


STEP = 5000  # the fake axis runs 5 IU per cycle (lengths in 1/1000 IU)


class RAxis(FakeAxis):
    """A fake axis that runs to its target STEP per cycle: stop_motion ends where it is (the
    real axis brakes), a fault drops the motion, move_to is the restart's positioning."""

    def __init__(self, number: int) -> None:
        super().__init__(number)
        self.pos = 0
        self.speed = 0.0
        self.kept = False
        self.off = False
        self.fail: ClmError | None = None
        self.frame_shift = Fraction(0)  # SAC: readings = initial frame + shift

    @property
    def exact_target(self) -> Fraction:
        return Fraction(self.target, 1000)

    def position_incremental(self, distance: int, per_mille: int) -> None:
        self.moves.append(("inc", distance, per_mille))
        self.target += distance * self.factor // 1_000_000
        self.speed = float(per_mille)

    def position_absolute(self, target: int, per_mille: int) -> None:
        self.moves.append(("abs", target, per_mille))
        self.target = target * self.factor // 1_000_000
        self.speed = float(per_mille)

    def move_to(self, goal: Fraction, speed: float | None = None) -> None:
        self.moves.append(("to", goal, speed))
        self.target = int(goal * 1000)
        self.speed = self.speed if speed is None else speed
        self.kept = False

    def per_mille_speed(self, per_mille: int) -> float:
        return float(per_mille)

    def stop_motion(self) -> None:
        self.stops.append("pbk")
        self.target = self.pos

    def immediate_stop(self) -> None:
        self.stops.append("immediate")
        self.kept = True

    def resume(self) -> None:
        self.stops.append("resume")
        self.kept = False

    def fault_stop(self) -> None:
        self.stops.append("fault")
        self.off = True
        self.target = self.pos

    def clear_fault(self) -> None:
        self.stops.append("clear")
        self.off = False
        shift = int(self.frame_shift * 1000)  # the initial frame again (L2510)
        self.pos, self.target, self.frame_shift = self.pos - shift, self.target - shift, Fraction(0)

    def set_actual(self, position: float) -> None:
        self.pos = self.target = round(position * 1000)

    @property
    def motion_done(self) -> bool:
        return self.pos == self.target and not self.kept

    in_position = motion_done

    def tick(self, mode: str, enable_input: bool, estop_ok: bool):
        if not (self.kept or self.off):
            self.pos += max(-STEP, min(STEP, self.target - self.pos))
        self.actual_position = self.pos / 1000
        fail, self.fail = self.fail, None
        return fail


def rig(program: str, **kw) -> Rig:
    r = Rig(program, **kw)
    for n in list(r.axes):
        r.axes[n] = RAxis(n)
    r.run()  # power on
    return r


def pulse(r: Rig, name: str) -> None:
    r.set(name, 1)
    r.run()
    r.set(name, 0)


def restart(r: Rig) -> None:
    pulse(r, "I0.01.6")


def clear(r: Rig) -> None:
    pulse(r, "I0.00.7")


def run_until(r: Rig, done, limit: int = 2000) -> None:
    for _ in range(limit):
        if done():
            return
        r.run()
    raise AssertionError("not reached")


FEED = "0000 AEA Q1.00.2 1\n0001 PSI 1 +000100.000 999\n0002 AEA Q1.00.0 1\n0003 JST 0003\n"


def interrupted_feed(cycles: int = 8, program: str = FEED, **kw) -> Rig:
    r = rig(program, **kw)
    r.start()
    r.run(cycles)
    assert 0 < r.axes[1].pos < 100_000
    return r


# -- decision 1: the image; a feed goes on to the same absolute target -----------------------------


def test_feed_interrupted_by_manual_reaches_the_same_target():
    """L3821 "continues a program interrupted by ... a switch from Automatic to Manual Mode",
    L3827 "absolute target position": the feed of 100 is interrupted at about 40, the axis
    stops there; Re-Start makes it go on to 100 (no lost dimension, no second 100)."""
    r = interrupted_feed()
    r.set_mode("manual")
    r.run(3)
    stopped = r.axes[1].pos
    assert stopped < 100_000 and r.axes[1].target == stopped  # braked where it was
    assert r.bit("Q0.01.0") == 1  # "can also be set in Manual Mode" (L6074)
    r.set_mode("automatic")
    r.run()
    restart(r)
    run_until(r, lambda: r.bit("Q1.00.0") == 1)
    axis = r.axes[1]
    assert axis.pos == 100_000 and axis.moves.count(("inc", 100_000, 999)) == 1
    assert ("to", Fraction(100), 999.0) in axis.moves
    assert r.bit("Q1.00.2") == 1 and r.rt.tasks[0].pc == 3 and r.bit("Q0.01.0") == 0


def test_start_instead_of_restart_feeds_again_from_0000():
    """The counter-case (§5.5): Start after the mode change begins at 0000 and gives up the
    image: a second full feed from the stop point (decision 6)."""
    r = interrupted_feed()
    r.set_mode("manual")
    r.run(3)
    stopped = r.axes[1].pos
    r.set_mode("automatic")
    r.run()
    r.start()
    assert r.bit("Q0.01.0") == 0
    run_until(r, lambda: r.bit("Q1.00.0") == 1)
    assert r.axes[1].pos == stopped + 100_000


def test_image_holds_stack_outputs_markers_acc_fak():
    """Decision 1: stack, outputs, M2, ACC, FAK and FAK 5 come back with the restart."""
    program = ("0000 ACC 1 500 400\n0001 FAK 1 2.000000\n0002 FAK 5 1.500000\n0003 AEA M2.00.3 1\n0004 AEA Q1.01.1 1\n"
               "0005 JSR 0010\n0006 AEA Q1.00.0 1\n0007 JST 0007\n"
               "0010 PSI 1 +000050.000 999\n0011 RTS\n")
    r = rig(program)
    r.start()
    r.run(10)
    assert r.rt.tasks[0].pc == 10 and r.rt.tasks[0].stack == [6]
    r.set_mode("manual")
    r.run()
    assert r.bit("M2.00.3") == 0 and r.axes[1].factor == 1_000_000  # cleared / reset by the mode change
    r.set_mode("automatic")
    r.run()
    restart(r)
    assert r.bit("M2.00.3") == 1 and r.bit("Q1.01.1") == 1
    assert r.axes[1].acceleration == (500, 400) and r.axes[1].factor == 2_000_000 and r.rt.master_factor == 1_500_000
    run_until(r, lambda: r.bit("Q1.00.0") == 1)
    assert r.axes[1].pos == 100_000  # 50 x FAK 2, once


def test_wai_waits_its_full_time_again():
    """Decision 1: a command that waited starts again (WAI: its whole time)."""
    r = rig("0000 AEA Q1.00.2 1\n0001 WAI 00.100\n0002 AEA Q1.00.0 1\n0003 JST 0003\n")
    r.start()
    r.run(30)
    r.set_mode("manual")
    r.run()
    r.set_mode("automatic")
    r.run()
    restart(r)
    r.run(48)
    assert r.bit("Q1.00.0") == 0
    r.run(3)
    assert r.bit("Q1.00.0") == 1


# -- errors, E-Stop, and what is no restart (decisions 2-4) -----------------------------------------


def test_error_then_restart_restores_the_cleared_outputs():
    """L3821 "an error message": E-Stop (03) mid-feed clears the outputs (B018 default); after
    the clear, Re-Start sets them again and the feed goes on to 100."""
    r = interrupted_feed()
    r.set("I0.00.2", 0)
    r.run()
    assert r.fault == "03" and r.bit("Q1.00.2") == 0 and r.bit("Q0.01.0") == 1
    r.set("I0.00.2", 1)
    clear(r)
    assert r.fault is None and r.bit("Q0.01.0") == 1
    restart(r)
    assert r.bit("Q1.00.2") == 1
    run_until(r, lambda: r.bit("Q1.00.0") == 1)
    assert r.axes[1].pos == 100_000


def test_error_during_a_program_stop_is_no_restart():
    """L3837 (a): an error during a program stop (Immediate Stop): no image; Re-Start is then
    Start (L3831), from 0000 after the fault."""
    r = interrupted_feed()
    r.set("I0.00.4", 0)
    r.run()
    assert not r.rt.modes.running
    r.rt.modes.fault(ClmError("0C", "a fault while stopped"))
    r.set("I0.00.4", 1)
    clear(r)
    r.run()
    assert r.bit("Q0.01.0") == 0
    restart(r)
    assert r.rt.modes.running and r.rt.tasks[0].pc == 1  # began at 0000


def test_estop_in_manual_discards_the_image():
    """L3837 (a): an image from the switch to Manual is given up by an E-Stop in Manual."""
    r = interrupted_feed()
    r.set_mode("manual")
    r.run()
    assert r.bit("Q0.01.0") == 1
    r.set("I0.00.2", 0)
    r.run()
    assert r.bit("Q0.01.0") == 0


def test_manual_during_a_program_stop_takes_no_image():
    """L3825 "a program was running in Automatic Mode": Immediate Stop, then Manual: none."""
    r = interrupted_feed()
    r.set("I0.00.4", 0)
    r.run()
    r.set_mode("manual")
    r.run()
    assert r.bit("Q0.01.0") == 0


def test_lag_with_an_incremental_encoder_is_no_restart():
    """L3838 (b): Excess Pos Lag (43) on axis 1 with an incremental encoder (A120 type 0): no
    image; with an absolute encoder (type 2) a restart is possible."""
    for a120, possible in (("0 0 00 1", 0), ("0 2 24 1", 1)):
        r = interrupted_feed(params={"A120": a120})
        r.axes[1].fail = ClmError("43", "lag")
        r.run()
        assert r.fault == "43" and r.bit("Q0.01.0") == possible, a120


def test_drive_runaway_with_an_incremental_encoder_is_no_restart():
    """L3838 (b): Drive Runaway (42); another fault (Max Travel Lmt 47) keeps the image."""
    for code, possible in (("42", 0), ("47", 1)):
        r = interrupted_feed()
        r.axes[1].fail = ClmError(code, "axis")
        r.run()
        assert r.fault == code and r.bit("Q0.01.0") == possible, code


def test_flying_cutoff_is_no_restart():
    """L3839 (c), L1281: Ax00 mode 5 on axis 1: never an image."""
    r = interrupted_feed(program="0000 AEA Q1.00.2 1\n0001 PSI 1 +000100.000 999\n0002 JMP 0002\n",
                         params={"A100": "0 0 0 5 1", "A111": "01.00 1", "A109": "000 000"})
    assert r.fault is None
    r.set_mode("manual")
    r.run()
    assert r.bit("Q0.01.0") == 0


# -- the input and the output (decisions 5, 6, 12) ----------------------------------------------------


def test_restart_possible_output():
    """Decision 5: Q0.01.0 is 0 while the program runs, 1 from the interruption (in Manual too,
    L6074; while the fault is shown) until the restart, never in the status word (Q2.01.0)."""
    r = rig(FEED)
    assert r.bit("Q0.01.0") == 0
    r.start()
    r.run(5)
    assert r.bit("Q0.01.0") == 0
    r.set_mode("manual")
    r.run()
    assert r.bit("Q0.01.0") == 1 and r.bit("Q2.01.0") == 0
    r.set_mode("automatic")
    r.run()
    assert r.bit("Q0.01.0") == 1
    restart(r)
    assert r.bit("Q0.01.0") == 0 and r.bit("Q0.01.1") == 1  # Run Task


def test_restart_only_in_automatic():
    """L5925 "This input is available only in Automatic Mode": an edge in Manual does nothing."""
    r = interrupted_feed()
    r.set_mode("manual")
    r.run()
    restart(r)
    assert not r.rt.modes.running and r.bit("Q0.01.0") == 1


def test_restart_without_an_image_is_start():
    """L3831: no Restart possible -> Re-Start is Start: the program begins; after Immediate
    Stop it continues there."""
    r = rig(FEED)
    restart(r)
    assert r.rt.modes.running and r.bit("Q1.00.2") == 1
    r.set("I0.00.4", 0)
    r.run()
    r.set("I0.00.4", 1)
    r.run()
    restart(r)
    run_until(r, lambda: r.bit("Q1.00.0") == 1)
    assert r.axes[1].pos == 100_000


def test_start_discards_the_image():
    """Decision 6."""
    r = interrupted_feed()
    r.set_mode("manual")
    r.run()
    r.set_mode("automatic")
    r.run()
    r.start()
    r.set_mode("manual")  # now interrupted again: a new image of the new run
    r.run()
    assert r.rt.restart.image.tasks[1].pc == 1


def test_fieldbus_restart_input():
    """Decision 13: I2.01.6 (control word bit 14, L7619) is a Re-Start too."""
    r = interrupted_feed()
    r.set_mode("manual")
    r.run()
    r.set_mode("automatic")
    r.run()
    pulse(r, "I2.01.6")
    run_until(r, lambda: r.bit("Q1.00.0") == 1)
    assert r.axes[1].pos == 100_000


# -- B016 and RSV (decisions 7, 8) ----------------------------------------------------------------


def _after_fault(program: str) -> Rig:
    r = interrupted_feed(program=FEED + program, params={"B016": "2000"})
    r.set("I0.00.2", 0)
    r.run()
    r.set("I0.00.2", 1)
    clear(r)
    assert r.bit("Q1.00.2") == 0 and r.bit("Q0.01.0") == 1
    return r


def test_b016_restart_program_rsv_examples():
    """L2444-2462, B016 = 2000, the three restart programs of the manual (manual_examples
    rsv_program_1..3)."""
    # Program 1 (L2448): "RSV 1 0000 10000 - Terminate Restart Program and completely restore status"
    r = _after_fault(listing("rsv_program_1"))
    stopped = r.axes[1].pos
    restart(r)  # the RSV runs in this cycle; the interrupted program in the next (L2466)
    assert r.bit("Q1.00.2") == 1 and r.rt.tasks[0].pc == 1 and r.axes[1].target == 100_000
    run_until(r, lambda: r.bit("Q1.00.0") == 1)
    assert r.axes[1].pos == 100_000 and stopped < 100_000

    # Program 2 (L2453-2455): wait for I1.00.4, 1 s, then restore completely
    r = _after_fault(listing("rsv_program_2"))
    stopped = r.axes[1].pos
    restart(r)
    r.run(20)
    assert r.rt.tasks[0].pc == 2000 and r.axes[1].pos == stopped and r.bit("Q1.00.2") == 0
    assert r.bit("Q0.01.0") == 1 and r.bit("Q0.01.1") == 1  # the restart has not happened yet
    r.set("I1.00.4", 1)
    r.run(400)
    assert r.axes[1].pos == stopped and r.rt.tasks[0].pc == 2001  # "not initiated until the end" (L3850)
    run_until(r, lambda: r.bit("Q1.00.0") == 1)
    assert r.axes[1].pos == 100_000 and r.bit("Q1.00.2") == 1 and r.bit("Q0.01.0") == 0

    # Program 3 (L2459-2462): outputs first, then wait, then the rest "except for outputs"
    r = _after_fault(listing("rsv_program_3"))
    stopped = r.axes[1].pos
    restart(r)
    assert r.bit("Q1.00.2") == 1 and r.rt.tasks[0].pc == 2001 and r.axes[1].pos == stopped
    r.set("I1.00.4", 1)
    run_until(r, lambda: r.bit("Q1.00.0") == 1)
    assert r.axes[1].pos == 100_000 and r.bit("Q1.00.2") == 1


def test_rsv_without_the_outputs_flag_leaves_the_outputs():
    """Decision 8: RSV 1 0000 00000 alone restores all but the outputs."""
    r = _after_fault("2000 RSV 1 0000 00000\n")
    restart(r)
    run_until(r, lambda: r.axes[1].pos == 100_000 and r.rt.tasks[0].pc == 3)
    assert r.bit("Q1.00.2") == 0 and r.bit("Q1.00.0") == 1


def test_rsv_nnnn_continues_task_1_there():
    """Decision 8: nnnn > 0 is where Task 1 goes on (the axes still restored)."""
    r = _after_fault("0005 AEA Q1.01.0 1\n0006 JMP 0006\n2000 RSV 1 0005 10000\n")
    restart(r)
    r.run(3)
    assert r.bit("Q1.01.0") == 1 and r.bit("Q1.00.0") == 0 and r.rt.tasks[0].pc == 6
    run_until(r, lambda: r.axes[1].pos == 100_000)


def test_rsv_instruction_from_a_variable():
    """L2437 "RSV 1 V600 ...": the instruction field from V600 (= 5), flags as one block."""
    r = _after_fault("0005 AEA Q1.01.0 1\n0006 JMP 0006\n2000 RSV 1 V600 10000\n")
    r.rt.memory.variables.write(600, 5_000_000)
    restart(r)
    r.run(3)
    assert r.bit("Q1.01.0") == 1 and r.rt.tasks[0].pc == 6


def test_rsv_outside_a_restart_program():
    """Decision 8: no function, the next instruction follows."""
    r = rig("0000 RSV 1 0000 10000\n0001 AEA Q1.00.0 1\n0002 JST 0002\n")
    r.start()
    r.run(3)
    assert r.fault is None and r.bit("Q1.00.0") == 1


def test_interrupted_restart_program_keeps_the_image():
    """Decision 7: Manual during the restart program; the image still waits, the next Re-Start
    runs the restart program again."""
    r = _after_fault("2000 AKN I1.00.4 1\n2001 RSV 1 0000 10000\n")
    restart(r)
    r.run(5)
    r.set_mode("manual")
    r.run()
    assert r.bit("Q0.01.0") == 1 and not r.rt.modes.running
    r.set_mode("automatic")
    r.run()
    restart(r)
    assert r.rt.tasks[0].pc == 2000
    r.set("I1.00.4", 1)
    run_until(r, lambda: r.bit("Q1.00.0") == 1)
    assert r.axes[1].pos == 100_000


def test_tasks_2_4_5_wait_during_the_restart_program():
    """Decision 7: only Task 1 runs the restart program; Task 2 goes on after RSV."""
    program = FEED.replace("JST", "JMP") + "0200 AEA Q1.02.0 1\n0201 WAI 00.500\n0202 AEA Q1.02.1 1\n0203 JMP 0203\n2000 AKN I1.00.4 1\n2001 RSV 1 0000 10000\n"
    r = interrupted_feed(program=program, params={"B016": "2000", "B011": "0200 0000 0"})
    r.set_mode("manual")
    r.run()
    r.set_mode("automatic")
    r.run()
    restart(r)
    r.run(400)
    assert r.bit("Q1.02.1") == 0 and r.rt.tasks[1].pc == 201
    r.set("I1.00.4", 1)
    r.run(300)
    assert r.bit("Q1.02.1") == 1


def test_program_change_discards_the_image():
    """Decision 11."""
    r = interrupted_feed()
    r.set_mode("manual")
    r.run()
    r.rt.memory.version += 1  # what a serial write of an instruction does
    r.run(2)
    assert r.bit("Q0.01.0") == 0


def test_parameter_mode_discards_the_image():
    """Decision 2 / 11: Parameter mode (the parameters may change)."""
    r = interrupted_feed()
    r.set_mode("manual")
    r.run()
    r.set_mode("parameter")
    r.run()
    r.set_mode("manual")
    r.run()
    assert r.bit("Q0.01.0") == 0


# -- RMI (decision 9) ---------------------------------------------------------------------------


def test_rmi_raster_processing_is_not_restarted():
    """L2386 "The RMI command is not executed when a restart occurs", Fig. 5-20's program:
    interrupted during the tool program, the restart sends the main feed on to its target
    and Task 2 back to its RMI 1 0 (no offset from the old mark, no RMI 1 1)."""
    r = rig(listing("rmi_fig5_20"), params={"B011": "0200 0000 0"})  # L2404-2431
    r.start()
    r.run(3)
    r.set("I1.01.7", 1)  # the raster during the first feed
    run_until(r, lambda: r.bit("Q1.00.2") == 1)  # the offset is done, the tool works
    assert r.rt.registration.suspended_task == 1
    r.set("I1.01.7", 0)
    r.set_mode("manual")
    r.run()
    image = r.rt.restart.image
    assert image.tasks[2].pc == 200 and image.axes[1].target == Fraction(50)
    r.set_mode("automatic")
    r.run()
    restart(r)
    assert r.rt.tasks[1].pc == 200 and r.rt.registration.suspended_task is None
    run_until(r, lambda: r.bit("Q1.00.0") == 1)  # the main feed reached 50, punching unit 1
    assert r.axes[1].pos == 50_000


def test_sac_frame_change_keeps_the_target():
    """Decision 12: with a SAC shift of +10 the feed's target reads 110; the fault clear goes
    back to the initial frame (L2510), where the same place reads 100: the restart goes there."""
    r = rig(FEED)
    axis = r.axes[1]
    axis.frame_shift, axis.pos, axis.target = Fraction(10), 10_000, 10_000
    r.start()
    r.run(8)
    assert axis.target == 110_000
    r.set("I0.00.2", 0)
    r.run()
    r.set("I0.00.2", 1)
    clear(r)
    restart(r)
    run_until(r, lambda: r.bit("Q1.00.0") == 1)
    assert axis.pos == 100_000 and axis.frame_shift == 0
