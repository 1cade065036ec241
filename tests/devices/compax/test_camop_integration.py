"""The cam operation with the real parameter store and cam memory (parameters.py, cammemory.py,
curves.py): acceptance events SETC / LOOP / cycle end, E17 from the cam memory, the delivery curve."""

from __future__ import annotations

import pytest

from axisline.devices.compax import CompaxError
from axisline.devices.compax.camop import CamOperation, CamState
from axisline.devices.compax.cammemory import CamMemory
from axisline.devices.compax.parameters import Parameters
from axisline.motion.axis import Axis, AxisConfig

from .test_camop_rig import Encoder


def setup():
    params = Parameters()
    memory = CamMemory()
    axis = Axis(AxisConfig(name="s", unit="deg", counts_per_unit=1000.0, v_max=1e7, a_max=1e9,
                           following_error_limit=1e6), 0.001)
    axis.power(True)
    enc = Encoder()
    inputs = {"I13": False, "I16": False}
    op = CamOperation(axis, params, memory, encoder=enc, inputs=inputs)
    return params, memory, axis, enc, inputs, op


def run(op, axis, enc, n, speed, state):
    for _ in range(n):
        state[0] += 1
        enc.counts += speed
        op.tick(state[0])
        axis.update_setpoint(state[0])
        axis.position_loop(axis.command_position - axis.position_offset)


def test_delivery_curve_straight_line_and_e17():
    # §0 "State of delivery: With curve 1 COMPAX contains a straight line with gradient 1."
    params, memory, axis, enc, inputs, op = setup()
    with pytest.raises(CompaxError) as e:
        op.setc(2)
    assert e.value.code == 17 and op.status(30) == 17
    op.setc(1)
    assert op.chain.scaled_cycle == 16384.0  # §7 X4 with the default P98 = 360, P143 = 4096
    op.setm(0.0)
    op.loop(0)
    inputs["I13"] = True
    cycle = [0]
    run(op, axis, enc, 1, 0, cycle)
    inputs["I16"] = True
    run(op, axis, enc, 1, 0, cycle)
    run(op, axis, enc, 100, 64, cycle)  # 6400 increments = 140.625 deg
    assert op.state is CamState.SYNC and axis.command_position == pytest.approx(140.625)
    assert params[93] == 3  # the default: reset mode
    run(op, axis, enc, 300, 64, cycle)  # past the cycle end: reset mode counts back by 360
    assert 0.0 <= op.status(1) < 360.0


def test_p36_armed_by_vp_becomes_valid_at_the_curve_zero_point():
    # parameters.py "VP & curve zero / SETC" with the cam operation's cycle-end event
    params, memory, axis, enc, inputs, op = setup()
    params[93] = 1
    params.make_valid("VP")
    op.setc(1)
    op.loop(0)
    inputs["I13"] = True
    cycle = [0]
    run(op, axis, enc, 1, 0, cycle)
    inputs["I16"] = True
    run(op, axis, enc, 1, 0, cycle)
    run(op, axis, enc, 128, 64, cycle)  # half a cycle: 180 deg
    params[36] = 2.0
    params.make_valid("VP")
    assert params[36] == 1.0  # armed only
    run(op, axis, enc, 10, 64, cycle)
    assert axis.command_position == pytest.approx(180.0 + 14.0625)
    run(op, axis, enc, 118, 64, cycle)  # the wrap: P36 valid, the finished cycle with P36 = 1
    assert params[36] == 2.0 and op.p36 == 2.0
    assert axis.command_position == pytest.approx(360.0)
    run(op, axis, enc, 10, 64, cycle)
    assert axis.command_position == pytest.approx(360.0 + 2 * 14.0625)


def test_setc_reads_the_valid_copy_as_it_is_after_each_vf():
    # SETC selects the curve of the valid copy (curves.read_curve): a curve rewritten in the memory
    # is seen only after VF, at once after it, and every SETC gives the operation a new curve object
    # (programrun logs a curve transfer by it), also when the curve was prepared before
    from axisline.devices.compax.curves import CurveRecord, write_curve

    params, memory, axis, enc, inputs, op = setup()
    op.setc(1)
    first = op.curve
    assert first.master_cycle == 360.0 and first.fractions == (0.0, 1.0)
    write_curve(memory, CurveRecord(number=1, master_cycle=720.0, slave_cycle=360.0, set_points=[0.0, 0.5, 0.25]))
    op.setc(1)
    assert op.curve is not first and op.curve.master_cycle == 360.0  # not valid yet
    memory.vf()
    op.setc(1)
    assert op.curve.master_cycle == 720.0 and op.curve.fractions == (0.0, 0.5, 0.25)
    again = op.curve
    op.setc(1)
    assert op.curve is not again and op.curve.fractions == (0.0, 0.5, 0.25)
