"""The FS701 master: Encoder 1 or the virtual master axis, in line units (cutter.py describes
the cycle and its decisions).
"""

from __future__ import annotations

from typing import Any

from axisline.motion.master import EncoderMaster, VirtualMaster

from .cut_settings import CutterSettings
from .cut_states import ACC_WINDOW

__all__ = ["LineMaster"]

class LineMaster:
    """The FS701 master: Encoder 1 (an EncoderMaster) or the virtual master axis (C18).

    Position in LU, `counts` in line increments, accumulated from the selected source so the
    material length does not jump when the source is switched (only in Stop, manual §4.1.1).
    Velocity: the source's (the encoder's "window" filter = Sampling Time, spec §2.4)."""

    def __init__(self, settings: CutterSettings, period: float, encoder: Any = None) -> None:
        self.settings = settings
        self.period = float(period)
        kl = settings.line_counts_per_lu
        self.counts_per_unit = kl
        self.encoder_master: Any = None
        if encoder is not None:
            if hasattr(encoder, "update") and hasattr(encoder, "velocity"):
                self.encoder_master = encoder  # an EncoderMaster (or any master in LU)
            else:
                sign = 1 if settings.dir_counter_1 == 1 else -1
                self.encoder_master = EncoderMaster(
                    encoder,
                    kl,
                    self.period,
                    multiplier=sign,
                    velocity_filter="window",
                    sampling_time=max(settings.sampling_time, 1) / 1000.0,
                )
        vm = settings.v_max_line
        ramp = settings.ramp_vir_master
        acc = vm / ramp if ramp > 0 else vm / self.period
        self.virtual = VirtualMaster(self.period, acceleration=acc, counts_per_unit=kl)
        self.use_virtual = self.encoder_master is None
        self._last_src = 0
        self._counts = 0
        self._v = 0.0
        self._a = 0.0
        self._cycle: int | None = None
        self._virtual_running = False
        self._virtual_target = 0.0
        # stopped and standing still: its state cannot change until Run Virt. Master, so its
        # per-cycle update is skipped (run_virtual catches its cycle up before a new ramp)
        self._virtual_idle = False
        # the line acceleration: the second difference of the counts over ACC_WINDOW (a
        # ring of 2N + 1 counts); see the `acceleration` property
        n_acc = max(1, int(round(ACC_WINDOW / self.period)))
        self._acc_n = n_acc
        self._acc_scale = 1.0 / (kl * (n_acc * self.period) ** 2)
        self._acc_ring = [0] * (2 * n_acc + 1)
        self._acc_head = 0
        self._acc_fill = 0

    def _source(self) -> Any:
        return self.virtual if self.use_virtual else self.encoder_master

    def select(self, virtual: bool) -> None:
        """Switch the source (the cutter calls this only in Stop)."""
        virtual = virtual or self.encoder_master is None
        if virtual != self.use_virtual:
            self.use_virtual = virtual
            self._last_src = self._source().counts

    def run_virtual(self, on: bool, speed_lu_min: float | None = None) -> None:
        """Run Virt. Master: ramp to the (quantised) Virt. Line Speed, or to standstill.
        A changed Virt. Line Speed or Ramp Vir. Master ramps from the current speed."""
        if not on and not self._virtual_running:
            return  # stopped and staying stopped (the target of a stopped master is 0)
        s = self.settings
        v = (s.virtual_speed_effective() if speed_lu_min is None else speed_lu_min) / 60.0
        if s.dir_frequency != 1:
            v = -v
        target = v if on else 0.0
        if on != self._virtual_running or target != self._virtual_target:
            self._virtual_running = on
            self._virtual_target = target
            virtual = self.virtual
            if self._virtual_idle and self._cycle is not None:
                virtual.update(self._cycle)  # the ramp starts from the last cycle, as always
            self._virtual_idle = False
            vm = s.v_max_line
            acc = vm / s.ramp_vir_master if s.ramp_vir_master > 0 else vm / self.period
            virtual.acceleration_limit = virtual.deceleration_limit = acc
            virtual.set_velocity(target)

    def update(self, cycle: int) -> None:
        if cycle == self._cycle:
            return
        first = self._cycle is None
        self._cycle = cycle
        # the virtual master always runs (its motion-detection output, Adjust reference),
        # except when it stands still stopped (_virtual_idle)
        if not self._virtual_idle:
            virtual = self.virtual
            virtual.update(cycle)
            if not self._virtual_running and virtual.in_velocity:
                self._virtual_idle = True
        if self.encoder_master is not None:
            self.encoder_master.update(cycle)
        src = self._source()
        c = int(src.counts)
        if first:
            self._last_src = c
        self._counts += c - self._last_src
        self._last_src = c
        self._v = float(src.velocity)
        counts = self._counts
        ring = self._acc_ring
        n = len(ring)
        i = self._acc_head + 1
        if i == n:
            i = 0
        self._acc_head = i
        ring[i] = counts
        if self.use_virtual:
            self._a = float(src.acceleration)  # the virtual master's profile: exact
        elif self._acc_fill < n - 1:
            self._acc_fill += 1
            self._a = 0.0
        else:
            na = self._acc_n
            j = i - na
            if j < 0:
                j += n
            k = i + 1  # the oldest entry, 2N cycles back
            if k == n:
                k = 0
            self._a = (counts - 2 * ring[j] + ring[k]) * self._acc_scale

    @property
    def counts(self) -> int:
        return self._counts

    @property
    def position(self) -> float:
        return self._counts / self.counts_per_unit

    @property
    def velocity(self) -> float:
        return self._v

    @property
    def acceleration(self) -> float:
        """LU/s²: the virtual master's own; of Encoder 1 the second difference of the counts
        over ACC_WINDOW, (x(t) - 2 x(t - W) + x(t - 2W)) / W², exact on a ramp and W late.
        The window filter's acceleration at a 1 ms Sampling Time is count noise (one
        increment per ms² is 1000² increments/s²), too rough for a feed-forward."""
        return self._a

    @property
    def velocity_now(self) -> float:
        """LU/s: the measured speed with its lag (Sampling Time / 2) made up, x acceleration,
        when the acceleration feed-forward is on (C26, loop.py L10); otherwise, and for the
        virtual master (exact), the measurement itself, as the FS701 uses it."""
        lag = self.settings.line_speed_lag
        if lag > 0.0 and not self.use_virtual:
            return self._v + lag * self._a
        return self._v

    @property
    def cycle(self) -> int | None:
        return self._cycle

    def reset_counts(self) -> None:
        old = self._counts
        self._counts = 0
        ring = self._acc_ring
        for k in range(len(ring)):  # the acceleration estimate does not see the jump
            ring[k] -= old
