"""Errors, warnings, the single error memory and the LEDs of the 750-672 (manual §3.12, §4.4; wago.md §8, §1.7).

Every code of the manual's table §4.4.7 is here as data (`ERRORS`): code, designation,
description, cause/solution and its class, which the first digit gives (§4.4.1-4.4.4):

* 1111..1999 ACKNOWLEDGE: cleared by a rising edge of Error_Quit (or DIAG_QUIT_ERROR) once
  the cause is gone;
* 2111..2999 WARM_START: only a warm start of the module clears them (Reset bit follows);
* 3111..3999 FATAL: the module stops; only switching it off and on clears them;
* 5111..5999 WARNING: only signalled (Warning bit), no error state, no stop.

"The module has an error memory that can record exactly one error code" (§3.12.1): the
first error is kept until it is acknowledged (wago.md §8.1 [AMBIGUOUS], recommended
reading); later errors are not recorded while it is held. Warnings have their own slot,
since the Warning bit (S3.6) is separate from Error (S2.7).

An error may carry a `cause`: a callable that says whether the condition is still there
(Error_Set bit still 1, overcurrent still integrating, ...). "If the cause of the error is
not eliminated, the bit Error is set again" (§3.12.2): an acknowledge keeps such an error.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from enum import Enum

__all__ = [
    "ErrorClass",
    "ErrorCode",
    "ERRORS",
    "WagoError",
    "error_class",
    "describe",
    "ErrorMemory",
    "err_flag",
    "blink_sequence",
    "blink_signal",
]


class ErrorClass(Enum):
    ACKNOWLEDGE = "acknowledge"  # 1xxx
    WARM_START = "warm start"  # 2xxx
    FATAL = "fatal"  # 3xxx
    WARNING = "warning"  # 5xxx


def error_class(code: int) -> ErrorClass:
    """The class of a code from its first digit (§4.4.1-4.4.4)."""
    if isinstance(code, bool) or not isinstance(code, int) or not 1000 <= code <= 5999 or code // 1000 == 4:
        raise ValueError(f"error code must be 1111..3999 or 5111..5999, got {code!r}")
    return {1: ErrorClass.ACKNOWLEDGE, 2: ErrorClass.WARM_START, 3: ErrorClass.FATAL, 5: ErrorClass.WARNING}[code // 1000]


@dataclass(frozen=True, slots=True)
class ErrorCode:
    code: int
    name: str
    description: str
    cause: str

    @property
    def klass(self) -> ErrorClass:
        return error_class(self.code)


# (code, designation, description, possible cause/solution) - manual §4.4.7, in its order.
# Designations are the manual's with the line-break blanks of the PDF removed.
_TABLE = (
    (1111, 'CI_UNKNOWN_COMMAND', 'internal', 'Internal'),
    (1112, 'CI_UNKNOWN_COMMAND2', 'Unknown command', 'A drive command was received with an unknown command. Check command (and possibly the run program).'),
    (1113, 'CI_ERR1', 'Unknown command, like Error 1112', 'Same as for Error 1112.'),
    (1114, 'CI_NOT_IMPLEMENTED', 'Command not implemented', 'Command has been prepared but has not (yet) been implemented, otherwise same as Error 1112.'),
    (1115, 'CI_COMMAND_DENIED', 'Command could not be executed', 'It was not possible to execute a command, as the marginal conditions do not permit it. (incorrect mode, incorrect parameter, for this command)'),
    (1116, 'CI_SPEED1', 'Configuration: maximum frequency invalid', 'Unacceptable value specified for maximum frequency.'),
    (1117, 'CI_SPEED2', 'Frequency setting invalid', 'Unacceptable value specified for set frequency.'),
    (1118, 'CI_SPEED3', 'internal', 'Internal'),
    (1121, 'CI_ACC1', 'Acceleration value invalid', 'Check the specified acceleration value (configuration, Move program, process data).'),
    (1122, 'CI_ACC2', 'Acceleration value invalid', 'Same as for Error 1121.'),
    (1123, 'CI_ROTARY_AXIS_PERIOD_SETPOINT', 'Operation with round axis: absolute position set point value exceeds the round axis range', 'During operation with the rotary shaft, the absolute position must lie within the range of 0 ... RotaryShaftRange. Check the position data and parameters for the rotary shaft.'),
    (1124, 'CI_POS_TABLE', 'Invalid table selected for positioning on positioning table', 'Check Parameter 2 for a command "MOVE_L".'),
    (1125, 'CI_SET_POS', 'Actual value can not be set (e.g. while positioning task in progress)', 'The drive must be motionless for one SET_POS command.'),
    (1141, 'CM_UNKNOWN_CMDSOURCE', 'internal', 'internal'),
    (1142, 'CM_AUTOSTART_NOT_POSSIBLE', 'Autostart of a Move program not possible (not available)', 'Load the Move program to the module, or de-activate the autostart.'),
    (1161, 'CONFIG_WRITE_SIZE', 'Illegal variable when writing the configuration', 'An attempt was made to enter an element into the configuration with a length less than 1 byte or greater than 4 bytes.'),
    (1162, 'CONFIG_WRONGPASSWORD', 'Password not accepted', 'Specify a correct password'),
    (1211, 'CTRLOUT_FREF', 'Configuration: maximum frequency invalid', 'The maximum frequency must be between 1.....25000.'),
    (1212, 'CTRLOUT_F_FREF', 'Maximum frequency reached', 'An attempt was made to specify a frequency that is greater than the maximum frequency. Check the specified target frequency and the maximum frequency values.'),
    (1213, 'CTRLOUT_CURRENT_SCALE', 'Configuration: nominal current invalid', 'Incorrect rated motor current specified. Check the configuration.'),
    (1214, 'CTRLOUT_OPERATION_MODE', 'Configuration: The selected application is not present in this module', 'Check the configuration value for Mode 1.'),
    (1215, 'CTRLOUTP_CURR_PARAM', 'Configuration: current controller password does not agree with current controller parameters', 'Configuration: Check the parameters for current regulation with the password for current regulation.'),
    (1216, 'CTRLOUTP_F_DIV', 'Configuration: frequency prescaler faulty', 'Configuration: Check parameters for frequency prescaler.'),
    (1217, 'CTRLOUT_CURRENT_FACTOR', 'Current setting incorrect (greater than 150%)', 'Invalid parameterization for current setting, check configuration, check Move program of Mailbox commands where applicable'),
    (1218, 'CTRLLOUTP_CURR_PARAM2', 'Configuration: current controller password does not agree with current controller parameters (750-673).', 'Configuration: Check the parameters for current regulation (750-673) with Password2 for current regulation.'),
    (1241, 'IO_BITINDEXTOLARGE', 'Access to non-existing bit (internal)', 'Configuration, check Move program and Mailbox commands for incorrect bit addresses.'),
    (1242, 'IO_ILLEGAL_USERBITNR', 'Bit cannot be modified by user', 'An attempt was made to change a bit not linked to MZERO or MONE using the Move program of Mailbox command'),
    (1243, 'IO_USERBIT_READONLY', 'Bit cannot be written', 'Bit not authorized for external write access.'),
    (1245, 'IO_RECURSIVE_LINK', 'Nesting of linked bits exceeds parameters', 'A linkable bit was linked to a linkable bit that was linked to a linkable bit, etc.; A linkable bit may be linked to itself.'),
    (1246, 'IO_TIMER_1', 'Configuration: filter function not defined', 'Check configuration for filter functions.'),
    (1247, 'IO_UNKNOWN_TIMER', 'A filter with this number does not exist', 'Check configuration for filter functions.'),
    (1248, 'IO_TIMERMODE', 'Filter function does not permit write access', 'The current filter function configuration does not permit writing of the filter.'),
    (1249, 'IO_BITNOTIMPLEMENTED', 'Requested bit not implemented (internal)', 'A bit being used can not be queried (internal error).'),
    (1251, 'IO_DIVISION_ZERO', 'Filter function division: division by zero', 'Analyze run program and ensure that the denominator can never be 0.'),
    (1261, 'MEAS_SETPOSITION', 'For operation with the rotary axis, the command SET_POSITION was used with a position outside the rotary axis.', 'For this parameter, the precondition $Drive_Range_Neg \\leq setpoint\\ position \\leq Drive_Range_Pos$ must be fulfilled.'),
    (1311, 'TBL_PROGRAM_STOP1', 'Motion program terminated with error message 1', 'Check the termination condition of the Move program.'),
    (1312, 'TBL_PROGRAM_STOP2', 'Motion program terminated with error message 2', 'Check the termination condition of the Move program.'),
    (1313, 'TBL_PROGRAM_STOP3', 'Motion program terminated with error message 3', 'Check the termination condition of the Move program.'),
    (1314, 'TBL_PROGRAM_STOP4', 'Motion program terminated with error message 4', 'Check the termination condition of the Move program.'),
    (1315, 'TBL_PROGRAM_STOP5', 'Motion program terminated with error message 5', 'Check the termination condition of the Move program.'),
    (1316, 'TBL_PROGRAM_STOP6', 'Motion program terminated with error message 6', 'Check the termination condition of the Move program.'),
    (1317, 'TBL_PROGRAM_STOP7', 'Motion program terminated with error message 7', 'Check the termination condition of the Move program.'),
    (1319, 'TBL_PROGRAM_END', 'Move program not ended properly', 'Move program ended without the regular Stop command.'),
    (1321, 'TBL_UNKNOWN_CMD', 'Unknown command for table processing (internal)', '(internal)'),
    (1322, 'TBL_LABELNOTFOUND', 'Label as jump target not available in motion program', 'Check the definition of the label in the Move program.'),
    (1323, 'TBL_ENDOFTABLE', 'Jump target exceeds motion program', 'Check the step targets in the Move program.'),
    (1331, 'TBL_CAM9PARMS', 'Configuration: faulty parameter for camshaft channel 9', 'Check configuration for camshaft channel 9, the cycle may not be 0.'),
    (1332, 'TBL_INDEX_OUT_OF_RANGE', 'Table access out of table range', 'Check the tables and table access.'),
    (1333, 'TBL_INVALID', 'Access to invalid table', 'Check access to tables.'),
    (1334, 'TBL_COPY_FAILED', 'Version can not be written to EEPROM.', 'Component error'),
    (1351, 'OPC_START', 'START command not accepted', 'Start may only be set when a mode is active.'),
    (1352, 'OPC_TBL_START', 'Motion program cannot be started (not available).', 'Motion program cannot be started (not available).'),
    (1353, 'INV_CONTR_IN_PULSE_MODE', 'Mode not available in selected application', 'Check the activation of operating modes and configuration of mode 1.'),
    (1354, 'OPC_MULTIMODE_1', 'Multiple modes selected', 'Selection of mode is ambiguous.'),
    (1355, 'OPC_MULTIMODE_2', 'Multiple modes selected', 'Selection of mode is ambiguous.'),
    (1356, 'OPC_WHOOPS1', 'Unknown mode selected (internal).', 'Unknown mode selected (internal).'),
    (1358, 'OPC_EXT_ERROR', 'User bit Error_Set is set', 'Reset user bit Error_Set.'),
    (1359, 'OPC_MODE', 'The selected operating mode is not available in the current application', 'Ensure that a valid operating mode is selected.'),
    (1361, 'OPC_QUIT_START', 'Start not accepted as long as Quit is active', 'Set the control bit Error_Quit to 0.'),
    (1362, 'OPC_TMS_RDY', 'Start/selection of an operating mode is not accepted when TMS is not ready', 'Monitor supply voltages.'),
    (1363, 'OPC_TMS_SPI', 'Start/selection of an operating mode is not accepted when SPI contact is not present', '24 V control voltage dropped'),
    (1411, 'PARTMODL_CURRENT', 'internal', 'internal'),
    (1412, 'PARTMODL_CURRENT_SET', 'Current setting could not be executed.', 'Check parameter for Move command SET_CURRENT'),
    (1413, 'PARTMODL_CURRENT_TIME', 'Time limit for overcurrent reached', 'The drive has been operated too long at a current >150%. Check move profile and current setting.'),
    (1414, 'PARTMODL_FIFONOTREADY', 'internal', 'internal'),
    (1415, 'PARTMODL_POSITION_RANGE', 'The movement calculator has determined partial movement that exceeds the internal 32-bit position range.', 'Check movement parameters. This error occurs on unrealistic settings for velocity, acceleration or positions. With extreme parameters, braking from a high speed, for example, at the lowest deceleration yields a brake path that far exceeds the internal value range.'),
    (1416, 'PARTMODL_SPEED_RANGE', 'The movement calculator has determined partial movement that exceeds the permissible velocity range.', 'Check the specified velocities'),
    (1417, 'PARTMODL_INTERNI', 'Unknown status of internal FIFO: internal', 'internal'),
    (1418, 'PARTMODL_ALIGNTIMOUT', 'Timeout in the motor alignment (750-673)', 'Check drive parameters.'),
    (1431, 'PROT_REF_DIR', 'Reference motion without direction setting', 'The reference run via the process image must be informed of the starting direction through Direction_Neg or Direction_Pos.'),
    (1432, 'PULSE_TRAIN_NO_CAM_ACTIVE', 'Pulse train generator cannot be started when camshaft is not defined.', 'Download the definition for the pulse chain from the camshaft table.'),
    (1433, 'PROT_UNKNOW_MODE', 'No application selected', 'Check configuration of mode 1.'),
    (1434, 'PROT_TEST_MODE', 'Special function Integration Test active', 'The module is switched to the test mode via register 32.'),
    (1435, 'PROT_CURR', 'Current setpoint outside acceptable range', 'Run commands TORQ or TORQ_IMM were called up with unacceptable current setpoint.'),
    (1451, 'REF_SWITCH_NOT_FOUND', 'Reference switch not found', 'Check reference switch.'),
    (1452, 'REF_LIM_SWITCH', 'Reference switch not unique at start of reference motion.', 'Both limit switches active simultaneously during search for reference switch.'),
    (1453, 'REF_SPEED', 'Speed setting missing for reference run', 'Reference speed of 0 is not accepted.'),
    (1454, 'REF_START_DIR_LIMIT', 'Reference motion at Limit switch. Limit switch already actuated.', 'Reference run at Limit switch: limit switch already actuated.'),
    (1455, 'ERROR_REF_LIM_SWITCH_NOT_EXPECTED', 'Reference motion: limit switch unexpected', 'Check limit switch wiring; was the reference run started beyond the limit switch?'),
    (1456, 'REF_ALIGNMENT_NEEDS_ENCODER', 'Command for motor alignment was started, but incremental encoder is not active.', 'Motor alignment requires an incremental encoder to be activated using parameter 413, bit 1.'),
    (1511, 'UNITS_POS_INT_RESULT', 'Conversion of position in user-specific unit to internal unit: range exceeded', 'Configuration: Check units conversion..'),
    (1512, 'UNITS_POS_USER_RESULT', 'Conversion of position in internal unit to user-specific unit: range exceeded', 'Configuration: Check units conversion.'),
    (1513, 'UNITS_SPEED_INT_RESULT', 'Conversion of speed in user-specific unit to internal unit: range exceeded', 'Configuration: Check units conversion.'),
    (1514, 'UNITS_SPEED_USER_RESULT', 'Conversion of speed in internal unit to user-specific unit: range exceeded', 'Configuration: Check units conversion.'),
    (1515, 'UNITS_ACC_INT_RESULT', 'Conversion of acceleration in user-specific unit to internal unit: range exceeded', 'Configuration: Check units conversion.'),
    (1516, 'UNITS_ACC_USER_RESULT', 'Conversion of acceleration in internal unit to user-specific unit: range exceeded', 'Configuration: Check units conversion.'),
    (1517, 'UNITS_PARAM_ZERO', 'Parameter for conversion is zero', 'Configuration: Units conversion: Divisor is zero'),
    (1521, 'SYS_MODE', 'Configuration: application cannot be executed on this terminal. Acceptable value range: 1, 5', 'Check value ranges 1, 5'),
    (1551, 'MCALC_SPEED1', 'internal', 'internal'),
    (1552, 'MCALC_SPEED2', 'internal', 'internal'),
    (1553, 'MCALC_SPEED3', 'internal', 'internal'),
    (1554, 'MCALC_ACC1', 'During the ramp run at a defined ramp time the movement calculator has determined partial movement that exceeds the internal value range for acceleration', 'Adapt ramp time setting.'),
    (1555, 'MCALC_ACC2', 'Same as MCALC_ACC1', 'Same as MCALC_ACC1'),
    (1556, 'MCALC_ACC3', 'During the ramp run at a defined ramp path the movement calculator has determined partial movement that exceeds the internal value range for acceleration', 'Adapt ramp path setting.'),
    (1557, 'MCALC_PARA', 'The movement calculator has received invalid parameters', 'Check all parameters: acceleration, moving velocity, ramp time, ramp path, ramp type, starting position, target position'),
    (1561, 'MCALC_TIME1', 'Internal motion time range exceeded', 'Check parameterization. *'),
    (1562, 'MCALC_TIME2', 'The movement calculator has determined partial movement that exceeds the internal time range (>500 h)', 'Check parameterization. *'),
    (1563, 'MCALC_TIME3', 'Internal motion time range exceeded', 'Check parameterization. *'),
    (1564, 'MCALC_TIME4', 'The movement calculator has determined a movement sequence that exceeds the internal time range (>500 h).', 'Check parameterization. *'),
    (1565, 'MCALC_DIST1', 'Internal motion travel range exceeded', 'Check parameterization. *'),
    (1566, 'MCALC_DIST2', 'Internal motion travel range exceeded', 'Check parameterization. *'),
    (1567, 'MCALC_DIST3', 'Same as PARTMODL_POSITION_RANGE', 'Check parameterization. *'),
    (1568, 'MCALC_DIST4', 'Internal motion travel range exceeded', 'Check parameterization. *'),
    (1569, 'MCALC_DIST5', 'Same as PARTMODL_POSITION_RANGE', 'Check parameterization. *'),
    (1571, 'MCALC_MOVE1', 'Internal: Movement calculator can find no solution', 'Check parameterization. *'),
    (1572, 'MCALC_MOVE2', 'Internal: Movement calculator can find no solution', 'Check parameterization. *'),
    (1573, 'MCALC_MOVE3', 'Internal: Movement calculator can find no solution', 'Check parameterization. *'),
    (1574, 'MCALC_CURR', 'Current setpoint outside acceptable range', 'Reduce default value'),
    (1611, 'ERR_ILLEGAL_ERR_ORCODE', 'Illegal error code to be signaled', 'internal'),
    (1715, 'SPI_TELEGRAM3_FAIL', 'Timeout for data transfer (750-673)', 'internal'),
    (1716, 'SPI_VAR_READ_FAIL', 'Internal buffer of SPI data transfer is too small', 'internal'),
    (1717, 'SPI_VAR_READ_FAIL2', 'Internal error of SPI data transfer', 'internal'),
    (1718, 'SPI_VAR_LAST_READ', 'internal error', 'internal'),
    (1811, 'TMS', 'internal TMS error', 'internal'),
    (1812, 'TMS_OVERCURRENT_HW', 'Overcurrent output stage (750-673)', 'Overcurrent output stage (750-673): Short circuit or ground leak on the motor circuit'),
    (1813, 'TMS_OVERVOLTAGE_24V', 'Overvoltage in the 24 V control voltage', '24 V control voltage shall not exceed 36 V.'),
    (1814, 'TMS_UNDERVOLTAGE_24V', 'Undervoltage in the 24 V control voltage', '24 V control voltage shall not exceed 16 V.'),
    (1815, 'TMS_OVERVOLTAGE_V_DC', 'Overvoltage in the output voltage supply', 'Output voltage supply shall not be larger than that configured in parameter 410.'),
    (1816, 'TMS_UNDERVOLTAGE_V_DC', 'Undervoltage in the output voltage supply', 'Output voltage supply shall not be smaller than that configured in parameter 408.'),
    (1817, 'TMS_V_DC', 'Error in parameterization of output voltage supply monitoring', 'Parameter 408 or 410 is configured incorrectly.'),
    (1818, 'TMS_ENC_RESOLUTION', 'Unacceptable resolution of incremental encoder configured', 'Resolution of 0 is not allowed.'),
    (1819, 'TMS_MOTOR_FULL_STEPS', 'Unacceptable number of motor full steps configured', 'Number of motor full steps shall not be 0 and must be divisible by four.'),
    (1823, 'TMS_SPEEDMEASURETIMEA', 'Unacceptable gate time for absolute rotational speed measurement', 'Parameter 428 is configured incorrectly.'),
    (1824, 'TMS_SPEEDMEASURETIMEOUTA', 'Unacceptable timeout period for absolute rotational speed measurement', 'Parameter 432 is configured incorrectly.'),
    (1825, 'TMS_SPEEDMEASURETIMEV', 'Unacceptable gate time for internal rotational speed measurement', 'Parameter 436 is configured incorrectly.'),
    (1826, 'TMS_SPEEDMEASURETIMEOUTV', 'Unacceptable timeout period for internal rotational speed measurement', 'Parameter 440 is configured incorrectly.'),
    (1827, 'TMS_SENSOR_SUPPLY_SHORT', 'Short circuit/overload of incremental encoder supply', 'Check incremental encoder connection.'),
    (1831, 'TMS_SPEEDMEASUREDIVZERO_1', 'internal', 'internal'),
    (1832, 'TMS_SPEEDMEASUREDIVZERO_2', 'internal', 'internal'),
    (1833, 'TMS_ENCODER_RESOLUTION', 'Unacceptable incremental encoder resolution', 'Incremental encoder resolution shall not be 0.'),
    (1854, 'TMS_MODE_ERROR', 'Unacceptable TMS mode', 'internal'),
    (1859, 'TMS_CURRENT_CONTR_TYPE', 'Unacceptable current controller type', 'Correct parameter 396.'),
    (1881, 'TMS_PARAM_CHANGED', 'Parameter shall not be changed while motor is running', 'Change parameter only when motor is stopped.'),
    (1882, 'TMS_PARAM_NOT_OK', 'internal', 'internal'),
    (1884, 'TMS_NOT_ALIGNED', 'Operation with field orientation without previous motor alignment', 'Perform motor alignment.'),
    (1886, 'TMS_SWITCHING_FREQUENCY', 'Maximum acceptable switching frequency of output stage exceeded', 'Configure current controller.'),
    (1887, 'TMS_BRIDGE_A_LOW', 'No load detected on motor circuit A', 'Check motor connection.'),
    (1889, 'TMS_BRIDGE_B_LOW', 'No load detected on motor circuit B', 'Check motor connection.'),
    (1891, 'TMS_TRACKING_V', 'Speed contouring error', 'Check speed contouring error.'),
    (1892, 'TMS_TRACKING_S', 'Position contouring error', 'Check position contouring error.'),
    (1893, 'TMS_TEMP_HIGH', 'Output stage temperature higher than max. acceptable temp.', 'Decrease load cycle.'),
    (1894, 'TMS_TEMP_HIGH_WARN', 'Output stage temperature higher than parameterized warning threshold', 'Check parameters, decrease load cycle.'),
    (1911, 'COMMAND_IS_RUNNING', 'Command can not be executed, as another command is currently being processed', 'internal'),
    (1912, 'HIGH_Prio_COMMAND_IS_RUNNING', 'Command can not be executed, as another command of higher priority is currently being processed', 'internal'),
    (1931, 'PARTMODL_LIMITSWITCH', 'Command can not be executed, as a limit switch is active', 'Move drive away from limit switch.'),
    (2811, 'KBUS', 'internal', 'Internal'),
    (2821, 'CFG_FACTORY_LOAD', 'A Factory_Default data set has been copied for upload to RAM', 'A CONFIG_RESTORE command has been executed without a warm start. The module is not operational in this state. → Conduct a warm start or Power-on reset.'),
    (2831, 'MEASURE_ERR1', 'internal: hardware unknown', 'internal'),
    (2832, 'MEASURE_ERR2', 'same as MEASURE_ERR1', 'internal'),
    (2833, 'MCALC_INTERN1', 'Internal: error in travel calculation', 'internal'),
    (2834, 'MCALC_INTERN2', 'Internal: error in travel calculation', 'internal'),
    (2835, 'MCALC_INTERN3', 'Internal: unknown acceleration profile', 'internal'),
    (2836, 'MCALC_INTERN4', 'MCALC_INTERN3', 'internal'),
    (2837, 'MCALC_INTERN5', 'MCALC_INTERN3', 'internal'),
    (2838, 'MCALC_INTERN6', 'MCALC_INTERN3', 'internal'),
    (2839, 'MCALC_INTERN7', 'MCALC_INTERN3', 'internal'),
    (2841, 'MCALC_INTERN8', 'MCALC_INTERN3', 'internal'),
    (2842, 'MCALC_INTERN9', 'MCALC_INTERN3', 'internal'),
    (2843, 'MCALC_INTERN10', 'MCALC_INTERN3', 'internal'),
    (2844, 'MCALC_INTERN11', 'MCALC_INTERN3', 'internal'),
    (2845, 'MCALC_BUFFER_FULL', 'internal: buffer overflow', 'internal'),
    (2846, 'MOVECALC_ACC2', 'internal', 'internal'),
    (2863, 'TEST_EERPOM_FAILURE', 'Auto test: EEPROM failure', 'Hardware defective'),
    (2864, 'TEST_CPLD_FAILURE', 'Auto test: CPLD failure', 'Hardware defective'),
    (2865, 'TEST_INVALID_MODULE', 'Auto test: unknown hardware', 'Hardware defective'),
    (2866, 'GENERIC_TEST', 'Auto test: invalid hardware', 'Hardware defective'),
    (2871, 'RS232_TX_TIMEOUT', 'internal:time limit exceeded in debug interface', 'internal'),
    (2881, 'SYS_IDLE_RECURSIVE', 'internal', 'internal'),
    (2882, 'SYS_SPI_TIMEOUT', 'internal', 'internal'),
    (2883, 'SPI_CONTACTLOST', 'No more contact to TMS', '24 V control voltage possibly dropped'),
    (2891, 'VERSION_UNKNOWN_IDENT', 'Unknown hardware', 'Hardware defective'),
    (2892, 'VERSION_NOT_COMPATIBLE_HW', 'Hardware not compatible with software', 'Hardware defective'),
    (2893, 'VERSION_WRONG_TMS_VERSION', 'Wrong version of TMS firmware', 'Update TMS to correct version.'),
    (2911, 'TMS_NOTSPECIFIED', 'unspecified TMS error', 'internal'),
    (2912, 'TMS_RESET', 'TMS restart detected', 'Check 24 V control voltage.'),
    (2913, 'SPI_TMS_PARAMINDEX', 'TMS: wrong parameter index in SPI transfer', 'internal'),
    (2914, 'SPI_TMS_TOGGLETIMEOUT', 'TMS: SPI transfer timeout', 'internal'),
    (2915, 'SPI_TMS_SENSORDIRECTION', 'TMS: wrong rotational direction of motor or encoder', 'Reconnect motor circuits or incremental encoder connector.'),
    (2916, 'SPI_TMS_NO_SENSOR', 'TMS: no incremental encoder during alignment', 'Check incremental encoder connector'),
    (2917, 'SPI_TMS_Z_JITTER', 'TMS: Z pulse outside the acceptable jitter range', 'The Z pulse was recorded at various positions. -> Check incremental encoder connector -> Check parameter 426'),
    (2918, 'ALIGN_WITHOUT_Z', 'TMS: Motor alignment with stored measurement values requires Z pulse configuration', 'Configure Z pulse -> Check parameter 413'),
    (3111, 'INT_KBUS', 'internal', 'internal'),
    (3112, 'INT_WATCHDOG', 'internal: watchdog', 'internal'),
    (3113, 'INT_SPURIOUS', 'internal', 'internal'),
    (3114, 'INT_UNUSED', 'internal', 'internal'),
    (3115, 'INT_FIQ', 'internal', 'internal'),
    (3116, 'INT_SWI', 'internal', 'internal'),
    (3117, 'INT_UNDEF_INST', 'internal', 'internal'),
    (3118, 'INT_FETCH', 'internal', 'internal'),
    (3119, 'INT_DATA_ACCESS', 'internal', 'internal'),
    (3121, 'INT_ROM_ISR', 'internal', 'internal'),
    (3122, 'INT_STACK_OVERFLOW', 'internal', 'internal'),
    (3142, 'SYS_PLL_NOT_LOCKED', 'internal', 'internal'),
    (3143, 'SYS_ADC_TIMEOUT', 'internal', 'internal'),
    (3144, 'SYSTEMEXIT', 'internal', 'internal'),
    (3155, 'ERR_ILLEGAL_ERRORCODE', 'Illegal error code to be signaled', 'internal'),
    (3166, 'OPC_MULTIMODE_1', 'internal', 'internal'),
    (3167, 'OPC_MULTIMODE_2', 'internal', 'internal'),
    (3168, 'OPC_WHOOPS1', 'internal', 'internal'),
    (3179, 'TBL_COPY_FAILED', 'Error when writing to EEPROM', 'internal'),
    (3211, 'PARTMODL_FIFONOTREADY', 'internal', 'internal'),
    (3212, 'PARTMODL_POSITION_RANGE', 'internal', 'internal'),
    (3213, 'PARTMODL_SPEED_RANGE', 'internal', 'internal'),
    (3214, 'PARTMODL_INTERN1', 'internal', 'internal'),
    (3215, 'PARTMODL_ERR4', 'internal', 'internal'),
    (3216, 'PARTMODL_ERR5', 'internal', 'internal'),
    (3231, 'TBL_INVALID', 'internal', 'internal'),
    (3232, 'TBL_CP2EEPROM_FAIL', 'internal', 'internal'),
    (3233, 'TBL_COPY_INVALID', 'internal', 'internal'),
    (3234, 'TBL_UNKNOWN_TTYPE', 'internal', 'internal'),
    (3271, 'TEST_FLASH', 'Error in checksum of program memory', 'internal'),
    (3272, 'TEST_FLASH_CRCGEN', 'Checksum for program memory not available', 'internal'),
    (3273, 'TEST_EERPOM_FAILURE', 'Auto test: EEPROM failure', 'internal'),
    (3274, 'TEST_CPLD_FAILURE', 'Auto test: CPLD failure', 'internal'),
    (3275, 'TEST_INVALID_MODULE', 'Auto test: unknown hardware', 'internal'),
    (3276, 'GENERIC_TEST', 'Auto test: invalid hardware', 'internal'),
    (3277, 'TEST_ENDOF_FUNCTION_TEST', 'Self test completed', 'internal A reset is required after a self test.'),
    (3811, 'TMS_SWITCH_ALIGN', 'internal', 'internal'),
    (5887, 'ERROR_WARN_BRIDGE_A_LOW', 'No motor detected at output stage A', 'Check motor connection.'),
    (5889, 'ERROR_WARN_BRIDGE_B_LOW', 'No motor detected at output stage B', 'Check motor connection'),
    (5891, 'ERROR_WARN_TMS_TRACKING_V', 'Contouring error speed', 'Increase parameter 482 (TrackingError_Range_Speed).'),
    (5892, 'ERROR_WARN_TMS_TRACKING_S', 'Position contouring error', 'Increase parameter 484 (TrackingError_Range_Position).'),
    (5893, 'ERROR_WARN_TMS_TEMP_HIGH_WARN', 'Output stage temperature higher than parameterized warning threshold', 'Either decrease current or increase parameter 406 (Warn_Threshold_Temperature)'),
    (5917, 'ERROR_WARN_SPI_TMS_Z_JITTER', 'TMS: Z pulse outside the acceptable jitter range', 'Increase parameter 426 (Encoder_IndexMeasureJitterRange).'),
    # [RECONSTRUCTED] PROG_STOP with error message 8 (wago.md §5.6): the table stops at 1317.
    (1318, 'TBL_PROGRAM_STOP8', 'Motion program terminated with error message 8', 'Check the termination condition of the Move program.'),
)

ERRORS: dict[int, ErrorCode] = {c: ErrorCode(c, n, d, s) for c, n, d, s in _TABLE}


def describe(code: int) -> str:
    """'1413 PARTMODL_CURRENT_TIME: Time limit for overcurrent reached' (unknown codes too)."""
    e = ERRORS.get(code)
    return f"{code} {e.name}: {e.description}" if e is not None else f"{code} (not in the manual's error table)"


class WagoError(Exception):
    """A command or setting rejected with the device's error code; the message names field, value, range."""

    def __init__(self, code: int, text: str) -> None:
        super().__init__(f"{describe(code)} - {text}")
        self.code = code
        self.text = text


@dataclass(slots=True)
class _Entry:
    code: int
    extra: int
    text: str
    cause: Callable[[], bool] | None


class ErrorMemory:
    """The single error memory plus the warning slot (§3.12.1)."""

    def __init__(self) -> None:
        self._error: _Entry | None = None
        self._warning: _Entry | None = None

    # ---- read-outs
    @property
    def error(self) -> int:
        """Code of the error held (0: none) - what DIAG_RD_ERROR returns first."""
        return self._error.code if self._error is not None else 0

    @property
    def warning(self) -> int:
        return self._warning.code if self._warning is not None else 0

    @property
    def code(self) -> int:
        """DIAG_RD_ERROR: the error, else the warning, else 0."""
        return self.error or self.warning

    @property
    def extra(self) -> int:
        """Extra information of the entry `code` reports (content not specified by the manual)."""
        e = self._error or self._warning
        return e.extra if e is not None else 0

    @property
    def text(self) -> str:
        e = self._error or self._warning
        return e.text if e is not None else ""

    @property
    def error_class(self) -> ErrorClass | None:
        return error_class(self._error.code) if self._error is not None else None

    # ---- raising
    def raise_code(self, code: int, text: str = "", extra: int = 0, cause: Callable[[], bool] | None = None) -> bool:
        """Record `code`; True if it was recorded (the memory was free), False if it was held.

        Warnings (5xxx) go to the warning slot; the first warning is kept the same way.
        """
        klass = error_class(code)
        entry = _Entry(code, int(extra) & 0xFFFF, text or describe(code), cause)
        if klass is ErrorClass.WARNING:
            if self._warning is None:
                self._warning = entry
                return True
            return False
        if self._error is None:
            self._error = entry
            return True
        return False

    def acknowledge(self) -> bool:
        """Error_Quit rising edge / DIAG_QUIT_ERROR. Returns True if a warm start is due.

        1xxx errors and warnings are cleared unless their cause is still present. A 2xxx
        error asks for a warm start (the device performs it, which clears the memory);
        a 3xxx error stays until power-off.
        """
        if self._warning is not None and not (self._warning.cause is not None and self._warning.cause()):
            self._warning = None
        e = self._error
        if e is None:
            return False
        klass = error_class(e.code)
        if klass is ErrorClass.FATAL:
            return False
        if klass is ErrorClass.WARM_START:
            return True
        if e.cause is not None and e.cause():
            return False
        self._error = None
        return False

    def clear(self) -> None:
        """Warm start or power-on: the memory is empty again."""
        self._error = None
        self._warning = None

    def __repr__(self) -> str:
        return f"ErrorMemory(error={self.error}, warning={self.warning})"


def err_flag(error_mode: int, warning_mode: int, error: bool, warning: bool, error_quit: bool) -> bool:
    """S0.6 ERR (§3.7.2, §3.12.3): follows Error/Warning where bit 0 of ErrorNotificationMode
    (addr 113) / WarningNotificationMode (addr 116) enables it; "addressed continuously as long
    as the error is present and Error_Quit is not set"."""
    if error_quit:
        return False
    return bool((error_mode & 1 and error) or (warning_mode & 1 and warning))


# ---------------------------------------------------------------- LED A blink code (§4.4.5)
# The manual: a first sequence at about 10 Hz, "shortly afterward" the highest digit at about
# 2 Hz, then after a 1 s pause each the other digits down to the lowest, then repeat.
# [RECONSTRUCTED] timing: 10 Hz burst of 1 s (50 ms on / 50 ms off), 500 ms gap, digit
# blinks 250 ms on / 250 ms off, 1 s pause after each digit (the last one included).
_BURST_MS, _BURST_HALF, _GAP_MS, _DIGIT_HALF, _PAUSE_MS = 1000, 50, 500, 250, 1000


def blink_sequence(code: int) -> list[tuple[bool, int]]:
    """One period of the LED A pattern for `code` as (level, duration ms) pairs."""
    seq: list[tuple[bool, int]] = []
    for _ in range(_BURST_MS // (2 * _BURST_HALF)):
        seq += [(True, _BURST_HALF), (False, _BURST_HALF)]
    seq.append((False, _GAP_MS))
    for digit in str(int(code)):
        for _ in range(int(digit)):
            seq += [(True, _DIGIT_HALF), (False, _DIGIT_HALF)]
        seq.append((False, _PAUSE_MS))
    return seq


def blink_signal(code: int, t_ms: int) -> bool:
    """Level of LED A (bit ERR_Code) at `t_ms` since the code was raised (0: off)."""
    if not code:
        return False
    seq = blink_sequence(code)
    period = sum(d for _, d in seq)
    t = int(t_ms) % period
    for level, d in seq:
        if t < d:
            return level
        t -= d
    return False  # pragma: no cover - t < period
