"""CLM1.4 master encoders 1 and 2 on the plant: the measuring-wheel encoder inputs (C000-C003
and C004-C007, manual §8.4 L5474-5561; spec §5.4), position and velocity in IU, V011, Status 47.

    [device]
    master_encoder_1 = "wheel"        # a machine [[master]] of kind "wheel"
    master_encoder_2 = "wheel2"       # the same for master encoder 2 (C004-C007)

    me = MasterEncoder(machine.masters["wheel"], rt)            # rt.master_encoder (number 1)
    me2 = MasterEncoder(machine.masters["wheel2"], rt, 2)       # rt.master_encoder_2
    me.sample(cycle)                  # once per NC cycle, before the runtime's step
    me.position, me.velocity          # IU (exact Fraction), IU/s (32-cycle average)

One class for both: number 1 reads C000-C002 and FAK 5, number 2 C004-C006 (FAK 5 is master
encoder 1's, L1935). Master encoder n is the measuring wheel of axis n (L4228): on construction
it hands itself to that axis (``ClmAxis.attach_wheel``), which uses it in Ax00 modes 3/4
(measuring_wheel.py). Without ``master_encoder_1`` nothing of this exists (``rt.master_encoder
is None``): no work per cycle, VEO 5 / AEO proceed at once, V011 reads its stored 0, Status 47
answers 10 / 09.

Decisions (spec line -> choice, why)
------------------------------------
1. C000 "pulses per encoder revolution" (L5479) -> lines: the CLM counts 4 x C000 edges per
   revolution as for its axis encoders (Status 03, Figs. 9-17/9-18); the plant wheel's counts
   (lines_per_revolution x multiplier) are taken as they come, so a wheel with
   ``lines_per_revolution = C000`` and ``multiplier = 4`` matches. Position = counts x C002 x
   FAK 5 / (4 x C000) as an exact Fraction of the integer counts (no drift).
   test_position_is_exact_counts_times_c002.
2. C002 x FAK 5 (L1913-1949 "the feed rate constant of Master Encoder 1 ... is multiplied") ->
   the factor is taken whenever the encoder is read, not only in flying cutoff (the scale of
   master encoder 1 is one thing for V011, Status 47, VEO 5 and AEO);
   test_position_is_exact_counts_times_c002.
3. C001 encoder direction (L5495-5497 "0 = do not turn, 1 = turn") -> 1 negates the counts;
   averaging (flying cutoff only, L5485) is the flying cutoff's (cutoff.py decision 12), track
   monitoring is not modelled; C003 "currently
   has no function" (L5531) -> ignored. test_direction_digit_turns_the_count.
4. Velocity (L7191 "average values (calculated over 32 control cycles)") -> V011 and Status 47
   are the count difference over the last 32 NC cycles (fewer right after power on) x scale /
   time: quantised to one count per 32 cycles. test_v011_and_status_47_follow_the_line.
5. Status 47 ``Xs47_0_+1234.56_`` (L7183-7193) -> the digit is 0 (the C-VELOCITY-FLAG "1 =
   enabled axis" of status decision 4; the encoder is no axis and the manual prints 0), the value
   is the encoder's revolutions per minute like 48's 1/min, clipped to +-9999.99; C000 without a
   resolution -> error 10; no encoder wired on the plant -> 09 "status not present" (status
   decision 5). test_v011_and_status_47_follow_the_line.
6. "Set up correctly" for VEO 5 / AEO (L2880, L1450 "C000 to C003") -> master encoder 1 is wired
   (``master_encoder_1``) and C000 in 100..10000, C002 in 0.01..5000; otherwise the command
   proceeds at once. test_veo5_scales_the_feed_with_the_line.
7. Master encoder 2 (C004-C007, L5533-5561: "the same" as master encoder 1) -> the same class
   with C004 / C005 / C006; FAK 5 is not applied to it (L1935 names master encoder 1 only);
   C005's direction digit turns it as C001 does; it is axis 2's measuring wheel (L4228) and FUN's
   second channel (V042/V043). tests/devices/clm/test_measuring_wheel.py::
   test_master_encoder_2_reads_c004_c006_without_fak5, test_master_encoder_2_is_the_wheel_of_axis_2.
"""

from __future__ import annotations

from fractions import Fraction
from typing import Any

from .measuring_wheel import install

__all__ = ["MasterEncoder", "MasterEncoder1", "WINDOW"]

WINDOW = 32  # NC cycles of the velocity average (L7191)
_MILLION = 1_000_000


# the parameters of each master encoder: data (graduation), type (direction), feed constant
_PARAMETERS = {1: ("C000", "C001", "C002"), 2: ("C004", "C005", "C006")}


class MasterEncoder:
    """Master encoder `number` (1 or 2) read from a machine master's integer counts (see the
    module docstring)."""

    def __init__(self, master: Any, rt: Any, number: int = 1) -> None:
        if number not in _PARAMETERS:
            raise ValueError(f"the CLM has master encoders 1 and 2, not {number}")
        self.number = number
        self._ids = _PARAMETERS[number]
        self.master = master
        self.rt = rt
        self.nc_cycle_s = float(rt.nc_cycle_s)
        self._ring = [0] * (WINDOW + 1)
        self._head = 0
        self._fill = 0
        self._origin = int(master.counts)
        self.counts = 0  # since power on, in the direction of C001
        self._key: tuple[Any, ...] | None = None
        self._param_cache: tuple[Any, int, tuple[int, int, Fraction]] | None = None
        self._scale = Fraction(0)
        self._num, self._den = 0, 1  # the scale's numerator and denominator
        self._seen_params: Any = None  # what `scale` was last worked out from
        self._seen_version = -1
        self._seen_factor: Any = None
        axis = rt.axes.get(number)  # the measuring wheel of axis `number` (L4228)
        attach = getattr(axis, "attach_wheel", None)
        if attach is not None:
            attach(self)
        install(rt)  # V040-V043, V047/V048 read live (measuring_wheel.py)

    # -- parameters --------------------------------------------------------------------------

    def _params(self) -> tuple[int, int, Fraction]:
        p = self.rt.memory.parameters
        cached = self._param_cache
        if cached is not None and cached[0] is p and cached[1] == p.version:
            return cached[2]  # (read up to four times a cycle; parameters change in Parameter mode)
        data, kind, constant = self._ids
        graduation = int(p.get(data)["graduation"])
        direction = int(p.get(kind)["encoder_direction"])
        feed = Fraction(str(p.get(constant).number("feed_constant")))
        self._param_cache = (p, p.version, (graduation, direction, feed))
        return graduation, direction, feed

    @property
    def factor(self) -> int:
        """FAK 5 in millionths for master encoder 1 (decision 2); master encoder 2 has none."""
        return int(self.rt.master_factor) if self.number == 1 else _MILLION

    @property
    def set_up(self) -> bool:
        """Decision 6: C000 and C002 (C004, C006) in their ranges (L5479, L5523)."""
        graduation, _, feed = self._params()
        return 100 <= graduation <= 10000 and Fraction(1, 100) <= feed <= 5000

    @property
    def scale(self) -> Fraction:
        """IU per count: C002 x FAK 5 / (4 x C000), signed by C001's direction (decisions 1-3);
        C006 / (4 x C004), signed by C005, for master encoder 2."""
        # read several times a cycle: its inputs (the parameter set and its version, FAK 5) are
        # compared first, the scale is worked out again only after one of them changed
        rt = self.rt
        p = rt.memory.parameters
        if p is self._seen_params and p.version == self._seen_version and rt.master_factor == self._seen_factor:
            return self._scale
        self._seen_params, self._seen_version, self._seen_factor = p, p.version, rt.master_factor
        graduation, direction, feed = self._params()
        factor = self.factor
        key = (graduation, direction, feed, factor)
        if key != self._key:
            self._key = key
            sign = -1 if direction == 1 else 1
            self._scale = Fraction(0) if graduation <= 0 else sign * feed * Fraction(factor, _MILLION) / (4 * graduation)
            self._num, self._den = self._scale.numerator, self._scale.denominator
        return self._scale

    def travel(self, counts: int) -> float:
        """float(counts x scale) in IU, correctly rounded (an int true division: the same float
        as the Fraction's, without one per cycle)."""
        self.scale  # (brought up to date after a parameter or FAK 5 change)
        return counts * self._num / self._den

    @property
    def counts_per_revolution(self) -> int:
        """4 x C000 (C004): the counts of one wheel revolution (decision 1), 0 when unset."""
        return 4 * max(0, self._params()[0])

    # -- the cycle ---------------------------------------------------------------------------

    def sample(self, cycle: int) -> None:
        self.master.update(cycle)
        counts = int(self.master.counts) - self._origin
        self.counts = counts
        n = len(self._ring)
        self._head = (self._head + 1) % n
        self._ring[self._head] = counts
        if self._fill < n:
            self._fill += 1

    # -- values ------------------------------------------------------------------------------

    @property
    def position(self) -> Fraction:
        """IU since power on (exact)."""
        return self.counts * self.scale

    def _delta(self) -> tuple[int, int]:
        """(counts, cycles) over the last WINDOW cycles (fewer after power on)."""
        span = self._fill - 1
        if span <= 0:
            return 0, 1
        n = len(self._ring)
        oldest = self._ring[(self._head - span) % n]
        return self._ring[self._head] - oldest, span

    @property
    def velocity(self) -> float:
        """IU/s, the 32-cycle average (decision 4); V011."""
        d, span = self._delta()
        return float(d * self.scale / span) / self.nc_cycle_s

    @property
    def rpm(self) -> float:
        """Encoder revolutions per minute, the 32-cycle average (Status 47, decision 5)."""
        graduation, direction, _ = self._params()
        d, span = self._delta()
        if graduation <= 0:
            return 0.0
        sign = -1 if direction == 1 else 1
        return sign * d / (4 * graduation) / (span * self.nc_cycle_s) * 60.0


#: the name master encoder 1 had before master encoder 2 came (personality, tests)
MasterEncoder1 = MasterEncoder
