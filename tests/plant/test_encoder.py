"""Incremental encoder: quantisation, x1/x2/x4, wrap, index latch, measuring wheel."""

from __future__ import annotations

import math

import numpy as np
import pytest

from axisline.plant import IncrementalEncoder, MaterialLine, MeasuringWheel, SpeedChange


class Shaft:
    """A bare position source (no sub-cycle trace): the encoder interpolates linearly."""

    def __init__(self, position: float = 0.0) -> None:
        self.position = position


@pytest.mark.parametrize(("multiplier", "counts"), [(1, 1234), (2, 2469), (4, 4938)])
def test_counts_for_a_known_position(multiplier, counts):
    shaft = Shaft(1.23456)
    encoder = IncrementalEncoder(shaft, lines_per_unit=1000.0, multiplier=multiplier)
    assert encoder.sample() == counts
    shaft.position = -1.23456
    assert encoder.sample() == -counts - 1  # floor: one edge further below zero


def test_decimal_positions_give_the_count_they_name():
    shaft = Shaft(0.7)  # 0.7 * 4000 is 2799.9999999999995 in binary
    assert IncrementalEncoder(shaft, 1000.0, 4).sample() == 2800


def test_mirrored_encoder_counts_the_other_way():
    shaft = Shaft(0.25)
    assert IncrementalEncoder(shaft, 100.0, 4, direction=-1).sample() == -100


def test_counter_wraps_at_its_width_and_delta_stays_signed():
    shaft = Shaft(0.0)
    encoder = IncrementalEncoder(shaft, 1.0, 1, counter_bits=16)
    shaft.position = -1.0
    assert encoder.sample() == 65535
    old = encoder.counts
    shaft.position = 2.0
    assert encoder.sample() == 2
    assert encoder.delta(encoder.counts, old) == 3
    assert encoder.delta(old, encoder.counts) == -3


def test_index_latch_fraction_is_exact_at_constant_speed():
    line = MaterialLine(speed=0.3)
    encoder = IncrementalEncoder(line, 1000.0, 4, index_every_units=0.25, index_offset=0.1)
    encoder.arm_index()
    dt = 0.001
    for n in range(1, 400):
        line.step(dt)
        encoder.sample()
        if encoder.index_latched:
            break
    t_index = 0.1 / 0.3
    assert n == math.ceil(t_index / dt)
    assert encoder.index_fraction == pytest.approx(t_index / dt - (n - 1), abs=1e-9)
    assert encoder.index_position == 0.1
    assert encoder.index_count == 400
    assert encoder.index_pulses == 1
    # the latch holds until re-armed
    for _ in range(1000):
        line.step(dt)
        encoder.sample()
    assert encoder.index_position == 0.1


@pytest.mark.parametrize("dt", [0.00025, 0.001, 0.004])
def test_index_latch_time_is_exact_while_accelerating(dt):
    line = MaterialLine([SpeedChange(0.0, 5.0, 2.0)], speed=0.1)
    encoder = IncrementalEncoder(line, 500.0, 4, index_every_units=1.0, index_offset=0.37)
    encoder.arm_index()
    n = 0
    while not encoder.index_latched:
        line.step(dt)
        encoder.sample()
        n += 1
    t_exact = (-0.1 + math.sqrt(0.01 + 2 * 2.0 * 0.37)) / 2.0
    assert (n - 1 + encoder.index_fraction) * dt == pytest.approx(t_exact, abs=1e-12)


def test_index_from_a_bare_source_is_interpolated_linearly():
    shaft = Shaft(0.0)
    encoder = IncrementalEncoder(shaft, 100.0, 4, index_every_units=1.0, index_offset=0.5)
    encoder.arm_index()
    shaft.position = 0.8
    encoder.sample()
    assert encoder.index_latched
    assert encoder.index_fraction == pytest.approx(0.5 / 0.8)


def test_measuring_wheel_sees_the_material_less_its_slip():
    line = MaterialLine(speed=100.0)
    wheel = MeasuringWheel(line, lines_per_unit=5.0, multiplier=4, slip=0.01, circumference=200.0)
    wheel.arm_index()
    for _ in range(3000):
        line.step(0.001)
        wheel.sample()
    assert line.position == pytest.approx(300.0)
    assert wheel.wheel_position == pytest.approx(297.0)
    assert wheel.counts == 297 * 20
    # index once per revolution of the wheel: at 200 units rolled, 200/0.99 of material
    assert wheel.index_position == 200.0


def test_measuring_wheel_slip_jitter_is_reproducible_with_the_seed():
    def counts(seed: int) -> int:
        line = MaterialLine(speed=100.0)
        wheel = MeasuringWheel(line, 1000.0, 4, slip=0.01, slip_jitter=0.002, jitter_length=1.0,
                               rng=np.random.default_rng(seed))
        for _ in range(1000):
            line.step(0.001)
            wheel.sample()
        return wheel.counts

    assert counts(3) == counts(3)
    assert counts(3) != counts(4)
