"""The PLC side of a WAGO 750-672 behind a Modbus TCP coupler: handshakes over Modbus.

    from axisline.devices.wago672.client import Wago672Client

    with Wago672Client("127.0.0.1", 1502, module=0) as plc:
        plc.enable()                                   # Enable, Stop2_N -> Ready, Stop_N_ACK
        plc.move_to(25600, velocity=20000, acceleration=2000)   # single positioning, waits On_Target
        print(plc.status().position)                   # microsteps (user units of the module)
        plc.reference(direction=-1)                    # reference run, waits Reference_OK
        plc.jog(+1); ...; plc.jog(0)                   # JogMode by Direction_Pos/Neg: press, release
        plc.speed(5000, 1000)                          # speed control
        reply = plc.mailbox(0x49)                      # any mailbox opcode: toggle handshake
        plc.download_table(1, 1, rows)                 # DLD_START, DLD_CONT x n, DLD_END (byte sum)

The client keeps the module's 12-byte output image and exchanges it with the coupler: it
writes the 6 output registers (FC16) and reads the 6 input registers (FC4) - one
`exchange()`, as a PLC task does each cycle (register map: docs/wago672-modbus.md). Every
handshake polls by exchanging, so the coupler's watchdog is fed while the client waits; a
background task (`cycle` seconds, default 20 ms; None: off) keeps exchanging between calls, so
a motion started with wait=False goes on while the program does something else. Close the
client (or let it die) and the coupler's watchdog stops the motor with its STOP ramp.

Errors: `Wago672Timeout` when a handshake does not complete in time (the message shows the
status bytes), `Wago672DeviceError` when the module reports Error (S2.7; `read_error()` reads
its code through the mailbox, `quit_error()` acknowledges it), `MailboxError` for a mailbox
return code other than 0, `Wago672ClientError` for Modbus failures.

Everything a PLC would do is done with the process image only (manual §3.7, §3.11): the
mailbox opcodes, the configuration and table downloads follow the manual's request layouts
(§3.8, wago.md §3.7-3.10); whether the module answers them is the module's business.
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass

from pymodbus.client import ModbusTcpClient
from pymodbus.exceptions import ModbusException

from axisline.devices.wago672.config_table import ConfigTable
from axisline.devices.wago672.coupler import OUTPUT_READBACK, REGISTERS_PER_MODULE, WATCHDOG_STATUS, WATCHDOG_TIME, pack, unpack
from axisline.devices.wago672.mailbox import MbxOpcode
from axisline.devices.wago672.image import (
    IMAGE_SIZE,
    OFFSET_C0,
    OFFSET_C1,
    OFFSET_C2,
    OFFSET_C3,
    OFFSET_D0,
    C0,
    C1,
    C2,
    C3,
    S0,
    S1,
    S2,
    S3,
    PositioningActuals,
    PositioningSetpoints,
    ProgramSetpoints,
    SpeedSetpoints,
)

__all__ = [
    "Wago672Client",
    "Status",
    "MailboxReply",
    "Wago672ClientError",
    "Wago672Timeout",
    "Wago672DeviceError",
    "MailboxError",
    "MODES",
    "Mbx",
    "program_rows",
    "checksum",
]

# Command field values (C1 >> 3) and the C1 bits that select them (speed control: C1.3 + C1.4)
MODES: dict[str, int] = {"idle": 0, "positioning": 1, "program": 2, "speed": 3, "reference": 4, "jog": 8, "mailbox": 16}
_MODE_BITS = 0xF8
_RUN = C1.Enable | C1.Stop2_N


# the module's own opcode table: the client speaks exactly what the mailbox implements
Mbx = MbxOpcode


class Wago672ClientError(RuntimeError):
    """Modbus communication failed, or a request was refused by the coupler."""


class Wago672Timeout(Wago672ClientError, TimeoutError):
    """A handshake did not complete in time."""


class Wago672DeviceError(Wago672ClientError):
    """The module reports Error (S2.7)."""

    def __init__(self, text: str, status: "Status") -> None:
        super().__init__(text)
        self.status = status


class MailboxError(Wago672ClientError):
    """A mailbox request answered with a return code other than 0 (or a refused status)."""

    def __init__(self, text: str, reply: "MailboxReply") -> None:
        super().__init__(text)
        self.reply = reply


@dataclass(frozen=True, slots=True)
class Status:
    """The module's input image, decoded (S0..S3 and the actual values)."""

    s0: int
    s1: int
    s2: int
    s3: int
    data: bytes

    @classmethod
    def from_bytes(cls, raw: bytes) -> "Status":
        return cls(raw[OFFSET_C0], raw[OFFSET_C1], raw[OFFSET_C2], raw[OFFSET_C3], bytes(raw[OFFSET_D0 : OFFSET_D0 + 7]))

    ready = property(lambda self: bool(self.s1 & S1.Ready))
    stop_n_ack = property(lambda self: bool(self.s1 & S1.Stop_N_ACK))
    start_ack = property(lambda self: bool(self.s1 & S1.Start_ACK))
    on_target = property(lambda self: bool(self.s2 & S2.On_Target))
    busy = property(lambda self: bool(self.s2 & S2.Busy))
    standstill = property(lambda self: bool(self.s2 & S2.StandStill))
    on_speed = property(lambda self: bool(self.s2 & S2.On_Speed))
    direction = property(lambda self: bool(self.s2 & S2.Direction))
    reference_ok = property(lambda self: bool(self.s2 & S2.Reference_OK))
    precalc_ack = property(lambda self: bool(self.s2 & S2.PreCalc_ACK))
    error = property(lambda self: bool(self.s2 & S2.Error))
    warning = property(lambda self: bool(self.s3 & S3.Warning))
    reset = property(lambda self: bool(self.s3 & S3.Reset))
    mailbox = property(lambda self: bool(self.s0 & S0.MBX))

    @property
    def mode(self) -> int:
        """Command_Ack: the active mode (0 idle, 1 positioning, 2 program, 3 speed, 4 reference, 8 jog, 16 mailbox)."""
        return (self.s1 >> 3) & 0x1F

    @property
    def inputs(self) -> tuple[bool, ...]:
        """Input1 .. Input6 (S3.0 .. S3.5)."""
        return tuple(bool(self.s3 >> i & 1) for i in range(6))

    @property
    def position(self) -> int | None:
        """Actual position (D4..D6, user units; microsteps by default); None while the mailbox is on."""
        return None if self.mailbox else PositioningActuals.decode(self.data).position

    @property
    def velocity(self) -> int | None:
        """Actual velocity (D0..D1, user units); None while the mailbox is on."""
        return None if self.mailbox else PositioningActuals.decode(self.data).velocity

    @property
    def mailbox_reply(self) -> bytes:
        return self.data[0:6]

    def __str__(self) -> str:
        flags = [n for n in ("ready", "stop_n_ack", "start_ack", "on_target", "busy", "standstill", "on_speed",
                             "reference_ok", "error", "warning", "reset", "mailbox") if getattr(self, n)]
        where = "" if self.mailbox else f" position={self.position} velocity={self.velocity}"
        return (f"S0={self.s0:#04x} S1={self.s1:#04x} S2={self.s2:#04x} S3={self.s3:#04x} mode={self.mode}"
                f"{where} [{' '.join(flags)}]")


@dataclass(frozen=True, slots=True)
class MailboxReply:
    """MB0 (opcode echo), the return code (Status_Mbx bits 0..6) and MB2..MB5."""

    opcode: int
    code: int
    data: bytes

    @property
    def ok(self) -> bool:
        return self.code == 0

    @property
    def value(self) -> int:
        """MB2..MB5 as a 32-bit little-endian unsigned value."""
        return int.from_bytes(self.data, "little")


def program_rows(lines: Iterable[tuple[int, int]]) -> list[bytes]:
    """Run-program lines (opcode, 24-bit data) -> compressed 24-bit DLD_CONT rows (MB2..MB5)."""
    rows = []
    for opcode, data in lines:
        if not 0 <= opcode <= 0xFF:
            raise ValueError(f"opcode {opcode} is outside 0 .. 0xFF")
        if not -(1 << 23) <= data < (1 << 24):
            raise ValueError(f"data {data} does not fit 24 bits")
        rows.append(bytes([opcode]) + (data & 0xFFFFFF).to_bytes(3, "little"))
    return rows


def checksum(rows: Iterable[bytes]) -> int:
    """DLD_END checksum: the plain sum of every byte sent with DLD_CONT (32 bit)."""
    return sum(sum(bytes(r)) for r in rows) & 0xFFFFFFFF


class Wago672Client:
    """Modbus TCP client doing the PLC's handshakes with one 750-672 on a coupler.

    `module`: the module's position on the coupler (its registers start at 6 * module).
    `cycle`: seconds between background exchanges (None: only the calls exchange).
    `timeout`: the Modbus request timeout.
    """

    def __init__(
        self,
        host: str = "127.0.0.1",
        port: int = 502,
        module: int = 0,
        *,
        timeout: float = 3.0,
        cycle: float | None = 0.02,
        device_id: int = 1,
        connect: bool = True,
    ) -> None:
        if module < 0:
            raise ValueError(f"module must be >= 0, got {module}")
        self.host, self.port, self.module = host, port, module
        self.base = REGISTERS_PER_MODULE * module
        self.device_id = device_id
        self.cycle = cycle
        self._mb = ModbusTcpClient(host, port=port, timeout=timeout, retries=1)
        self._lock = threading.RLock()
        self._out = bytearray(IMAGE_SIZE)
        self._status = Status.from_bytes(bytes(IMAGE_SIZE))
        self._toggle = 0
        self._last = 0.0
        self._stop = threading.Event()
        self._thread: threading.Thread | None = None
        self.exchanges = 0
        if connect:
            self.connect()

    # ------------------------------------------------------------------ connection

    def connect(self, *, take_over: bool = True) -> "Wago672Client":
        """Open the connection; take_over=False only opens it (reads only: the watchdog is not fed)."""
        if not self._mb.connect():
            raise Wago672ClientError(f"cannot connect to the coupler at {self.host}:{self.port}")
        if not take_over:
            return self
        with self._lock:
            # start from what the coupler holds: a reconnecting PLC keeps its image (zeros would
            # drop Enable, and the motor would coast); a mailbox left on keeps its toggle
            self._out[:] = self.read_outputs()
            if self._out[OFFSET_C0] & C0.MBX:
                self._toggle = self._out[OFFSET_D0 + 1] & 0x80
            self.exchange()
        if self.cycle is not None and self._thread is None:
            self._stop.clear()
            self._thread = threading.Thread(target=self._background, name=f"wago672-plc-{self.module}", daemon=True)
            self._thread.start()
        return self

    def close(self) -> None:
        """Stop the background task and close the connection (the watchdog then stops the motor)."""
        self._stop.set()
        if self._thread is not None:
            self._thread.join(2.0)
            self._thread = None
        with self._lock:
            self._mb.close()

    def __enter__(self) -> "Wago672Client":
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def _background(self) -> None:
        assert self.cycle is not None
        while not self._stop.wait(self.cycle / 4):
            if time.monotonic() - self._last >= self.cycle:
                try:
                    self.exchange()
                except Wago672ClientError:
                    if self._stop.is_set():
                        return
                    time.sleep(self.cycle)

    # ------------------------------------------------------------------ registers

    def _check(self, rr, what: str):
        if rr.isError():
            code = getattr(rr, "exception_code", None)
            raise Wago672ClientError(f"{what}: the coupler answered with exception {code}")
        return rr

    def _call(self, what: str, fn: Callable, *args, **kwargs):
        try:
            return self._check(fn(*args, device_id=self.device_id, **kwargs), what)
        except ModbusException as e:
            raise Wago672ClientError(f"{what}: {e}") from None

    def exchange(self) -> Status:
        """Write the output image (FC16 at 6 * module), read the input image (FC4): one PLC cycle."""
        with self._lock:
            self._call("write the output image", self._mb.write_registers, self.base, pack(self._out))
            rr = self._call("read the input image", self._mb.read_input_registers, self.base, count=REGISTERS_PER_MODULE)
            self._status = Status.from_bytes(unpack(rr.registers))
            self._last = time.monotonic()
            self.exchanges += 1
            return self._status

    def status(self, fresh: bool = True) -> Status:
        """The input image (exchanged now, or the last one with fresh=False)."""
        return self.exchange() if fresh else self._status

    def read_inputs(self) -> bytes:
        """The 12 input bytes (FC4, without writing)."""
        rr = self._call("read the input image", self._mb.read_input_registers, self.base, count=REGISTERS_PER_MODULE)
        return unpack(rr.registers)

    def read_outputs(self) -> bytes:
        """The 12 output bytes as the coupler holds them (read back at 0x0200 + 6 * module, FC3)."""
        rr = self._call("read back the outputs", self._mb.read_holding_registers, OUTPUT_READBACK + self.base, count=REGISTERS_PER_MODULE)
        return unpack(rr.registers)

    def read_watchdog(self) -> tuple[int, int]:
        """(watchdog time [ms], status: 0 not started, 1 running, 2 expired)."""
        t = self._call("read the watchdog time", self._mb.read_holding_registers, WATCHDOG_TIME, count=1)
        s = self._call("read the watchdog status", self._mb.read_holding_registers, WATCHDOG_STATUS, count=1)
        return t.registers[0], s.registers[0]

    @property
    def outputs(self) -> bytes:
        """The output image the client writes."""
        return bytes(self._out)

    def _set(self, offset: int, value: int) -> None:
        self._out[offset] = value & 0xFF

    def _data(self, data: bytes) -> None:
        self._out[OFFSET_D0 : OFFSET_D0 + 7] = bytes(data).ljust(7, b"\x00")[:7]

    # ------------------------------------------------------------------ waiting

    def wait(self, predicate: Callable[[Status], bool], timeout: float, what: str, *, errors: bool = True) -> Status:
        """Exchange until predicate(status); Wago672Timeout after `timeout` s; Wago672DeviceError on Error."""
        deadline = time.monotonic() + timeout
        while True:
            st = self.exchange()
            if predicate(st):
                return st
            if errors and st.error:
                raise Wago672DeviceError(f"{what}: the module reports Error (S2.7): {st}; read_error() reads the code", st)
            if time.monotonic() > deadline:
                raise Wago672Timeout(f"{what}: not within {timeout:g} s: {st}")
            time.sleep(0.001)

    # ------------------------------------------------------------------ enable, modes, start

    def enable(self, timeout: float = 2.0, *, reset_quit: bool = True) -> Status:
        """Enable + Stop2_N; wait Ready and Stop_N_ACK (Reset acknowledged with Reset_Quit)."""
        with self._lock:
            st = self.exchange()
            if st.error:
                raise Wago672DeviceError(f"enable: the module reports Error (S2.7): {st}; acknowledge with quit_error()", st)
            if not self._out[OFFSET_C1] & C1.Enable:
                # Enable 0 first: the module latches Freq_Range_Sel/Acc_Range_Sel (C2) only then
                self._set(OFFSET_C1, 0)
                self.exchange()
            if reset_quit and st.reset:
                self.reset_quit(timeout)
            self._set(OFFSET_C1, _RUN)
            try:
                return self.wait(lambda s: s.ready and s.stop_n_ack, timeout, "enable")
            except Wago672Timeout:
                st = self._status
                if st.ready and not st.inputs[0]:
                    raise Wago672Timeout(f"enable: Ready, but no Stop_N_ACK: Input1 (Stop1_N) is 0: {st}") from None
                raise

    def disable(self, timeout: float = 2.0) -> Status:
        """Enable 0: output stage off at once (no ramp); use stop() first for a ramp."""
        with self._lock:
            self._set(OFFSET_C1, 0)
            return self.wait(lambda s: not s.ready, timeout, "disable", errors=False)

    def reset_quit(self, timeout: float = 2.0) -> Status:
        """Acknowledge Reset (S3.7) with Reset_Quit (C3.7)."""
        with self._lock:
            self._set(OFFSET_C3, self._out[OFFSET_C3] | C3.Reset_Quit)
            st = self.wait(lambda s: not s.reset, timeout, "Reset_Quit", errors=False)
            self._set(OFFSET_C3, self._out[OFFSET_C3] & ~C3.Reset_Quit)
            self.exchange()
            return st

    def select_mode(self, mode: str | int, timeout: float = 2.0) -> Status:
        """Select an operating mode and wait for its Command_ACK ("positioning", "speed", ...)."""
        value = MODES[mode] if isinstance(mode, str) else int(mode)
        if value not in MODES.values():
            raise ValueError(f"mode {mode!r}: one of {', '.join(MODES)} (or {sorted(MODES.values())})")
        with self._lock:
            if value != MODES["mailbox"] and self._out[OFFSET_C0] & C0.MBX:
                self.mailbox_off(timeout)  # the cyclic modes need D0..D6, not the mailbox
            st = self.exchange()
            if st.mode == value and (self._out[OFFSET_C1] & _MODE_BITS) == value << 3:
                return st
            if st.mode != 0 or self._out[OFFSET_C1] & _MODE_BITS:
                # leave the active mode first: the module brakes, Command_ACK clears at standstill
                self._set(OFFSET_C1, self._out[OFFSET_C1] & _RUN)
                self.wait(lambda s: s.mode == 0, timeout, "leave the mode")
            if value == 0:
                return self._status
            self._set(OFFSET_C1, (self._out[OFFSET_C1] & _RUN) | value << 3)
            return self.wait(lambda s: s.mode == value, timeout, f"select mode {mode!r}")

    def start(self, timeout: float = 2.0) -> Status:
        """Start 0 -> 1, wait Start_ACK, Start -> 0, wait Start_ACK 0 (the Start handshake)."""
        with self._lock:
            if self._out[OFFSET_C1] & C1.Start:
                self._set(OFFSET_C1, self._out[OFFSET_C1] & ~C1.Start)
                self.wait(lambda s: not s.start_ack, timeout, "Start 0")
            self._set(OFFSET_C1, self._out[OFFSET_C1] | C1.Start)
            st = self.wait(lambda s: s.start_ack, timeout, "Start_ACK")
            self._set(OFFSET_C1, self._out[OFFSET_C1] & ~C1.Start)
            self.wait(lambda s: not s.start_ack, timeout, "Start_ACK 0")
            return st

    # ------------------------------------------------------------------ motion

    def move_to(
        self, target: int, velocity: int = 10000, acceleration: int = 1000, *, wait: bool = True, timeout: float = 60.0
    ) -> Status:
        """Single positioning to `target` (user units); wait=True waits On_Target (Busy 0)."""
        with self._lock:
            self.select_mode("positioning")
            self._data(PositioningSetpoints(velocity, acceleration, target).encode())
            self.start()
            if not wait:
                return self._status
            return self.wait_on_target(timeout)

    def wait_on_target(self, timeout: float = 60.0) -> Status:
        return self.wait(lambda s: s.on_target and not s.busy, timeout, "On_Target")

    def speed(self, velocity: int, acceleration: int = 1000, *, wait: bool = True, timeout: float = 30.0) -> Status:
        """Speed control (C1.3 + C1.4): run at `velocity` (signed); wait=True waits until it is reached."""
        with self._lock:
            self.select_mode("speed")
            self._data(SpeedSetpoints(velocity, acceleration).encode())
            self.start()
            if not wait:
                return self._status
            return self.wait(lambda s: s.on_target and not s.busy, timeout, "speed reached")

    def reference(self, direction: int = -1, *, mode: int | None = None, timeout: float = 60.0) -> Status:
        """Reference run in `direction` (+1/-1); `mode`: Reference_Mode written first (needs the mailbox).

        Waits Reference_OK with Busy 0."""
        if direction not in (1, -1):
            raise ValueError(f"direction must be +1 or -1, got {direction!r}")
        with self._lock:
            if mode is not None:
                self.config_write("Reference_Mode", mode)
            self.select_mode("reference")
            c3 = self._out[OFFSET_C3] & ~(C3.Direction_Pos | C3.Direction_Neg)
            self._set(OFFSET_C3, c3 | (C3.Direction_Pos if direction > 0 else C3.Direction_Neg))
            try:
                self.start()
                return self.wait(lambda s: s.reference_ok and not s.busy, timeout, "Reference_OK")
            finally:
                self._set(OFFSET_C3, self._out[OFFSET_C3] & ~(C3.Direction_Pos | C3.Direction_Neg))

    def jog(self, direction: int) -> Status:
        """JogMode: +1 presses Direction_Pos, -1 Direction_Neg, 0 releases (the drive ramps down)."""
        if direction not in (-1, 0, 1):
            raise ValueError(f"direction must be -1, 0 or +1, got {direction!r}")
        with self._lock:
            self.select_mode("jog")
            c3 = self._out[OFFSET_C3] & ~(C3.Direction_Pos | C3.Direction_Neg)
            if direction:
                c3 |= C3.Direction_Pos if direction > 0 else C3.Direction_Neg
            self._set(OFFSET_C3, c3)
            return self.exchange()

    def run_program(self, start_counter: int = 0, timeout: float = 2.0) -> Status:
        """Run-program mode: start the active program at `start_counter` (a table is needed)."""
        with self._lock:
            self.select_mode("program")
            self._data(ProgramSetpoints(start_counter).encode())
            return self.start(timeout)

    def stop(self, timeout: float = 10.0) -> Status:
        """Stop2_N 0: brake with the STOP ramp; at standstill the mode ends; then Stop2_N 1 again."""
        with self._lock:
            self._set(OFFSET_C1, self._out[OFFSET_C1] & C1.Enable)
            self.wait(lambda s: not s.stop_n_ack and s.standstill, timeout, "stop", errors=False)
            if self._out[OFFSET_C1] & C1.Enable:
                self._set(OFFSET_C1, _RUN)
                return self.wait(lambda s: s.stop_n_ack or not s.ready, timeout, "Stop2_N 1", errors=False)
            return self._status

    def quit_error(self, timeout: float = 2.0) -> Status:
        """Error_Quit edge (C2.7): acknowledge errors and warnings; Reset_Quit after a warm start."""
        with self._lock:
            self._set(OFFSET_C2, self._out[OFFSET_C2] | C2.Error_Quit)
            try:
                st = self.wait(lambda s: not s.error, timeout, "Error_Quit", errors=False)
            finally:
                self._set(OFFSET_C2, self._out[OFFSET_C2] & ~C2.Error_Quit)
                self.exchange()
            if st.reset:
                st = self.reset_quit(timeout)
            return st

    # ------------------------------------------------------------------ mailbox

    def mailbox_on(self, timeout: float = 2.0) -> Status:
        """C0.5 = 1 (MB0..MB5 replace D0..D5), wait S0.5. The request bytes start as IDLE."""
        with self._lock:
            if not self._out[OFFSET_C0] & C0.MBX:
                self._data(bytes([Mbx.IDLE, self._toggle, 0, 0, 0, 0]))
                self._set(OFFSET_C0, C0.MBX)
            return self.wait(lambda s: s.mailbox, timeout, "mailbox on", errors=False)

    def mailbox_off(self, timeout: float = 2.0) -> Status:
        with self._lock:
            self._set(OFFSET_C0, 0)
            self._data(bytes(7))
            return self.wait(lambda s: not s.mailbox, timeout, "mailbox off", errors=False)

    def mailbox(self, opcode: int, data: bytes | Sequence[int] = b"", *, timeout: float = 2.0, check: bool = False) -> MailboxReply:
        """One mailbox request: MB2..MB5 = data, MB0 = opcode, toggle MB1.7; wait for the reply
        with the same toggle and opcode. check=True raises MailboxError for a return code != 0."""
        payload = bytes(data)
        if len(payload) > 4:
            raise ValueError(f"mailbox data is at most 4 bytes (MB2..MB5), got {len(payload)}")
        if not 0 <= opcode <= 0xFF:
            raise ValueError(f"opcode {opcode} is outside 0 .. 0xFF")
        with self._lock:
            self.mailbox_on(timeout)
            self._toggle ^= 0x80
            toggle = self._toggle
            self._data(bytes([opcode, toggle]) + payload.ljust(4, b"\x00"))
            st = self.wait(lambda s: s.mailbox and s.mailbox_reply[0] == opcode and (s.mailbox_reply[1] & 0x80) == toggle,
                           timeout, f"mailbox opcode {opcode:#04x}", errors=False)
            mb = st.mailbox_reply
            reply = MailboxReply(mb[0], mb[1] & 0x7F, bytes(mb[2:6]))
        if check and not reply.ok:
            raise MailboxError(f"mailbox opcode {opcode:#04x}: return code {reply.code:#04x}", reply)
        return reply

    def drive_command(self, command: int, data: int | bytes = 0, *, timeout: float = 2.0, check: bool = True) -> MailboxReply:
        """DRIVE_COMMAND (0x40) with a move-mode command (needs the mode "run commands via mailbox")."""
        with self._lock:
            if self._status.mode != MODES["mailbox"]:
                self.select_mode("mailbox")
            d = data if isinstance(data, (bytes, bytearray)) else (int(data) & 0xFFFFFF).to_bytes(3, "little")
            return self.mailbox(Mbx.DRIVE_COMMAND, bytes([command]) + bytes(d).ljust(3, b"\x00")[:3], timeout=timeout, check=check)

    def read_error(self) -> tuple[int, int]:
        """DIAG_RD_ERROR: (error code, extra information)."""
        r = self.mailbox(Mbx.DIAG_RD_ERROR, check=True)
        return int.from_bytes(r.data[0:2], "little"), int.from_bytes(r.data[2:4], "little")

    def read_variable(self, number: int) -> int:
        """DIAG_RD_VAR: an internal state variable (32-bit)."""
        r = self.mailbox(Mbx.DIAG_RD_VAR, number.to_bytes(4, "little"), check=True)
        return int.from_bytes(r.data, "little", signed=True)

    @staticmethod
    def _config_address(key: str | int, size: int | None) -> tuple[int, int]:
        if isinstance(key, str):
            e = ConfigTable.entry(key)
            return e.address, size or e.size
        return int(key), size or 1

    def config_write(self, key: str | int, value: int, size: int | None = None) -> None:
        """CONFIG_SET_PTR + CONFIG_WR: a configuration value by name (or byte address and size)."""
        address, n = self._config_address(key, size)
        self.mailbox(Mbx.CONFIG_SET_PTR, bytes([address & 0xFF, address >> 8, n, 0]), check=True)
        self.mailbox(Mbx.CONFIG_WR, (int(value) & ((1 << 8 * n) - 1)).to_bytes(n, "little"), check=True)

    def config_read(self, key: str | int, size: int | None = None, *, signed: bool | None = None) -> int:
        """CONFIG_RD: a configuration value by name (or byte address and size)."""
        address, n = self._config_address(key, size)
        r = self.mailbox(Mbx.CONFIG_RD, bytes([address & 0xFF, address >> 8, n, 0]), check=True)
        if signed is None:
            signed = ConfigTable.entry(key).signed if isinstance(key, str) else False
        return int.from_bytes(r.data[:n], "little", signed=signed)

    def download_table(self, location: int, table_type: int, rows: Sequence[bytes], *, transfer: int = 0,
                       activate: bool = False, timeout: float = 2.0) -> int:
        """Table download (DLD_START, one DLD_CONT per 4-byte row, DLD_END with the byte sum).

        location: 1 RAM1, 2 RAM2; table_type: 1 run program, 2 camshaft, 3 position table,
        4 configuration; transfer: 0 compressed 24-bit, 2 expanded 32-bit. Returns the checksum
        the module stored. activate=True sends TABLE_START afterwards."""
        n = len(rows)
        if not 1 <= n <= 0xFFF:
            raise ValueError(f"a table download takes 1 .. 4095 rows, got {n}")
        for i, row in enumerate(rows):
            if len(bytes(row)) != 4:
                raise ValueError(f"row {i}: a DLD_CONT row is 4 bytes (MB2..MB5), got {len(bytes(row))}")
        start = self.mailbox(Mbx.DLD_START, bytes([location, table_type, n & 0xFF, (transfer & 0x0F) << 4 | (n >> 8) & 0x0F]),
                             timeout=timeout, check=True)
        if start.data[0] != 0:
            raise MailboxError(f"DLD_START: status {start.data[0]} (download not possible)", start)
        for i, row in enumerate(rows):
            r = self.mailbox(Mbx.DLD_CONT, bytes(row), timeout=timeout)
            if not r.ok:
                raise MailboxError(f"DLD_CONT row {i}: return code {r.code:#04x}", r)
        total = checksum(rows)
        end = self.mailbox(Mbx.DLD_END, total.to_bytes(4, "little"), timeout=timeout, check=True)
        if end.value != total:
            raise MailboxError(f"DLD_END: the module stored checksum {end.value:#x}, sent {total:#x}", end)
        if activate:
            self.table_start(location, table_type, timeout=timeout)
        return end.value

    def table_start(self, location: int, table_type: int, *, timeout: float = 2.0) -> MailboxReply:
        """TABLE_START: activate a downloaded table (status 0: activated)."""
        r = self.mailbox(Mbx.TABLE_START, bytes([location, table_type]), timeout=timeout, check=True)
        if r.data[0] != 0:
            raise MailboxError(f"TABLE_START: status {r.data[0]} (activation aborted)", r)
        return r
