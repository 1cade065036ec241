"""FS701 command inputs, output signals and their hardware assignment (manual §4.1, §11; spec fs701.md §3.1, §3.2)."""

from __future__ import annotations

import pytest

from axisline.devices.fs701.io_assign import (
    INPUT_FUNCTIONS,
    OUTPUT_SIGNALS,
    SERIAL_COMMAND_MASK,
    EdgeDetector,
    IOAssignment,
    IOAssignmentError,
    SignalType,
    bit_names,
    input_function,
    output_signal,
)


def test_command_table_of_section_11():
    assert [f.bit for f in INPUT_FUNCTIONS] == list(range(32))
    for f in INPUT_FUNCTIONS:
        if f.attr == "print_mark":
            assert f.code is None and not f.serial and f.default_input == 15
        else:
            assert f.code == 0x0900 + f.bit
    assert SERIAL_COMMAND_MASK == 0xFFFF_FFFF & ~(1 << 14)
    named = {f.attr: (f.bit, f.type) for f in INPUT_FUNCTIONS if f.in_use}
    assert named == {
        "control_enable": (0, SignalType.STATIC), "start_stop": (1, SignalType.STATIC),
        "select_virmaster": (2, SignalType.STATIC), "run_virt_master": (3, SignalType.STATIC),
        "immediate_cut": (4, SignalType.RISING), "cut_completed": (5, SignalType.EDGE_SENSE),
        "cut_test_length": (6, SignalType.STATIC_OR_PULSE), "clear_error": (7, SignalType.RISING),
        "set_zero_pos": (8, SignalType.STATIC), "jog_forward": (9, SignalType.STATIC),
        "jog_reverse": (10, SignalType.STATIC), "decr_batch_cou": (11, SignalType.RISING),
        "start_gap": (12, SignalType.STATIC), "teach_printmark": (13, SignalType.STATIC),
        "print_mark": (14, SignalType.PRINTMARK_EDGE), "reset_diff_cou": (16, SignalType.STATIC),
        "reset_batch_cou": (17, SignalType.STATIC), "sync_mode_enable": (18, SignalType.STATIC),
        "store_to_eeprom": (29, SignalType.RISING), "adjust_program": (30, SignalType.SERIAL_ONLY),
        "test_program": (31, SignalType.SERIAL_ONLY),
    }  # fmt: skip
    assert input_function("decrement_batch_counter").bit == 11 and input_function(29).attr == "store_to_eeprom"


def test_output_table_of_section_11():
    assert [(s.bit, s.code) for s in OUTPUT_SIGNALS] == [(n, 0x0A00 + n) for n in range(32)]
    assert [s.attr for s in OUTPUT_SIGNALS if s.in_use] == [
        "ready", "ready_to_cut", "home", "alarm", "length_pulses", "gap_completed", "master_reverse", "error",
        "master_in_motion", "vir_m_in_motion", "no_printmark", "printmark_window", "virt_printmark",
        "max_correction", "printm_teached",
    ]  # fmt: skip
    assert output_signal("printmark_teached").bit == 14
    assert bit_names(0b1000_0011, "outputs") == ["ready", "ready_to_cut", "error"]
    assert bit_names(1 << 29 | 1, "commands") == ["control_enable", "store_to_eeprom"]


def test_default_assignment_fs701_md_7_e24():
    io = IOAssignment.default()
    inputs = ["control_enable", "start_stop", "select_virmaster", "run_virt_master", "immediate_cut", "cut_completed",
              "cut_test_length", "clear_error", "set_zero_pos", "jog_forward", "jog_reverse", "decr_batch_cou",
              "start_gap", "teach_printmark", "print_mark", "command_15"]  # fmt: skip
    for n, name in enumerate(inputs, 1):
        assert io.inputs_of(name) == {n} and io.functions_of_input(n) == [name]
    outputs = ["ready", "ready_to_cut", "home", "alarm", "length_pulses", "gap_completed", "master_reverse", "error"]
    for n, name in enumerate(outputs, 1):
        assert io.outputs_of(name) == {n} and io.signals_of_output(n) == [name]
    assert io.inputs_of("reset_batch_cou") == set() and io.outputs_of("master_in_motion") == set()
    assert io.is_manual_compatible()


def test_one_input_switches_several_functions_and_outputs_are_ored():
    io = IOAssignment.default()
    io.assign_input("reset_batch_cou", 12)  # In12 now decrements and resets the batch counter
    assert io.functions_of_input(12) == ["decr_batch_cou", "reset_batch_cou"]
    word = io.hardware_command_word(1 << 11)
    assert word == (1 << 11) | (1 << 17)
    io.assign_output("master_in_motion", 8)  # Error OR Master in motion on Out8
    assert io.hardware_output_levels(1 << 8) == 1 << 7
    assert io.hardware_output_levels(1 << 7) == 1 << 7
    assert io.hardware_output_levels(0) == 0
    assert io.is_manual_compatible()


def test_axisline_extensions_several_terminals_and_inversion():
    io = IOAssignment.default()
    io.assign_input("clear_error", [8, 16])  # either input clears
    assert io.hardware_command_word(1 << 15) & (1 << 7)
    io.assign_output("alarm", (4, 5))  # one signal on two outputs
    assert io.hardware_output_levels(1 << 3) == 0b11000
    assert not io.is_manual_compatible()
    io2 = IOAssignment.default()
    io2.set_inverted_inputs([1])  # Control Enable wired active low
    assert io2.hardware_command_word(0) & 1 and not io2.hardware_command_word(1) & 1
    io2.set_inverted_outputs([1])
    assert io2.hardware_output_levels(0) == 1 and io2.hardware_output_levels(1) == 0  # Ready on Out1, inverted
    assert not io2.is_manual_compatible()


def test_print_mark_level_shows_in_bit_14():
    io = IOAssignment.default()
    assert io.hardware_command_word(1 << 14) == 1 << 14  # In15 (terminal bit 14): Print Mark
    assert io.hardware_command_word(1 << 15) == 1 << 15  # In16: "(Command 15)"
    assert io.printmark_level(1 << 14) and not io.printmark_level(0)


def test_validation_names_the_problem():
    io = IOAssignment.default()
    before = io.copy()
    with pytest.raises(IOAssignmentError, match="fixed to In15"):
        io.assign_input("print_mark", 3)
    with pytest.raises(IOAssignmentError, match="serial/bus only"):
        io.assign_input("adjust_program", 1)
    with pytest.raises(IOAssignmentError, match="1..16"):
        io.assign_input("start_gap", 17)
    with pytest.raises(IOAssignmentError, match="1..8"):
        io.assign_output("alarm", 9)
    with pytest.raises(IOAssignmentError, match="1..16"):
        io.assign_input("start_gap", [13, 0])
    with pytest.raises(IOAssignmentError, match="no FS701 input function 'start_gapp'"):
        io.assign_input("start_gapp", 1)
    with pytest.raises(IOAssignmentError, match="no FS701 output signal"):
        io.assign_output("ready_to_cutt", 1)
    with pytest.raises(IOAssignmentError):
        IOAssignment({"start_gap": 13, "jog_forward": 99})
    with pytest.raises(IOAssignmentError):
        io.set_inverted_inputs([0])
    assert io == before and io.diff(before) == []
    io.assign_input("start_gap", None)
    assert io.inputs_of("start_gap") == set() and io.diff(before) == ["input start_gap: [] != [13]"]


def test_dict_round_trip_and_assign_in_place():
    io = IOAssignment.default()
    io.assign_input("sync_mode_enable", [3, 4])
    io.set_inverted_outputs([2])
    again = IOAssignment.from_dict(io.as_dict())
    assert again == io
    with pytest.raises(IOAssignmentError):
        IOAssignment.from_dict({"inputs": {}, "extra": 1})
    target = IOAssignment()
    target.assign(io)
    assert target == io and target is not io


def test_edges_respect_edge_sense_and_printmark_edge():
    det = EdgeDetector()
    cut = 1 << 5
    e = det.update(cut)
    assert e.triggered("cut_completed") and not e.triggered("cut_completed", edge_sense=1)
    e = det.update(0)
    assert e.triggered("cut_completed", edge_sense=1) and not e.triggered("cut_completed")
    e = det.update(1 << 4 | 1 << 14 | 1)
    assert e.triggered("immediate_cut") and e.triggered("print_mark") and not e.triggered("print_mark", printmark_edge=1)
    assert not e.triggered("control_enable") and e.on("control_enable")  # static: read the level
    e = det.update(1 << 4 | 1)
    assert not e.triggered("immediate_cut") and e.triggered("print_mark", printmark_edge=1)
