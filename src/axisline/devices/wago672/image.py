"""The 12-byte process image of the WAGO 750-672, bit for bit (manual §3.7, wago.md §3.1-3.6).

Output image (PLC -> module) and input image (module -> PLC), one logical channel:

    offset  output (C0.5 = 0)  output (C0.5 = 1)   input (S0.5 = 0)  input (S0.5 = 1)
    0       C0                 C0                  S0                S0
    1       reserved           reserved            reserved          reserved
    2..8    D0..D6             MB0..MB5, reserved  D0..D6            MB0..MB5, reserved
    9       C3                 C3                  S3                S3
    10      C2                 C2                  S2                S2
    11      C1                 C1                  S1                S1

Multi-byte values are little-endian (LSB at the lowest offset; manual §3.10.2, wago.md
conventions). Positions are 24-bit two's complement, velocities and accelerations 16 bit.

The names of the bits are the manual's (§3.7.2): a PLC programmer reading a trace sees
`Stop_N_ACK`, not `stop_ack`. The data bytes D0..D6 have one layout per operating mode
(§3.6): `PositioningSetpoints`/`PositioningActuals` (single positioning, referencing, jog),
`SpeedSetpoints` (speed control), `ProgramSetpoints`/`ProgramActuals` (run program).

While the mailbox is on (C0.5, acknowledged by S0.5) bytes 2..7 carry MB0..MB5 instead of
D0..D5 and byte 8 is reserved; C1..C3/S1..S3 keep their meaning (§3.7.4).

Readings (wago.md §3.1): "Output byte D0 and input byte D0 are reserved" [AMBIGUOUS] is not
followed - the per-mode tables use D0 (velocity low byte), byte offset 1 is the reserved one.
The overview table of §3.7.1 has its column headings swapped [CONFLICT]; §3.7.3/§3.7.4 hold.
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import IntFlag

__all__ = [
    "MODE_BITS",
    "IMAGE_SIZE",
    "OFFSET_C0",
    "OFFSET_D0",
    "OFFSET_C3",
    "OFFSET_C2",
    "OFFSET_C1",
    "MAILBOX_SLICE",
    "C0",
    "C1",
    "C2",
    "C3",
    "S0",
    "S1",
    "S2",
    "S3",
    "MODE_IDLE",
    "MODE_POSITIONING",
    "MODE_PROGRAM",
    "MODE_SPEED",
    "MODE_REFERENCING",
    "MODE_JOG",
    "MODE_MAILBOX",
    "MODE_NAMES",
    "ImageError",
    "OutputImage",
    "InputImage",
    "PositioningSetpoints",
    "PositioningActuals",
    "SpeedSetpoints",
    "ProgramSetpoints",
    "ProgramActuals",
    "encode_int24",
    "decode_int24",
    "encode_int16",
    "decode_int16",
    "encode_uint16",
    "decode_uint16",
]

IMAGE_SIZE = 12
OFFSET_C0 = 0  # C0 / S0
OFFSET_D0 = 2  # D0 .. D6 at 2 .. 8
OFFSET_C3 = 9  # C3 / S3
OFFSET_C2 = 10  # C2 / S2
OFFSET_C1 = 11  # C1 / S1
MAILBOX_SLICE = slice(2, 8)  # MB0 .. MB5 while C0.5 / S0.5 is set

INT24_MIN, INT24_MAX = -8388608, 8388607


class ImageError(ValueError):
    """A process image or a data field that cannot be encoded/decoded (names the field)."""


# ---------------------------------------------------------------- control and status bits


class C0(IntFlag):
    """Control byte C0 (§3.7.2): only MBX is defined, the other bits are reserved (0)."""

    MBX = 0x20  # 1: mailbox activated (bytes 2..7 = MB0..MB5)


class S0(IntFlag):
    """Status byte S0 (§3.7.2)."""

    MBX = 0x20  # mirrors the mailbox state
    ERR = 0x40  # error/warning present, if enabled by Error/WarningNotificationMode bit 0


class C1(IntFlag):
    """Control byte C1 (§3.7.2): Enable, Stop2_N, Start, Command[1..5] (one-hot mode bits)."""

    Enable = 0x01
    Stop2_N = 0x02
    Start = 0x04
    M_Positioning = 0x08  # Command[1]: single positioning (value 1)
    M_Program = 0x10  # Command[2]: run program (value 2)
    M_Reference = 0x20  # Command[3]: referencing (value 4)
    M_Jog = 0x40  # Command[4]: JogMode (value 8)
    M_DriveByMbx = 0x80  # Command[5]: run commands via mailbox (value 16)


class S1(IntFlag):
    """Status byte S1 (§3.7.2): Ready, Stop_N_ACK, Start_ACK, Command_ACK[1..5]."""

    Ready = 0x01
    Stop_N_ACK = 0x02
    Start_ACK = 0x04
    M_Positioning_ACK = 0x08
    M_Program_ACK = 0x10
    M_Reference_ACK = 0x20
    M_Jog_ACK = 0x40
    M_DriveByMbx_ACK = 0x80


class C2(IntFlag):
    """Control byte C2 (§3.7.2). Bits 4 and 5 are reserved."""

    Freq_Range_Sel_0 = 0x01
    Freq_Range_Sel_1 = 0x02
    Acc_Range_Sel_0 = 0x04
    Acc_Range_Sel_1 = 0x08
    PreCalc = 0x40
    Error_Quit = 0x80


class S2(IntFlag):
    """Status byte S2 (§3.7.2)."""

    On_Target = 0x01
    Busy = 0x02
    StandStill = 0x04
    On_Speed = 0x08
    Direction = 0x10
    Reference_OK = 0x20
    PreCalc_ACK = 0x40
    Error = 0x80


class C3(IntFlag):
    """Control byte C3 (§3.7.2). Bit 6 is SetupSpeed_Active only after relinking (wago.md §3.5)."""

    SetActual_Pos = 0x01
    Direction_Pos = 0x04
    Direction_Neg = 0x08
    Setup_Speed_Active = 0x40  # KBUS_CTRL3_6: free source bit with the default links
    Reset_Quit = 0x80


class S3(IntFlag):
    """Status byte S3 (§3.7.2): the six inputs, Warning, Reset."""

    Input1 = 0x01
    Input2 = 0x02
    Input3 = 0x04
    Input4 = 0x08
    Input5 = 0x10
    Input6 = 0x20
    Warning = 0x40
    Reset = 0x80


# Command field (C1 >> 3) values as the manual lists them (§3.7.2). Speed control is the
# value 3 (C1.3 and C1.4 together), see device.py "Decisions".
MODE_IDLE = 0
MODE_POSITIONING = 1
MODE_PROGRAM = 2
MODE_SPEED = 3
MODE_REFERENCING = 4
MODE_JOG = 8
MODE_MAILBOX = 16
MODE_NAMES = {
    MODE_IDLE: "Idle",
    MODE_POSITIONING: "Single positioning",
    MODE_PROGRAM: "Run program",
    MODE_SPEED: "Speed control",
    MODE_REFERENCING: "Referencing",
    MODE_JOG: "JogMode",
    MODE_MAILBOX: "Run commands via mailbox",
}


# ---------------------------------------------------------------- integer fields


def _int_field(name: str, value: object, lo: int, hi: int) -> int:
    if isinstance(value, bool) or not isinstance(value, int):
        raise ImageError(f"{name} must be an integer in {lo} .. {hi}, got {value!r}")
    if not lo <= value <= hi:
        raise ImageError(f"{name} = {value} is outside {lo} .. {hi}")
    return value


def encode_int24(value: int, name: str = "position") -> bytes:
    """24-bit two's complement, little-endian (positions, §3.10.6.1.2)."""
    v = _int_field(name, value, INT24_MIN, INT24_MAX)
    return (v & 0xFFFFFF).to_bytes(3, "little")


def decode_int24(data: bytes) -> int:
    """Sign-extend bit 23 (a target 0xFFFC18 is -1000)."""
    if len(data) != 3:
        raise ImageError(f"a 24-bit value needs 3 bytes, got {len(data)}")
    return int.from_bytes(data, "little", signed=True)


def encode_int16(value: int, name: str = "velocity") -> bytes:
    return _int_field(name, value, -32768, 32767).to_bytes(2, "little", signed=True)


def decode_int16(data: bytes) -> int:
    if len(data) != 2:
        raise ImageError(f"a 16-bit value needs 2 bytes, got {len(data)}")
    return int.from_bytes(data, "little", signed=True)


def encode_uint16(value: int, name: str = "value") -> bytes:
    return _int_field(name, value, 0, 0xFFFF).to_bytes(2, "little")


def decode_uint16(data: bytes) -> int:
    if len(data) != 2:
        raise ImageError(f"a 16-bit value needs 2 bytes, got {len(data)}")
    return int.from_bytes(data, "little")


def _byte(name: str, value: object) -> int:
    return _int_field(name, value, 0, 0xFF)


def _seven(name: str, data: bytes | bytearray) -> bytes:
    data = bytes(data)
    if len(data) != 7:
        raise ImageError(f"{name} must be 7 bytes (D0..D6), got {len(data)}")
    return data


# ---------------------------------------------------------------- per-mode data layouts


@dataclass(frozen=True, slots=True)
class PositioningSetpoints:
    """Output D0..D6 in single positioning (§3.11.1.4.1): Velocity, Acceleration, Target position.

    The codec carries any 16-bit value: the range rules (velocity 1..25000, acceleration
    1..32767) are the module's, which answers a bad value with its error code on Start.
    """

    velocity: int = 0
    acceleration: int = 0
    target: int = 0

    def encode(self) -> bytes:
        return (
            encode_int16(self.velocity, "Velocity")
            + encode_int16(self.acceleration, "Acceleration")
            + encode_int24(self.target, "Target position")
        )

    @classmethod
    def decode(cls, data: bytes) -> PositioningSetpoints:
        d = _seven("PositioningSetpoints", data)
        return cls(decode_int16(d[0:2]), decode_int16(d[2:4]), decode_int24(d[4:7]))


@dataclass(frozen=True, slots=True)
class PositioningActuals:
    """Input D0..D6 in single positioning, referencing, jog and speed control (§3.6.1):
    Actual velocity (signed, user units), D2..D3 reserved, Actual position (24 bit)."""

    velocity: int = 0
    position: int = 0

    def encode(self) -> bytes:
        return encode_int16(self.velocity, "Actual Velocity") + b"\x00\x00" + encode_int24(self.position, "Actual position")

    @classmethod
    def decode(cls, data: bytes) -> PositioningActuals:
        d = _seven("PositioningActuals", data)
        return cls(decode_int16(d[0:2]), decode_int24(d[4:7]))


@dataclass(frozen=True, slots=True)
class SpeedSetpoints:
    """Output D0..D6 in speed control (§3.11.1.11.1): signed Velocity, Acceleration; D4..D6 reserved."""

    velocity: int = 0
    acceleration: int = 0

    def encode(self) -> bytes:
        return encode_int16(self.velocity, "Velocity") + encode_int16(self.acceleration, "Acceleration") + b"\x00\x00\x00"

    @classmethod
    def decode(cls, data: bytes) -> SpeedSetpoints:
        d = _seven("SpeedSetpoints", data)
        return cls(decode_int16(d[0:2]), decode_int16(d[2:4]))


@dataclass(frozen=True, slots=True)
class ProgramSetpoints:
    """Output D0..D6 in run program (§3.11.1.7.1): D2..D3 starting value of the command counter."""

    start_counter: int = 0

    def encode(self) -> bytes:
        return b"\x00\x00" + encode_uint16(self.start_counter, "Starting value for command counter") + b"\x00\x00\x00"

    @classmethod
    def decode(cls, data: bytes) -> ProgramSetpoints:
        d = _seven("ProgramSetpoints", data)
        return cls(decode_uint16(d[2:4]))


@dataclass(frozen=True, slots=True)
class ProgramActuals:
    """Input D0..D6 in run program: current velocity, command counter, current position."""

    velocity: int = 0
    counter: int = 0
    position: int = 0

    def encode(self) -> bytes:
        return (
            encode_int16(self.velocity, "Current velocity")
            + encode_uint16(self.counter, "Current value for command counter")
            + encode_int24(self.position, "Current position")
        )

    @classmethod
    def decode(cls, data: bytes) -> ProgramActuals:
        d = _seven("ProgramActuals", data)
        return cls(decode_int16(d[0:2]), decode_uint16(d[2:4]), decode_int24(d[4:7]))


# ---------------------------------------------------------------- whole images


@dataclass(frozen=True, slots=True)
class OutputImage:
    """The 12 bytes the PLC writes. `data` is D0..D6 (or MB0..MB5 + reserved with C0.MBX)."""

    c0: int = 0
    c1: int = 0
    c2: int = 0
    c3: int = 0
    data: bytes = bytes(7)

    def __post_init__(self) -> None:
        for name in ("c0", "c1", "c2", "c3"):
            _byte(name.upper(), getattr(self, name))
        object.__setattr__(self, "data", _seven("D0..D6", self.data))

    @property
    def mailbox(self) -> bool:
        return bool(self.c0 & C0.MBX)

    @property
    def mailbox_request(self) -> bytes:
        """MB0..MB5 (opcode, Control_Mbx, 4 request parameter bytes)."""
        return self.data[0:6]

    @property
    def command(self) -> int:
        """The Command field: C1 >> 3 (0 idle, 1, 2, 3, 4, 8, 16)."""
        return (self.c1 >> 3) & 0x1F

    def to_bytes(self) -> bytes:
        out = bytearray(IMAGE_SIZE)
        out[OFFSET_C0] = self.c0
        out[OFFSET_D0 : OFFSET_D0 + 7] = self.data
        out[OFFSET_C3] = self.c3
        out[OFFSET_C2] = self.c2
        out[OFFSET_C1] = self.c1
        return bytes(out)

    @classmethod
    def from_bytes(cls, raw: bytes | bytearray) -> OutputImage:
        raw = bytes(raw)
        if len(raw) != IMAGE_SIZE:
            raise ImageError(f"the output image is {IMAGE_SIZE} bytes, got {len(raw)}")
        return cls(raw[OFFSET_C0], raw[OFFSET_C1], raw[OFFSET_C2], raw[OFFSET_C3], raw[OFFSET_D0 : OFFSET_D0 + 7])

    @classmethod
    def build(
        cls,
        c1: int = 0,
        c2: int = 0,
        c3: int = 0,
        *,
        mailbox: bool = False,
        data: bytes | PositioningSetpoints | SpeedSetpoints | ProgramSetpoints | None = None,
        mailbox_request: bytes | None = None,
    ) -> OutputImage:
        """Convenience for PLC code and tests: control bytes plus the mode's data or MB0..MB5."""
        if mailbox_request is not None:
            req = bytes(mailbox_request)
            if len(req) != 6:
                raise ImageError(f"mailbox_request must be 6 bytes (MB0..MB5), got {len(req)}")
            raw = req + b"\x00"
            mailbox = True
        elif data is None:
            raw = bytes(7)
        elif isinstance(data, (bytes, bytearray)):
            raw = bytes(data)
        else:
            raw = data.encode()
        return cls(C0.MBX if mailbox else 0, int(c1), int(c2), int(c3), raw)


@dataclass(frozen=True, slots=True)
class InputImage:
    """The 12 bytes the module returns. `data` is D0..D6 (or MB0..MB5 + reserved with S0.MBX)."""

    s0: int = 0
    s1: int = 0
    s2: int = 0
    s3: int = 0
    data: bytes = bytes(7)

    def __post_init__(self) -> None:
        for name in ("s0", "s1", "s2", "s3"):
            _byte(name.upper(), getattr(self, name))
        object.__setattr__(self, "data", _seven("D0..D6", self.data))

    @property
    def mailbox(self) -> bool:
        return bool(self.s0 & S0.MBX)

    @property
    def mailbox_reply(self) -> bytes:
        return self.data[0:6]

    @property
    def command_ack(self) -> int:
        """The Command_Ack field: S1 >> 3 (0 idle, 1, 2, 3, 4, 8, 16)."""
        return (self.s1 >> 3) & 0x1F

    def positioning(self) -> PositioningActuals:
        return PositioningActuals.decode(self.data)

    def program(self) -> ProgramActuals:
        return ProgramActuals.decode(self.data)

    def to_bytes(self) -> bytes:
        out = bytearray(IMAGE_SIZE)
        out[OFFSET_C0] = self.s0
        out[OFFSET_D0 : OFFSET_D0 + 7] = self.data
        out[OFFSET_C3] = self.s3
        out[OFFSET_C2] = self.s2
        out[OFFSET_C1] = self.s1
        return bytes(out)

    @classmethod
    def from_bytes(cls, raw: bytes | bytearray) -> InputImage:
        raw = bytes(raw)
        if len(raw) != IMAGE_SIZE:
            raise ImageError(f"the input image is {IMAGE_SIZE} bytes, got {len(raw)}")
        return cls(raw[OFFSET_C0], raw[OFFSET_C1], raw[OFFSET_C2], raw[OFFSET_C3], raw[OFFSET_D0 : OFFSET_D0 + 7])

# mode -> its Command bits C1.3 .. C1.7 as a number (speed control: Command[]=3, D1)
MODE_BITS = {MODE_POSITIONING: 1, MODE_PROGRAM: 2, MODE_SPEED: 3, MODE_REFERENCING: 4, MODE_JOG: 8, MODE_MAILBOX: 16}
