"""The CLM's process image: every input, output and marker byte in one flat byte array.

    image = ProcessImage()
    image.set(parse_operand("I1.00.6", bit=True), 1)
    image.get(parse_operand("I1.00", bit=False))      # -> 0b0100_0000 = 64

One ``bytearray`` holds all thirteen sources of `operands` (I0-I2, Q0-Q2, M0-M6), each source's
bytes contiguous, in the order of `LAYOUT`. The Logic Task compiles an operand once to its place
(`locate`: index, shift, mask) and then works on ``data`` directly; the NC tasks (part 2) use
`get` / `set`. `copy` is one ``bytearray`` copy, so a snapshot per cycle is cheap.

Decisions (spec line -> choice, why)
------------------------------------
1. §3.3 source map -> the sizes come from `operands.exists`, not from a second table here, so
   the image and the operand checker cannot disagree about a byte (I0.00-I0.02, M6.00-M6.39,
   ...). Test: test_layout_follows_operand_ranges.
2. "For inputs not present in the hardware, the signal level is always set to 0" (L1479) ->
   the bits a source does not have (I0.02.6-7, Q0.02.2-7, Q1.06.3-7) stay 0: a byte write
   keeps only the bits that exist, and a fresh image is all 0. Test:
   test_missing_bits_read_zero.
3. A parameter's ``00.00.0`` "not programmed" (§3.3) names nothing -> it reads 0 and a write to
   it changes nothing, so a caller need not test for it. Test: test_unset_operand_reads_zero.
4. A value that does not fit (a bit other than 0/1, a byte outside 0..255) or an operand the
   CLM does not have is a programming error of the caller, not CLM input -> ``ValueError``,
   not `ClmError`. Test: test_set_refuses_values_that_do_not_fit.
"""

from __future__ import annotations

from .operands import LT_READ, NC_READ, Operand, exists

__all__ = ["LAYOUT", "ProcessImage"]


def _valid_bits(area: str, source: int, byte: int) -> int:
    """The mask of the bits byte `byte` of the source has (0xFF but for a short last byte)."""
    mask = 0
    for bit in range(8):
        if exists(Operand(area, source, byte, bit)):
            mask |= 1 << bit
    return mask


def _layout() -> tuple[dict[tuple[str, int], tuple[int, int]], bytes]:
    layout: dict[tuple[str, int], tuple[int, int]] = {}
    valid = bytearray()
    for area, source in sorted(NC_READ | LT_READ, key=lambda k: ("IQM".index(k[0]), k[1])):
        count = 0
        while exists(Operand(area, source, count)):
            count += 1
        layout[(area, source)] = (len(valid), count)
        valid.extend(_valid_bits(area, source, byte) for byte in range(count))
    return layout, bytes(valid)


#: (area, source) -> (index of its byte 00 in `ProcessImage.data`, number of bytes).
LAYOUT, _VALID = _layout()
_SIZE = len(_VALID)


class ProcessImage:
    """All inputs, outputs and markers of one CLM; everything starts at 0."""

    __slots__ = ("data",)

    def __init__(self, data: bytearray | None = None) -> None:
        if data is not None and len(data) != _SIZE:
            raise ValueError(f"a CLM process image has {_SIZE} bytes, not {len(data)}")
        #: The bytes of all sources in `LAYOUT` order (read and written in place by the Logic Task).
        self.data = data if data is not None else bytearray(_SIZE)

    @staticmethod
    def locate(op: Operand) -> tuple[int, int, int]:
        """Where `op` lives: (index into ``data``, shift, mask of the value after the shift).

        A bit gives mask 1; a byte gives shift 0 and the mask of the bits the byte has.
        Remembered per operand: the NC tasks and the mode machine ask for the same few every
        cycle, and an operand never moves.
        """
        place = _PLACES.get(op)
        if place is None:
            place = _PLACES[op] = _locate(op)
        return place

    def get(self, op: Operand) -> int:
        """A bit as 0/1, a byte as 0..255 (bit 7 the most significant)."""
        place = _PLACES.get(op)
        if place is None:
            if op.unset:
                return 0
            place = self.locate(op)
        at, shift, mask = place
        return self.data[at] >> shift & mask

    def set(self, op: Operand, value: int) -> None:
        """Write a bit (0/1) or a byte (0..255; bits the byte does not have are dropped)."""
        place = _PLACES.get(op)
        if place is None:
            if op.unset:
                return
            place = self.locate(op)
        at, shift, mask = place
        if not 0 <= value <= (1 if op.bit is not None else 0xFF):
            raise ValueError(f"{op} = {value}: a {'bit is 0 or 1' if op.bit is not None else 'byte is 0..255'}")
        data = self.data
        data[at] = data[at] & ~(mask << shift) | (value & mask) << shift

    def copy(self) -> ProcessImage:
        return ProcessImage(bytearray(self.data))

    def __eq__(self, other: object) -> bool:
        return isinstance(other, ProcessImage) and self.data == other.data

    __hash__ = None  # type: ignore[assignment]  # mutable

    def __repr__(self) -> str:
        used = [f"{area}{source}.{byte:02d}={self.data[start + byte]:08b}"
                for (area, source), (start, count) in LAYOUT.items()
                for byte in range(count) if self.data[start + byte]]
        return f"ProcessImage({', '.join(used)})"


_PLACES: dict[Operand, tuple[int, int, int]] = {}  # at most the CLM's few thousand operands


def _locate(op: Operand) -> tuple[int, int, int]:
    start, count = LAYOUT.get(op.key, (0, -1))
    if not 0 <= op.byte < count:
        raise ValueError(f"{op} is not an input, output or marker of the CLM")
    at = start + op.byte
    if op.bit is None:
        return at, 0, _VALID[at]
    if not 0 <= op.bit < 8 or not _VALID[at] >> op.bit & 1:
        raise ValueError(f"{op} is not an input, output or marker of the CLM")
    return at, op.bit, 1

