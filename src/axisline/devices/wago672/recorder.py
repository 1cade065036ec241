"""The data recorder (trace) of the 750-672 (manual §3.13.2; wago.md §8.5).

    rec = DataRecorder(dev, tables)     # mailbox.attach() does this
    ... a 0->1 edge of TRACE_TRIGGER (bit 222, default source Busy) while Trace_Armed (bit 223,
    default MONE) starts a recording of TraceVar1 / TraceVar2 (configuration 264 / 268, internal
    state variable numbers as DIAG_RD_VAR) every TraceMsecCycleTime ms (272); after 500 samples
    Trace_Stored (bit 32) is set.
    rec.samples                          # [(var1, var2), ...] of the stored data set
    upload: DLD_START (location 1, type 5, transfer 3 = 32-bit upload, 1000 data sets),
            1000 x DLD_CONT (var1[0], var2[0], var1[1], ...), DLD_END (reply: checksum)

Trace_Stored is 0 from a new start until the data set is complete; with Trace_Armed = 0 no
trigger starts a recording and the stored data set is kept. Link TRACE_TRIGGER/Trace_Armed to
MZERO/MONE to trigger from the PLC with WR_BIT (DRIVE_COMMAND) and read Trace_Stored with
DIAG_RD_BIT. The data are volatile (a warm start clears them) and cannot be copied to the EEPROM.

Decisions ([RECONSTRUCTED]/[AMBIGUOUS] points of wago.md §8.5; the manual wins):
* R1 Data order (wago.md §8.5 [RECONSTRUCTED]): the 1000 data sets of the upload are the 500
  samples interleaved, var1[i] then var2[i], each a 32-bit two's complement value (one DLD_CONT
  per value, LSB in MB2, transfer 1 or 3). Test: test_recorder::test_upload_through_the_table_manager.
* R2 Sampling: the first sample is taken in the tick of the trigger edge, then every
  TraceMsecCycleTime ms (0 is taken as 1 ms); the variables and the cycle time are latched at the
  trigger. A trigger edge during a recording is ignored. Sampling runs after the device has
  written its status bits of the tick (the trigger sees this tick's Busy). Test:
  test_recorder::test_a_move_triggers_a_recording_of_position_and_frequency,
  test_recorder::test_sampling_period_and_variables,
  test_recorder::test_remote_trigger_with_wr_bit_and_a_trigger_during_a_recording_is_ignored.
* R3 An upload before a data set is complete (Trace_Stored = 0) is refused (DLD_START status 1,
  0x31); variable numbers above the bit range (> 0x10FF) record 0. Test:
  test_recorder::test_no_upload_without_a_stored_data_set.
* R4 The first tick after a reset only samples TRACE_TRIGGER (an input already 1 is no edge).
  Test: test_recorder::test_a_trigger_already_set_at_reset_is_no_edge.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from axisline.devices.wago672.bits import Bit
from axisline.devices.wago672.errors import WagoError

if TYPE_CHECKING:
    from axisline.devices.wago672.device import Wago672
    from axisline.devices.wago672.tables import TableManager

__all__ = ["DataRecorder", "TRACE_SAMPLES"]

TRACE_SAMPLES = 500  # "500 values are recorded each time"
_TRACE_STORED = int(Bit.Trace_Stored)


def _s32(value: int) -> int:
    value = int(value) & 0xFFFFFFFF
    return value - 0x100000000 if value & 0x80000000 else value


class DataRecorder:
    """Records two state variables on a trigger (see the module docstring)."""

    def __init__(self, device: Wago672, tables: TableManager | None = None) -> None:
        self.device = device
        self._trigger_bits = device.bits.group((Bit.TRACE_TRIGGER, Bit.Trace_Armed))  # read every tick
        self.reset()
        device.tick_hooks.append(self.tick)
        if tables is not None:
            tables.trace_source = self.upload_data

    def reset(self) -> None:
        """Warm start: no data set, not recording."""
        self._samples: list[tuple[int, int]] = []
        self.recording = False
        self.stored = False
        self._prev: bool | None = None
        self._next = 0
        self._period = 1
        self._vars = (0, 0)
        self.device.bits.put(Bit.Trace_Stored, False)

    @property
    def samples(self) -> list[tuple[int, int]]:
        """The samples recorded so far (the complete data set once `stored`)."""
        return list(self._samples)

    def upload_data(self) -> list[int] | None:
        """The 1000 values of the stored data set in upload order (R1), None without one."""
        if not self.stored:
            return None
        return [v for pair in self._samples for v in pair]

    def _read(self, n: int) -> int:
        if not 0 <= n <= 0x10FF:
            return 0
        return _s32(self.device.state_variable(n))

    def tick(self, cycle: int) -> None:
        dev = self.device
        try:
            w = dev.bits.word(self._trigger_bits)
        except WagoError as e:
            dev.raise_error(e.code, e.text)
            return
        trigger, armed = w & 1 == 1, w & 2 == 2
        edge = trigger and self._prev is False
        self._prev = trigger
        if edge and armed and not self.recording:
            c = dev.config
            self._vars = (c["TraceVar1"], c["TraceVar2"])
            self._period = max(1, c["TraceMsecCycleTime"])
            self._samples = []
            self.stored = False
            self.recording = True
            self._next = cycle
        if self.recording and cycle >= self._next:
            self._samples.append((self._read(self._vars[0]), self._read(self._vars[1])))
            self._next = cycle + self._period
            if len(self._samples) >= TRACE_SAMPLES:
                self.recording = False
                self.stored = True
        dev.bits.field[_TRACE_STORED] = 1 if self.stored else 0
