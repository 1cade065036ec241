"""The CLM's modes, start/stop, faults, vectors, Logic Task timing and system variables (no plant)."""

from __future__ import annotations

from .clmrig import Rig


def test_mode_outputs_follow_the_mode_inputs():
    """§9.1 (spec §2.1): I0.00.0 / I0.00.1 select Parameter / Automatic; Q0.00.0-2 show the mode,
    mirrored into the status word Q2.00."""
    rig = Rig("0000 JMP 0000\n", mode="manual")
    rig.run()
    assert (rig.bit("Q0.00.0"), rig.bit("Q0.00.1"), rig.bit("Q0.00.2")) == (1, 0, 0)
    rig.set_mode("automatic")
    rig.run()
    assert (rig.bit("Q0.00.0"), rig.bit("Q0.00.1"), rig.bit("Q2.00.1")) == (0, 1, 1)
    rig.set_mode("parameter")
    rig.run()
    assert rig.bit("Q0.00.2") == 1 and rig.bit("Q2.00.2") == 1
    assert rig.bit("Q0.00.5") == 1  # Error output active low: 1 = no fault (errata §1.19)


def test_parameter_and_automatic_together_is_fault_08():
    rig = Rig("0000 JMP 0000\n")
    rig.set("I0.00.0", 1)
    rig.run()
    assert rig.fault == "08" and rig.bit("Q0.00.5") == 0 and rig.bit("Q2.00.5") == 0
    rig.set("I0.00.7", 1)  # External Clear while the cause is there: stays
    rig.run()
    assert rig.fault == "08"
    rig.set("I0.00.0", 0)
    rig.set("I0.00.7", 0)
    rig.run()
    rig.set("I0.00.7", 1)
    rig.run()
    assert rig.fault is None


def test_estop_is_fault_03_and_stops_the_program():
    rig = Rig("0000 AEA Q1.00.0 1\n0001 JMP 0001\n")
    rig.run()
    rig.start()
    rig.set("I0.00.2", 0)
    rig.run()
    assert rig.fault == "03" and not rig.rt.modes.running
    assert "fault" in rig.axes[1].stops
    assert rig.bit("Q1.00.0") == 0  # B018 default 0: outputs cleared on the fault


def test_first_fault_is_kept():
    """Decision C-FAULT-FIRST."""
    rig = Rig("0000 RTS\n")
    rig.run()
    rig.start()
    rig.set("I0.00.2", 0)
    rig.run()
    assert rig.fault == "0C"


def test_start_after_a_fault_begins_at_0000():
    """§5.5 (spec §2.6): after an error is cleared the program starts at 0000 again."""
    rig = Rig("0000 AEA Q1.00.1 1\n0001 WAI 00.100\n0002 RTS\n")
    rig.run()
    rig.start()
    rig.run(100)
    assert rig.fault == "0C"
    rig.set("I0.00.7", 1)
    rig.run()
    rig.set("I0.00.7", 0)
    assert rig.fault is None
    rig.start()
    assert rig.rt.tasks[0].pc == 1


def test_immediate_stop_keeps_the_place_and_the_remaining_distance():
    """§5.5 (spec §2.4): Immediate Stop (active low) stops the tasks and the axes keep the
    remaining distance; the next Start continues from the point of interruption."""
    rig = Rig("0000 PSI 1 +000100.000 999\n0001 AEA Q1.00.0 1\n0002 JST 0000\n", travel_cycles=10)
    rig.run()
    rig.start()
    rig.run(2)
    rig.set("I0.00.4", 0)
    rig.run()
    assert not rig.rt.modes.running and rig.bit("Q0.01.1") == 0 and rig.axes[1].stops[-1] == "immediate"
    rig.run(50)
    assert rig.rt.tasks[0].pc == 0 and rig.bit("Q1.00.0") == 0
    rig.set("I0.00.4", 1)
    rig.start()  # continues: the axis resumes, the PSI still waits for it
    assert rig.axes[1].stops[-1] == "resume" and len(rig.axes[1].moves) == 1
    rig.run(12)
    assert rig.bit("Q1.00.0") == 1


def test_interface_stop_needs_the_interface_start():
    """L7325: a program stopped by !STOP restarts only by !START, not by the Start input."""
    rig = Rig("0000 AEA Q1.00.0 1\n0001 JMP 0001\n")
    rig.run()
    rig.start()
    rig.rt.modes.immediate_stop(interface=True)
    rig.start()
    assert not rig.rt.modes.running
    rig.rt.modes.start(interface=True)
    assert rig.rt.modes.running


def test_leaving_automatic_starts_again_at_0000():
    rig = Rig("0000 AEA M2.00.0 1\n0001 WAI 01.000\n0002 JST 0000\n")
    rig.run()
    rig.start()
    rig.run(3)
    assert rig.bit("M2.00.0") == 1
    rig.set_mode("manual")
    rig.run()
    assert rig.bit("M2.00.0") == 0  # M2 cleared on leaving Automatic
    rig.set_mode("automatic")
    rig.run()
    rig.start()
    assert rig.rt.tasks[0].pc == 1


def test_tasks_2_and_3_start_at_b011():
    """§7.5 (L3428, L3455; decision C-TASK-ENABLE): B011 = 0200 0800 0 enables Task 2 at 0200 and
    Task 3 at 0800; Task 3 runs from power-on, also in Manual, and not in Parameter mode."""
    program = "0000 JMP 0000\n0200 AEA M2.00.2 1\n0201 JMP 0201\n0800 COU +00000 M3.00.0 999999\n0801 JMP 0800\n"
    rig = Rig(program, params={"B011": "0200 0800 0"}, mode="manual")
    rig.run(10)
    assert rig.rt.tasks[2].running and rig.rt.memory.program.counters[800] == 5
    assert not rig.rt.tasks[1].running
    rig.set_mode("automatic")
    rig.run()
    rig.start()
    assert rig.bit("M2.00.2") == 1
    rig.set_mode("parameter")
    rig.run()
    count = rig.rt.memory.program.counters[800]
    rig.run(10)
    assert rig.rt.memory.program.counters[800] == count


def test_automatic_without_the_axis_enable_is_drive_not_ready():
    """§9.1: switching to Automatic without Enable Axis 1 -> error 40 'Drive 1 not ready'."""
    rig = Rig("0000 JMP 0000\n", mode="manual")
    rig.run()
    rig.set("I0.00.5", 0)
    rig.set_mode("automatic")
    rig.run()
    assert rig.fault == "40"


def test_leaving_parameter_mode_checks_parameters_and_compiles_the_logic_task():
    rig = Rig("0000 JMP 0000\n", mode="parameter")
    rig.run()
    rig.rt.memory.parameters.set("A106", "000000.000")  # Vmax 0
    rig.set_mode("manual")
    rig.run()
    assert rig.fault == "02" and rig.rt.modes.fault_error.where == "A106"
    rig = Rig("0000 JMP 0000\n", mode="parameter", logic={0: "LD I1.00.0", 1: "ST M2.00.0", 2: "END"})
    rig.run()
    rig.set_mode("manual")
    rig.run()
    assert rig.fault == "38" and rig.rt.modes.fault_error.where == "LT0001"


def test_parameter_mode_clears_outputs_and_non_retained_markers():
    """L3177: 'The outputs and non-retained marker flags are cleared'; M3 and M6.00-19 are kept."""
    rig = Rig("0000 AEA Q1.00.0 1\n0001 AEA M2.00.0 1\n0002 AEA M3.00.0 1\n0003 AEA M4.00.0 1\n0004 JST 0004\n")
    rig.run()
    rig.start()
    rig.run(4)
    rig.set_mode("parameter")
    rig.run()
    assert (rig.bit("Q1.00.0"), rig.bit("M2.00.0"), rig.bit("M3.00.0"), rig.bit("M4.00.0")) == (0, 0, 1, 0)


def test_logic_task_scan_takes_its_time():
    """Errata §1.3 (decision C-LT-SCAN): 6 assignments scan in max(4, 6) = 6 ms; at T = 2 ms the
    output follows its input after 3 cycles at most and reads the input of the scan start."""
    logic = {0: "LD I1.00.0", 1: "ST Q1.00.0", 2: "NOP", 3: "NOP", 4: "NOP", 5: "END"}
    rig = Rig("0000 JMP 0000\n", logic=logic, mode="manual")
    rig.run(3)  # scans run from power-on
    rig.set("I1.00.0", 1)
    seen = []
    for _ in range(7):
        rig.run()
        seen.append(rig.bit("Q1.00.0"))
    assert seen[0] == 0 and seen[-1] == 1
    assert 3 <= seen.index(1) + 1 <= 6  # not before one whole scan, at most two


def test_system_variables():
    """Decision C-SYSVAR: V000 counts NC cycles, V002 is Task 1's instruction, V100 axis 1's position."""
    rig = Rig("0000 POA 1 +000012.500 999\n0001 JMP 0001\n")
    rig.run()
    rig.start()
    rig.run(10)
    assert rig.var(0) == rig.rt.cycle  # the cycles run so far
    assert rig.var(2) == 1
    assert rig.var(100) == 12.5


def test_manual_vector_example():
    """L3389-3396: B014 = I1.01.0 0 0400; 0400 AEA Q1.00.0 0, 0401 AEA Q1.00.1 0, 0402 RTS:
    'Outputs Q1.00.0 and Q1.00.1 are cleared when the manual vector is invoked.'"""
    program = "0400 AEA Q1.00.0 0\n0401 AEA Q1.00.1 0\n0402 RTS\n"
    rig = Rig(program, params={"B014": "I1.01.0 0 0400"}, mode="manual")
    rig.set("Q1.00", 0b11)
    rig.run(2)
    assert rig.bit("Q1.00.0") == 1
    rig.set("I1.01.0", 1)
    rig.run(4)
    assert rig.bit("Q1.00.0") == 0 and rig.bit("Q1.00.1") == 0
    assert not rig.rt.modes.manual_vector and rig.fault is None
    assert rig.bit("Q0.01.1") == 0  # the manual vector does not set Run Task


def test_interrupt_vector_sends_task_1_to_its_program():
    """§7.4 (spec §3.10): B015 = input, mode 1 (always, rising edge), positioning 0, address."""
    program = "0000 JSR 0010\n0010 WAI 09.000\n0500 AEA Q1.00.3 1\n0501 JST 0501\n"
    rig = Rig(program, params={"B015": "I1.00.5 1 0 0500"})
    rig.run()
    rig.start()
    rig.run(5)
    rig.set("I1.00.5", 1)
    rig.run(3)
    assert rig.bit("Q1.00.3") == 1 and rig.rt.tasks[0].stack == []


def test_interface_switches_an_axis_off_until_mxon_or_an_estop():
    """Spec §8.6 !MxOFF: a command to the axis is fault 4E, its enable loss is no error; the state
    survives mode changes; !MxON or an E-Stop switch it on again."""
    rig = Rig("0000 POI 1 +000010.000 999\n0001 JST 0001\n", mode="manual")
    rig.run()
    rig.rt.modes.interface_enable(1, False)
    rig.set_mode("automatic")
    rig.set("I0.00.5", 0)  # its enable input may go: no 40
    rig.run()
    assert rig.fault is None and rig.axes[1].stops[-1] == "off"
    rig.set("I0.00.5", 1)
    rig.start()
    assert rig.fault == "4E"
    rig.set("I0.00.2", 0)  # E-Stop
    rig.run()
    assert 1 in rig.rt.modes.enabled_axes and rig.axes[1].stops[-1] == "on"


def test_time_counter_clears():
    rig = Rig("0000 JMP 0000\n", cycle_s=0.004)
    rig.rt.cycle = 1_000_000  # 4000 s of running
    assert rig.var(19) == 1.0
    rig.rt.clear_time_counter()
    assert rig.var(19) == 0.0


def test_fak_5_resets_on_clearing_an_error_and_leaving_parameter_mode():
    """L1935-1937: the master encoder 1 factor (FAK 5) is reset to 1.000000 after power up, after an
    error is cleared, or after exiting Parameter Mode."""
    rig = Rig("0000 FAK 5 1.500000\n0001 RTS\n")
    rig.run()
    rig.start()
    assert rig.rt.master_factor == 1_500_000
    rig.run()
    assert rig.fault == "0C"
    rig.set("I0.00.7", 1)
    rig.run()
    assert rig.fault is None and rig.rt.master_factor == 1_000_000
    rig.set("I0.00.7", 0)
    rig.rt.master_factor = 1_500_000
    rig.set_mode("parameter")
    rig.run()
    rig.set_mode("manual")
    rig.run()
    assert rig.rt.master_factor == 1_000_000
