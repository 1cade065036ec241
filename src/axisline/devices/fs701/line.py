"""The simulated cut-to-length line around an FS701: the shear, the cut measurement, the batch job.

The FS701 itself (cutter.py) only sees its encoders and inputs. What a real line adds around it
is simulated here, for the personality (personality.py) and for test rigs:

    Shear       the cutting tool on the carriage: when Ready to Cut rises, the blade passes the
                material `blade_delay` later (the cut instant) and the tool's "Cut completed"
                signal follows `cut_time` after Ready to Cut, `pulse` long (idle LOW and a HIGH
                pulse with Edge Sense 0; idle HIGH and a LOW pulse with Edge Sense 1)
    CutMeter    measures every cut on the simulated material, not on the controller's counters:
                the material point cut is (material travel - carriage position) at the cut
                instant, both from the plant; a piece is the difference of two such points less
                the Tool Width. Print-mark cuts also get their offset to the nearest mark
    BatchJob    the line's PLC: Control Enable, then Start; Stop once `batch` pieces (Batch
                Counter cuts) are cut; Control Enable off once the carriage stands at home
    batch_statistics   max / mean / std of the length error, cuts in tolerance

Accuracy classes (the tolerance a cut is checked against; both in carriage encoder increments):
a piece whose two cuts both happened at the same constant line speed is checked against
`tolerance` (the example: 1 increment), any other piece (a cut during a line speed ramp)
against `ramp_tolerance` (the example: 2 increments; the manual §9 expects 4..7 increments in
practice). The carriage's position error at the two cuts of a piece differs when the speed
differs, which is why ramps get the wider bound.

Decisions:
 M1 The cut instant is the blade's passage (`blade_delay` after Ready to Cut), cutter.py C17; the
    positions are those at the cycle boundary where it falls (material and carriage alike, so
    the point is exact to the plant's integration).
 M2 The first cut of a run has no previous cut: it is recorded (target and actual length None)
    and not counted as a piece; a cut with target length None (an Immediate or late cut) is a
    waste piece: recorded, not checked against the tolerance.
 M3 The "material" is the simulated strip under a measuring wheel (line = a "wheel" master);
    with a feed roll's motor encoder as the line (an "axis_encoder" master) it is the roll's
    surface (the feed drive's position; constant speed: its set point does not accelerate);
    with the FS701's virtual master it is the virtual master's travel: then the pieces are
    measured on the controller's own master.
 M4 Print-mark cuts: the offset to the nearest mark's active edge (leading edge with Printmark
    Edge 0, trailing with 1) on the material; checked against `mark_tolerance`.
 M5 Additional cuts (Cutting Mode 3) are not at a mark: they are measured and checked like
    length cuts (the piece since the previous cut against the FIFO's piece length: the tail,
    Add. Cut 3/2 Length), never against the nearest mark (`cut(..., at_mark=False)`); the cut
    on the trigger mark itself is a print-mark cut (M4). Test (machine level):
    test_cutting_mode_3_cuts_the_additional_pieces_before_each_mark.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, field
from typing import Any, Callable, cast

__all__ = ["Shear", "CutMeasurement", "CutMeter", "BatchJob", "batch_statistics"]


class Shear:
    """The cutting tool (see the module docstring). `step` once per cycle after the cutter's tick."""

    def __init__(self, period: float, *, blade_delay: float = 0.02, cut_time: float = 0.06, pulse: float = 0.02) -> None:
        self.period = float(period)
        self.blade_cycles = max(0, int(round(blade_delay / self.period)))
        self.cut_cycles = max(1, int(round(cut_time / self.period)))
        self.pulse_cycles = max(1, int(round(pulse / self.period)))
        self.level = False  # the "Cut completed" signal
        self._rtc = False
        self._blade_at: int | None = None
        self._on_at: int | None = None
        self._off_at: int | None = None
        self.cuts = 0

    @property
    def busy(self) -> bool:
        return self._blade_at is not None or self._on_at is not None or self._off_at is not None

    def step(self, cycle: int, ready_to_cut: bool, edge_sense: int) -> bool:
        """Advance one cycle; True when the blade passes the material in this cycle (the cut)."""
        idle = edge_sense == 1
        if self._blade_at is None and self._on_at is None and self._off_at is None:  # not busy
            self.level = idle
            if not ready_to_cut or self._rtc:  # and no new cut: nothing below would happen
                self._rtc = ready_to_cut
                return False
        if ready_to_cut and not self._rtc:
            self._blade_at = cycle + self.blade_cycles
            self._on_at = cycle + self.cut_cycles
            self._off_at = self._on_at + self.pulse_cycles
        self._rtc = ready_to_cut
        cut = False
        if self._blade_at is not None and cycle >= self._blade_at:
            self._blade_at = None
            self.cuts += 1
            cut = True
        if self._on_at is not None and cycle >= self._on_at:
            self._on_at = None
            self.level = not idle
        if self._off_at is not None and self._on_at is None and cycle >= self._off_at:
            self._off_at = None
            self.level = idle
        return cut


@dataclass
class CutMeasurement:
    """One cut, measured on the simulated material (lengths in LU, errors also in increments)."""

    index: int  # 1, 2, ... in the order of the cuts
    time: float  # s, the cut instant
    kind: str  # the cutter's CutKind name (NORMAL, TEST, PRINTMARK, ...)
    target_length: float | None  # LU: the nominal piece this cut ends (None: first cut, waste)
    actual_length: float | None  # LU: material between this cut and the previous, less Tool Width
    error_lu: float | None  # actual - target
    error_counts: float | None  # the same in carriage encoder increments
    line_speed: float  # LU/min, the material's speed at the cut (plant)
    line_speed_measured: float  # LU/min, the FS701's own line speed (#2) at the cut
    constant_speed: bool  # this cut and the previous one at the same, constant line speed
    following_error: float  # carriage increments: the FS701's Position Error (#3) at the cut
    following_error_lu: float
    material_point: float  # LU: the material coordinate of the cut
    max_pos_error_counts: float | None = None  # largest |Position Error| from Ready to Cut to the cut
    mark_offset: float | None = None  # LU: cut point - nearest mark's active edge (print marks)
    mark_offset_counts: float | None = None
    tolerance: float | None = None  # increments the piece is checked against (None: not checked)
    in_tolerance: bool | None = None

    def as_dict(self) -> dict[str, Any]:
        return {k: (None if isinstance(v, float) and not math.isfinite(v) else v) for k, v in asdict(self).items()}


class CutMeter:
    """Measures cuts on the plant (module docstring, M1..M4).

    material: () -> (position, velocity, acceleration) of the material (LU, LU/s, LU/s^2);
    tool: () -> the carriage's (tool's) position on the line (LU, plant);
    marks: optional (point) -> offset to the nearest mark's active edge (LU)."""

    def __init__(
        self,
        material: Callable[[], tuple[float, float, float]],
        tool: Callable[[], float],
        *,
        counts_per_lu: Callable[[], float],
        tool_width: Callable[[], float],
        tolerance: float = 1.0,
        ramp_tolerance: float = 2.0,
        mark_tolerance: float = 2.0,
        marks: Callable[[float], float | None] | None = None,
    ) -> None:
        self.material = material
        self.tool = tool
        self.counts_per_lu = counts_per_lu
        self.tool_width = tool_width
        self.tolerance = float(tolerance)
        self.ramp_tolerance = float(ramp_tolerance)
        self.mark_tolerance = float(mark_tolerance)
        self.marks = marks
        self.records: list[CutMeasurement] = []
        self._last_point = math.nan
        self._last_speed: float | None = None  # material speed at the previous cut if constant

    def cut(
        self,
        time: float,
        *,
        kind: str,
        target_length: float | None,
        line_speed_measured: float,
        following_error: float,
        at_mark: bool = True,
        max_pos_error: float | None = None,
    ) -> CutMeasurement:
        x, v, a = self.material()
        point = x - self.tool()
        kc = self.counts_per_lu()
        constant = a == 0.0 and v != 0.0
        speed_here = v if constant else None
        first = math.isnan(self._last_point)
        actual = None if first else point - self._last_point - self.tool_width()
        if target_length is not None and (math.isnan(target_length) or first):
            target_length = None
        err = None if actual is None or target_length is None else actual - target_length
        both_constant = speed_here is not None and self._last_speed is not None and speed_here == self._last_speed
        rec = CutMeasurement(
            index=len(self.records) + 1,
            time=time,
            kind=kind,
            target_length=target_length,
            actual_length=actual,
            error_lu=err,
            error_counts=None if err is None else err * kc,
            line_speed=v * 60.0,
            line_speed_measured=line_speed_measured,
            constant_speed=both_constant,
            following_error=following_error,
            following_error_lu=following_error / kc,
            max_pos_error_counts=max_pos_error,
            material_point=point,
        )
        if self.marks is not None and at_mark:
            off = self.marks(point)
            if off is not None:
                rec.mark_offset = off
                rec.mark_offset_counts = off * kc
                rec.tolerance = self.mark_tolerance
                rec.in_tolerance = abs(rec.mark_offset_counts) <= self.mark_tolerance
        elif rec.error_counts is not None:
            rec.tolerance = self.tolerance if both_constant else self.ramp_tolerance
            rec.in_tolerance = abs(rec.error_counts) <= rec.tolerance + 1e-9
        self._last_point = point
        self._last_speed = speed_here
        self.records.append(rec)
        return rec


class BatchJob:
    """The line's PLC for one batch (module docstring). Levels for Control Enable and Start/Stop.

    batch: pieces to cut (cuts the FS701 counts in its Batch Counter: not waste); 0: never stop.
    start_delay: s between Control Enable and Start (the carriage's loop closes)."""

    def __init__(self, batch: int, period: float, *, start_delay: float = 0.02) -> None:
        self.batch = int(batch)
        self.period = float(period)
        self.start_cycles = max(1, int(round(start_delay / self.period)))
        self.control_enable = False
        self.start_stop = False
        self.state = "idle"  # idle -> enabled -> running -> stopping -> done
        self.counted = 0  # batch cuts since Start
        self.events: list[dict[str, Any]] = []
        self._enabled_at = 0

    @property
    def done(self) -> bool:
        return self.state == "done"

    def _event(self, cycle: int, text: str) -> None:
        self.events.append({"t": round(cycle * self.period, 6), "text": text})

    def count(self, waste: bool) -> None:
        """A cut reached Ready to Cut (the FS701's batch / waste counting moment)."""
        if not waste and self.state == "running":
            self.counted += 1

    def step(self, cycle: int, carriage_parked: Callable[[], bool]) -> None:
        """One cycle of the PLC. `carriage_parked()`: the carriage stands at home, settled, with
        no cut cycle running -- asked only while stopping (it is not free to compute)."""
        st = self.state
        if st == "idle":
            self.control_enable = True
            self._enabled_at = cycle
            self.state = "enabled"
            self._event(cycle, "Control Enable ON")
        elif st == "enabled":
            if cycle - self._enabled_at >= self.start_cycles:
                self.start_stop = True
                self.state = "running"
                self._event(cycle, "Start")
        elif st == "running":
            if self.batch > 0 and self.counted >= self.batch:
                self.start_stop = False
                self.state = "stopping"
                self._event(cycle, f"Stop: batch of {self.batch} cut")
        elif st == "stopping":
            if carriage_parked():
                self.control_enable = False
                self.state = "done"
                self._event(cycle, "Control Enable OFF: carriage at home")


def _std(xs: list[float]) -> float:
    if not xs:
        return math.nan
    m = sum(xs) / len(xs)
    return math.sqrt(sum((x - m) ** 2 for x in xs) / len(xs))


def batch_statistics(records: list[CutMeasurement]) -> dict[str, Any]:
    """The batch summary: length errors (LU and increments), tolerance, print-mark offsets."""
    pieces = [r for r in records if r.error_lu is not None]
    # (a piece has both errors: cast, not a filter)
    e_lu = [cast(float, r.error_lu) for r in pieces]
    e_c = [cast(float, r.error_counts) for r in pieces]
    const = [abs(e) for r, e in zip(pieces, e_c) if r.constant_speed]
    ramp = [abs(e) for r, e in zip(pieces, e_c) if not r.constant_speed]
    checked = [r for r in records if r.in_tolerance is not None]
    marks = [r.mark_offset_counts for r in records if r.mark_offset_counts is not None]

    def mx(xs: list[float]) -> float | None:
        return max(xs) if xs else None

    def mean(xs: list[float]) -> float | None:
        return sum(xs) / len(xs) if xs else None

    def std(xs: list[float]) -> float | None:
        return _std(xs) if xs else None

    return {
        "cuts": len(records),
        "pieces": len(pieces),
        "waste_cuts": sum(1 for r in records if r.kind in ("TEST", "IMMEDIATE", "LATE")),
        "max_abs_error_lu": mx([abs(x) for x in e_lu]),
        "max_abs_error_counts": mx([abs(x) for x in e_c]),
        "mean_error_lu": mean(e_lu),
        "mean_error_counts": mean(e_c),
        "std_error_lu": std(e_lu),
        "std_error_counts": std(e_c),
        "max_abs_error_counts_constant_speed": mx(const),
        "max_abs_error_counts_ramps": mx(ramp),
        "pieces_constant_speed": len(const),
        "pieces_ramps": len(ramp),
        "max_abs_mark_offset_counts": mx([abs(x) for x in marks]),
        "mean_mark_offset_counts": mean(marks),
        "std_mark_offset_counts": std(marks),
        "checked": len(checked),
        "in_tolerance": sum(1 for r in checked if r.in_tolerance),
        "out_of_tolerance": [r.index for r in checked if not r.in_tolerance],
    }


@dataclass
class CommissioningReport:
    """What the Adjust program (loop.py, manual §7) found and set."""

    ran: bool = False
    ok: bool = True
    steps: list[dict[str, Any]] = field(default_factory=list)
