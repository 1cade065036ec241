"""The FS701 cutter's command inputs and status outputs (manual §4.1), and the record of each
piece it cut (cutter.py describes the cycle and its decisions).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields
from typing import TYPE_CHECKING

from mypy_extensions import mypyc_attr

if TYPE_CHECKING:
    from .cutter import Cutter

__all__ = ["CutRecord", "CutRecorder", "CutterInputs", "CutterOutputs"]

# a plain Python class also when compiled: the personality sets the fields through __dict__
@mypyc_attr(native_class=False)
@dataclass
class CutterInputs:
    """Command inputs (manual §4.1.1), already OR'ed over hardware / serial / CAN (io_assign).

    Static inputs are levels; edge inputs (Immediate Cut, Cut completed, Clear Error, Decr.
    Batch Cou.) are detected by the cutter from the levels it sees at its ticks. Print marks
    come with sub-cycle times through `Cutter.print_mark_edge`."""

    control_enable: bool = False
    start_stop: bool = False
    select_vir_master: bool = False
    run_virt_master: bool = False
    immediate_cut: bool = False
    cut_completed: bool = False
    cut_test_length: bool = False
    clear_error: bool = False
    set_zero_pos: bool = False
    jog_forward: bool = False
    jog_reverse: bool = False
    decr_batch_cou: bool = False
    start_gap: bool = False
    teach_printmark: bool = False
    reset_diff_cou: bool = False
    reset_batch_cou: bool = False
    sync_mode_enable: bool = False


_INPUT_NAMES = tuple(f.name for f in fields(CutterInputs))


@dataclass
class CutterOutputs:
    """Output signals (manual §4.1.2); bit numbers of register 0x0B04 in `bits()`."""

    ready: bool = False
    ready_to_cut: bool = False
    home: bool = False
    alarm: bool = False
    length_pulses: bool = False
    gap_completed: bool = False
    master_reverse: bool = False
    error: bool = False
    master_in_motion: bool = False
    vir_m_in_motion: bool = False
    no_printmark: bool = False
    printmark_window: bool = False
    virt_printmark: bool = False
    max_correction: bool = False
    printm_teached: bool = False

    def bits(self) -> int:
        """Output Status word (0x0B04): bit n = output n of the manual's table."""
        word = 0
        for i, f in enumerate(fields(self)):
            if getattr(self, f.name):
                word |= 1 << i
        return word





@dataclass
class CutRecord:
    """One piece, measured on the (simulated) material at the cut instant (C17)."""

    index: int
    cycle: int
    kind: str
    target_length: float  # LU, nominal piece length ending at this cut (nan: first cut)
    actual_length: float  # LU, material between this cut and the previous one, less Tool Width
    error_lu: float  # actual - target
    error_counts: float  # in carriage encoder increments
    line_speed: float  # LU/min at the cut (the cutter's filtered line speed)
    following_error: float  # carriage position error at the cut, increments (+: lags)
    material_point: float  # LU: material travel at which the cut point passed the tool origin


@mypyc_attr(native_class=False)  # (per cut, not per cycle: stays open to wrapping, e.g. in tests)
class CutRecorder:
    """Collects `CutRecord`s: call `cut(...)` at the instant the blade passes the material.

    material_position: material travel (LU) at that instant; carriage_position: the carriage's
    ACTUAL position (LU, axis frame = tool position). The point cut has material coordinate
    material_position - carriage_position; a piece is the difference of two such points less
    Tool Width."""

    def __init__(self, cutter: "Cutter") -> None:
        self.cutter = cutter
        self.records: list[CutRecord] = []
        self._last_point = math.nan

    def cut(self, cycle: int, material_position: float, carriage_position: float) -> CutRecord:
        c = self.cutter
        s = c.settings
        point = material_position - carriage_position
        info = c.current_cut
        target = info.piece_length if info is not None else math.nan
        kind = info.kind.name if info is not None else "UNKNOWN"
        if math.isnan(self._last_point):
            actual = math.nan
        else:
            actual = point - self._last_point - s.tool_width
        self._last_point = point
        err = actual - target if not (math.isnan(actual) or math.isnan(target)) else math.nan
        rec = CutRecord(
            index=len(self.records),
            cycle=cycle,
            kind=kind,
            target_length=target,
            actual_length=actual,
            error_lu=err,
            error_counts=err * s.cut_counts_per_lu if not math.isnan(err) else math.nan,
            line_speed=c.line_speed,
            following_error=c.position_error,
            material_point=point,
        )
        self.records.append(rec)
        return rec
