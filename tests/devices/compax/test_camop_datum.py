"""§2.4 machine datum before cam operation (D20), §2.11 POSA HOME / Shift I2 during cam operation
(D21), D/A monitor at power on (D22), HEDA master (D23)."""

from __future__ import annotations

import pytest

from axisline.devices.compax import CompaxError
from axisline.devices.compax.ascii import AsciiEndpoint
from axisline.devices.compax.camop import E_NOT_AVAILABLE, CamState
from axisline.devices.compax.cammemory import CamMemory
from axisline.devices.compax.parameters import Parameters
from axisline.motion.axis import AxisState
from axisline.motion.homing import DirectHoming

from .test_camop_rig import Rig, line

LIMITS = {"P93": 1, "P11": 500.0, "P12": -100.0}


def _coupled(rig: Rig) -> None:
    rig.op.setc(1)
    rig.op.loop(0)
    rig.inputs["I13"] = True
    rig.step()
    rig.start_master(4)
    rig.step(20)
    assert rig.op.state is CamState.SYNC


def test_limit_supervision_in_normal_mode_needs_the_machine_datum():
    # §2.4 "When limit supervision is activated in normal mode after "Power on", normal operation is
    # only initiated once the machine datum has been reached."
    rig = Rig({1: line()}, **LIMITS)
    rig.op.setc(1)
    for command in (lambda: rig.op.loop(0), rig.op.posr_cam):
        with pytest.raises(CompaxError) as err:
            command()
        assert err.value.code == E_NOT_AVAILABLE
    assert not rig.op.loop_active and rig.op.status(30) == E_NOT_AVAILABLE
    rig.op.posa_home()
    rig.step(2)
    assert rig.op.datum_reached
    rig.op.loop(0)
    assert rig.op.loop_active


def test_datum_not_reached_during_the_datum_travel():
    # §2.4 "This also applies for the time between the activation of the machine datum travel until
    # the machine datum is reached."
    class Slow(DirectHoming):
        def __init__(self) -> None:
            super().__init__(0.0)
            self.n = 0

        def step(self, axis):  # type: ignore[override]
            self.n += 1
            return self.n > 5

    rig = Rig({1: line()}, **LIMITS)
    rig.op.homing = Slow()
    rig.op.setc(1)
    rig.op.posa_home()
    rig.step(2)
    assert rig.axis.state is AxisState.HOMING and not rig.op.datum_reached
    with pytest.raises(CompaxError):
        rig.op.loop(0)
    rig.step(10)
    assert rig.op.datum_reached
    rig.op.loop(0)
    assert rig.op.loop_active


@pytest.mark.parametrize("params", [{"P93": 3, "P11": 500.0, "P12": -100.0}, {"P93": 2, "P11": 500.0},
                                    {"P93": 1}])
def test_no_datum_needed_without_supervision(params):
    # §2.4 "For endless axes, use P93="3". In this case, software end limit supervision is ineffective";
    # P11 = +4e6 / P12 = -4e6: supervision off
    rig = Rig({1: line()}, **params)
    rig.op.setc(1)
    rig.op.loop(0)
    assert rig.op.loop_active


def test_posa_home_during_cam_operation_over_the_interface():
    # §2.11 "Exception: If the curve commands are specified via an interface (not as a set command),
    # COMPAX also reacts during the cam operation to the command "POSA HOME" or Shift I2."
    rig = Rig({1: line()})
    _coupled(rig)
    memory, params = CamMemory(), Parameters()
    ep = AsciiEndpoint(memory, params, rig.op)
    assert ep.execute("SETM 0").startswith(b"!E107")  # other commands still refused (§11.2)
    assert not ep.execute("POSA HOME").startswith(b"!E")
    assert not ep.execute("POSAHOME").startswith(b"!E")  # blanks do not count (§2.11 "POSA HOME")
    assert not rig.op.loop_active and rig.op.state is CamState.IDLE
    rig.until(lambda: rig.op.datum_reached, 5000)
    assert rig.axis.state is AxisState.STANDSTILL and not rig.op.output(16)
    assert rig.op.home_command is not None and rig.op.home_command.done


def test_posa_home_as_a_set_command_is_refused_during_cam_operation():
    rig = Rig({1: line()})
    _coupled(rig)
    with pytest.raises(CompaxError) as err:
        rig.op.posa_home(interface=False)
    assert err.value.code == E_NOT_AVAILABLE and rig.op.loop_active


def test_shift_i2_during_cam_operation_starts_the_datum_travel():
    rig = Rig({1: line()})
    rig.inputs.update({"I1": False, "I2": False})
    _coupled(rig)
    rig.inputs["I2"] = True  # I2 alone: no shift
    rig.step(3)
    assert rig.op.loop_active
    rig.inputs["I1"] = True  # Shift I2
    rig.step()
    assert not rig.op.loop_active
    rig.until(lambda: rig.op.datum_reached, 5000)
    assert rig.axis.state is AxisState.STANDSTILL


def test_da_monitor_is_10v_during_the_activation_after_power_on():
    # manual §13.2 "During the activation (after "Power-On") the analogous output is 10V."
    rig = Rig({1: line()})
    for signal in (20, 21, 22, 23, 24):
        assert rig.op.da_monitor(signal, 1.0) == 10.0
    rig.step()
    assert rig.op.da_monitor(22, 1.0) == 0.0
    assert rig.op.da_monitor(20, 1.0) == 0.0


@pytest.mark.parametrize("params", [{"P188": 40, "P31": 9}, {"P188": 42}, {"P188": 140, "P31": 9}, {"P243": 2}])
def test_heda_master_is_not_modelled(params):
    # D23: §2.6 HEDA (option A1/A3) as the master source is not modelled: cam operation refused
    rig = Rig({1: line()}, **params)
    rig.op.setc(1)
    with pytest.raises(CompaxError) as err:
        rig.op.loop(0)
    assert err.value.code == E_NOT_AVAILABLE and not rig.op.loop_active
    assert rig.op.status(30) == E_NOT_AVAILABLE
