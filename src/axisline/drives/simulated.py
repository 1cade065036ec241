"""A simulated CiA 402 servo drive: canopen's LocalNode with the shipped object dictionary around
the plant's servo model, on a python-can bus (the virtual one in tests and examples).

The drive is a slave like a real one: it boots (boot-up message), answers SDO, takes its PDO
mapping, heartbeat time, heartbeat consumer and cycle period (0x1006) from the controller, and
runs when NMT puts it in OPERATIONAL. At each SYNC it takes the controlword and targets of the
RPDOs received before it, runs the CiA 402 state machine, advances the plant's servo
(plant.drives.ServoDrive) by one cycle period and its motor encoder, and sends its TPDOs. Its
time is the SYNC count x the cycle period: it never reads the wall clock for its motion.

In CSP the drive closes the position loop itself: velocity = feed_forward x velocity offset
(0x60B1) + kv x (target - actual), with actual its encoder's last count, then the servo's
velocity loop. In PV (0x6060 = 3) it commands the target velocity (0x60FF). QUICK STOP ACTIVE
ramps the velocity command to 0 at the quick stop deceleration (0x6085), then (0x605A = 1, 2,
3) goes to SWITCH ON DISABLED. Disabled or in FAULT the motor coasts, as the embedded servo does.
Homing mode (6), started by controlword bit 4: methods 35 and 37 only (see _home).

Decisions
1. Issue 20 "trace agrees with the embedded-plant run": the simulated drive's position loop uses
   the axis' own kv and velocity_feed_forward on the actual value it reported, and the servo and
   encoder of the machine file; so a drive on the bus reproduces the embedded plant cycle by
   cycle, apart from the integer targets (0x607A, 0x60B1 in increments): within one encoder
   count (tests/drives/test_positioning.py).
2. Issue 20 "the drive's own quick stop when the controller goes away": the heartbeat consumer
   (0x1016) is watched on the wall clock, as a real drive's is (the controller's heartbeat is
   sent on it); once it expires the drive runs its quick stop ramp at once in simulated time
   (nobody sends SYNC any more) and sends EMCY 0x8130 (tests/drives/test_faults.py::
   test_controller_loss_quick_stops_the_drive).
"""

from __future__ import annotations

import math
import struct
import threading
import time
from pathlib import Path
from typing import Any

import canopen

from ..plant.drives import ServoDrive
from ..plant.encoder import IncrementalEncoder
from .bus import open_network
from .cia402 import (
    CSP,
    CW_FAULT_RESET,
    CW_HOMING_START,
    FOLLOWING_ERROR,
    HEARTBEAT_ERROR,
    HOMING,
    PV,
    SW_HOMING_ATTAINED,
    SW_HOMING_ERROR,
    SW_TARGET_REACHED,
    command_of,
    statusword_of,
)
from .config import GENERIC_EDS

__all__ = ["SimulatedDrive"]

_INT32 = (-(2**31), 2**31 - 1)
_CONSUMER_POLL_S = 0.005  # how often the heartbeat consumer looks (a real drive: every ms or so)


def _int32(x: float) -> int:
    n = round(x)
    return _INT32[0] if n < _INT32[0] else _INT32[1] if n > _INT32[1] else n


class SimulatedDrive:
    """A CiA 402 servo drive slave wrapping `servo` (user units) and `encoder` (counts)."""

    def __init__(
        self,
        node_id: int,
        servo: ServoDrive,
        encoder: IncrementalEncoder,
        *,
        kv: float,
        feed_forward: float = 1.0,
        interface: str = "virtual",
        channel: str = "axisline",
        bitrate: int = 1_000_000,
        eds: Path = GENERIC_EDS,
    ) -> None:
        self.servo = servo
        self.encoder = encoder
        self.kv = float(kv)
        self.feed_forward = float(feed_forward)
        self._unit_per_count = 1.0 / encoder.counts_per_unit
        self._cpu = encoder.counts_per_unit
        self.state = "SWITCH ON DISABLED"  # after NOT READY TO SWITCH ON's self-test
        self._shift = 0  # counts added to the encoder's: the home frame (homing mode)
        self._homing = ""  # "", "attained" or "error"
        self.counts = encoder.sample()
        self.velocity_counts = 0
        self.following_error = 0
        self.error_code = 0
        self.mode = CSP
        self.syncs = 0  # SYNCs acted on: the drive's clock
        self._last_cw = 0
        self._pending_fault: tuple[int, bool] | None = None
        self._qs_velocity = 0.0
        self._silent = False
        self._lock = threading.RLock()
        self._consumer_seen = time.monotonic()
        self._closed = threading.Event()
        self.network = open_network(interface, channel, bitrate, f"simulated drive {node_id}")
        self.node = canopen.LocalNode(node_id, str(eds))
        self.network.add_node(self.node)
        self.node.add_read_callback(self._on_read)
        self.node.add_write_callback(self._on_write)
        self.network.subscribe(0x80, self._on_sync)
        self.network.subscribe(0, self._on_nmt)
        self._rx: dict[int, Any] = {}
        self._tx: list[Any] = []
        self._consumer: tuple[int, float] | None = None
        self._watch = threading.Thread(target=self._consumer_loop, name=f"cia402-sim-{node_id}-hb", daemon=True)
        self._watch.start()
        # power-up: boot-up message, then PRE-OPERATIONAL (CiA 301)
        self.node.nmt.send_command(0x81)
        self.node.nmt.send_command(0x80)

    @property
    def node_id(self) -> int:
        return self.node.id

    # -- what a test does to a drive ------------------------------------------------------------

    def inject_fault(self, code: int, *, emcy: bool = True) -> None:
        """The drive faults at its next SYNC with `code` (EMCY sent unless emcy=False)."""
        with self._lock:
            self._pending_fault = (code, emcy)

    def go_silent(self, *, heartbeat_only: bool = False) -> None:
        """The drive drops off the bus: no heartbeat, no answer to SYNC (cable pulled); or,
        heartbeat_only, it stops its heartbeat and keeps answering (a heartbeat-only loss)."""
        with self._lock:
            self._silent = not heartbeat_only
            self.node.nmt.stop_heartbeat()

    # -- object dictionary --------------------------------------------------------------------

    def _actual(self, index: int) -> int | None:
        if index == 0x6041:
            sw = statusword_of(self.state) | (0x0200 if self.node.nmt.state == "OPERATIONAL" else 0)
            if self.mode == HOMING and self._homing:
                sw |= SW_HOMING_ATTAINED | SW_TARGET_REACHED if self._homing == "attained" else SW_HOMING_ERROR
            return sw
        if index == 0x6064:
            return _int32(self.counts)
        if index == 0x606C:
            return _int32(self.velocity_counts)
        if index == 0x60F4:
            return _int32(self.following_error)
        if index == 0x6061:
            return self.mode
        if index == 0x603F:
            return self.error_code
        return None

    def _on_read(self, index: int, subindex: int, od: Any) -> int | None:
        with self._lock:
            return self._actual(index)

    def _on_write(self, index: int, subindex: int, od: Any, data: bytes) -> None:
        if index == 0x6040:  # a controlword by SDO acts at once (commissioning, start-up, homing)
            with self._lock:
                cw = od.decode_raw(data)
                start = cw & CW_HOMING_START and not self._last_cw & CW_HOMING_START
                self._control(cw)
                if start and self.mode == HOMING and self.state == "OPERATION ENABLED":
                    self._home()
        elif index == 0x6060:
            self.mode = od.decode_raw(data)
            self._homing = ""

    def _od(self, index: int, subindex: int = 0) -> int:
        """A parameter as the controller wrote it (or the EDS default)."""
        return int.from_bytes(self.node.get_data(index, subindex), "little", signed=index in (0x605A, 0x6060, 0x6098, 0x607C))

    def _home(self) -> None:
        """Homing mode: methods 35 and 37 (CiA 402: the current position is home) set the
        position to the home offset at once; a method that searches a switch or an index is not
        simulated and reports a homing error."""
        if self._od(0x6098) in (35, 37):
            offset = self._od(0x607C)
            self._shift += offset - self.counts
            self.counts = offset
            self._homing = "attained"
        else:
            self._homing = "error"

    def _on_nmt(self, can_id: int, data: bytes, timestamp: float) -> None:
        cmd, node = struct.unpack_from("BB", data)
        if node in (0, self.node.id) and cmd == 0x01:  # start: take the PDO setup the controller wrote
            with self._lock:
                self._start()

    def _start(self) -> None:
        self.node.rpdo.read()
        self.node.tpdo.read()
        self._rx = {v.index: v for m in self.node.rpdo.map.values() if m.enabled for v in m.map}
        self._tx = [m for m in self.node.tpdo.map.values() if m.enabled and m.trans_type is not None and 1 <= m.trans_type <= 240]
        self._period = self._od(0x1006) / 1e6
        consumer = self._od(0x1016, 1)
        self._consumer = ((consumer >> 16) & 0x7F, (consumer & 0xFFFF) / 1000.0) if consumer & 0xFFFF else None
        if self._consumer is not None:
            self.network.subscribe(0x700 + self._consumer[0], self._on_consumer)
        self._consumer_seen = time.monotonic()

    def _on_consumer(self, can_id: int, data: bytes, timestamp: float) -> None:
        self._consumer_seen = time.monotonic()

    def _value(self, index: int) -> int:
        var = self._rx.get(index)
        return int(var.raw) if var is not None else self._od(index)

    # -- the CiA 402 state machine ----------------------------------------------------------------

    def _control(self, cw: int) -> None:
        rising_reset = cw & CW_FAULT_RESET and not self._last_cw & CW_FAULT_RESET
        self._last_cw = cw
        state = self.state
        if state == "FAULT":
            if rising_reset:  # transition 15
                self.state = "SWITCH ON DISABLED"
                self.error_code = 0
                self.node.emcy.reset()
            return
        cmd = command_of(cw)
        if cmd == "disable voltage":
            self.state = "SWITCH ON DISABLED"
        elif cmd == "quick stop":
            if state == "OPERATION ENABLED":
                self._enter_quick_stop()
            elif state != "QUICK STOP ACTIVE":
                self.state = "SWITCH ON DISABLED"
        elif cmd == "shutdown":
            if state in ("SWITCH ON DISABLED", "SWITCHED ON", "OPERATION ENABLED"):
                self.state = "READY TO SWITCH ON"
        elif cmd == "switch on":
            if state in ("READY TO SWITCH ON", "OPERATION ENABLED"):
                self.state = "SWITCHED ON"
        else:  # enable operation: 4 from SWITCHED ON, 3 + 4 from READY, 16 from QUICK STOP
            if state in ("READY TO SWITCH ON", "SWITCHED ON", "QUICK STOP ACTIVE"):
                self.state = "OPERATION ENABLED"

    def _enter_quick_stop(self) -> None:
        self.state = "QUICK STOP ACTIVE"
        self._qs_velocity = self.servo.velocity

    def _fault(self, code: int, emcy: bool = True) -> None:
        self.state = "FAULT"
        self.error_code = code
        if emcy:
            register = 0x10 if code == HEARTBEAT_ERROR else 0x01  # communication / generic
            self.node.emcy.send(code, register)

    # -- one cycle ---------------------------------------------------------------------------------

    def _on_sync(self, can_id: int, data: bytes, timestamp: float) -> None:
        with self._lock:
            if self._silent or self.node.nmt.state != "OPERATIONAL" or self._closed.is_set():
                return
            self._cycle()
            for m in self._tx:
                m.transmit()

    def _cycle(self) -> None:
        self.syncs += 1
        if self._pending_fault is not None:
            code, emcy = self._pending_fault
            self._pending_fault = None
            self._fault(code, emcy)
        rx = self._rx
        if 0x6040 in rx:
            self._control(int(rx[0x6040].raw))
        if 0x6060 in rx:
            self.mode = int(rx[0x6060].raw)
        target = self._value(0x607A)
        self._move(target)
        self.counts = counts = self.encoder.sample() + self._shift
        self.velocity_counts = _int32(self.servo.velocity * self._cpu)
        self.following_error = target - counts if self.mode == CSP else 0
        window = self._od(0x6065)
        if self.state == "OPERATION ENABLED" and window != 0xFFFFFFFF and abs(self.following_error) > window:
            self._fault(FOLLOWING_ERROR)
        for m in self._tx:
            for var in m.map:
                value = self._actual(var.index)
                if value is not None:
                    var.raw = value

    def _move(self, target: int) -> None:
        """Advance the servo by one cycle period under this cycle's state and targets."""
        servo, dt = self.servo, self._period
        state = self.state
        if state == "OPERATION ENABLED":
            servo.enable(True)
            if self.mode == PV:
                servo.command_velocity(self._value(0x60FF) * self._unit_per_count)
            else:
                upc = self._unit_per_count
                offset = self._value(0x60B1) * upc if 0x60B1 in self._rx else 0.0
                servo.command_velocity(self.feed_forward * offset + self.kv * (target * upc - self.counts * upc))
        elif state == "QUICK STOP ACTIVE":
            self._quick_stop_step(dt)
            return
        else:
            servo.enable(False)
        servo.step(dt)

    def _quick_stop_step(self, dt: float) -> None:
        servo = self.servo
        servo.enable(True)
        dec = self._od(0x6085) * self._unit_per_count
        v = self._qs_velocity
        dv = dec * dt
        v = 0.0 if abs(v) <= dv else v - math.copysign(dv, v)
        self._qs_velocity = v
        servo.command_velocity(v)
        servo.step(dt)
        if v == 0.0 and abs(servo.velocity) < 1e-9 * max(1.0, self._cpu) and self._od(0x605A) in (0, 1, 2, 3):
            self.state = "SWITCH ON DISABLED"

    # -- heartbeat consumer -------------------------------------------------------------------

    def _consumer_loop(self) -> None:
        while not self._closed.wait(_CONSUMER_POLL_S):
            with self._lock:
                c = self._consumer
                if c is None or self._silent or self.node.nmt.state != "OPERATIONAL":
                    continue
                if time.monotonic() - self._consumer_seen <= c[1]:
                    continue
                self._controller_lost()

    def _controller_lost(self) -> None:
        """No controller heartbeat: quick stop (the ramp runs now, in simulated time), EMCY 0x8130."""
        self._consumer = None  # acted on once
        self.node.emcy.send(HEARTBEAT_ERROR, 0x10)
        if self.state == "OPERATION ENABLED":
            self._enter_quick_stop()
            dt = self._period or 0.001
            for _ in range(1_000_000):  # ends: the ramp is finite (checked deceleration > 0)
                if self.state != "QUICK STOP ACTIVE":
                    break
                self._quick_stop_step(dt)
                self.counts = self.encoder.sample() + self._shift
            self.velocity_counts = _int32(self.servo.velocity * self._cpu)

    def close(self) -> None:
        self._closed.set()
        self.node.nmt.stop_heartbeat()
        try:
            self.network.disconnect()
        except Exception:  # noqa: BLE001 - a bus already gone has nothing left to release
            pass
