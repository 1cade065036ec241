"""Move commands (DRIVE_COMMAND sub-commands, manual §4.3; wago.md §3.9) and the mailbox seam (§3.7.4)."""

from __future__ import annotations

import pytest

from axisline.devices.wago672.device import RC, Opcode, Wago672
from axisline.devices.wago672.image import C0, C1, S0, S1, S2, OutputImage

from .rig import Rig


def d24(value: int) -> bytes:
    return value.to_bytes(3, "little", signed=True)


def mbx_rig(**values) -> Rig:
    values.setdefault("Freq_Div", 10)  # 8 microsteps/s per speed unit: short tests
    r = Rig(**values)
    r.c0 = C0.MBX
    r.enable()
    r.select(C1.M_DriveByMbx)
    assert r.has(S0.MBX) and r.has(S1.M_DriveByMbx_ACK)
    return r


def test_move_commands_need_the_mailbox_move_mode():
    r = Rig()
    r.enable()
    assert r.dev.drive_command(Opcode.MOVE, d24(100)) == RC.ACCESS_DENIED
    r.select(C1.M_Positioning)
    assert r.dev.drive_command(Opcode.MOVE, d24(100)) == RC.ACCESS_DENIED
    assert r.dev.drive_command(Opcode.MOVE, d24(100), source="program") == RC.ACCESS_DENIED


def test_move_sets_on_target_at_the_target_and_a_second_move_is_not_accepted_meanwhile():
    r = mbx_rig()
    dev = r.dev
    assert dev.drive_command(Opcode.SET_VELOCITY, (0x10, 0x27, 0)) == RC.OK  # 10000
    assert dev.drive_command(Opcode.SET_ACC, (0xFF, 0x7F, 0)) == RC.OK  # 32767 both phases
    assert dev.drive_command(Opcode.MOVE, d24(65065)) == RC.OK
    r.step()
    assert r.has(S2.Busy) and not r.has(S2.On_Target)
    assert dev.drive_command(Opcode.MOVE, d24(0)) == RC.NOT_ACCEPTED
    r.until(lambda: r.has(S2.On_Target), 10000)
    assert dev.actual_position == 65065
    # MOVE_REL from the last accepted target, MOVE_IMMEDIATE interrupts
    assert dev.drive_command(Opcode.MOVE_REL, d24(-65)) == RC.OK
    r.step(20)
    assert dev.drive_command(Opcode.MOVE_IMMEDIATE, d24(1000)) == RC.OK
    r.until(lambda: r.has(S2.On_Target), 10000)
    assert dev.actual_position == 1000


def test_move_rel_adds_to_the_last_accepted_target_not_the_current_position():
    r = mbx_rig()
    dev = r.dev
    dev.drive_command(Opcode.SET_VELOCITY, (0x10, 0x27, 0))
    dev.drive_command(Opcode.MOVE, d24(5000))
    r.step(30)
    assert dev.drive_command(Opcode.MOVE_REL, d24(100)) == RC.NOT_ACCEPTED  # busy: not accepted
    r.until(lambda: r.has(S2.On_Target), 10000)
    dev.drive_command(Opcode.MOVE_REL, d24(100))
    r.until(lambda: r.has(S2.On_Target), 10000)
    assert dev.actual_position == 5100


def test_speed_and_stop_fast():
    r = mbx_rig(Acceleration_Stop_Fast=2000)
    dev = r.dev
    assert dev.drive_command(Opcode.SPEED, (0x30, 0xF8, 0)) == RC.OK  # -2000
    r.until(lambda: r.has(S2.On_Target), 2000)  # set when the speed is reached
    assert dev.actual_velocity == -2000
    assert dev.drive_command(Opcode.SPEED, (0x10, 0x27, 0)) == RC.OK  # completed: accepted
    r.step(10)
    assert dev.drive_command(Opcode.STOP_FAST) == RC.OK
    r.until(lambda: r.has(S2.StandStill), 2000)
    assert not r.has(S2.Busy) and r.error == 0 and not r.has(S2.On_Target)
    # D17: after the stop no process runs, so MOVE is accepted; D18: MOVE_REL from the actual position
    here = dev.actual_position
    assert dev.drive_command(Opcode.MOVE_REL, d24(300)) == RC.OK
    r.until(lambda: r.has(S2.On_Target), 2000)
    assert dev.actual_position == here + 300


def test_stop_no_ramp_sets_the_frequency_to_zero_at_once():
    r = mbx_rig()
    dev = r.dev
    dev.drive_command(Opcode.SPEED_IMMEDIATE, (0x10, 0x27, 0))
    r.step(100)
    assert dev.drive_command(Opcode.STOP_NO_RAMP) == RC.OK
    r.step()
    assert r.has(S2.StandStill) and dev.velocity_steps == 0.0


def test_start_referencing_does_not_set_on_target():
    # D5: via the mailbox only Reference_OK and Busy = 0 mark the end
    r = mbx_rig(SetupSpeed=5000, SetupAcceleration=4000)
    r.inputs["Input2"] = lambda: 2000 <= r.x <= 4000
    assert r.dev.drive_command(Opcode.START_REFERENCING, (0, 0, 0b110)) == RC.OK  # switch, start +, positive end
    r.until(lambda: r.has(S2.Reference_OK), 5000)
    assert not r.has(S2.On_Target) and not r.has(S2.Busy)
    # D6: DIR (bit 2) is read for a reference-switch run: the positive end was latched
    assert r.x > 4000 and abs((r.x - 4000) - r.dev.actual_position) <= 41  # one cycle at 40000 microsteps/s


def test_start_referencing_at_a_limit_switch_is_access_denied():
    r = mbx_rig()
    r.inputs["Input6"] = True
    r.step()  # the module samples its inputs each tick
    assert r.dev.drive_command(Opcode.START_REFERENCING, (0, 0, 0b000)) == RC.ACCESS_DENIED
    assert r.error == 0


def test_settings_are_range_checked_with_the_device_codes():
    for opcode, data, code in (
        (Opcode.SET_VELOCITY, (0, 0, 0), 1117),
        (Opcode.SET_ACC, (0, 0, 0), 1121),
        (Opcode.SET_ACC_MODE, (0x03, 0, 0), 1557),
        (Opcode.SET_ACC_PARAM_UP, (0, 0, 0), 1557),
        (Opcode.SET_CURRENT, (151, 1, 0), 1217),
        (Opcode.TORQ, (0, 0, 0), 1114),
        (0x7E, (0, 0, 0), 1112),
    ):
        r = mbx_rig()
        rc = r.dev.drive_command(opcode, data)
        assert r.error == code and rc in (RC.GENERAL_ERROR, RC.UNKNOWN_COMMAND), (opcode, rc)


def test_set_acc_mode_and_set_current_apply_to_the_next_moves():
    r = mbx_rig()
    dev = r.dev
    assert dev.drive_command(Opcode.SET_ACC_MODE, (0x22, 0, 0)) == RC.OK  # sin^2 both phases
    assert dev.drive_command(Opcode.SET_ACC_PARAM_UP, d24(50)) == RC.OK
    assert dev.drive_command(Opcode.SET_ACC_PARAM_DOWN, d24(50)) == RC.OK
    assert dev.drive_command(Opcode.SET_CURRENT, (40, 0b0101, 0)) == RC.OK  # standstill, drive
    r.step()
    assert dev.current_ratio == 40
    dev.drive_command(Opcode.MOVE, d24(20000))
    r.until(lambda: r.has(S2.On_Target), 10000)
    assert dev.actual_position == 20000


def test_set_actual_position_at_standstill_only():
    r = mbx_rig()
    dev = r.dev
    assert dev.drive_command(Opcode.SET_ACTUALPOSITION, d24(-500)) == RC.OK
    r.step()
    assert dev.actual_position == -500
    assert dev.drive_command(Opcode.SET_ACTUALPOSITION_ZERO) == RC.OK
    r.step()
    assert dev.actual_position == 0
    dev.drive_command(Opcode.SPEED_IMMEDIATE, (0x10, 0x27, 0))
    r.step(5)
    assert dev.drive_command(Opcode.SET_ACTUALPOSITION, d24(0)) == RC.GENERAL_ERROR and r.error == 1125


def test_start_in_mailbox_mode_is_ignored():
    r = mbx_rig()
    r.c1 |= C1.Start
    r.step(3)
    assert not r.has(S1.Start_ACK) and r.error == 0


def test_default_mailbox_answers_with_the_toggle_and_unknown_command():
    r = Rig()
    r.c0 = C0.MBX
    r.data = bytes([0x52, 0x80, 4, 0, 2, 0, 0])  # CONFIG_RD, toggle 1
    r.step()
    reply = r.inp.mailbox_reply
    assert r.has(S0.MBX) and reply[0] == 0x52 and reply[1] == 0x80 | RC.UNKNOWN_COMMAND
    r.data = bytes([0x00, 0x00, 0, 0, 0, 0, 0])  # IDLE, toggle 0
    r.step()
    assert r.inp.mailbox_reply[:2] == bytes([0x00, 0x00])
    r.c0 = 0
    r.step()
    assert not r.has(S0.MBX)


def test_a_mailbox_handler_gets_the_six_bytes_and_answers():
    seen = []

    class Echo:
        def exchange(self, request: bytes, device: Wago672) -> bytes:
            seen.append(request)
            return bytes([request[0], request[1], 1, 2, 3, 4])

    r = Rig()
    r.dev.mailbox = Echo()
    r.step()
    assert seen == []  # only while C0.5 is set
    r.dev.write_outputs(OutputImage.build(mailbox_request=bytes([0x49, 0x80, 9, 9, 9, 9])).to_bytes())
    r.c0 = C0.MBX
    r.data = bytes([0x49, 0x80, 9, 9, 9, 9, 0])
    r.step()
    assert seen[-1] == bytes([0x49, 0x80, 9, 9, 9, 9])
    assert r.inp.to_bytes()[2:9] == bytes([0x49, 0x80, 1, 2, 3, 4, 0])


def test_program_mode_without_a_program_is_1352():
    r = Rig()
    r.enable()
    r.select(C1.M_Program)
    r.c1 |= C1.Start
    r.step()
    assert r.error == 1352


def test_program_hook_is_started_with_the_counter_of_the_process_image():
    class Program:
        running = False
        counter = 0

        def start(self, address, device):
            self.running, self.counter = True, address

        def stop(self, device):
            self.running = False

        def tick(self, cycle, device):
            if self.counter == 7:
                assert device.drive_command(Opcode.MOVE, d24(300), source="program") == RC.OK
                self.counter = 8

    r = Rig()
    prog = Program()
    r.dev.program = prog
    r.enable()
    r.select(C1.M_Program)
    from axisline.devices.wago672.image import ProgramSetpoints

    r.data = ProgramSetpoints(7).encode()
    r.start()
    assert prog.running
    r.until(lambda: r.has(S2.On_Target), 5000)
    assert r.inp.program().position == 300 and r.inp.program().counter == 8
    from axisline.devices.wago672.bits import Bit

    assert r.dev.bits.read(Bit.Program_Running) and r.dev.leds()["C"]
    r.c1 &= ~C1.M_Program
    r.step()
    assert not prog.running


@pytest.mark.parametrize("index", [1, 2, 9, 21, 0x1030])
def test_state_variables(index):
    r = Rig()
    r.enable()
    r.step()
    values = {1: 0, 2: 0, 9: 8, 21: 0, 0x1030: 1}
    assert r.dev.state_variable(index) == values[index]


def test_state_variables_while_moving_agree_with_their_aliases():
    """DIAG_RD_VAR (manual §4.7): 0/1024 the cycle, 1/1025 the actual position, 2/1026 the actual
    velocity, 20/55 the prescaler; an index the module does not know reads 0."""
    from .rig import ON

    r = Rig()
    r.c1 = ON
    r.step()
    r.c1 = ON | C1.M_Positioning
    r.step()
    r.positioning(20000, 3000, 65065)
    r.c1 = ON | C1.M_Positioning | C1.Start
    r.step()
    r.c1 = ON | C1.M_Positioning
    for _ in range(200):
        r.step()
    sv = r.dev.state_variable
    assert sv(1) == sv(1025) == r.dev.actual_position > 0
    assert sv(2) == sv(1026) != 0
    assert sv(0) == sv(1024) > 0
    assert sv(20) == sv(55) == r.dev.scaling.prescaler
    assert sv(3) == 0 and sv(999) == 0
