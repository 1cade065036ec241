"""A WAGO Modbus TCP fieldbus coupler with one or several 750-672 modules behind it.

The coupler maps the 12-byte process images of its modules into 16-bit Modbus registers
the way a WAGO ETHERNET coupler (750-341/-352 family) packs complex modules: each 750-672
takes 6 input and 6 output registers, module n's registers follow module n-1's.

    address            FC        what
    0x0000 + 6n + k    3, 4      input image of module n, register k (read)
    0x0000 + 6n + k    6, 16     output image of module n, register k (write)
    0x0200 + 6n + k    3, 4      output image of module n, read back
    0x1000             3, 4      watchdog time [ms] (read only; set in the machine file)
    0x1006             3, 4      watchdog status: 0 not started (or off), 1 running, 2 expired

Register k holds byte 2k of the module image in its low byte and byte 2k+1 in its high byte
(the byte order of the module's little-endian fields is kept, so the 24-bit position D4..D6 =
image bytes 6..8 lies in the high byte of register 2, register 3 and the low byte of register 4
... see docs/wago672-modbus.md for the whole map). Any other address, a read of count 0, a
value outside 0..0xFFFF is refused (`RegisterRefused`, Modbus exception 02); a refused
request changes nothing.

K-bus cycle (`tick`, every 1 ms): the coupler hands each module its outputs, runs the module's
tick and takes its inputs, so KBUS_Active stays 1 while the coupler runs. Requests arrive at
cycle boundaries (the Modbus server goes through the machine's command queue), so a register
block written with one FC16 reaches the module in one piece, as the coupler's exchange does.

Fieldbus watchdog (the coupler's, armed by the first write to the output image; every later
write to it re-triggers it; reads do not): when no write came for longer than the watchdog
time, the coupler clears the output image (the read-back shows zeros), sets the status to 2
(expired) and counts the expiry. What the modules see then:

1. until the module is at standstill: Enable as the PLC last wrote it, every other bit 0.
   Stop2_N = 0 (and the mode bit = 0) makes the 750-672 brake with Acceleration_Stop_Fast
   (the STOP ramp) and end its mode; Stop_N_ACK drops at standstill.
2. then: all bytes 0, as a WAGO coupler sets its outputs after a watchdog timeout. Enable = 0
   switches the output stage off (the motor is at rest already).

[Decision W1] A WAGO coupler clears the outputs at once. For a 750-672 that means Enable = 0,
which switches the output stage off without a ramp (manual §3.7.2: "the drive can coast to a
stop. When closing down with a stop ramp, Stop2_N must be used"). The issue asks for a stop
with the stop ramp, so the coupler keeps Enable for the time of the ramp (step 1) and clears
it at standstill (step 2): the end state is the coupler's, the way there is the ramp's.

[Decision W2] Watchdog time 0 switches the watchdog off (as on a WAGO coupler, whose watchdog
time 0 means no watchdog): writes never arm it, the status stays 0, nothing stops the motors -
for hand tools (mbpoll, a Modbus client typed at) that write once and then read; 1 .. 9 ms is
refused in the machine file (shorter than a request's round trip). `on_expiry(cycle, ticks)`
is told of each expiry: the personality prints one line on the console (test_plc_script.py
test_watchdog_off_a_hand_tool_may_write_once_and_the_move_completes,
test_watchdog_on_trips_and_says_so_once_naming_the_module_and_the_time).

A client that disconnects: the Modbus server cannot tell the device a connection closed, and
a PLC may reconnect on purpose. The watchdog covers it: no writes, so after the watchdog time
the motor stops with its ramp. The next write re-arms the watchdog; the module then sees the
image the client writes (after an expiry the rest of the image is 0: write all 6 registers).
"""

from __future__ import annotations

import math
import struct
from collections.abc import Callable, Sequence
from typing import Any

from axisline.devices.wago672.image import IMAGE_SIZE, OFFSET_C1, C1, S1
from axisline.fieldbus.modbus import RegisterRefused

__all__ = [
    "REGISTERS_PER_MODULE",
    "INPUT_BASE",
    "OUTPUT_BASE",
    "OUTPUT_READBACK",
    "WATCHDOG_TIME",
    "WATCHDOG_STATUS",
    "WD_NOT_STARTED",
    "WD_RUNNING",
    "WD_EXPIRED",
    "MAX_MODULES",
    "pack",
    "unpack",
    "Coupler",
]

REGISTERS_PER_MODULE = IMAGE_SIZE // 2  # 6 registers carry the 12 bytes of a 750-672
INPUT_BASE = 0x0000  # input images, FC3 and FC4
OUTPUT_BASE = 0x0000  # output images, FC6 and FC16
OUTPUT_READBACK = 0x0200  # output images read back, FC3 and FC4
WATCHDOG_TIME = 0x1000  # watchdog time [ms], read only
WATCHDOG_STATUS = 0x1006  # 0 not started, 1 running, 2 expired (as a WAGO coupler's WD status)
MAX_MODULES = 16  # as many 750-672 as the largest WAGO ETHERNET controllers take

WD_NOT_STARTED = 0
WD_RUNNING = 1
WD_EXPIRED = 2

_STOPPING = 1  # fail-safe step 1: Enable kept, the module brakes with its STOP ramp
_CLEARED = 2  # fail-safe step 2: everything 0


def pack(image: bytes | bytearray) -> list[int]:
    """Bytes -> registers: register k = byte 2k (low byte) | byte 2k+1 (high byte)."""
    data = bytes(image)
    if len(data) % 2:
        raise ValueError(f"an image packs into registers only with an even length, got {len(data)} bytes")
    return list(struct.unpack(f"<{len(data) // 2}H", data))


def unpack(registers: Sequence[int]) -> bytes:
    """Registers -> bytes: the inverse of `pack`."""
    try:
        return struct.pack(f"<{len(registers)}H", *registers)  # the PLC's cyclic write: every cycle
    except struct.error:
        pass  # a value that is not a 16-bit integer: named below
    out = bytearray()
    for r in registers:
        r = int(r)
        if not 0 <= r <= 0xFFFF:
            raise ValueError(f"register value {r} is outside 0 .. 0xFFFF")
        out += bytes((r & 0xFF, r >> 8))
    return bytes(out)


class Coupler:
    """Process image and watchdog of a WAGO Modbus TCP coupler with 750-672 modules.

    `modules`: the Wago672 devices in the order they sit on the K-bus. `watchdog_ms`: the
    fieldbus watchdog time. `tick_s`: the K-bus cycle (the 750-672's 1 ms TICK).
    `writes_allowed`: the operator's enable for network writes (read by the Modbus server
    through `network_writes`); without it the attribute can be set directly.
    """

    def __init__(
        self,
        modules: Sequence[Any],
        watchdog_ms: int = 100,
        *,
        tick_s: float = 0.001,
        writes_allowed: Callable[[], bool] | None = None,
        on_expiry: Callable[[int, int], None] | None = None,
    ) -> None:
        if not 1 <= len(modules) <= MAX_MODULES:
            raise ValueError(f"a coupler takes 1 .. {MAX_MODULES} modules, got {len(modules)}")
        if isinstance(watchdog_ms, bool) or not isinstance(watchdog_ms, int) or watchdog_ms < 0:
            raise ValueError(f"watchdog_ms must be an integer >= 0 (0: off), got {watchdog_ms!r}")
        self.modules = list(modules)
        self.watchdog_ms = watchdog_ms
        self.tick_s = tick_s
        #: ticks without a write after which the watchdog expires (more than watchdog_ms)
        self.watchdog_cycles = max(1, math.ceil(watchdog_ms / (tick_s * 1000.0) - 1e-9))
        self._writes_allowed = writes_allowed
        #: called as on_expiry(cycle, ticks since the last write) when the watchdog expires
        self.on_expiry = on_expiry
        self._network_writes = False
        n = len(self.modules)
        self._out = [bytearray(IMAGE_SIZE) for _ in range(n)]  # what the PLC wrote
        self._seen = [bytes(IMAGE_SIZE) for _ in range(n)]  # what the modules got last tick
        self._in = [bytes(IMAGE_SIZE) for _ in range(n)]
        self._failsafe = [0] * n  # 0 normal, _STOPPING, _CLEARED
        self.watchdog_status = WD_NOT_STARTED
        self.since_write = 0  # ticks since the last write
        self.expiries = 0
        self.last_expiry_cycle: int | None = None
        self.reads = 0
        self.writes = 0
        self.cycle: int | None = None

    # ------------------------------------------------------------------ operator's enable

    @property
    def network_writes(self) -> bool:
        if self._writes_allowed is not None:
            return bool(self._writes_allowed())
        return self._network_writes

    @network_writes.setter
    def network_writes(self, value: bool) -> None:
        self._network_writes = bool(value)

    # ------------------------------------------------------------------ layout

    @property
    def size(self) -> int:
        """Registers of each image (6 per module)."""
        return REGISTERS_PER_MODULE * len(self.modules)

    def outputs(self, module: int = 0) -> bytes:
        """The output image of `module` as the PLC wrote it (zeros after a watchdog expiry)."""
        return bytes(self._out[module])

    def module_outputs(self, module: int = 0) -> bytes:
        """The output image `module` was given at the last tick (the fail-safe image after an expiry)."""
        return self._seen[module]

    def inputs(self, module: int = 0) -> bytes:
        """The input image of `module` as of the last tick."""
        return self._in[module]

    @property
    def watchdog_expired(self) -> bool:
        return self.watchdog_status == WD_EXPIRED

    # ------------------------------------------------------------------ RegisterEndpoint

    def read_registers(self, kind: str, address: int, count: int) -> list[int]:
        """FC3 ("holding") and FC4 ("input"): the same map for both."""
        if kind not in ("holding", "input"):
            raise RegisterRefused(f"unknown register kind {kind!r}")
        if count < 1:
            raise RegisterRefused(f"a read needs at least one register, got {count}")
        size = self.size
        end = address + count
        if INPUT_BASE <= address and end <= INPUT_BASE + size:
            regs = self._image_registers(self._in, address - INPUT_BASE, count)
        elif OUTPUT_READBACK <= address and end <= OUTPUT_READBACK + size:
            regs = self._image_registers(self._out, address - OUTPUT_READBACK, count)
        elif all(a in (WATCHDOG_TIME, WATCHDOG_STATUS) for a in range(address, end)):
            regs = [self._status_register(a) for a in range(address, end)]
        else:
            raise RegisterRefused(
                f"registers {address:#06x} .. {end - 1:#06x} are not all in the coupler's map: inputs 0x0000 .. "
                f"{size - 1:#06x}, outputs read back {OUTPUT_READBACK:#06x} .. {OUTPUT_READBACK + size - 1:#06x}, "
                f"watchdog {WATCHDOG_TIME:#06x} and {WATCHDOG_STATUS:#06x}"
            )
        self.reads += 1
        return regs

    def _status_register(self, address: int) -> int:
        if address == WATCHDOG_TIME:
            return min(self.watchdog_ms, 0xFFFF)
        return self.watchdog_status

    @staticmethod
    def _image_registers(images: list, offset: int, count: int) -> list[int]:
        flat = b"".join(bytes(i) for i in images)
        return pack(flat[2 * offset : 2 * (offset + count)])

    def write_registers(self, address: int, values: list[int]) -> None:
        """FC6 and FC16: output images from address 0; a write re-triggers the watchdog."""
        count = len(values)
        if count < 1:
            raise RegisterRefused("a write needs at least one register")
        if not (OUTPUT_BASE <= address and address + count <= OUTPUT_BASE + REGISTERS_PER_MODULE * len(self.modules)):
            if WATCHDOG_TIME <= address <= WATCHDOG_STATUS:
                raise RegisterRefused(f"register {address:#06x} is read only: the watchdog time is set in the machine file")
            raise RegisterRefused(
                f"registers {address:#06x} .. {address + count - 1:#06x} are not writable: "
                f"the output images are 0x0000 .. {OUTPUT_BASE + self.size - 1:#06x}"
            )
        try:
            data = unpack(values)
        except ValueError as e:
            raise RegisterRefused(str(e)) from None
        self._store(2 * (address - OUTPUT_BASE), data)

    def write_images(self, data: bytes) -> None:
        """The whole output area at once, as bytes (module 0's 12 bytes first): the write of a
        PLC's cyclic exchange, the FC16 of all registers from 0 without packing them."""
        if len(data) != IMAGE_SIZE * len(self.modules):
            raise ValueError(f"the output area of {len(self.modules)} modules is {IMAGE_SIZE * len(self.modules)} bytes, got {len(data)}")
        self._store(0, data)

    def _store(self, k: int, data: bytes) -> None:
        """Output bytes from byte `k` of the output area on; re-triggers the watchdog."""
        if self.watchdog_status == WD_EXPIRED:
            self._rearm()
        done = 0
        if k == 0 and len(data) == IMAGE_SIZE * len(self._out):  # all images (a PLC's cyclic write)
            for image in self._out:
                image[:] = data[done : done + IMAGE_SIZE]
                done += IMAGE_SIZE
        while done < len(data):  # module by module: the part of `data` in each image
            module, offset = divmod(k, IMAGE_SIZE)
            take = min(IMAGE_SIZE - offset, len(data) - done)
            self._out[module][offset : offset + take] = data[done : done + take]
            k += take
            done += take
        if self.watchdog_ms:  # watchdog_ms 0: off, never armed (status stays 0)
            self.watchdog_status = WD_RUNNING
        self.since_write = 0
        self.writes += 1

    def _rearm(self) -> None:
        for n in range(len(self.modules)):
            self._failsafe[n] = 0

    # ------------------------------------------------------------------ K-bus cycle

    def tick(self, cycle: int) -> None:
        """One K-bus cycle: watchdog, outputs to the modules, module ticks, inputs back."""
        self.cycle = cycle
        if self.watchdog_status == WD_RUNNING:
            self.since_write += 1
            if self.since_write > self.watchdog_cycles:
                self._expire(cycle)
        elif self.watchdog_status == WD_EXPIRED:
            self.since_write += 1
        for n, dev in enumerate(self.modules):
            state = self._failsafe[n]
            if state == 0:
                image = bytes(self._out[n])
            elif state == _STOPPING:
                image = self._stop_image(self._seen[n])
            else:
                image = bytes(IMAGE_SIZE)
            dev.write_outputs(image)
            dev.tick(cycle)
            self._seen[n] = image
            self._in[n] = dev.read_inputs()
            if state == _STOPPING:
                s1 = self._in[n][OFFSET_C1]
                if not (s1 & S1.Ready) or not (s1 & S1.Stop_N_ACK):
                    self._failsafe[n] = _CLEARED  # at standstill (or off): clear as the coupler does

    def _expire(self, cycle: int) -> None:
        self.watchdog_status = WD_EXPIRED
        self.expiries += 1
        self.last_expiry_cycle = cycle
        for n in range(len(self.modules)):
            self._out[n][:] = bytes(IMAGE_SIZE)
            self._failsafe[n] = _STOPPING
        if self.on_expiry is not None:
            self.on_expiry(cycle, self.since_write)

    def stop_modules(self) -> None:
        """Shutdown of the simulation (serve stopped): every module brakes as on a watchdog expiry."""
        for n in range(len(self.modules)):
            self._out[n][:] = bytes(IMAGE_SIZE)
            if self._failsafe[n] == 0:
                self._failsafe[n] = _STOPPING

    @staticmethod
    def _stop_image(last: bytes) -> bytes:
        """Fail-safe step 1: only Enable as the module last had it (W1)."""
        image = bytearray(IMAGE_SIZE)
        image[OFFSET_C1] = last[OFFSET_C1] & C1.Enable
        return bytes(image)

    # ------------------------------------------------------------------ report

    def summary(self) -> dict[str, Any]:
        return {
            "registers_per_module": REGISTERS_PER_MODULE,
            "modules": len(self.modules),
            "watchdog_ms": self.watchdog_ms,
            "watchdog_status": "off" if not self.watchdog_ms else ("not started", "running", "expired")[self.watchdog_status],
            "watchdog_expiries": self.expiries,
            "reads": self.reads,
            "writes": self.writes,
        }
