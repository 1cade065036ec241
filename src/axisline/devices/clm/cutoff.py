"""CLM1.4 flying cutoff (Ax00 mode 5 on axis 1; manual §7.12 L3858-4030, LML L2119-2131, EOS
L1905-1911, Status 54 L7250-7266, !sCL0 / !sCLL1 / !sCLL2 L7370-7394; spec §4.12).

    rt.cutoff                         # FlyingCutoff when axis 1 is in Ax00 mode 5, else None
    rt.cutoff.lml(task, ins, length)  # LML 1 LLLLLL.LLL: waits until synchronous (cutoff_raster.op_lml)
    rt.cutoff.eos(task)               # EOS: the carriage leaves the material and returns home
    rt.cutoff.material_length, .product_length   # Status 54 (IU)

The parts: this module (the cut cycle, the counters, test mode, C008, C001), `cutoff_inputs`
(A133-A137, A142, indexing), `cutoff_raster` (LMK, LMR), `cutoff_reverse` (A139 / A140),
`material_length` (MLO, MLT), `cutreport` (every cut measured on the simulated material).

A stationary measuring wheel (master encoder 1, master_encoder.py) measures the material; the
carriage (axis 1) carries the tool. Material coordinates: the point of the material under the
tool is ``c = m - s`` (m: master encoder 1's position, s: the carriage's position, home = 0), so
a carriage geared 1:1 to the wheel keeps its tool on one point of the material. For each length
instruction the cut point is the previous one plus the length (plus the A141 tool width); the
carriage is coupled with the kernel's gear in position (`motion.gear_in_position.GearInPos`, the flying
saw) so that it reaches the sync stroke ``s_sync`` at the material's speed exactly when the
wheel passes ``m_sync = c + s_sync``: from there on the integer gear law holds the tool on the
cut point (no drift: counts, not floats). LML proceeds when the carriage is synchronous, the
processing program runs, EOS ends the synchronous phase and the carriage returns home at A106.

Decisions (spec line -> choice, why)
------------------------------------
1. L3866 "When the desired material length has been fed through, the CLM accelerates the
   carriage to synchronize" -> the sync stroke is the distance the carriage needs to reach the
   material speed V with Ax08 (s_sync = V^2 / (2 Ax08), from rest at home); the approach is
   planned when the material still has that acceleration's master distance (2 s_sync) plus 10
   NC cycles of travel to go, with V the speed then (a plan made long before would scale its
   ramps with the speed change in between). The carriage therefore meets the cut point at the
   material speed with one acceleration ramp and no wait. test_lml_meets_the_cut_point_at_line_speed.
2. L3866 "Any fine adjustment of the position to the exact processing location is not linked
   to the material speed" -> a carriage that starts late (its return ended after the planning
   point: a short piece, a fast line) does not cut long: the sync stroke grows (bisection up to
   Ax04) until the approach, faster than the material up to A106, reaches the cut point; only
   when even Ax04 is not enough is it fault 47 "Max Travel Lmt" naming the length.
   test_a_late_carriage_catches_up_the_cut_point.
3. L3883 "the next length" and L3866 -> each length counts from the previous cut point on the
   material (the planned one: the gear holds the tool on it), never from the end of the return;
   the first length of a run counts from the material point under the tool when Automatic is
   switched on (without indexing: L3981-3985, the 1000 mm of a manual cut are not counted).
   test_consecutive_pieces_have_the_programmed_length.
4. L3866 "moves to its original position at maximum speed" -> EOS replans the carriage from its
   synchronous state to position 0 at A106 with the ACC / Ax08 ramps (Ax09 is 000 000 in flying
   cutoff, L3935); LML of the next piece waits until that return has ended.
   test_eos_returns_home_at_a106.
5. L1908 "A processing program must always end with this command" -> error 35 when Task 1 ends
   the processing program (RTS) or reaches the next length instruction while the carriage is
   still synchronous (no EOS since LML). check.py also reports 35 at load.
   test_processing_program_without_eos_is_35.
6. L3931 and spec §4.12 "On switching Manual->Automatic the axis must be at its home position,
   else error 36" -> home = |actual position of axis 1| within the Ax27 switching threshold (the
   window the CLM uses for "in position"); checked when Automatic is selected.
   test_automatic_away_from_home_is_36.
7. L3931, L4955-4962 -> Start and Immediate Stop have no function; Task 1 starts when
   Automatic is selected, at the last length instruction reached minus 1 (0000 before any),
   at 0000 when A138 says always, when the A138 input was seen in Manual, or after !sCL0 in
   Manual; tasks 2, 4, 5 at B011 / B012. After a fault the program starts again the same way
   (Manual, then Automatic). test_auto_start_at_the_old_length_instruction_minus_1.
8. L3990-3994, L7250-7266 -> the counters sum master encoder 1's movement (IU, exact): the
   material length counter in Manual and Automatic, the product length counter in Automatic;
   Status 54 ``54 vmmmmmmmm vpppppppp`` gives both in whole IU (sign + 8 digits, truncated);
   !sCLL1 clears the material, !sCLL2 the product length counter. test_length_counters_and_status_54.
9. A141 (L2127, L4022) -> the tool width is added to every LML length: the distance between
   cut points is length + width, so the piece (less the kerf) has the programmed length.
   test_tool_width_is_added_to_the_length.
10. C008 (L5563-5582: "material velocity from the programmed variable (IU/s), switched
    immediately without ramp", <= A106) -> while the input is 1 the master the carriage is geared
    to runs at the variable's speed (V610 for "610", clipped to 0..A106) from where it is; the
    wheel's counts are replaced, not added, and when the input drops the master goes on from the
    wheel without a jump (the difference is kept). The length counters stay on the wheel.
    tests/devices/clm/test_cutoff_inputs.py::test_no_material_runs_on_the_variable.
11. Test mode (A100's test digit, L3968-3972: "the material feed is simulated by an internal
    clock generator ... increased or decreased in 32 steps between zero and the maximum velocity
    (Parameter A106)"; the display keys) -> the material is a clock at steps/32 x A106 in
    Automatic (the wheel is not read; the length counters count the clock); `test_key("up" |
    "down" | "zero")` are the display's keys (axisline has no front panel: the machine file's
    ``device.test_speed_steps`` presses "up" that many times when the cutoff first runs);
    leaving Automatic sets the speed to 0. test_test_mode_cuts_on_the_internal_clock.
12. C001 averaging (L5485-5493: "0 = off, 1..7 = average of 2, 4, ... 128 values", flying
    cutoff only) -> the master's velocity the carriage is fed forward with and the approach is
    planned for is the mean of the last 2^n NC cycles' count increments; the position stays the
    counts themselves (averaging it would put every cut 2^(n-1) cycles of travel late).
    test_c001_averaging_smooths_the_master_velocity.
"""

from __future__ import annotations

from collections import deque
from fractions import Fraction
from typing import TYPE_CHECKING, Any

from axisline.motion.gear import Gear
from axisline.motion.gear_in_position import GearInPos, GearInPosError

from .cutoff_inputs import CutoffInputs
from .cutoff_raster import RasterWatch, Spot
from .cutoff_reverse import ReverseOptimisation
from .errors import ClmError, axis_fault
from .material_length import LengthCounters

if TYPE_CHECKING:
    from .nc import NcTask

__all__ = ["FlyingCutoff", "WheelMaster", "HOME", "APPROACH", "SYNC", "RETURNING", "HELD"]

HOME, APPROACH, SYNC, RETURNING = "home", "approach", "synchronous", "returning"
HELD = "held"  # stopped after EOS, the return held by the reverse inhibit (cutoff_inputs.py 5)
_PLAN_LEAD_CYCLES = 10  # decision 1: plan this many cycles of material travel before the ramp must start


class WheelMaster:
    """Master encoder 1 as the Gear's master, in the CLM's IU (C002 x FAK 5 / 4 C000 per count).

    Reads the plant wheel when the gear samples (the cycle's own count, not the one the
    personality sampled before the runtime step)."""

    def __init__(self, encoder: Any, averaging: int = 0, cycle_s: float = 0.002) -> None:
        self.encoder = encoder
        self._ring: deque[int] | None = deque(maxlen=2**averaging + 1) if averaging else None  # decision 12
        self._cycle_s = cycle_s
        scale = encoder.scale
        self.source_scale = scale  # the encoder's own object: unchanged while it is the same
        self._sign = -1 if scale < 0 else 1
        self.scale = abs(scale)  # IU per count (Fraction)
        self._num, self._den = self.scale.numerator, self.scale.denominator
        self.counts_per_unit = float(1 / self.scale) if self.scale else 1.0
        self._scale_f = float(self.scale)  # (the velocity's factor, read every cycle)
        self._origin = int(encoder.master.counts)  # (the encoder's own origin is its power on)
        self._base = int(encoder.counts) * self._sign
        self.shift = 0  # counts added by the no-material function (C008, decision 10)
        self.override: float | None = None  # its velocity (IU/s) while the input is on

    def update(self, cycle: int) -> None:
        self.encoder.master.update(cycle)

    @property
    def wheel_counts(self) -> int:
        return self._base + (int(self.encoder.master.counts) - self._origin) * self._sign

    @property
    def counts(self) -> int:  # (wheel_counts + shift in one call: the gear reads it every cycle)
        return self._base + (int(self.encoder.master.counts) - self._origin) * self._sign + self.shift

    @property
    def position(self) -> float:
        # counts x num / den as an int true division: correctly rounded, the same float as
        # float(counts x scale) without a Fraction per cycle
        return self.counts * self._num / self._den

    @property
    def exact_position(self) -> Fraction:
        return self.counts * self.scale

    def exact_at(self, counts: int) -> Fraction:
        """The exact position (IU) at `counts` (a spot of an earlier cycle, cutoff_raster)."""
        return counts * self.scale

    def record(self) -> None:
        """Once per NC cycle: the counts for C001's average (decision 12)."""
        if self._ring is not None:
            self._ring.append(self.counts)

    @property
    def velocity(self) -> float:
        if self.override is not None:
            return self.override
        ring = self._ring
        if ring is not None and len(ring) > 1:
            return float((ring[-1] - ring[0]) * self.scale) / ((len(ring) - 1) * self._cycle_s)
        m = self.encoder.master
        return float(m.velocity) * float(m.counts_per_unit) * self._scale_f * self._sign

    @property
    def acceleration(self) -> float:
        if self.override is not None:
            return 0.0
        m = self.encoder.master
        return float(m.acceleration) * float(m.counts_per_unit) * self._scale_f * self._sign


class ClockMaster:
    """Test mode (decision 11): the internal clock generator as the material, 1/1000 IU a count."""

    encoder = None
    scale = Fraction(1, 1000)
    counts_per_unit = 1000.0
    acceleration = 0.0

    def __init__(self) -> None:
        self._counts = 0.0
        self.velocity = 0.0

    def update(self, cycle: int) -> None:
        pass

    def advance(self, velocity: float, seconds: float) -> None:
        self.velocity = velocity
        self._counts += velocity * seconds * 1000.0

    @property
    def counts(self) -> int:
        return round(self._counts)

    @property
    def position(self) -> float:
        return self.counts / 1000.0

    @property
    def exact_position(self) -> Fraction:
        return Fraction(self.counts, 1000)

    def exact_at(self, counts: int) -> Fraction:
        return Fraction(counts, 1000)


class FlyingCutoff(CutoffInputs):
    """The flying cutoff of axis 1; see the module docstring (the input functions: cutoff_inputs)."""

    def __init__(self, rt: Any) -> None:
        self.rt = rt
        self.axis = rt.axes[1]  # the carriage: CLM axis 1 (the same object for the runtime's life)
        params = rt.memory.parameters
        self.tool_width = Fraction(str(params.get("A141").number("tool_width")))
        a138 = params.get("A138")
        self._always_zero = int(a138["always_start_at_0000"]) == 1
        op = a138["start_at_0000_input"]
        self._zero_input = None if op.unset else op
        self.start_at_zero = False  # !sCL0 or the A138 input in Manual (decision 7)
        self.length_instruction: int | None = None  # the last LML / LMK / LMR reached
        self.state = HOME
        self.gear: GearInPos | None = None
        self.master: WheelMaster | None = None
        self.last_cut: Fraction | None = None  # material coordinate of the previous cut point
        self.target: Fraction | None = None  # ... of the cut point of the running length
        self.length: Fraction | None = None  # the running length (with the tool width)
        self.programmed: Fraction | None = None  # ... as programmed (the report's target)
        self._target_of: Fraction | None = None  # the target `_target_f` is the float of
        self._target_f = 0.0
        self.counters = LengthCounters()  # material and product length (material_length.py)
        self._counts: int | None = None
        self.max_lag = 0.0  # |lag| over the synchronous phase (IU), for the cut report
        self.cuts: list[dict[str, Any]] = []  # per EOS: the planned cut (personality measures it)
        self._index_check = False  # the first length after Automatic with indexing (3A)
        self._configure_inputs(params)
        c008 = params.get("C008")
        op = c008["no_material_input"]
        self._nm_input = None if op.unset else op
        self._nm_variable = int(c008["material_speed_variable"])
        self._virtual = 0.0
        # LMK / LMR (cutoff_raster.py): ("LMK", offset, None) / ("LMR", offset, raster distance)
        self.raster = RasterWatch(rt, level=int(a138["raster_detection"]) == 1)
        self.raster_mode: tuple[str, Fraction, Fraction | None] | None = None
        self._raster_used = False
        self._awaiting_raster = False
        self._pending_raster: Fraction | None = None
        self.reverse = ReverseOptimisation(rt, params)  # A139 / A140 (cutoff_reverse.py)
        self.test_mode = int(params.get("A100")["test_mode"]) == 1  # decision 11
        self._averaging = int(params.get("C001")["averaging"])  # decision 12
        self.test_steps = 0
        self.clock = ClockMaster() if self.test_mode else None

    # -- the pieces ---------------------------------------------------------------------------

    def _master(self) -> Any:
        if self.clock is not None:
            return self.clock  # test mode (decision 11)
        me = self.rt.master_encoder
        if me is None:
            return None
        scale = me.scale
        master = self.master
        if master is not None and scale is master.source_scale and master.encoder is me:
            return master  # (the scale object stays while C000-C002 and FAK 5 do; never 0 here)
        if not scale:
            return None
        if master is None or master.encoder is not me or abs(scale) != master.scale:
            old = self.master
            self.master = WheelMaster(me, self._averaging, self.rt.nc_cycle_s)
            if old is not None and old.encoder is me:
                self.master.shift = old.shift
        return self.master

    def material_point(self) -> Fraction | None:
        """The material coordinate under the tool now (master - carriage), IU."""
        m = self._master()
        if m is None:
            return None
        return m.exact_position - Fraction(self.axis.actual_position)

    def spot(self) -> Spot | None:
        """What the material point now is made of, kept as it is read (the exact Fraction is
        worked out only for a cycle that has a raster, cutoff_raster.point_of)."""
        m = self._master()
        if m is None:
            return None
        return m, m.counts, self.axis.axis.actual_position  # (the kernel axis' own, as material_point reads it)

    # -- per cycle ----------------------------------------------------------------------------

    def tick(self, mode: str) -> None:
        """Before the tasks: the length counters, the end of the return, the A138 input."""
        me = self.rt.master_encoder if self.clock is None else self.clock
        if self.clock is not None:  # test mode: the internal clock is the material (decision 11)
            if mode != "automatic":
                self.test_steps = 0
            self.clock.advance(self.test_steps / 32 * float(self.axis.maximum_velocity), self.rt.nc_cycle_s)
        if me is not None:
            counts = int(me.counts)
            if self._counts is not None and counts != self._counts and mode in ("manual", "automatic"):
                self.counters.add(counts - self._counts, me.scale, product=mode == "automatic" and not self.inhibited)
            self._counts = counts
        if self.state == RETURNING and self.axis.motion_done:
            self.state = HOME
        elif self.state == SYNC:
            lag = abs(self.axis.lag)
            if lag > self.max_lag:
                self.max_lag = lag
        if mode == "manual" and self._zero_input is not None and self.rt.read_bit(self._zero_input):
            self.start_at_zero = True
        self.tick_inputs(mode)  # cutoff_inputs.py
        if self._nm_input is not None:
            self._no_material()
        if self._averaging and self.clock is None:
            master = self._master()
            if master is not None:
                master.record()
        self._raster_tick()  # cutoff_raster.py
        if self.reverse.active:
            self.reverse.tick(self)  # cutoff_reverse.py

    def _no_material(self) -> None:
        """C008 (decision 10): while its input is on, the material runs at the variable's speed."""
        op = self._nm_input
        master = self._master() if op is not None and self.clock is None else None
        if master is None or op is None:
            return
        if not self.rt.read_bit(op):
            master.override = None
            return
        raw = self.rt.memory.variables[self._nm_variable] if self._nm_variable else 0
        v = min(max(raw / 1_000_000, 0.0), float(self.axis.maximum_velocity))
        if master.override is None:
            self._virtual = float(master.counts)
        master.override = v
        self._virtual += v * self.rt.nc_cycle_s / float(master.scale)
        master.shift = round(self._virtual) - master.wheel_counts

    def _raster_tick(self) -> None:
        """Raster 1 from the de-synchronization to the synchronization (cutoff_raster 2, 3)."""
        r = self.raster.seen(self.spot())
        if self.state == SYNC or not self.rt.modes.running:
            return
        waiting = self.rt.tasks[0].wait == "cutoff"
        mode = self.raster_mode
        if r is None and waiting and mode is not None and mode[2] is not None and not self._raster_used \
                and self.raster.last is not None:
            now = self.material_point()
            if now is not None and now >= self.raster.last + mode[2]:
                r = self.raster.last + mode[2]  # LMR: a missing mark is taken where it was due
        if r is None:
            return
        if not waiting:
            self._pending_raster = r  # for the length instruction that comes next
            return
        self._use_raster(r)

    def _use_raster(self, r: Fraction) -> None:
        mode = self.raster_mode
        if mode is None or self._raster_used:
            return
        self._raster_used = True
        self._awaiting_raster = False
        self.raster.last = r
        self.target = r + mode[1]
        if self.state == APPROACH:  # replan from the moving carriage (L2107)
            self.state = HOME
            self._approach(replan=True)

    # -- the length counters (Status 54; material_length.LengthCounters) ----------------------

    @property
    def material_length(self) -> Fraction:
        return self.counters.material

    @property
    def product_length(self) -> Fraction:
        return self.counters.product

    # -- mode changes -------------------------------------------------------------------------

    def carry(self, old: FlyingCutoff) -> None:
        """After Parameter mode: the counters and the length instruction go on."""
        self.counters = old.counters
        self.length_instruction, self.cuts = old.length_instruction, old.cuts

    def enter_automatic(self) -> None:
        """Automatic selected (decisions 6, 7): 36 away from home, else Task 1 starts."""
        axis = self.axis
        window = float(getattr(axis, "threshold", 0.0))
        if abs(axis.actual_position) > window:
            raise ClmError("36", f"Automatic selected with the carriage (axis 1) at {axis.actual_position:+.3f}, "
                                 f"not within A127 {window:.3f} of its home position 0 (L3931)")
        at = self.length_instruction
        start = 0 if (at is None or self._always_zero or self.start_at_zero) else max(0, at - 1)
        self.start_at_zero = False
        self.state = HOME
        self.gear = None
        self.last_cut = self.material_point()  # decision 3
        self.target = None
        self._index_check = False
        if self.indexing and self.last_cut is not None:  # cutoff_inputs.py decision 8
            lengths = getattr(self.rt, "feed_lengths", None)
            if lengths is not None and "material" in lengths.start:
                self.last_cut -= lengths.current("material")
                self._index_check = True
        self.rt.tasks[0].start(start)

    def leave_automatic(self) -> None:
        """Manual / Parameter / a fault: the gear is dropped (the axis brakes, modes.py)."""
        self.gear = None
        self.state = HOME
        self.target = None
        self.reverse_held = False
        self.retract_fault = None
        if self.reverse.active:
            self.reverse._set(False)

    # -- commands -------------------------------------------------------------------------------

    def lml(self, task: NcTask, number: int, length: Fraction | None, wait_for_raster: bool = False) -> bool:
        """LML (decisions 1-5, 9; LMK / LMR: cutoff_raster.py): True when the carriage is
        synchronous with the cut point. `length` is read when the instruction is reached (it may
        be None on the cycles the task waits on it)."""
        if task.wait is None:
            if self.state == SYNC:
                raise ClmError("35", f"Missing EOS Cmd: the length instruction {number:04d} is reached while the carriage "
                                     "is still synchronous (the processing program has no EOS, L1908)")
            self.length_instruction = number
            assert length is not None
            self.programmed = length
            self.length = length + self.tool_width
            if self.last_cut is None:
                self.last_cut = self.material_point()
            task.wait = "cutoff"
            self.target = None if self.last_cut is None else self.last_cut + self.length
            self._raster_used = False
            self._awaiting_raster = wait_for_raster
            if wait_for_raster:
                self.target = None
            pending, self._pending_raster = self._pending_raster, None
            if pending is not None:
                self._use_raster(pending)
            if self.state == RETURNING and self.target is not None:
                self.reverse.plan(self)  # the next cut point is known: an optimised return
            if self._index_check:  # cutoff_inputs.py decision 8
                self._index_check = False
                fed = self.material_point()
                if self.target is not None and fed is not None and fed > self.target:
                    raise ClmError("3A", f"Index Length: {float(fed - self.target + self.length):.3f} of material went through "
                                         f"the tool since the manual cut, more than the length {float(self.length):.3f}")
        if self.target is None and self._awaiting_raster:
            return False  # LMR: the first raster sets the cut point
        if self.target is None:  # no master encoder yet: the material cannot be measured
            self.last_cut = self.material_point()
            self.target = None if self.last_cut is None else self.last_cut + self.length  # type: ignore[operator]
            return False
        if self.state == RETURNING and self.axis.motion_done:
            self.state = HOME
        if self.state == HOME and not self.inhibited:
            self._approach()
        if self.state == APPROACH and self.gear is not None and self.gear.in_gear:
            self.state = SYNC
            self.max_lag = 0.0
            return True
        return False

    def set_length(self, length: Fraction) -> None:
        """The waiting length instruction's length becomes `length` (crop cut, cutoff_inputs 4)."""
        self.programmed = length
        self.length = length + self.tool_width
        if self.last_cut is not None:
            self.target = self.last_cut + self.length

    def cut_now(self) -> None:
        """Immediate cut (cutoff_inputs 1): the cut point a plain ramp meets at once."""
        master, point = self._master(), self.material_point()
        if master is None or point is None or master.velocity <= 0.0:
            return
        v = master.velocity
        self.target = point + Fraction(v * v / (2.0 * float(self.axis.acceleration)))
        self._approach(now=True)

    def return_home(self) -> None:
        """The carriage to position 0 at A106 (decision 4)."""
        clm = self.axis
        clm.move_to(Fraction(0), float(clm.maximum_velocity))
        self.state = RETURNING

    def _approach(self, now: bool = False, replan: bool = False) -> None:
        """Plan and start the gear in position when the material is close enough (decision 1)."""
        clm = self.axis
        master = self._master()
        if master is None or not (clm.motion_done or replan) or not (clm.drive_enabled and clm.axis.powered):
            return
        v = master.velocity
        if v <= 0.0:
            return  # the material stands (or runs back): nothing to synchronize with
        accel = float(clm.acceleration)
        s0 = float(clm.command_position)
        s_min = s0 + v * v / (2.0 * accel)
        target = self.target
        assert target is not None
        if target is not self._target_of:  # (asked every cycle until the plan: one float per target)
            self._target_of, self._target_f = target, float(target)
        togo = self._target_f + s_min - master.position
        if not (now or replan) and togo > 2.0 * (s_min - s0) + _PLAN_LEAD_CYCLES * v * self.rt.nc_cycle_s:
            return
        vmax = float(clm.maximum_velocity)
        num, den = Gear.counts_ratio(1, Fraction(1) / master.scale, clm.axis.config.counts_per_unit)

        def gear_for(s_sync: float) -> GearInPos:
            return GearInPos(master, clm.axis, num, den, master_sync_position=float(self.target) + s_sync,  # type: ignore[arg-type]
                             slave_sync_position=s_sync, velocity=vmax, master_velocity=v, acceleration=accel,
                             deceleration=float(clm.deceleration))

        try:
            gear = gear_for(s_min)
        except GearInPosError:
            gear = self._catch_up(gear_for, s_min, float(clm.max_travel))
        clm.synchronize(gear)
        self.gear = gear
        self.state = APPROACH

    def _catch_up(self, gear_for: Any, s_min: float, s_max: float) -> GearInPos:
        """Decision 2: the smallest sync stroke up to Ax04 that reaches the cut point."""
        try:
            best = gear_for(s_max)
        except GearInPosError:
            raise ClmError(axis_fault(0x07, 1), f"flying cutoff: the carriage cannot reach the cut point of the length "
                                                f"{float(self.length or 0):.3f} within A104 = {s_max:.3f} (the piece is too "
                                                "short for the line speed and the return)") from None
        lo, hi = s_min, s_max
        for _ in range(40):
            mid = 0.5 * (lo + hi)
            try:
                best, hi = gear_for(mid), mid
            except GearInPosError:
                lo = mid
            if hi - lo < 1e-3:
                break
        return best

    def eos(self, task: NcTask) -> None:
        """EOS (decision 4): the synchronous phase ends, the carriage returns home at A106."""
        if self.retract_fault is not None:
            self.after_retract()  # the rapid stop / maximum stroke program ended: 3B / 3C
        if self.state != SYNC:
            return  # no synchronous phase (a manual cut program): nothing to end
        self.cuts.append({"length": self.length, "target": self.target, "cycle": self.rt.cycle,
                          "max_lag": self.max_lag})
        self.last_cut = self.target
        self.gear = None
        if self._reverse_in is not None:  # reverse inhibit (cutoff_inputs 5): stop, wait for the input
            self.axis.stop_motion()
            self.state = HELD
            self.reverse_held = True
            return
        self.return_home()

    def end_of_program(self, task: NcTask) -> None:
        """RTS of Task 1 (decision 5): still synchronous = the processing program had no EOS."""
        if self.state == SYNC and task.number == 1:
            raise ClmError("35", "Missing EOS Cmd: the processing program returns (RTS) while the carriage is still "
                                 "synchronous (L1908)")

    def test_key(self, key: str) -> None:
        """Test mode's display keys (decision 11): "up" / "down" one of 32 steps, "zero"."""
        if key == "up":
            self.test_steps = min(32, self.test_steps + 1)
        elif key == "down":
            self.test_steps = max(0, self.test_steps - 1)
        elif key == "zero":
            self.test_steps = 0
        else:
            raise ValueError(f"test mode keys: 'up', 'down', 'zero', not {key!r}")

    # -- serial ---------------------------------------------------------------------------------

    def status_54(self) -> str:
        """``54 vmmmmmmmm vpppppppp`` (decision 8)."""
        return self.counters.status_54()

    def clear_counter(self, which: int) -> None:
        """!sCLL1 (material) / !sCLL2 (product)."""
        self.counters.clear(which)
