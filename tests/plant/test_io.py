"""Digital and analog I/O image: per-cycle image, edges, forcing, clamping."""

from __future__ import annotations

import pytest

from axisline.plant import AnalogIO, DigitalIO


def test_inputs_reach_the_image_at_the_next_sample_with_edges():
    io = DigitalIO(inputs=["start", "ref"], outputs=["brake"])
    io.set_input("start", True)
    assert not io.read("start")  # not sampled yet
    io.sample()
    assert io.read("start") and io.rising("start") and not io.falling("start")
    io.sample()
    assert io.read("start") and not io.rising("start")
    io.set_input("start", False)
    io.sample()
    assert io.falling("start")


def test_forcing_overrides_inputs_and_outputs_until_released():
    io = DigitalIO(inputs=["ref"], outputs=["brake"])
    io.force("ref", True)
    io.sample()
    assert io.read("ref") and io.is_forced("ref")
    io.write("brake", True)
    io.force("brake", False)
    assert not io.output("brake")
    io.release("brake")
    io.release("ref")
    assert io.output("brake")
    io.sample()
    assert not io.read("ref") and io.falling("ref")


def test_unknown_and_duplicate_names_are_refused():
    io = DigitalIO(inputs=["a"], outputs=["q"])
    with pytest.raises(KeyError):
        io.set_input("q", True)
    with pytest.raises(KeyError):
        io.write("a", True)
    with pytest.raises(ValueError):
        DigitalIO(inputs=["a"], outputs=["a"])


def test_analog_channels_clamp_and_quantise():
    io = AnalogIO(inputs=["tension"], outputs=["speed"], input_bits=12, output_bits=14)
    assert io.write("speed", 12.0) == 10.0
    assert io.write("speed", -11.0) == -10.0
    assert io.write("speed", 1.0) == pytest.approx(1.0, abs=20.0 / 2**14)
    io.set_input("tension", 3.3)
    io.sample()
    step = 20.0 / 2**12
    assert io.read("tension") == pytest.approx(round(3.3 / step) * step)
    io.force("speed", 50.0)
    assert io.output("speed") == 10.0
