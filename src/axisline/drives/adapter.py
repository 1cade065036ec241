"""A CiA 402 drive on CANopen behind the plant's drive interface: set point in, actual values out.

The machine treats it like the plant's stepper (a drive that takes the set point itself): each
cycle `command_position` gets the axis' set point (plant frame), `step` writes the RPDOs
(controlword, target position, mode; velocity offset, target velocity) and hands over to the
bus, which sends the SYNC and collects the TPDOs (statusword, position actual value, mode
display; following error, velocity actual value). `position`, `velocity`, `enabled` are the
drive's answer. `watch` (INPUTS, before the axis reads the position) turns EMCY, the fault bit,
a lost heartbeat and a drive that left OPERATIONAL into the axis' ErrorStop.

No wait is without a bound: each SDO and each SYNC's TPDOs at most `response_timeout`, the
drive's homing at start at most `homing_timeout`. The heartbeat is supervised on the wall
clock, as the drive sends it; it changes nothing in a run unless a heartbeat is really missed.

Decisions
1. Issue 20 "the CiA 402 state machine follows the axis' power and reset": at start the drive is
   brought to READY TO SWITCH ON (shutdown, by SDO); the axis' power on sends "enable
   operation" (0x0F: transitions 3 + 4 in one SYNC, so the drive is enabled in the cycle the
   axis is, as the embedded servo is); power off sends "shutdown" (0x06: the motor coasts, as
   the embedded servo disabled does). A drive fault puts the axis in ErrorStop; the axis' reset
   then sends "fault reset" (bit 7, rising edge) and the drive comes back to READY TO SWITCH ON,
   and to OPERATION ENABLED if the axis is powered. Quick stop (0x02) is sent when axisline
   leaves the bus with drives enabled (close) (tests/drives/test_state_machine.py).
2. Issue 20 "EMCY or a fault bit -> ErrorStop with the drive's error code and text": the axis'
   error_id is the EMCY error code (0x603F read by SDO when the fault bit comes without EMCY),
   its text names the node and the code in words (cia402.error_text)
   (tests/drives/test_faults.py).
3. Issue 20 "heartbeat loss stops the others with their ramps and names the node": the lost
   drive's axis gets ErrorStop 0x8130 ("heartbeat lost", CiA 301's code); a drive that leaves
   three SYNCs in a row unanswered (each waited for response_timeout) counts as lost too, as its
   actual position is no longer known (else the axis' following-error check would name the
   wrong cause first); every other axis of the
   machine gets MC_Stop with its own stop ramp, released at once (it returns to Standstill when
   at rest); the machine's fault list names the node and bus (tests/drives/test_faults.py).
4. Issue 20 "Profile Velocity for jog where the user chooses it": with jog = "pv" the drive runs
   in PV (0x6060 = 3) while the axis' active command is a jog, with target velocity = the axis'
   set-point velocity (its own jog ramp), and returns to CSP at the set point after it.
5. Position scaling: the axis' counts_per_unit are the drive's increments (0x6064, 0x607A,
   0x60F4 per user unit; 0x606C, 0x60B1, 0x60FF per unit/s); axisline writes no factor group.
"""

from __future__ import annotations

import math
import threading
import time
from collections import deque
from typing import Any, Callable

import canopen
from canopen.sdo import SdoAbortedError, SdoCommunicationError

from ..motion.axis import AxisState
from ..plant.kinematics import linear_crossing
from .bus import CanBus, DriveError
from .cia402 import (
    CSP,
    CW_DISABLE_VOLTAGE,
    CW_ENABLE_OPERATION,
    CW_FAULT_RESET,
    CW_HOMING_START,
    HOMING,
    SW_HOMING_ATTAINED,
    SW_HOMING_ERROR,
    CW_QUICK_STOP,
    CW_SHUTDOWN,
    HEARTBEAT_ERROR,
    PV,
    error_text,
    state_of,
)
from .config import Cia402Entry

__all__ = ["Cia402Drive", "REQUIRED_RX", "REQUIRED_TX"]

#: objects a CSP drive must have in a SYNC PDO, by direction
REQUIRED_RX = {0x6040: "controlword", 0x607A: "target position"}
REQUIRED_TX = {0x6041: "statusword", 0x6064: "position actual value"}
_NAMES = {
    0x1000: "device type", 0x1006: "communication cycle period", 0x1016: "consumer heartbeat time",
    0x1017: "producer heartbeat time", 0x6040: "controlword", 0x6041: "statusword", 0x6060: "modes of operation",
    0x6064: "position actual value", 0x6085: "quick stop deceleration", 0x60C2: "interpolation time period",
    0x603F: "error code",
}
_LATE_SYNCS = 3  # SYNCs in a row a drive may leave unanswered before it counts as lost
_RESET_CYCLES = 50  # cycles a fault reset may take before the fault counts again
_INT32_MAX = 2**31 - 1
_FAULTS = ("FAULT", "FAULT REACTION ACTIVE")


def _int32(x: float) -> int:
    if not x == x:  # NaN: no target
        return 0
    n = round(x) if abs(x) < 2**62 else (1 if x > 0 else -1) * 2**62
    return -_INT32_MAX - 1 if n < -_INT32_MAX - 1 else _INT32_MAX if n > _INT32_MAX else n


class Cia402Drive:
    """One CiA 402 drive in CSP: the plant Drive protocol (plant/interfaces.py) over CANopen."""

    def __init__(self, cfg: Cia402Entry, bus: CanBus, axis: Any, *, counts_per_unit: float, eds: str, where: str) -> None:
        self.cfg = cfg
        self.bus = bus
        self.axis = axis
        self.node_id = cfg.node_id
        self.where = where
        self.counts_per_unit = float(counts_per_unit)
        self._upc = 1.0 / self.counts_per_unit
        self.max_velocity = math.inf  # the drive limits itself; the axis' v_max limits the set points
        self.position = 0.0
        self.velocity = 0.0
        self.acceleration = 0.0
        self.following_error = 0.0  # the drive's own (0x60F4), user units
        self.statusword = 0
        self.state = "NOT READY TO SWITCH ON"
        self.mode_display = CSP
        self.counts = 0
        self.missed = 0  # SYNCs whose TPDOs did not come within response_timeout
        self.on_lost: Callable[["Cia402Drive", str], None] | None = None
        self._x0 = 0.0
        self._want_on = False
        self._target = 0
        self._cw = CW_SHUTDOWN
        self._late = 0  # SYNCs in a row without the TPDOs
        self._emcy: deque[Any] = deque()
        self._faulted = False  # we put the axis in ErrorStop for a drive reason
        self._lost = False
        self._reset_left = 0
        self._heard = time.monotonic()
        self._nmt_state = 5
        self._got = 0
        self._arrived = threading.Event()
        self._operational = threading.Event()
        self._watching = False
        try:
            self.node = canopen.RemoteNode(cfg.node_id, eds)
        except Exception as e:  # noqa: BLE001 - any parse error of the file is the file's
            raise DriveError(where, [f"drive.eds = {eds!r}: not a readable EDS file ({type(e).__name__}: {e})"]) from None
        bus.network.add_node(self.node)
        self.node.sdo.RESPONSE_TIMEOUT = cfg.response_timeout
        self.node.sdo.MAX_RETRIES = 1  # one try (canopen counts tries; 0 would retry forever)
        self.node.emcy.add_callback(self._emcy.append)
        self.node.nmt.add_heartbeat_callback(self._on_heartbeat)

    # -- start ---------------------------------------------------------------------------------

    def _sdo(self, index: int, sub: int | None = None, value: int | None = None) -> int:
        """One SDO read (value None) or write, or a DriveError naming node and object."""
        what = f"0x{index:04X}" + (f":{sub}" if sub is not None else "") + f" ({_NAMES.get(index, 'object')})"
        try:
            var = self.node.sdo[index] if sub is None else self.node.sdo[index][sub]
            if value is None:
                return int(var.raw)
            var.raw = value
            return value
        except SdoCommunicationError:
            raise DriveError(self.where, [
                f"drive node {self.node_id} on {self.bus.name}: no answer to SDO {what} within {self.cfg.response_timeout:g} s "
                f"(is the drive powered and connected, are node_id = {self.node_id} and bitrate = {self.bus.bitrate} right?)"
            ]) from None
        except SdoAbortedError as e:
            raise DriveError(self.where, [f"drive node {self.node_id}: SDO {what} refused ({e})"]) from None
        except KeyError:
            raise DriveError(self.where, [f"drive node {self.node_id}: the EDS has no object {what}"]) from None

    def start(self, period_us: int) -> None:
        """Bring the drive up: identify it, write cycle, heartbeats and PDO mapping, go OPERATIONAL."""
        cfg = self.cfg
        device_type = self._sdo(0x1000)
        if device_type & 0xFFFF != 402:
            raise DriveError(self.where, [
                f"drive node {self.node_id}: device type 0x{device_type:08X} is not a CiA 402 drive (profile {device_type & 0xFFFF}, expected 402)"
            ])
        self.node.nmt.state = "PRE-OPERATIONAL"
        self._sdo(0x1006, value=period_us)
        if 0x60C2 in self.node.object_dictionary:
            value, index = _interpolation_period(period_us)
            self._sdo(0x60C2, 1, value)
            self._sdo(0x60C2, 2, index & 0xFF if index >= 0 else index)
        self._sdo(0x1016, 1, (self.bus.controller_id << 16) | cfg.controller_timeout_ms)
        self._sdo(0x1017, value=cfg.heartbeat_ms)
        decel = cfg.quick_stop_deceleration
        if decel is None:
            decel = self.axis.config.error_deceleration or self.axis.config.d_max
        if 0x6085 in self.node.object_dictionary:
            self._sdo(0x6085, value=min(_INT32_MAX, max(1, round(decel * self.counts_per_unit))))
        self._map_pdos()
        if 0x6060 in self.node.object_dictionary:
            self._sdo(0x6060, value=CSP)
        self._read_actual()
        if self.state not in _FAULTS:  # a faulted drive starts faulted: the axis reports it
            self._sdo(0x6040, value=CW_SHUTDOWN)
            self._read_actual()
        self._target = self.counts
        self._x0 = self.position
        self._operational.clear()
        self.node.nmt.state = "OPERATIONAL"
        # from its first heartbeat in OPERATIONAL on, the drive's heartbeats are watched (one
        # sent before the NMT start may still arrive after it)
        if not self._operational.wait(cfg.heartbeat_timeout_ms / 1000.0):
            raise DriveError(self.where, [
                f"drive node {self.node_id} on {self.bus.name}: no heartbeat in OPERATIONAL within "
                f"heartbeat_timeout_ms = {cfg.heartbeat_timeout_ms} after the NMT start (heartbeat_ms = {cfg.heartbeat_ms})"
            ])
        self._heard = time.monotonic()
        self._nmt_state = 5
        self._watching = True
        if cfg.homing_method is not None:
            self._home_by_drive(cfg.homing_method)

    def _home_by_drive(self, method: int) -> None:
        """The drive's own homing (mode 6) by SDO: method, home offset, enable, start (bit 4),
        until "homing attained" (bit 12) or "homing error" (bit 13); then CSP again, disabled."""
        cfg = self.cfg
        for index in (0x6060, 0x6098):
            if index not in self.node.object_dictionary:
                raise DriveError(self.where, [f"drive.homing_method = {method}: the EDS has no 0x{index:04X}, so the drive cannot home"])
        self._sdo(0x6098, value=method)
        if 0x607C in self.node.object_dictionary:
            self._sdo(0x607C, value=_int32(cfg.home_offset * self.counts_per_unit))
        self._sdo(0x6060, value=HOMING)
        for cw in (CW_SHUTDOWN, CW_ENABLE_OPERATION, CW_ENABLE_OPERATION | CW_HOMING_START):
            self._sdo(0x6040, value=cw)
        end = time.monotonic() + cfg.homing_timeout
        sw = self._sdo(0x6041)
        while not sw & (SW_HOMING_ATTAINED | SW_HOMING_ERROR) and time.monotonic() < end:
            time.sleep(0.01)  # the drive homes on its own; its statusword says when
            sw = self._sdo(0x6041)
        self._sdo(0x6040, value=CW_SHUTDOWN)
        self._sdo(0x6060, value=CSP)
        if sw & SW_HOMING_ERROR or not sw & SW_HOMING_ATTAINED:
            why = "homing error (statusword bit 13)" if sw & SW_HOMING_ERROR else f"not attained within homing_timeout = {cfg.homing_timeout:g} s"
            raise DriveError(self.where, [f"drive node {self.node_id}: homing by the drive, method {method}: {why}, statusword 0x{sw:04X}"])
        self._read_actual()
        self._target = self.counts
        self._x0 = self.position

    def _map_pdos(self) -> None:
        """The EDS's PDO mapping, written to the drive; the objects CSP needs must be in SYNC PDOs."""
        node = self.node
        try:
            node.rpdo.read(from_od=True)
            node.tpdo.read(from_od=True)
            node.rpdo.save()
            node.tpdo.save()
        except SdoCommunicationError:
            self._sdo(0x1400)  # the same question again, for the error text
        except SdoAbortedError as e:
            raise DriveError(self.where, [f"drive node {self.node_id}: writing the PDO mapping of the EDS was refused ({e})"]) from None
        self._rx = _mapped(node.rpdo)
        self._tx_maps = [m for m in node.tpdo.map.values() if m.enabled and m.trans_type is not None and 1 <= m.trans_type <= 240]
        self._tx = _mapped(node.tpdo)
        self._rx_maps = [m for m in node.rpdo.map.values() if m.enabled and m.map]
        for required, mapped, kind in ((REQUIRED_RX, self._rx, "RPDO"), (REQUIRED_TX, self._tx, "TPDO")):
            for index, name in required.items():
                if index not in mapped:
                    raise DriveError(self.where, [
                        f"drive.eds: 0x{index:04X} ({name}) is in no {kind} sent on SYNC; CSP needs it there (see docs/drives.md)"
                    ])
        for m in self._tx_maps:
            m.add_callback(self._on_tpdo)
        self._need = len(self._tx_maps)

    def _read_actual(self) -> None:
        self.statusword = self._sdo(0x6041)
        self.state = state_of(self.statusword)
        self.counts = self._sdo(0x6064)
        self.position = self.counts * self._upc

    # -- plant drive interface --------------------------------------------------------------------

    @property
    def enabled(self) -> bool:
        return self.state == "OPERATION ENABLED"

    def enable(self, on: bool) -> None:
        self._want_on = bool(on)

    def command_position(self, position: float) -> int:
        """The set point (plant frame, user units) as the next target position, increments."""
        self._target = _int32(position * self.counts_per_unit)
        return self._target

    def step(self, dt: float) -> None:
        """Write this cycle's RPDOs; the bus sends the SYNC after the last drive on it."""
        self._x0 = self.position
        if self.bus.closed:
            return
        rx = self._rx
        cw = self._controlword()
        rx[0x6040].raw = cw
        rx[0x607A].raw = self._target
        jog = self.cfg.jog == "pv" and self._jogging()
        if 0x6060 in rx:
            rx[0x6060].raw = PV if jog else CSP
        cpu = self.counts_per_unit
        if 0x60B1 in rx:
            rx[0x60B1].raw = _int32(self.axis.command_velocity * cpu)
        if 0x60FF in rx:
            rx[0x60FF].raw = _int32(self.axis.command_velocity * cpu) if jog else 0
        for m in self._rx_maps:
            m.transmit()
        self.bus.stepped()

    def _jogging(self) -> bool:
        cmd = self.axis.active_command
        return cmd is not None and cmd.kind == "jog" and self.axis.state is AxisState.CONTINUOUS_MOTION

    def _controlword(self) -> int:
        state = self.state
        if state in _FAULTS:
            if self._reset_left > 0 and not self._cw & CW_FAULT_RESET:
                self._cw = CW_FAULT_RESET  # the rising edge
            else:
                self._cw = CW_SHUTDOWN  # bit 7 low again: the next reset is an edge too
        elif state == "QUICK STOP ACTIVE":
            self._cw = CW_DISABLE_VOLTAGE  # (the drive stopped on its own) -> SWITCH ON DISABLED first
        elif state in ("SWITCH ON DISABLED", "NOT READY TO SWITCH ON"):
            self._cw = CW_SHUTDOWN  # "enable operation" is no command from here: READY first
        elif self._want_on and not self._lost:
            self._cw = CW_ENABLE_OPERATION
        else:
            self._cw = CW_SHUTDOWN
        return self._cw

    # -- the bus' side of the cycle ----------------------------------------------------------------

    def before_sync(self) -> None:
        self._got = 0
        self._arrived.clear()

    def _on_tpdo(self, pdo_map: Any) -> None:  # (the bus' receive thread)
        self._got += 1
        if self._got >= self._need:
            self._arrived.set()

    def await_tpdos(self) -> None:
        if not self._arrived.wait(0.0 if self._lost else self.cfg.response_timeout):
            self.missed += 1
            self._late += 1
            return
        self._late = 0
        tx = self._tx
        self.statusword = sw = int(tx[0x6041].raw)
        self.state = state_of(sw)
        self.counts = counts = int(tx[0x6064].raw)
        x = counts * self._upc
        self.position = x
        v_prev = self.velocity
        if 0x606C in tx:
            self.velocity = int(tx[0x606C].raw) * self._upc
        else:
            self.velocity = (x - self._x0) / self.axis.period
        self.acceleration = (self.velocity - v_prev) / self.axis.period
        if 0x60F4 in tx:
            self.following_error = int(tx[0x60F4].raw) * self._upc
        if 0x6061 in tx:
            self.mode_display = int(tx[0x6061].raw)

    # -- supervision (INPUTS) ----------------------------------------------------------------------

    def _on_heartbeat(self, state: int) -> None:  # (the bus' receive thread)
        if state == 5:
            self._operational.set()
        if self._watching:
            self._heard = time.monotonic()
            self._nmt_state = state

    def watch(self, cycle: int) -> None:
        """EMCY, fault bit, heartbeat and NMT state -> the axis (ErrorStop) and the other axes."""
        axis = self.axis
        if self._faulted and axis.state is not AxisState.ERROR_STOP:
            self._faulted = False  # the axis was reset: reset the drive too
            self._lost = False
            self._reset_left = _RESET_CYCLES
            self._emcy.clear()
        silent = time.monotonic() - self._heard
        why = ""
        if silent > self.cfg.heartbeat_timeout_ms / 1000.0:
            why = f"heartbeat lost (none for {silent:.2f} s)"
        elif self._late >= _LATE_SYNCS:
            why = f"no TPDO after {self._late} SYNCs in a row (response_timeout = {self.cfg.response_timeout:g} s)"
        if why:
            if not self._lost:
                self._lost = True
                self._fault(HEARTBEAT_ERROR, f"drive node {self.node_id} on {self.bus.name}: {why}")
                if self.on_lost is not None:
                    self.on_lost(self, f"drive node {self.node_id} on {self.bus.name} (axis {axis.name}): {why}; the other axes were stopped")
            return
        if self._nmt_state not in (5,) and not self._lost:
            self._lost = True
            state = canopen.nmt.NMT_STATES.get(self._nmt_state, str(self._nmt_state))
            self._fault(HEARTBEAT_ERROR, f"drive node {self.node_id} on {self.bus.name}: left OPERATIONAL (NMT state {state})")
            return
        while self._emcy:
            e = self._emcy.popleft()
            if e.code & 0xFF00 == 0:
                continue  # error reset / no error
            self._fault(e.code, f"drive node {self.node_id}: EMCY {error_text(e.code)}")
        if self.state in _FAULTS:
            if self._reset_left > 0:
                self._reset_left -= 1
                if self._reset_left > 0:
                    return
            if not self._faulted:
                code = self._sdo_quiet(0x603F)
                self._fault(code, f"drive node {self.node_id}: fault {error_text(code)}")
        elif self._reset_left > 0:
            self._reset_left = 0
        if self.state == "QUICK STOP ACTIVE" and not self._faulted:
            self._fault(HEARTBEAT_ERROR, f"drive node {self.node_id}: in quick stop (lost the controller's heartbeat?)")

    def _sdo_quiet(self, index: int) -> int:
        try:
            return int(self.node.sdo[index].raw)
        except (SdoCommunicationError, SdoAbortedError, KeyError):
            return 0xFF00

    def _fault(self, code: int, text: str) -> None:
        if self._faulted:
            return
        self._faulted = True
        self._reset_left = 0
        self.axis.fault(code, text)

    # -- the plant's sensors ask where the motor was during the cycle (switches on the axis) ----

    def position_bounds(self) -> tuple[float, float]:
        a, b = self._x0, self.position
        return (a, b) if a <= b else (b, a)

    def crossings(self, x: float) -> tuple[tuple[float, int], ...]:
        return linear_crossing(self._x0, self.position, x)

    # -- leaving -----------------------------------------------------------------------------------

    def close(self) -> None:
        """Quick stop an enabled drive (its own ramp), then leave it to its heartbeat consumer."""
        if self.state == "OPERATION ENABLED" and not self.bus.closed:
            try:
                self._rx[0x6040].raw = CW_QUICK_STOP
                for m in self._rx_maps:
                    m.transmit()
                self.bus.network.sync.transmit()
            except Exception:  # noqa: BLE001 - leaving a broken bus: nothing more to do
                pass


def _mapped(pdo: Any) -> dict[int, Any]:
    """Object index -> its PDO variable, over the enabled SYNC PDOs (the first map wins)."""
    out: dict[int, Any] = {}
    for m in pdo.map.values():
        if m.enabled and m.trans_type is not None and m.trans_type <= 240:
            for var in m.map:
                out.setdefault(var.index, var)
    return out


def _interpolation_period(period_us: int) -> tuple[int, int]:
    """0x60C2: the period as value x 10^index s with value <= 255 (1000 us: 1, -3)."""
    for index in (-3, -4, -5, -6):
        scale = 10 ** (6 + index)  # microseconds per unit of 10^index s
        if period_us % scale == 0 and period_us // scale <= 255:
            return period_us // scale, index
    return min(255, period_us), -6
