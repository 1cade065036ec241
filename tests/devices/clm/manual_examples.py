r"""Worked examples of the Rexroth CLM1.4 manual, as test data (no tests here).

Source: /work/shared/seeds/000_d9997d133cbde588.txt ("the manual"); ``lines`` are manual line
numbers (first, last), inclusive. Cross-checked with /work/shared/spec/clm.md and clm-errata.md;
where they disagree, the manual wins.

Every ``text`` was cut from the manual by line number, not retyped. Conventions:

* PROGRAM_LISTINGS / LOGIC_TASK_LISTINGS: the listing lines joined by '\n', verbatim (tabs, trailing
  tabs, comments, heading rows such as 'Task 1'). Only two kinds of line are dropped: blank lines,
  and the '------' underline rows that the text extraction left under some one-line examples.
  ``note`` says what a parser/test must know.
* TELEGRAMS / PARAMETER_SAMPLES: ``printed`` is verbatim, with '_' for blanks and markdown such as
  '**' or '\$' where the manual has it. ``text`` is what the checksum covers, from the first control
  character to the character before '$'. It is built by one rule: drop markup and every literal space
  (the spaces are typographic, as in '_ _ _' or '# _K'), then turn each '_' into a blank. ``checksum``
  is the printed hh. ``verifies`` is a literal, clm_checksum(text) == checksum. ``computed`` is
  clm_checksum(text). ``corrected`` (None when it verifies) is the nearest string that verifies,
  with ``reason``.
* TELEGRAM_FORMATS: telegram shapes that carry only a placeholder ('$hh'), or no checksum at all.
  PROFIBUS_ASCII: the ASCII strings inside the Profibus service channel. They carry no checksum, no
  station and no CR LF (L7790).

Checksum (spec 8.3; matches every verifying entry here)::

    def clm_checksum(s):
        t = sum(s.encode('ascii')); t = (t >> 8) + (t & 0xFF)
        return '%02X' % ((-t) & 0xFF)

Blank rules seen in the verified telegrams:

* Program telegrams ('#sN') have ONE blank before '$'. Parameter samples ('#sK') have none.
* The fields are column-aligned. Counted 0-based from the '#': number at 3-6, command at 8-10,
  data from 12. A BPA mask begins at 28 (20 from the command's first letter).
* Fig. 9-12 POI: the axis is at 12, then four blanks, the sign at 17, the velocity at 29. The station
  is the second character: a blank on RS232, '1'-'9'/'A'-'W' on RS485.

Not included: the CTA display mock-ups of chapter 8, the figure-only examples (CST, RTS, LMR
sketches), and motion-physics calculations (Kv, monitoring window, override speeds).
"""



# 1. Every NC program listing printed in the manual (in manual order).
#    Keys: name, lines, text (verbatim), note. A few entries add more keys.
PROGRAM_LISTINGS = [
    # 0002 AKN lacks its state digit; comments say 100 %/50 % for 999/500 per mille.
    {
        'name': 'acc_fig5_3',
        'lines': (1417, 1424),
        'text': (
            '0000\tACC\t1 999 999\t- Set acceleration to 100%\n'
            '0001\tPOI\t1 +000200.000 999\t- Position, then proceed immediately to next instruction\n'
            '0002\tAKN\tM2.00.0\t- Wait until position is reached Programmed in Parameter Ax27\n'
            '0003\tACC\t1 500 999\t- Reduce acceleration to 50%\n'
            '0004\tWAI\t00.100\t- Wait until drive unit is stabilized\n'
            '0005\tPSI\t1 +000300.000 999\t- Positioning at 50% acceleration without proceeding to next instruction\n'
            '0006\tWAI\t02.000\t- Wait 2 seconds\n'
            '0007\tJST\t0000\t- Program end in instruction 0000'
        ),
        'note': (
            'Complete program (Fig. 5-3). ACC fields are axis, accel per mille, decel per mille of '
            "Ax08. The comments call 999 '100%' and 500 '50%' although the unit is per mille (999 = "
            '99.9 %, PBK text L2230). 0003 halves the acceleration only; the deceleration stays 999. '
            "Instruction 0002 'AKN M2.00.0' is printed WITHOUT its state digit (AKN needs bit + "
            "state, L1472-1473): presumably 'AKN M2.00.0 1', waiting for the in-position flag (Ax27) "
            'of axis 1; a strict parser rejects it as printed.'
        ),
    },
    # Operand garbled; mask printed in table cells.
    {
        'name': 'akp_mask',
        'lines': (1495, 1496),
        'text': (
            '0008_AKP_M_0_._0_2_ _2\t1\t0\t0\t1\t2\t2\t0\n'
            '\t7\t6\t5\t4\t3\t2\t1'
        ),
        'note': (
            "Single instruction. The 8 mask digits (bit 7 first: 2 1 0 0 1 2 2 0 = '21001220') are "
            'printed as table cells; L1496 is the bit-number row (7..1, the label 0 is lost). The '
            "operand is garbled as 'M_0_._0_2' (reads M0.02 if the underscores are dropped); spec "
            '10.3 assumes M2.02. Expected (L1498-1500): bits 0, 4, 5 must be 0; bits 3, 6 must be 1; '
            'bits 1, 2, 7 are not checked. Not parseable as printed.'
        ),
    },
    {
        'name': 'ape_example_a',
        'lines': (1520, 1521),
        'text': (
            '0008_APE_M2.02\t_2\t1\t0\t0\t2\t2\t1\t0\t\n'
            '\t\t7\t6\t5\t4\t3\t2\t1\t0'
        ),
        'note': (
            "Single instruction; mask in table cells, bit 7 first: '21002210'; L1521 is the "
            'bit-number row. Expected (L1523-1525): bits 0, 4, 5 -> 0; bits 1, 6 -> 1; bits 2, 3, 7 '
            'unchanged.'
        ),
    },
    {
        'name': 'ape_example_b',
        'lines': (1529, 1530),
        'text': (
            '0008_APE_M2.02\t_2\t1\t1\t1\t0\t0\t0\t2\t\n'
            '\t\t7\t6\t5\t4\t3\t2\t1\t0'
        ),
        'note': (
            "Single instruction; mask '21110002' (bit 7 first). Expected (L1532-1534): bits 1, 2, 3 "
            '-> 0; bits 4, 5, 6 -> 1; bits 0 and 7 unchanged.'
        ),
    },
    {
        'name': 'bac_example_a',
        'lines': (1548, 1551),
        'text': (
            '0000\tWAI\t01.000\n'
            '0001\tPSI\t1 +000050.000 250\n'
            '0002\tBAC\t0000 +0000 00010\n'
            '0003\tJST\t0000'
        ),
        'note': (
            "Complete program 'count following the event': PSI runs 10 times, then JST 0000 waits for"
            ' Start (L1553). BAC increments first, then compares; jumps to 0000 while count < 00010; '
            'at the target it resets the count and proceeds. BAC offset field has 4 digits (+0000).'
        ),
    },
    {
        'name': 'bac_example_b',
        'lines': (1557, 1561),
        'text': (
            '0000\tBAC\t0002 +0000 00010\n'
            '0001\tJST\t0000\n'
            '0002\tPSI\t1 +000050.000 250\n'
            '0003\tWAI\t01.000\n'
            '0004\tJMP\t0000'
        ),
        'note': (
            "Complete program 'count prior to the event': PSI runs 9 times (L1563), because the 10th "
            'BAC execution reaches the target, resets and proceeds to 0001 JST 0000 instead of '
            'jumping to 0002.'
        ),
    },
    {
        'name': 'bio_example',
        'lines': (1645, 1649),
        'text': (
            '0032_BIO_0123_M2.02_Q1.00\t1\t1\t1\t1\t0\t0\t0\t0\n'
            'Compare Byte 1\t1\t1\t1\t0\t0\t0\t1\t0\n'
            'Compare Byte 2\t1\t1\t0\t0\t0\t0\t1\t0\n'
            'Result\t1\t1\tX\tX\t0\t0\tX\t0\n'
            '\t7\t6\t5\t4\t3\t2\t1\t0'
        ),
        'note': (
            "Single instruction 'BIO 0123 M2.02 Q1.00' with its mask printed as table cells (bit 7 "
            'first: 11110000) plus the worked compare table (byte 1 = 11100010, byte 2 = 11000010, '
            'result 1 1 X X 0 0 X 0, bit-number row L1649). X = bit fails, so the condition is not '
            'met and no jump to 0123 happens (L1651). Not parseable as printed (mask in cells).'
        ),
    },
    # Count printed with one digit.
    {
        'name': 'cio_example',
        'lines': (1687, 1687),
        'text': '0456 CIO I1.01.0 M2.02.0 5',
        'note': (
            "Single instruction. The count is printed as one digit '5' although the field has two "
            "digits (syntax L1678 '07', serial format L6566 '08'); a tolerant parser should accept it"
            ' as 05. Expected (L1690-1698): I1.01 = 10101011 -> M2.02 = 00001011 from 00000000 (bits '
            '0-4 copied). The printed marker rows have lost one column (7 values each).'
        ),
    },
    {
        'name': 'cou_example',
        'lines': (1742, 1748),
        'text': (
            '0000 CLC 0002\n'
            '0001 AEA Q1.00.4 0\n'
            '0002 COU +00000 Q1.00.4 000010\n'
            '0003 PSI 1 +000050.000 999\n'
            '0004 WAI 01.000\n'
            '0005 BCE 0001 Q1.00.4 0\n'
            '0006 JST 0001'
        ),
        'note': (
            'Complete program. PSI runs 10 times, then Q1.00.4 = 1 and JST 0001 waits for Start '
            '(L1751). COU increments before the PSI, so at the 10th COU the bit is set and the count '
            'reset; BCE 0001 Q1.00.4 0 jumps back while the bit is 0. After Start, 0001 clears '
            'Q1.00.4 again; CLC 0002 at 0000 only runs at the very first start.'
        ),
    },
    # No instruction numbers; WAI 00.02 has two decimals.
    {
        'name': 'cvt_decade_switch_fig5_10',
        'lines': (1889, 1901),
        'text': (
            'APE Q1.01 22220001\tSelect Decade 4 10^0\n'
            'WAI 00.02\tWait Until Level is Stable\n'
            'CIO I1.01.0 M2.03.0 04\tLoad Value of the Decade Switch\n'
            'APE Q1.01 22220010\tSelect Decade 3 10^1\n'
            'WAI 00.02\tWait Until Level is Stable\n'
            'CIO I1.01.0 M2.03.4 04\tLoad Value of the Decade Switch\n'
            'APE Q1.01 22220100\tSelect Decade 2 10^2\n'
            'WAI 00.02\tWait Until Level is Stable\n'
            'CIO I1.01.0 M2.04.0 04\tLoad Value of the Decade Switch\n'
            'APE Q1.01 22221000\tSelect Decade 1 10^3\n'
            'WAI 00.02\tWait Until Level is Stable\n'
            'CIO I1.01.0 M2.04.4 04\tLoad Value of the Decade Switch\n'
            'CVT V600 M2.00 0 1\tWrite Decade Switch Value after V600'
        ),
        'note': (
            "Listing without instruction numbers (Fig. 5-10: 'Commands<TAB>Comment' table). 'WAI "
            "00.02' has only two decimals (the field is ss.sss, e.g. 00.500 elsewhere), so a strict "
            "fixed-format parser rejects it; read as 00.020. CIO count '04' (two digits). CVT V600 "
            'M2.00 0 1: format 0 = BCD, last digit 1 = markers -> variable (inferred). Decade 1 = '
            '10^3 ... decade 4 = 10^0 go into M2.03.0, M2.03.4, M2.04.0, M2.04.4, i.e. the integer '
            "part of the BCD layout of Fig. 5-8. Comments are a separate tab cell without the '- ' "
            'prefix used in most listings.'
        ),
    },
    {
        'name': 'fak_fig5_13',
        'lines': (1939, 1945),
        'text': (
            '0000\tPSI\t1 +000100.000 999\t- Positioning = 100\n'
            '0001\tJSR\t0100\t\n'
            '0002\tFAK\t1 1.234500\t\n'
            '0003\tPSI\t1 +000100.000 999\t- Positioning = 123.45\n'
            '0004\tJSR\t0100\t\n'
            '0005\tFAK\t1 1.000300\t\n'
            '0006\tPSI\t1 +000100.000 999\t- Positioning = 100.03'
        ),
        'note': (
            'Fragment: JSR 0100 targets a subroutine that is not shown; no program end after 0006. '
            'The factor replaces the previous one (not cumulative): 100 -> 100, x1.2345 -> 123.45, '
            'x1.0003 -> 100.03. Lines 0001, 0002, 0004, 0005 end with a trailing tab.'
        ),
    },
    {
        'name': 'hom_example',
        'lines': (2020, 2022),
        'text': (
            '0011\tHOM\t1\t- Home Axis 1\n'
            '0012\tAKN\tM2.02.0 1\t- Wait until homing is completed\n'
            '0013\tPOA\t1 +000010.000 999\t- Positioning, Absolute'
        ),
        'note': (
            "Fragment starting at 0011. Needs Ax24 = 'M2.02.0 +100 0' (L2018): the homed output is "
            'marker M2.02.0, polled by AKN. HOM only starts homing and proceeds after one cycle.'
        ),
    },
    {
        'name': 'pbk_example',
        'lines': (2225, 2228),
        'text': (
            '0000\tCON\t1 1 +999\n'
            '0001\tWAI\t02.000\n'
            '0002\tPBK\t1\n'
            '0003\tPOI\t1 +000050.000 100'
        ),
        'note': (
            'Fragment (no program end after 0003). CON 1 1 +999 runs axis 1 continuously at 99.9 %; '
            'after 2 s PBK 1 stops it and discards the rest; the POI then adds 50 IU at 10 % with a '
            'continuous transition from 99.9 % to 10 % (L2230).'
        ),
    },
    {
        'name': 'poa_example_1',
        'lines': (2249, 2249),
        'text': '0000 POA 1 +000200.000 999',
        'note': (
            'Single instruction; from current position -100.000 the drive moves 300 forward to +200 '
            "(L2252). Needs a homed axis (else 'Not homed', L2265)."
        ),
    },
    {
        'name': 'poa_example_2',
        'lines': (2257, 2257),
        'text': '0011 POA 1 +000200.000 999',
        'note': (
            'Single instruction numbered 0011; from +400.000 the drive moves 200 backward to +200 '
            '(L2260).'
        ),
    },
    # 0000 has a 5-digit integer part (+00010.005): one digit lost.
    {
        'name': 'poa_jsr_example',
        'lines': (2270, 2275),
        'text': (
            '0000 POA 1 +00010.005 999\n'
            '0001 JSR 0100\n'
            '0002 POA 1 +000020.003 999\n'
            '0003 JSR 0100\n'
            '0004 POA 1 +000030.000 500\n'
            '0005 JSR 0100'
        ),
        'note': (
            "Fragment: JSR 0100 targets are not shown. Instruction 0000 is printed '+00010.005' with "
            "only FIVE integer digits, not the \u00b16.3 field '+000010.005' used everywhere else: a "
            'fixed-format parser rejects it as printed; a token parser reads 10.005.'
        ),
    },
    {
        'name': 'poi_example',
        'lines': (2293, 2296),
        'text': (
            '0000\tPOI\t1 -000100.000 999\n'
            '0001\tPSI\t1 +000200.000 999\n'
            '0002\tJSR\t0555\n'
            '0003\tJMP\t0000'
        ),
        'note': (
            'Loop program; JSR 0555 target not shown. POI -100 then PSI +200 from the same start: the'
            ' drive traverses -100 + 200 = +100 (L2291) and the PSI waits for the net target.'
        ),
    },
    {
        'name': 'psa_example',
        'lines': (2317, 2317),
        'text': '0000\tPSA\t1\t+000200.000\t999',
        'note': (
            "Single instruction; its fields are tab-separated ('1<TAB>+000200.000<TAB>999'); the "
            "following '------' underline row L2318 is dropped. With current +100.00 and Ax27 = 0.20 "
            'the program proceeds once the actual position is within +199.80..+200.20 (L2320).'
        ),
    },
    {
        'name': 'psi_example',
        'lines': (2334, 2338),
        'text': (
            '0000\tPSI\t1 +000100.000 999\n'
            '0001\tWAI\t00.500\n'
            '0002\tAEA\tQ1.00.6 1\n'
            '0003\tJSR\t0666\n'
            '0004\tJMP\t0000'
        ),
        'note': (
            'Loop program; JSR 0666 target not shown. Q1.00.6 is set 0.5 s after axis 1 is in '
            'position at +100 (L2340).'
        ),
    },
    {
        'name': 'rep_example_1',
        'lines': (2358, 2358),
        'text': '0020\tSRM\t1 +000000.000 +050 I1.01.0',
        'note': (
            "Single instruction (SRM without search limit). Velocity field is signed ('+050'). "
            'Underline row L2359 dropped.'
        ),
    },
    # Contradicts L2350 (REP must not follow SRM immediately).
    {
        'name': 'rep_example_2',
        'lines': (2364, 2365),
        'text': (
            '0030\tSRM\t1 +000000.000 +050 I1.01.0\n'
            '0031\tREP\t0900 1 000500.000'
        ),
        'note': (
            'SRM immediately followed by REP (max. search 500 IU, jump to 0900 not shown). L2350 says'
            " 'The REP command must not be executed immediately after the SRM command', yet this "
            "'permissible' combination does exactly that and error 1A (L8486) describes REP 'placed "
            "directly after an SRM' with a different axis: the pairing is REP right after SRM. REP "
            'length is unsigned 6.3.'
        ),
    },
    # Contains non-instruction heading rows; uses I1.01.7 not the raster input.
    {
        'name': 'rmi_fig5_20',
        'lines': (2404, 2431),
        'text': (
            'Task 1\t\t\t\n'
            '0000\tPSI\t1 +000050.000 999\t- Main Program\n'
            '0001\tJSR\t0005\t- Punching Unit 1\n'
            '0002\tPSI\t1 +000025.000 999\t\n'
            '0003\tJSR\t0009\t- Punching Unit 2\n'
            '0004\tJMP\t0000\t- New Cycle\n'
            'Punching Unit 1\t\t\t\n'
            '0005\tAEA\tQ1.00.0 1\t- Punching Unit 1 ON\n'
            '0006\tWAI\t00.200\t- Wait (Time Delay)\n'
            '0007\tAEA\tQ1.00.0 0\t- Punching Unit 1 OFF\n'
            '0008\tRTS\t\t- Back to Main Program\n'
            'Punching Unit 2\t\t\t\n'
            '0009\tAEA\tQ1.00.1 1\t- Punching Unit 2 ON\n'
            '0010\tWAI\t00.200\t- Wait (Time Delay)\n'
            '0011\tAEA\tQ1.00.1 0\t- Punching Unit 2 OFF\n'
            '0012\tRTS\t\t\n'
            'Task 2\t\t\t\n'
            '0200\tRMI\t1 0 I1.01.7\t- Wait for raster signal and movement of the offset\n'
            '0201\tPSI\t1 +000015.500 500\t- distance from the raster position\n'
            '0202\tJSR\t0210\t- Tool Program\n'
            '0203\tRMI\t1 1 I1.01.7\t- Perform feed operation in the Main Program\n'
            '0204\tJMP\t0200\t- New Cycle\n'
            'Tool Program\t\t\t\n'
            '0210\tAEA\tQ1.00.2 1\t- Cutting Mechanism ON\n'
            '0211\tWAI\t00.250\t- Wait (Time Delay)\n'
            '0212\tAEA\tQ1.00.2 0\t- Cutting Mechanism OFF\n'
            '0213\tWAI\t00.250\t- Wait (Time Delay)\n'
            '0214\tRTS\t\t'
        ),
        'note': (
            "Two tasks in one listing with heading rows ('Task 1', 'Punching Unit 1', 'Punching Unit "
            "2', 'Task 2', 'Tool Program', each followed by three tabs). Task 2 starts at 0200, which"
            " needs B011 = '0200 ...' (not shown). RMI uses the ordinary input I1.01.7, while "
            'L2606/L5936 say the raster input I0.01.7 serves RMI (errata 1.16). The offset move 0201 '
            'must directly follow RMI 1 0 (L2375). Rows 0002, 0012, 0214 have an empty comment cell '
            '(trailing tab).'
        ),
    },
    # Flag block printed joined (10000) vs blank-separated in the syntax line.
    {
        'name': 'rsv_program_1',
        'lines': (2448, 2448),
        'text': '2000\tRSV\t1 0000 10000\t- Terminate Restart Program and completely restore status',
        'note': (
            "Restart program at B016 = 2000 (L2444). Printed 'RSV 1 0000 10000': the five flags as "
            "ONE 5-digit block, whereas the syntax lines L2437-2438 show them blank-separated ('RSV 1"
            " 0000 1 0 0 1 1'). '10000' is described as 'completely restore status' here but 'RSV 0 "
            "0000 10000' as 'Restore status of outputs' in program 3: flags 2-5 are undocumented. "
            'Underline row L2449 dropped.'
        ),
    },
    {
        'name': 'rsv_program_2',
        'lines': (2453, 2455),
        'text': (
            '2000\tAKN\tI1.00.4 1\t- Wait for input\n'
            '2001\tWAI\t01.000\t- 1-second wait time\n'
            '2002\tRSV\t1 0000 10000\t- Terminate Restart Program and completely restore status'
        ),
        'note': (
            'Restart program at 2000: wait for I1.00.4, wait 1 s, then terminate and restore all. '
            'Same flag format remark as rsv_program_1.'
        ),
    },
    {
        'name': 'rsv_program_3',
        'lines': (2459, 2462),
        'text': (
            '2000\tRSV\t0 0000 10000\t- Restore status of outputs\n'
            '2001\tAKN\tI1.00.4 1\t- Wait for input\n'
            '2002\tWAI\t01.000\t- 1-second wait time\n'
            '2003\tRSV\t1 0000 00000\t- Terminate Restart Program and completely restore status, except for outputs'
        ),
        'note': (
            'Restart program at 2000: RSV 0 (do not terminate) restores the outputs first; RSV 1 ... '
            "00000 terminates and restores the rest 'except for outputs'. So flag 1 = outputs; 0 in "
            "flags 2-5 apparently still restores (contradicts reading '1 = restore'). Same flag "
            'format remark.'
        ),
    },
    {
        'name': 'srm_example',
        'lines': (2630, 2630),
        'text': '0000 SRM 1 +000000.000 +500 I1.01.0',
        'note': (
            'Single instruction. Vmax 200 IU/s, cycle 2 ms: search at 500 per mille = 100 IU/s, '
            'accuracy > 0.4 with a normal input (L2633).'
        ),
    },
    {
        'name': 'srm_offset_example',
        'lines': (2643, 2643),
        'text': '0000 SRM 1 +000200.000 +500 I1.01.0',
        'note': 'Single instruction; offset +200 from the detected mark (Fig. 5-27).',
    },
    # Pseudo-code with labels; cannot be parsed as a CLM program.
    {
        'name': 'srp_mode1_fig5_29',
        'lines': (2707, 2714),
        'text': (
            '\tSET\tV601 = 20\tDistance to End Position\n'
            '\tSET\tV602 = 10\tMaximum Correction\n'
            '\tSET\tV604 = 0\tNo Search Monitoring\n'
            '\tSRP\t1 1 0 V600 M2.02\t\n'
            '\tWAI\t0.1\t\n'
            'Start\tPSI\t1 +100 999\tFeed Command\n'
            '\tJSR\tProcessing\t\n'
            '\tJMP\tStart\t'
        ),
        'note': (
            'NOT valid CLM syntax: pseudo-code. No instruction numbers (first cell empty), labels '
            "('Start') and a symbolic JSR/JMP target ('Processing', 'Start'), abbreviated constants "
            "('SET V601 = 20' without sign/8.6 format, 'WAI 0.1', 'PSI 1 +100 999'). Variable field "
            'base V600 (V601 desired distance, V602 max correction, V604 = 0 no search monitoring). '
            "Subroutine 'Processing' not shown."
        ),
    },
    # Pseudo-code; the MAT minus sign is U+2013.
    {
        'name': 'srp_mode3_fig5_30',
        'lines': (2718, 2733),
        'text': (
            '\tSET\tV601 = 20\tDistance to End Position\n'
            '\tSET\tV602 = 10\tMaximum Correction\n'
            '\tSET\tV604 = 0\tNo Search Monitoring\n'
            '\tSET\tV700 = +100\tDesired Positioning\n'
            '\tSET\tV701 = +V700\tCalculated Positioning\n'
            '\tSET\tV702 = 0\tInterim Value\n'
            '\tSRP\t1 3 0 V600 M2.02\t\n'
            '\tWAI\t0.1\t\n'
            'Start\tPSI\t1 +V701 999\tFeed Command\n'
            '\tBCE\tCorr M2.02.4 1\t\n'
            '\tSET\tV701 = V700\t\n'
            '\tJMP\tProg\t\n'
            'Corr\tMAT\tV702 = V601 \u2013 V600\t\n'
            '\tMAT\tV701 = V700 + V702\t\n'
            'Prog\tJSR\tProcessing\t\n'
            '\tJMP\tStart\t'
        ),
        'note': (
            "NOT valid CLM syntax: pseudo-code with labels ('Start', 'Corr', 'Prog', 'Processing') as"
            " jump targets, no instruction numbers, abbreviated constants, 'SET V701 = V700' without "
            "a sign, and 'MAT V702 = V601 \u2013 V600' written with an EN DASH (U+2013), not '-'. Logic: "
            'after each feed, if M2.02.4 (raster detected) then V701 = V700 + (V601 - V600) else V701'
            ' = V700.'
        ),
    },
    # Blank counts in the 16-char text fields are lost.
    {
        'name': 'txt_status63',
        'lines': (2761, 2762),
        'text': (
            '0000 TXT 0 WAIT _ F O R _ _ _ _ _\n'
            '0001 TXT 0 FEED _ A N G L E _ _ _ _ _'
        ),
        'note': (
            'Two TXT mode 0 rows (code-fenced, blank-separated fields). The text is printed with '
            "spaced glyphs and '_' for blanks: 'WAIT _ F O R _ _ _ _ _' = 'WAIT FOR' + 5 blanks (13 "
            "chars) and 'FEED ANGLE' + 5 blanks (15 chars), although a TXT row holds 16 characters: "
            'blanks were lost. Status 63 reply L2768 (see TELEGRAM_FORMATS).'
        ),
    },
    {
        'name': 'txt_status53',
        'lines': (2782, 2785),
        'text': (
            '0000 TXT 1 STOP _ P R E S E N T _ _ _ _\n'
            '0001 TXT 0 WAIT _ F O R _ _ _ _ _\n'
            '0002 TXT 0 FEED _ A N G L E _ _ _ _ _\n'
            '0003 AEA Q1.00.6 1'
        ),
        'note': (
            "Automatic-mode program: TXT 1 'STOP PRESENT' (12 + 4 blanks = 16) for Status 53, two TXT"
            ' 0 rows for Status 63 (same lost-blank remark as txt_status63), then AEA. Up to 4 '
            'consecutive TXT rows execute in one cycle. Replies L2795 / L2805.'
        ),
    },
    {
        'name': 'vcc_mode0_fig5_31',
        'lines': (2826, 2832),
        'text': (
            '0000\tPOI\t1 +000100.000 999\t- Move 100 IU, then proceed to next instruction\n'
            '0001\tVCC\t1 +000050.000 250 0 0\t- after 50 IU, change to 25% velocity\n'
            '0002\tVCC\t1 +000075.000 500 0 0\t- after 75 IU, change to 50% velocity\n'
            '0003\tVCC\t1 +000090.000 100 0 0\t- after 90 IU, change to 10% velocity\n'
            '0004\tAKN\tM2.00.0 1\t- Wait until target position is reached\n'
            '0005\tWAI\t01.000\t- End of cycle, wait 1 second\n'
            '0006\tJMP\t0000\t- Repeat program'
        ),
        'note': (
            'Complete loop from start position 0: POI 100 at 999; after 50 IU -> 250, after 75 -> '
            '500, after 90 -> 100 per mille; AKN M2.00.0 waits for in-position. VCC fields: axis, '
            "\u00b16.3 distance, vvv, then two digits that both equal the mode here ('0 0')."
        ),
    },
    # Row 0005 has no command.
    {
        'name': 'vcc_mode1_fig5_32',
        'lines': (2851, 2856),
        'text': (
            '0000\tPOA\t1 +000300.000\t999\t- Move to absolute position +300 IU\n'
            '0001\tVCC\t1 +000200.000\t500 1 1\t- At position +200 IU, V = 50%\n'
            '0002\tVCC\t1 +000280.000\t100 1 1\t- At position +280 IU, V = 10%\n'
            '0003\tAKN\tM2.00.1\t1\t- Wait until target position is reached\n'
            '0004\tWAI\t01.000\t\t- End of cycle, wait 1 second\n'
            '0005\t\t'
        ),
        'note': (
            'Start position 100 (axis homed): POA 300; velocity 500 reached at +200, 100 at +280. '
            "Fields are split differently by tabs ('1 +000300.000<TAB>999', '500 1 1'). Instruction "
            "0005 is printed EMPTY ('0005<TAB><TAB>', command lost; mode-0 example ends with JMP "
            '0000). AKN waits on M2.00.1 here versus M2.00.0 in the mode-0 example.'
        ),
    },
    # Contains a comment-only row without instruction number.
    {
        'name': 'veo_examples',
        'lines': (2910, 2927),
        'text': (
            '0000\tBPA\t0004 M2.02 21022222\t- Program Selection; Jump to Progr. A\n'
            '0001\tBPA\t0006 M2.02 20122222\t- Program Selection; Jump to Progr. B\n'
            '0002\tBPA\t0008 M2.02 21122222\t- Program Selection; Jump to Progr. C\n'
            '0003\tJMP\t0000\t- Wait Loop\n'
            '0004\tVEO\t1 4 1 999 1\t- Program A; velocity unchanged\n'
            '0005\tJMP\t0009\t- Execute positioning function\n'
            '0006\tVEO\t1 4 1 700 1\t- Program B; velocity limited\n'
            '0007\tJMP\t0009\t- Execute positioning function\n'
            '0008\tVEO\t1 4 1 500 0\t- Program C; reduce velocity\n'
            '\t\t\t- Execute positioning function\n'
            '0009\tPOI\t1 +000100.000 999\t- Move 100 mm and proceed to next instruction\n'
            '0010\tVCC\t1 +000035.000 800 0 0\t- after 35mm, change to 80% velocity\n'
            '0011\tVCC\t1 +000050.000 600 0 0\t- after 50mm, change to 60% velocity\n'
            '0012\tVCC\t1 +000065.000 400 0 0\t- after 65mm, change to 40% velocity\n'
            '0013\tVCC\t1 +000080.000 200 0 0\t- after 80 mm, change to 20% velocity\n'
            '0014\tAKN\tM2.02.4 1\t- Wait until switching threshold is reached\n'
            '0015\tWAI\t01.000\t- At end of cycle, wait 1 second\n'
            '0016\tJMP\t0000\t- Jump to program selection'
        ),
        'note': (
            'Program selection via BPA on M2.02 (masks 21022222 / 20122222 / 21122222), then VEO 1 4 '
            '1 vvv f (s = 4: value from the command; f = 1 limit, f = 0 factor) and a VCC profile. '
            "L2919 is a comment-only row without an instruction number ('<TAB><TAB><TAB>- Execute "
            "positioning function'): 0008 falls through to 0009. Program A 999 limit = unchanged, B "
            'limit 70 %, C factor 500 (Figs. 5-34..5-36). AKN waits on M2.02.4 (switching threshold).'
        ),
    },
    {
        'name': 'gray_override_psi',
        'lines': (3327, 3327),
        'text': '0000\tPSI\t1\t+001000.000\t500',
        'note': (
            'Single instruction, fields tab-separated; underline row L3328 dropped. A106 = 000500.000'
            ' (L3322); 500 per mille -> 250 mm/s; with Gray inputs 1100 (I1.01.4..7) = 2 % -> 5 mm/s '
            '(L3342).'
        ),
    },
    {
        'name': 'manual_vector_b014',
        'lines': (3394, 3396),
        'text': (
            '0400\tAEA\tQ1.00.0 0\n'
            '0401\tAEA\tQ1.00.1 0\n'
            '0402\tRTS\t'
        ),
        'note': (
            "Manual vector program for B014 = 'I1.01.0 0 0400' (L3389): a rising edge on I1.01.0 in "
            'Manual clears Q1.00.0 and Q1.00.1. Ends with RTS (stack unchanged). Row 0402 has a '
            'trailing tab.'
        ),
    },
    {
        'name': 'task1_example',
        'lines': (3416, 3422),
        'text': (
            '0000\tAKN\tM2.00.0\t1\n'
            '0001\tPSI\t1 +000100.000\t999\n'
            '0002\tAEA\tQ1.01.0\t1\n'
            '0003\tWAI\t00.250\t\n'
            '0004\tAEA\tQ1.01.0\t0\n'
            '0005\tCOU\t+00000 Q1.00.0\t000100\n'
            '0006\tJMP\t0000\t'
        ),
        'note': (
            'Task 1 loop: wait M2.00.0, PSI 100, pulse Q1.01.0 for 250 ms, COU to 100 pieces sets '
            "Q1.00.0. Fields split by tabs at odd places ('M2.00.0<TAB>1', '+00000 "
            "Q1.00.0<TAB>000100')."
        ),
    },
    {
        'name': 'task2_example',
        'lines': (3433, 3443),
        'text': (
            '0200\tAKN\tI1.00.0\t1\n'
            '0201\tAEA\tQ1.00.0\t0\n'
            '0202\tPSI\t1 +000500.000\t999\n'
            '0203\tAPE\tQ1.01.0\t22001112\n'
            '0204\tWAI\t00.500\t\n'
            '0205\tAPE\tQ1.01.0\t22221112\n'
            '0206\tWAI\t00.800\t\n'
            '0207\tAPE\tQ1.01.0\t22000002\n'
            '0208\tWAI\t02.000\t\n'
            '0209\tCOU\t+00000 Q1.00.7\t000010\n'
            '0210\tJMP\t0200\t'
        ),
        'note': (
            "Task 2 program at 0200 for B011 = '0200 0000 0' (L3428). APE masks are 8 digits "
            '(22001112 etc.). COU to 10 sets Q1.00.7.'
        ),
    },
    # 0804 has an invalid operand I1.00.00.
    {
        'name': 'task3_example',
        'lines': (3460, 3469),
        'text': (
            '0800\tAKN\tI1.00.0\t1\n'
            '0801\tAPE\tQ1.01.0\t00000000\n'
            '0802\tWAI\t02.000\t\n'
            '0803\tAEA\tQ1.01.0\t1\n'
            '0804\tAKN\tI1.00.00\t1\n'
            '0805\tAEA\tQ1.01.0\t0\n'
            '0806\tAEA\tQ1.01.1\t1\n'
            '0807\tWAI\t00.100\t\n'
            '0808\tAEA\tQ1.01.1\t0\n'
            '0809\tJMP\t0802\t'
        ),
        'note': (
            "Task 3 program at 0800 for B011 = '0000 0800 0' (L3455); runs from power-up, also in "
            "Manual; no axis moves allowed. Instruction 0804 is printed 'AKN I1.00.00 1' with a "
            'TWO-digit bit number: invalid operand as printed (I1.00.0 meant); a strict parser must '
            "reject or repair it. APE '00000000' clears all 8 bits."
        ),
    },
    {
        'name': 'ids01_example',
        'lines': (3681, 3685),
        'text': (
            '0000\tPSI\t1 +V016\tV018\n'
            '0001\tAEA\tQ1.00.0\t1\n'
            '0002\tWAI\t00.500\t\n'
            '0003\tAEA\tQ1.00.0\t0\n'
            '0004\tJMP\t0000\t'
        ),
        'note': (
            "Uses system variables as data: '+V016' (IDS01 length 4.2) in the \u00b16.3 length field and "
            "'V018' (IDS01 velocity x 10) in the vvv field; variable fit rules (truncate, check) "
            'apply. Row 0000 is split by a tab before V018.'
        ),
    },
    # Ends with an 'etc.' row; header row L3872 dropped.
    {
        'name': 'flying_cutoff_fig7_19',
        'lines': (3873, 3883),
        'text': (
            '0000\tNOP\t\n'
            '0001\tLML 1 001000.000\tProduction length\n'
            '0002\tJSR 1000\tCutoff program\n'
            '0003\tBAC 0000 +0000 00100\tPiece count\n'
            '0004\tNOP\t\n'
            '0005\tNOP\t\n'
            '0006\tLML 1 002000.000\tProduction length\n'
            '0007\tJSR 1000\tCutoff program\n'
            '0008\tBAC 0005 +0000 00200\tPiece count\n'
            '0009\tNOP\t\n'
            'etc.\t\t'
        ),
        'note': (
            'Flying cutoff 5-instruction groups (Task 1, axis 1 mode 5). Fragment: ends with an '
            "'etc.' row (L3883), cutoff program 1000 not shown, no closing JMP. Columns are "
            "'number<TAB>command with data<TAB>comment' (data not split by a tab). LML/JSR not "
            'allowed in instruction 0000 (L2117, L2131) - here 0000 is NOP. BAC 0000 +0000 00100 '
            "repeats group 1 100 times. Comments are a third tab cell without the '- ' prefix."
        ),
    },
    # 1004 waits for the same input state as 1002 ('punch up' vs 'punch down').
    {
        'name': 'flying_cutoff_fig7_20',
        'lines': (3900, 3921),
        'text': (
            '\t\tProduct 1\n'
            '0000\tNOP\t\n'
            '0001\tLML 1 001000.000\tProduction length 1\n'
            '0002\tJSR 1000\tCutoff program\n'
            '0003\tBAC 0000 +0000 00100\tPiece count\n'
            '0004\tNOP\t\n'
            '\t\tProduct 2\n'
            '0005\tNOP\t\n'
            '0006\tLML 1 002000.000\tProduction length 2\n'
            '0007\tJSR 1000\tCutoff program\n'
            '0008\tBAC 0005 +0000 00200\tPiece count\n'
            '0009\tNOP\t\n'
            '0010\tJMP 0000\t\n'
            '\t\tCutoff program\n'
            '1000\tCPJ V100 < +01000.000 0000.00 1000\tMinimum cutoff stroke\n'
            '1001\tAEA Q1.00.0 1\tPunch down\n'
            '1002\tAKN I1.00.0 1\tWait until punch down\n'
            '1003\tAEA Q1.00.0 0\tPunch up\n'
            '1004\tAKN I1.00.0 1\tWait until punch up\n'
            '1005\tCPJ V100 < +02000.000 0000.00 1005\tMinimum carriage stroke\n'
            '1006\tEOS\tEnd of processing program\n'
            '1007\tRTS\tJump back'
        ),
        'note': (
            "Complete flying cutoff program with heading rows '<TAB><TAB>Product 1', 'Product 2', "
            "'Cutoff program'. 100 pieces of 1000, then 200 pieces of 2000, JMP 0000. CPJ V100 < ... "
            '<self> makes a wait loop on the axis 1 actual position (V100 = Vx00, readable). 1002 and'
            " 1004 both wait for 'AKN I1.00.0 1' although 1004 is 'Wait until punch up': probably "
            'should be 0 (errata lists the Fig. 7-20 strokes as ambiguous). CPJ constants are \u00b15.3 '
            "('+01000.000'). In flying cutoff, Task 1 starts at the previous length instruction minus"
            ' 1, not at 0000. Same column layout as Fig. 7-19 (data not split by a tab, comments '
            "without '- ')."
        ),
    },
]


# 2. Every Logic Task listing (chapter 6). Keys: name, lines, text (verbatim source line(s)),
#    program (the instructions, split), truth_table or symbols, note.
LOGIC_TASK_LISTINGS = [
    # Type column misprint 'bool1' for bool3 in all six tables.
    {
        'name': 'lt_and',
        'lines': (3060, 3064),
        'text': '\t<pre>LD bool1 AND bool2 ST bool3</pre>\t<pre>bool1: BOOL bool2: BOOL bool1: BOOL</pre>',
        'program': [
            'LD bool1',
            'AND bool2',
            'ST bool3',
        ],
        'truth_table': {
            'bool1': (1, 0, 1, 0),
            'bool2': (1, 1, 0, 0),
            'bool3': (1, 0, 0, 0),
        },
        'note': (
            'FBS/AWL example with symbolic BOOL operands, not CLM addresses, and no END. The AWL cell'
            " is one text line (instructions separated by blanks); 'program' splits it. The Type "
            "column prints 'bool1: BOOL' twice (third entry should be bool3). truth_table columns are"
            ' the four printed cases.'
        ),
    },
    {
        'name': 'lt_andn',
        'lines': (3066, 3070),
        'text': '\t<pre>LD bool1 ANDN bool2 ST bool3</pre>\t<pre>bool1: BOOL bool2: BOOL bool1: BOOL</pre>',
        'program': [
            'LD bool1',
            'ANDN bool2',
            'ST bool3',
        ],
        'truth_table': {
            'bool1': (1, 0, 1, 0),
            'bool2': (1, 1, 0, 0),
            'bool3': (0, 0, 1, 0),
        },
        'note': (
            'FBS/AWL example with symbolic BOOL operands, not CLM addresses, and no END. The AWL cell'
            " is one text line (instructions separated by blanks); 'program' splits it. The Type "
            "column prints 'bool1: BOOL' twice (third entry should be bool3). truth_table columns are"
            ' the four printed cases.'
        ),
    },
    {
        'name': 'lt_or',
        'lines': (3083, 3088),
        'text': '\t<pre>LD bool1 OR bool2 ST bool3</pre>\t<pre>bool1: BOOL bool2: BOOL bool1: BOOL</pre>\t\t\t\t\t\t\t\t\t\t\t\t\t\t\t\t',
        'program': [
            'LD bool1',
            'OR bool2',
            'ST bool3',
        ],
        'truth_table': {
            'bool1': (1, 0, 1, 0),
            'bool2': (1, 1, 0, 0),
            'bool3': (1, 1, 1, 0),
        },
        'note': (
            'FBS/AWL example with symbolic BOOL operands, not CLM addresses, and no END. The AWL cell'
            " is one text line (instructions separated by blanks); 'program' splits it. The Type "
            "column prints 'bool1: BOOL' twice (third entry should be bool3). truth_table columns are"
            ' the four printed cases. The table is printed twice (HTML on L3085, rows L3086-3088); '
            'both agree.'
        ),
    },
    {
        'name': 'lt_orn',
        'lines': (3090, 3095),
        'text': '\t<pre>LD bool1 ORN bool2 ST bool3</pre>\t<pre>bool1: BOOL bool2: BOOL bool1: BOOL</pre>\t\t\t\t\t\t\t\t\t\t\t\t\t\t\t\t',
        'program': [
            'LD bool1',
            'ORN bool2',
            'ST bool3',
        ],
        'truth_table': {
            'bool1': (1, 0, 1, 0),
            'bool2': (1, 1, 0, 0),
            'bool3': (1, 0, 1, 1),
        },
        'note': (
            'FBS/AWL example with symbolic BOOL operands, not CLM addresses, and no END. The AWL cell'
            " is one text line (instructions separated by blanks); 'program' splits it. The Type "
            "column prints 'bool1: BOOL' twice (third entry should be bool3). truth_table columns are"
            ' the four printed cases. Table printed twice (L3092 HTML, L3093-3095).'
        ),
    },
    {
        'name': 'lt_xor',
        'lines': (3108, 3113),
        'text': '\tLD bool1 XOR bool2 ST bool3\tbool1: BOOL bool2: BOOL bool1: BOOL\t\t\t\t\t\t\t\t\t\t\t\t\t\t\t\t',
        'program': [
            'LD bool1',
            'XOR bool2',
            'ST bool3',
        ],
        'truth_table': {
            'bool1': (1, 0, 1, 0),
            'bool2': (1, 1, 0, 0),
            'bool3': (0, 1, 1, 0),
        },
        'note': (
            'FBS/AWL example with symbolic BOOL operands, not CLM addresses, and no END. The AWL cell'
            " is one text line (instructions separated by blanks); 'program' splits it. The Type "
            "column prints 'bool1: BOOL' twice (third entry should be bool3). truth_table columns are"
            ' the four printed cases. No <pre> markup on this one. Table printed twice (L3110 HTML, '
            'L3111-3113).'
        ),
    },
    {
        'name': 'lt_xorn',
        'lines': (3115, 3120),
        'text': '\tLD bool1 XORN bool2 ST bool3\tbool1: BOOL bool2: BOOL bool1: BOOL\t\t\t\t\t\t\t\t\t\t\t\t\t\t\t\t',
        'program': [
            'LD bool1',
            'XORN bool2',
            'ST bool3',
        ],
        'truth_table': {
            'bool1': (1, 0, 1, 0),
            'bool2': (1, 1, 0, 0),
            'bool3': (1, 0, 0, 1),
        },
        'note': (
            'FBS/AWL example with symbolic BOOL operands, not CLM addresses, and no END. The AWL cell'
            " is one text line (instructions separated by blanks); 'program' splits it. The Type "
            "column prints 'bool1: BOOL' twice (third entry should be bool3). truth_table columns are"
            ' the four printed cases. Table printed twice (L3117 HTML, L3118-3120).'
        ),
    },
    {
        'name': 'lt_positive_edge',
        'lines': (3142, 3146),
        'text': (
            'LD   M6.20.0\n'
            'ANDN M6.20.4\n'
            'ST   M6.20.1\n'
            'LD   M6.20.0\n'
            'ST   M6.20.4'
        ),
        'program': [
            'LD M6.20.0',
            'ANDN M6.20.4',
            'ST M6.20.1',
            'LD M6.20.0',
            'ST M6.20.4',
        ],
        'symbols': {
            'M6.20.0': 'input',
            'M6.20.1': 'result',
            'M6.20.4': 'intermediate flag',
        },
        'note': (
            "'Spurious Pulse Positive Starting Edge' (L3130-3136). Code-fenced, mnemonic padded with "
            'blanks (no tabs, no instruction numbers), no END. M6.20.1 is 1 for exactly one scan '
            'after M6.20.0 rises. M6.20 is not in the retained range M6.00-19, so it starts at 0: an '
            'input already 1 at the first scan gives one pulse. L3147 (two blanks) is dropped.'
        ),
    },
    # The intermediate flag holds the negated input.
    {
        'name': 'lt_negative_edge',
        'lines': (3162, 3166),
        'text': (
            'LDN  M6.20.0\n'
            'ANDN M6.20.4\n'
            'ST   M6.20.1\n'
            'LDN  M6.20.0\n'
            'ST   M6.20.4'
        ),
        'program': [
            'LDN M6.20.0',
            'ANDN M6.20.4',
            'ST M6.20.1',
            'LDN M6.20.0',
            'ST M6.20.4',
        ],
        'symbols': {
            'M6.20.0': 'input',
            'M6.20.1': 'result',
            'M6.20.4': 'intermediate flag',
        },
        'note': (
            "'Spurious Pulse Negative Starting Edge' (L3150-3156). The flag stores the NEGATED input,"
            ' so result = NOT in AND in_prev: a falling edge pulse of one scan. With the flag '
            'initially 0, an input that is 0 at the first scan gives one pulse. No END.'
        ),
    },
]


# 3. Every serial telegram in the manual that prints a concrete checksum (the parameter table is in
#    PARAMETER_SAMPLES). No status reply, variable, Logic Task or '!' telegram in the manual carries a
#    real checksum: they have only the 'hh' placeholder, see TELEGRAM_FORMATS. The Profibus strings
#    carry none, see PROFIBUS_ASCII.
TELEGRAMS = [
    # As printed (L6512) it lacks 'POI' and '+'; the sum table gives the real string.
    {
        'name': 'checksum_example_1_fig9_12',
        'printed': '#_N0000_1_ _ _ _ 123456.789_123_ **\\$C4**',
        'lines': (6468, 6514),
        'text': '# N0000 1    123456.789 123 ',
        'checksum': 'C4',
        'verifies': False,
        'computed': 'F8',
        'corrected': '# N0000 POI 1    +123456.789 123 ',
        'reason': (
            "L6512 drops 'POI' and the '+' sign. The sum table L6472-6504 lists every character: '#',"
            " blank, 'N0000', blank, 'POI', blank, '1', FOUR blanks, '+123456.789', blank, '123', "
            "blank; running sum 0x636 (checked row by row), 06 + 36 = 3C, two's complement C4."
        ),
        'printed_alt': '#_N0000_POI_1_ _ _ _ 123456.789_123_ \\$',
        'printed_alt_lines': (6468, 6468),
        'note': (
            "printed_alt (L6468) shows 'POI' but still lacks '+' and has no checksum. Not a "
            "blank-only fix: the correction comes from the sum table. Trailing blank before '$' is "
            'part of the sum.'
        ),
    },
    {
        'name': 'checksum_example_2_fig9_12',
        'printed': '#5N0123_NOP_ _ _ **\\$45**',
        'lines': (6469, 6518),
        'text': '#5N0123 NOP   ',
        'checksum': '45',
        'verifies': False,
        'computed': '25',
        'corrected': '#5N0123 NOP  ',
        'reason': (
            "Printed with three blanks after NOP ('_ _ _'); the sum table (L6483-6484) has only TWO: "
            "running sum 0x2B9, 02 + B9 = BB, two's complement 45. One-blank change."
        ),
        'printed_alt': '#5N0123_NOP_ _ _ \\$',
        'printed_alt_lines': (6469, 6469),
        'note': "RS485 station '5' in the second position. NOP has no data; two blanks follow it.",
    },
    {
        'name': 'program_aea_n0101',
        'printed': '#_N0101_AEA_Q1.00.3_1_$C0',
        'lines': (6547, 6547),
        'text': '# N0101 AEA Q1.00.3 1 ',
        'checksum': 'C0',
        'verifies': True,
        'computed': 'C0',
        'corrected': None,
        'reason': None,
        'note': (
            "Verifies with the single blank before '$' (without it: E0). Columns from '#': N at 2, "
            'number 3-6, command 8-10, data from 12.'
        ),
    },
    # Lost one blank before the mask.
    {
        'name': 'program_bpa_n0102',
        'printed': '#_N0102_BPA_0123_M2.02_____21112212_$32',
        'lines': (6548, 6548),
        'text': '# N0102 BPA 0123 M2.02     21112212 ',
        'checksum': '32',
        'verifies': False,
        'computed': '52',
        'corrected': '# N0102 BPA 0123 M2.02      21112212 ',
        'reason': (
            "Printed with five blanks between 'M2.02' and the mask (checksum 52). Six blanks plus the"
            ' trailing blank give 32 (one-blank change); seven blanks without the trailing blank also'
            ' give 32, but every other program telegram has the trailing blank. With six blanks the '
            "mask starts at column 20 counted from the command letter 'B' (0-based), i.e. column 28 "
            'of the telegram, the same column as the BCE state digit in Fig. 9-13 '
            "('BCE_0234_I1.00.3____1_')."
        ),
    },
]


# 4. The parameter sample table, Figs. 9-14 (B0xx), 9-15 (Axxx, printed for axis 1 as A1xx),
#    9-16 (C0xx). The printed '# _K_' is '#', blank (station), 'K', blank: the space between '#' and
#    '_' is typographic. All 72 entries verify under that reading except B000, B001, B004, B008,
#    B017 and A123. ``label`` is the first column (e.g. 'Ax00'); ``parameter`` is the id.
PARAMETER_SAMPLES = [
    # Does not verify as printed.
    {
        'parameter': 'B000',
        'label': 'B000',
        'printed': '# _K_B000_0_0_0_0\\$8E',
        'lines': (6591, 6591),
        'text': '# K B000 0 0 0 0',
        'checksum': '8E',
        'verifies': False,
        'computed': '3E',
        'corrected': '# K B000 0 0 0',
        'reason': (
            "Printed data has one '0' (plus blank) too many: 0x50 too much in the sum. Verifies as '0"
            " 0 0' (errata 3.4, spec 8.3)."
        ),
    },
    # Does not verify as printed.
    {
        'parameter': 'B001',
        'label': 'B001',
        'printed': '# _K_B001_0_0_0_0\\$DD',
        'lines': (6592, 6592),
        'text': '# K B001 0 0 0 0',
        'checksum': 'DD',
        'verifies': False,
        'computed': '3D',
        'corrected': '# K B001 0 0',
        'reason': "Printed data has two '0 ' groups too many (0xA0). Verifies as '0 0' (errata 3.4).",
    },
    {
        'parameter': 'B002',
        'label': 'B002',
        'printed': '# _K_B002_019200_0_1_8_1\\$E4',
        'lines': (6593, 6593),
        'text': '# K B002 019200 0 1 8 1',
        'checksum': 'E4',
        'verifies': True,
        'computed': 'E4',
        'corrected': None,
        'reason': None,
    },
    {
        'parameter': 'B003',
        'label': 'B003',
        'printed': '# _K_B003_0_1_00_0_000_000\\$A8',
        'lines': (6594, 6594),
        'text': '# K B003 0 1 00 0 000 000',
        'checksum': 'A8',
        'verifies': True,
        'computed': 'A8',
        'corrected': None,
        'reason': None,
    },
    # Does not verify as printed.
    {
        'parameter': 'B004',
        'label': 'B004',
        'printed': '# _K_B004_000000_0_0_0_0_0\\$F8',
        'lines': (6595, 6595),
        'text': '# K B004 000000 0 0 0 0 0',
        'checksum': 'F8',
        'verifies': False,
        'computed': 'A8',
        'corrected': '# K B004 000000 0 0 0 0',
        'reason': (
            "One ' 0' too many. Verifies as '000000 0 0 0 0' (errata 3.4); compare B002 '019200 0 1 8"
            " 1' (four single digits)."
        ),
    },
    {
        'parameter': 'B005',
        'label': 'B005',
        'printed': '# _K_B005_0_0_00_0_000_000\\$A7',
        'lines': (6596, 6596),
        'text': '# K B005 0 0 00 0 000 000',
        'checksum': 'A7',
        'verifies': True,
        'computed': 'A7',
        'corrected': None,
        'reason': None,
    },
    {
        'parameter': 'B006',
        'label': 'B006',
        'printed': '# _K_B006_\\$59',
        'lines': (6597, 6597),
        'text': '# K B006 ',
        'checksum': '59',
        'verifies': True,
        'computed': '59',
        'corrected': None,
        'reason': None,
        'note': "Reserved/empty parameter: the blank after the number is kept ('# K B006 $hh').",
    },
    {
        'parameter': 'B007',
        'label': 'B007',
        'printed': '# _K_B007_\\$58',
        'lines': (6598, 6598),
        'text': '# K B007 ',
        'checksum': '58',
        'verifies': True,
        'computed': '58',
        'corrected': None,
        'reason': None,
        'note': "Reserved/empty parameter: the blank after the number is kept ('# K B007 $hh').",
    },
    # Does not verify as printed.
    {
        'parameter': 'B008',
        'label': 'B008',
        'printed': '# _K_B008_0_0_0_0_0_02\\$B3',
        'lines': (6599, 6599),
        'text': '# K B008 0 0 0 0 0 02',
        'checksum': 'B3',
        'verifies': False,
        'computed': '63',
        'corrected': '# K B008 0 0 0 0 02',
        'reason': (
            "One ' 0' too many. Verifies as '0 0 0 0 02' (errata 3.4); the errata 1.20 two-field "
            'question (format 0/1/2 vs fieldbus mode 0/3) is about these four digits.'
        ),
    },
    {
        'parameter': 'B009',
        'label': 'B009',
        'printed': '# _K_B009_\\$56',
        'lines': (6600, 6600),
        'text': '# K B009 ',
        'checksum': '56',
        'verifies': True,
        'computed': '56',
        'corrected': None,
        'reason': None,
        'note': "Reserved/empty parameter: the blank after the number is kept ('# K B009 $hh').",
    },
    {
        'parameter': 'B010',
        'label': 'B010',
        'printed': '# _K_B010_0.0\\$CF',
        'lines': (6601, 6601),
        'text': '# K B010 0.0',
        'checksum': 'CF',
        'verifies': True,
        'computed': 'CF',
        'corrected': None,
        'reason': None,
    },
    {
        'parameter': 'B011',
        'label': 'B011',
        'printed': '# _K_B011_0000_0000_0\\$6B',
        'lines': (6602, 6602),
        'text': '# K B011 0000 0000 0',
        'checksum': '6B',
        'verifies': True,
        'computed': '6B',
        'corrected': None,
        'reason': None,
    },
    {
        'parameter': 'B012',
        'label': 'B012',
        'printed': '# _K_B012_1000_2000\\$B7',
        'lines': (6603, 6603),
        'text': '# K B012 1000 2000',
        'checksum': 'B7',
        'verifies': True,
        'computed': 'B7',
        'corrected': None,
        'reason': None,
    },
    {
        'parameter': 'B013',
        'label': 'B013',
        'printed': '# _K_B013_\\$5B',
        'lines': (6604, 6604),
        'text': '# K B013 ',
        'checksum': '5B',
        'verifies': True,
        'computed': '5B',
        'corrected': None,
        'reason': None,
        'note': "Reserved/empty parameter: the blank after the number is kept ('# K B013 $hh').",
    },
    {
        'parameter': 'B014',
        'label': 'B014',
        'printed': '# _K_B014_00.00.0_0_0000\\$DB',
        'lines': (6605, 6605),
        'text': '# K B014 00.00.0 0 0000',
        'checksum': 'DB',
        'verifies': True,
        'computed': 'DB',
        'corrected': None,
        'reason': None,
    },
    {
        'parameter': 'B015',
        'label': 'B015',
        'printed': '# _K_B015_00.00.0_0_0_0000\\$8A',
        'lines': (6606, 6606),
        'text': '# K B015 00.00.0 0 0 0000',
        'checksum': '8A',
        'verifies': True,
        'computed': '8A',
        'corrected': None,
        'reason': None,
    },
    {
        'parameter': 'B016',
        'label': 'B016',
        'printed': '# _K_B016_0000\\$97',
        'lines': (6607, 6607),
        'text': '# K B016 0000',
        'checksum': '97',
        'verifies': True,
        'computed': '97',
        'corrected': None,
        'reason': None,
    },
    # Does not verify as printed.
    {
        'parameter': 'B017',
        'label': 'B017',
        'printed': '# _K_B017_0_0_0_0_0_0_0\\$95',
        'lines': (6608, 6608),
        'text': '# K B017 0 0 0 0 0 0 0',
        'checksum': '95',
        'verifies': False,
        'computed': '45',
        'corrected': '# K B017 0 0 0 0 0 0',
        'reason': "One ' 0' too many. Verifies as six single digits (errata 3.4).",
    },
    {
        'parameter': 'B018',
        'label': 'B018',
        'printed': '# _K_B018_0_0001000\\$B3',
        'lines': (6609, 6609),
        'text': '# K B018 0 0001000',
        'checksum': 'B3',
        'verifies': True,
        'computed': 'B3',
        'corrected': None,
        'reason': None,
    },
    {
        'parameter': 'B019',
        'label': 'B019',
        'printed': '# _K_B019_2_FF0000_00_00\\$B4',
        'lines': (6610, 6610),
        'text': '# K B019 2 FF0000 00 00',
        'checksum': 'B4',
        'verifies': True,
        'computed': 'B4',
        'corrected': None,
        'reason': None,
    },
    {
        'parameter': 'A100',
        'label': 'Ax00',
        'printed': '# _K_A100_1_0_0_0_0\\$EC',
        'lines': (6615, 6615),
        'text': '# K A100 1 0 0 0 0',
        'checksum': 'EC',
        'verifies': True,
        'computed': 'EC',
        'corrected': None,
        'reason': None,
    },
    {
        'parameter': 'A101',
        'label': 'Ax01',
        'printed': '# _K_A101_0010.00000\\$7D',
        'lines': (6616, 6616),
        'text': '# K A101 0010.00000',
        'checksum': '7D',
        'verifies': True,
        'computed': '7D',
        'corrected': None,
        'reason': None,
    },
    {
        'parameter': 'A102',
        'label': 'Ax02',
        'printed': '# _K_A102_0000_0000\\$BB',
        'lines': (6617, 6617),
        'text': '# K A102 0000 0000',
        'checksum': 'BB',
        'verifies': True,
        'computed': 'BB',
        'corrected': None,
        'reason': None,
        'note': (
            'Verifies with all-zero data although 0 is outside the input range of a used parameter: '
            'unused parameters are not range-checked (errata 3.4).'
        ),
    },
    {
        'parameter': 'A103',
        'label': 'Ax03',
        'printed': '# _K_A103_-111111.111\\$46',
        'lines': (6618, 6618),
        'text': '# K A103 -111111.111',
        'checksum': '46',
        'verifies': True,
        'computed': '46',
        'corrected': None,
        'reason': None,
    },
    {
        'parameter': 'A104',
        'label': 'Ax04',
        'printed': '# _K_A104_+100000.000\\$4F',
        'lines': (6619, 6619),
        'text': '# K A104 +100000.000',
        'checksum': '4F',
        'verifies': True,
        'computed': '4F',
        'corrected': None,
        'reason': None,
    },
    {
        'parameter': 'A105',
        'label': 'Ax05',
        'printed': '# _K_A105_000000.000_0\\$2A',
        'lines': (6620, 6620),
        'text': '# K A105 000000.000 0',
        'checksum': '2A',
        'verifies': True,
        'computed': '2A',
        'corrected': None,
        'reason': None,
    },
    {
        'parameter': 'A106',
        'label': 'Ax06',
        'printed': '# _K_A106_000100.000\\$78',
        'lines': (6621, 6621),
        'text': '# K A106 000100.000',
        'checksum': '78',
        'verifies': True,
        'computed': '78',
        'corrected': None,
        'reason': None,
    },
    {
        'parameter': 'A107',
        'label': 'Ax07',
        'printed': '# _K_A107_000100.000\\$77',
        'lines': (6622, 6622),
        'text': '# K A107 000100.000',
        'checksum': '77',
        'verifies': True,
        'computed': '77',
        'corrected': None,
        'reason': None,
    },
    {
        'parameter': 'A108',
        'label': 'Ax08',
        'printed': '# _K_A108_000010\\$35',
        'lines': (6623, 6623),
        'text': '# K A108 000010',
        'checksum': '35',
        'verifies': True,
        'computed': '35',
        'corrected': None,
        'reason': None,
    },
    {
        'parameter': 'A109',
        'label': 'Ax09',
        'printed': '# _K_A109_000_000\\$15',
        'lines': (6624, 6624),
        'text': '# K A109 000 000',
        'checksum': '15',
        'verifies': True,
        'computed': '15',
        'corrected': None,
        'reason': None,
    },
    {
        'parameter': 'A110',
        'label': 'Ax10',
        'printed': '# _K_A110_0.000\\$6F',
        'lines': (6625, 6625),
        'text': '# K A110 0.000',
        'checksum': '6F',
        'verifies': True,
        'computed': '6F',
        'corrected': None,
        'reason': None,
    },
    {
        'parameter': 'A111',
        'label': 'Ax11',
        'printed': '# _K_A111_01.00_0\\$1D',
        'lines': (6626, 6626),
        'text': '# K A111 01.00 0',
        'checksum': '1D',
        'verifies': True,
        'computed': '1D',
        'corrected': None,
        'reason': None,
    },
    {
        'parameter': 'A112',
        'label': 'Ax12',
        'printed': '# _K_A112_03000_10.0\\$88',
        'lines': (6627, 6627),
        'text': '# K A112 03000 10.0',
        'checksum': '88',
        'verifies': True,
        'computed': '88',
        'corrected': None,
        'reason': None,
    },
    {
        'parameter': 'A113',
        'label': 'Ax13',
        'printed': '# _K_A113_\\$5B',
        'lines': (6628, 6628),
        'text': '# K A113 ',
        'checksum': '5B',
        'verifies': True,
        'computed': '5B',
        'corrected': None,
        'reason': None,
        'note': "Reserved/empty parameter: the blank after the number is kept ('# K A113 $hh').",
    },
    {
        'parameter': 'A114',
        'label': 'Ax14',
        'printed': '# _K_A114_0_010_00.00.0\\$0B',
        'lines': (6629, 6629),
        'text': '# K A114 0 010 00.00.0',
        'checksum': '0B',
        'verifies': True,
        'computed': '0B',
        'corrected': None,
        'reason': None,
    },
    {
        'parameter': 'A115',
        'label': 'Ax15',
        'printed': '# _K_A115_00.00.0_00.00.0\\$9E',
        'lines': (6630, 6630),
        'text': '# K A115 00.00.0 00.00.0',
        'checksum': '9E',
        'verifies': True,
        'computed': '9E',
        'corrected': None,
        'reason': None,
    },
    {
        'parameter': 'A116',
        'label': 'Ax16',
        'printed': '# _K_A116_00_00_00.00.0\\$0A',
        'lines': (6631, 6631),
        'text': '# K A116 00 00 00.00.0',
        'checksum': '0A',
        'verifies': True,
        'computed': '0A',
        'corrected': None,
        'reason': None,
    },
    {
        'parameter': 'A117',
        'label': 'Ax17',
        'printed': '# _K_A117_0000.000\\$D7',
        'lines': (6632, 6632),
        'text': '# K A117 0000.000',
        'checksum': 'D7',
        'verifies': True,
        'computed': 'D7',
        'corrected': None,
        'reason': None,
    },
    {
        'parameter': 'A118',
        'label': 'Ax18',
        'printed': '# _K_A118_\\$56',
        'lines': (6633, 6633),
        'text': '# K A118 ',
        'checksum': '56',
        'verifies': True,
        'computed': '56',
        'corrected': None,
        'reason': None,
        'note': "Reserved/empty parameter: the blank after the number is kept ('# K A118 $hh').",
    },
    {
        'parameter': 'A119',
        'label': 'Ax19',
        'printed': '# _K_A119_01024_1024\\$75',
        'lines': (6634, 6634),
        'text': '# K A119 01024 1024',
        'checksum': '75',
        'verifies': True,
        'computed': '75',
        'corrected': None,
        'reason': None,
    },
    {
        'parameter': 'A120',
        'label': 'Ax20',
        'printed': '# _K_A120_0_0_00_1\\$0B',
        'lines': (6635, 6635),
        'text': '# K A120 0 0 00 1',
        'checksum': '0B',
        'verifies': True,
        'computed': '0B',
        'corrected': None,
        'reason': None,
    },
    {
        'parameter': 'A121',
        'label': 'Ax21',
        'printed': '# _K_A121_0_0_0\\$8B',
        'lines': (6636, 6636),
        'text': '# K A121 0 0 0',
        'checksum': '8B',
        'verifies': True,
        'computed': '8B',
        'corrected': None,
        'reason': None,
    },
    {
        'parameter': 'A122',
        'label': 'Ax22',
        'printed': '# _K_A122_00_+000000.000\\$CF',
        'lines': (6637, 6637),
        'text': '# K A122 00 +000000.000',
        'checksum': 'CF',
        'verifies': True,
        'computed': 'CF',
        'corrected': None,
        'reason': None,
    },
    # Does not verify as printed.
    {
        'parameter': 'A123',
        'label': 'Ax23',
        'printed': '# _K_A123_ 1.00.0_ 1.00.1\\$6A',
        'lines': (6638, 6638),
        'text': '# K A123 1.00.0 1.00.1',
        'checksum': '6A',
        'verifies': False,
        'computed': 'FC',
        'corrected': '# K A123 I1.00.0 I1.00.1',
        'reason': (
            "The 'I' of both input addresses was lost in the source (printed as a literal space). "
            "Restoring 'I1.00.0 I1.00.1' adds 2 x 0x29 and verifies (errata 3.4). No blank-only "
            'change can fix it.'
        ),
    },
    {
        'parameter': 'A124',
        'label': 'Ax24',
        'printed': '# _K_A124_Q1.00.0_-100_0\\$BA',
        'lines': (6639, 6639),
        'text': '# K A124 Q1.00.0 -100 0',
        'checksum': 'BA',
        'verifies': True,
        'computed': 'BA',
        'corrected': None,
        'reason': None,
    },
    {
        'parameter': 'A125',
        'label': 'Ax25',
        'printed': '# _K_A125_-00000.000\\$7B',
        'lines': (6640, 6640),
        'text': '# K A125 -00000.000',
        'checksum': '7B',
        'verifies': True,
        'computed': '7B',
        'corrected': None,
        'reason': None,
    },
    {
        'parameter': 'A126',
        'label': 'Ax26',
        'printed': '# _K_A126_\\$57',
        'lines': (6641, 6641),
        'text': '# K A126 ',
        'checksum': '57',
        'verifies': True,
        'computed': '57',
        'corrected': None,
        'reason': None,
        'note': "Reserved/empty parameter: the blank after the number is kept ('# K A126 $hh').",
    },
    {
        'parameter': 'A127',
        'label': 'Ax27',
        'printed': '# _K_A127_Q1.00.2_0010.000\\$44',
        'lines': (6642, 6642),
        'text': '# K A127 Q1.00.2 0010.000',
        'checksum': '44',
        'verifies': True,
        'computed': '44',
        'corrected': None,
        'reason': None,
    },
    {
        'parameter': 'A128',
        'label': 'Ax28',
        'printed': '# _K_A128_00.00.0_0000.000\\$68',
        'lines': (6643, 6643),
        'text': '# K A128 00.00.0 0000.000',
        'checksum': '68',
        'verifies': True,
        'computed': '68',
        'corrected': None,
        'reason': None,
    },
    {
        'parameter': 'A129',
        'label': 'Ax29',
        'printed': '# _K_A129_00.00.0_1.0_0000\\$76',
        'lines': (6644, 6644),
        'text': '# K A129 00.00.0 1.0 0000',
        'checksum': '76',
        'verifies': True,
        'computed': '76',
        'corrected': None,
        'reason': None,
    },
    {
        'parameter': 'A130',
        'label': 'Ax30',
        'printed': '# _K_A130_00.00.0_00.00.0\\$A1',
        'lines': (6645, 6645),
        'text': '# K A130 00.00.0 00.00.0',
        'checksum': 'A1',
        'verifies': True,
        'computed': 'A1',
        'corrected': None,
        'reason': None,
    },
    {
        'parameter': 'A131',
        'label': 'Ax31',
        'printed': '# _K_A131_00.00.0\\$0E',
        'lines': (6646, 6646),
        'text': '# K A131 00.00.0',
        'checksum': '0E',
        'verifies': True,
        'computed': '0E',
        'corrected': None,
        'reason': None,
    },
    {
        'parameter': 'A132',
        'label': 'Ax32',
        'printed': '# _K_A132_00.00.0_00.00.0\\$9F',
        'lines': (6647, 6647),
        'text': '# K A132 00.00.0 00.00.0',
        'checksum': '9F',
        'verifies': True,
        'computed': '9F',
        'corrected': None,
        'reason': None,
    },
    {
        'parameter': 'A133',
        'label': 'Ax33',
        'printed': '# _K_A133_00.00.0_00.00.0\\$9E',
        'lines': (6648, 6648),
        'text': '# K A133 00.00.0 00.00.0',
        'checksum': '9E',
        'verifies': True,
        'computed': '9E',
        'corrected': None,
        'reason': None,
    },
    {
        'parameter': 'A134',
        'label': 'Ax34',
        'printed': '# _K_A134_00.00.0_0100_0\\$D8',
        'lines': (6649, 6649),
        'text': '# K A134 00.00.0 0100 0',
        'checksum': 'D8',
        'verifies': True,
        'computed': 'D8',
        'corrected': None,
        'reason': None,
    },
    {
        'parameter': 'A135',
        'label': 'Ax35',
        'printed': '# _K_A135_00.00.0_00000\\$F8',
        'lines': (6650, 6650),
        'text': '# K A135 00.00.0 00000',
        'checksum': 'F8',
        'verifies': True,
        'computed': 'F8',
        'corrected': None,
        'reason': None,
    },
    {
        'parameter': 'A136',
        'label': 'Ax36',
        'printed': '# _K_A136_00.00.0_0000\\$28',
        'lines': (6651, 6651),
        'text': '# K A136 00.00.0 0000',
        'checksum': '28',
        'verifies': True,
        'computed': '28',
        'corrected': None,
        'reason': None,
    },
    {
        'parameter': 'A137',
        'label': 'Ax37',
        'printed': '# _K_A137_00000_0000\\$83',
        'lines': (6652, 6652),
        'text': '# K A137 00000 0000',
        'checksum': '83',
        'verifies': True,
        'computed': '83',
        'corrected': None,
        'reason': None,
    },
    {
        'parameter': 'A138',
        'label': 'Ax38',
        'printed': '# _K_A138_00.00.0_0_0\\$66',
        'lines': (6653, 6653),
        'text': '# K A138 00.00.0 0 0',
        'checksum': '66',
        'verifies': True,
        'computed': '66',
        'corrected': None,
        'reason': None,
    },
    {
        'parameter': 'A139',
        'label': 'Ax39',
        'printed': '# _K_A139_00.00.0_00.00.0\\$98',
        'lines': (6654, 6654),
        'text': '# K A139 00.00.0 00.00.0',
        'checksum': '98',
        'verifies': True,
        'computed': '98',
        'corrected': None,
        'reason': None,
    },
    {
        'parameter': 'A140',
        'label': 'Ax40',
        'printed': '# _K_A140_0.00_000_000\\$3B',
        'lines': (6655, 6655),
        'text': '# K A140 0.00 000 000',
        'checksum': '3B',
        'verifies': True,
        'computed': '3B',
        'corrected': None,
        'reason': None,
    },
    {
        'parameter': 'A141',
        'label': 'Ax41',
        'printed': '# _K_A141_00.00\\$6B',
        'lines': (6656, 6656),
        'text': '# K A141 00.00',
        'checksum': '6B',
        'verifies': True,
        'computed': '6B',
        'corrected': None,
        'reason': None,
    },
    {
        'parameter': 'A142',
        'label': 'Ax42',
        'printed': '# _K_A142_0000.00_00.00.0\\$9C',
        'lines': (6657, 6657),
        'text': '# K A142 0000.00 00.00.0',
        'checksum': '9C',
        'verifies': True,
        'computed': '9C',
        'corrected': None,
        'reason': None,
    },
    {
        'parameter': 'C000',
        'label': 'C000',
        'printed': '# _K_C000_01250_0000\\$84',
        'lines': (6662, 6662),
        'text': '# K C000 01250 0000',
        'checksum': '84',
        'verifies': True,
        'computed': '84',
        'corrected': None,
        'reason': None,
    },
    {
        'parameter': 'C001',
        'label': 'C001',
        'printed': '# _K_C001_0_0_00_0_0_0\\$6B',
        'lines': (6663, 6663),
        'text': '# K C001 0 0 00 0 0 0',
        'checksum': '6B',
        'verifies': True,
        'computed': '6B',
        'corrected': None,
        'reason': None,
    },
    {
        'parameter': 'C002',
        'label': 'C002',
        'printed': '# _K_C002_0020.00000\\$7A',
        'lines': (6664, 6664),
        'text': '# K C002 0020.00000',
        'checksum': '7A',
        'verifies': True,
        'computed': '7A',
        'corrected': None,
        'reason': None,
    },
    {
        'parameter': 'C003',
        'label': 'C003',
        'printed': '# _K_C003_+00000.000\\$80',
        'lines': (6665, 6665),
        'text': '# K C003 +00000.000',
        'checksum': '80',
        'verifies': True,
        'computed': '80',
        'corrected': None,
        'reason': None,
    },
    {
        'parameter': 'C004',
        'label': 'C004',
        'printed': '# _K_C004_01250_0000\\$80',
        'lines': (6666, 6666),
        'text': '# K C004 01250 0000',
        'checksum': '80',
        'verifies': True,
        'computed': '80',
        'corrected': None,
        'reason': None,
    },
    {
        'parameter': 'C005',
        'label': 'C005',
        'printed': '# _K_C005_0_0_00_0_0_0\\$67',
        'lines': (6667, 6667),
        'text': '# K C005 0 0 00 0 0 0',
        'checksum': '67',
        'verifies': True,
        'computed': '67',
        'corrected': None,
        'reason': None,
    },
    {
        'parameter': 'C006',
        'label': 'C006',
        'printed': '# _K_C006_0000.00000\\$78',
        'lines': (6668, 6668),
        'text': '# K C006 0000.00000',
        'checksum': '78',
        'verifies': True,
        'computed': '78',
        'corrected': None,
        'reason': None,
        'note': (
            'Verifies with all-zero data although 0 is outside the input range of a used parameter: '
            'unused parameters are not range-checked (errata 3.4).'
        ),
    },
    {
        'parameter': 'C007',
        'label': 'C007',
        'printed': '# _K_C007_+00000.000\\$7C',
        'lines': (6669, 6669),
        'text': '# K C007 +00000.000',
        'checksum': '7C',
        'verifies': True,
        'computed': '7C',
        'corrected': None,
        'reason': None,
    },
    {
        'parameter': 'C008',
        'label': 'C008',
        'printed': '# _K_C008_00.00.0_000\\$58',
        'lines': (6670, 6670),
        'text': '# K C008 00.00.0 000',
        'checksum': '58',
        'verifies': True,
        'computed': '58',
        'corrected': None,
        'reason': None,
    },
]


# Profibus service-channel ASCII (Figs. 10-18..10-31): the bytes as printed, decoded.
PROFIBUS_ASCII = [
    {
        'name': 'read_request_n0000',
        'lines': (7863, 7864),
        'bytes_hex': '3F 20 4E 30 30 30 30 20',
        'text': '? N0000 ',
        'note': (
            "Fig. 10-18 master write request, length 8: '? N0000 ' with a trailing blank. L7792 "
            "prints it as '? N0000'."
        ),
    },
    {
        'name': 'read_response_nop',
        'lines': (7888, 7906),
        'bytes_hex': '23 20 4E 30 30 30 30 20 4E 4F 50 20 20 20',
        'text': '# N0000 NOP   ',
        'note': (
            "Figs. 10-21/10-23: 14 bytes in fragments of 10 + 4: '# N0000 NOP' + THREE blanks. The "
            "read-back of a NOP instruction is '#' + station + 'N' + number + ' NOP   '."
        ),
    },
    {
        'name': 'write_request_nop',
        'lines': (7914, 7938),
        'bytes_hex': '23 20 4E 30 30 30 30 20 4E 4F 50 20',
        'text': '# N0000 NOP ',
        'note': (
            "Figs. 10-24/10-26: 12 bytes (10 + 2): '# N0000 NOP ' with ONE trailing blank (the glyph "
            "row prints the blank as '-'); L7914 prints '# N0000 NOP'. Same string as a serial "
            "program telegram without '$hh'."
        ),
    },
    {
        'name': 'confirmation_y',
        'lines': (7955, 7956),
        'bytes_hex': '59 20',
        'text': 'Y ',
        'note': "Fig. 10-28: transmission confirmation 'Y ' (the serial form is 'Y CR LF').",
    },
    {
        'name': 'read_request_n3000',
        'lines': (7996, 7997),
        'bytes_hex': '3F 20 4E 33 30 30 30 20',
        'text': '? N3000 ',
        'note': 'Fig. 10-31: request for instruction 3000 (> 2999) -> serial error 12.',
    },
    {
        'name': 'error_code_010c',
        'lines': (7998, 7999),
        'bytes_hex': '01 0C',
        'text': None,
        'note': (
            "Error word 0x010C = 0x01nn with nn = serial-interface error 12 DECIMAL ('Block # too "
            "large', L6818), written in hex: Status 01 numbers are decimal."
        ),
    },
    # Byte 2C printed under a '#' glyph.
    {
        'name': 'error_plain_text',
        'lines': (8001, 8008),
        'bytes_hex': '58 20 30 31 20 31 32 20 42 6C 6F 63 6B 20 2C 20 74 6F 6F 20 6C 61 72 67 65',
        'text': 'X 01 12 Block , too large',
        'text_glyphs': 'X 01 12 Block # too large',
        'note': (
            "25 bytes in 10 + 10 + 5. The byte under the '#' glyph is printed 2C (','): the bytes "
            "give 'X 01 12 Block , too large', the glyph row and L6818 give 'Block # too large'. 42 "
            "6C is 'Bl' (glyph row shows 'BI'). Unpadded, unlike the 20-char Status 01 text (errata "
            '1.12).'
        ),
    },
]


# Telegram formats and replies printed with placeholders only (no hex checksum value); 's' = station.
# ``printed`` is verbatim without code fences/backticks.
TELEGRAM_FORMATS = [
    {
        'printed': 'Xs63_WAIT_FOR_ _ _ _ _ _ FEED_ANGLE_ _ _ _ _ $ h h CR LF',
        'lines': (2768, 2768),
        'kind': 'status reply',
        'note': (
            "TXT example, Status 63: blanks collapsed/spaced ('_ _ _'); each TXT row contributes 16 "
            'characters.'
        ),
    },
    {
        'printed': '? s X _ 5 3 _ CR LF',
        'lines': (2791, 2791),
        'kind': 'status query',
        'note': "Spaced glyphs; ONE blank after 'X' ('?sX_53_'), see errata 1.6.",
    },
    {
        'printed': 'Xs53_00_STOP_PRESENT_ _ _ _ _ $hh CR LF',
        'lines': (2795, 2795),
        'kind': 'status reply',
        'note': 'TXT mode 1 text in Status 53 after error number 00.',
    },
    {
        'printed': '? s X _ 6 3 _ 1 2 _ CR LF',
        'lines': (2801, 2801),
        'kind': 'status query',
        'note': "'?sX_63_12_': lines 1 to 2, one blank after 'X'.",
    },
    {
        'printed': 'Xs63_WAIT_FOR_ _ _ _ _ _ FEED_ANGLE_ _ _ _ _ $ h h CR LF',
        'lines': (2805, 2805),
        'kind': 'status reply',
    },
    {
        'printed': '!_CLL2',
        'lines': (3990, 3990),
        'kind': 'interface command (in text)',
    },
    {
        'printed': '!_CLL1',
        'lines': (3994, 3994),
        'kind': 'interface command (in text)',
    },
    {
        'printed': '!_CLLVAR0019',
        'lines': (4033, 4033),
        'kind': 'interface command (in text)',
        'note': "'CLLVAR' here vs 'CCLVAR0019' in L7368.",
    },
    {
        'printed': '!_CLO',
        'lines': (4962, 4962),
        'kind': 'interface command (in text)',
        'note': "Letter O, while L7376 prints '!sCL0_' with digit zero.",
    },
    {
        'printed': '?AN0000CR LF',
        'lines': (6292, 6292),
        'kind': 'query',
        'note': "RS485 station 10 = 'A'; no blank before CR LF and no checksum.",
    },
    {
        'printed': '#AN0000_Instruction Contents CR LF',
        'lines': (6298, 6298),
        'kind': 'reply',
        'note': "Program read-back starts with '#'.",
    },
    {
        'printed': '#sNbbbb_ccc_ddddddddddddddddddd_$hh CR LF',
        'lines': (6533, 6533),
        'kind': 'program write',
        'note': 'Data field up to 32 characters (L6541).',
    },
    {
        'printed': '#_N0100_POI_1_+12345.786_123_$hh CR LF',
        'lines': (6546, 6546),
        'kind': 'program write',
        'note': (
            "'+12345.786' has five integer digits, unlike the \u00b16.3 POI field ('+123456.789' in Fig. "
            '9-12); no checksum printed.'
        ),
    },
    {
        'printed': '#sK_xxyy_dddddddddddddddd_$hh CR LF',
        'lines': (6578, 6578),
        'kind': 'parameter write',
        'note': (
            "Data up to 16 characters. The samples (PARAMETER_SAMPLES) have NO blank before '$', "
            'unlike this format line.'
        ),
    },
    {
        'printed': '?sVxxx CR LF',
        'lines': (6681, 6681),
        'kind': 'variable query',
    },
    {
        'printed': 'Vsxxx_+12345678.123456_$hh CR LF',
        'lines': (6687, 6687),
        'kind': 'variable reply',
        'note': 'Variable format +8.6.',
    },
    {
        'printed': '#sVxxx_+ddddddd.ddddddd_$hh CR LF',
        'lines': (6698, 6698),
        'kind': 'variable write',
        'note': (
            "Printed '+ddddddd.ddddddd' (7.7 digits) although variables are +8.6 (L1293): digit "
            'counts are sloppy.'
        ),
    },
    {
        'printed': '?sP_xxxx CR LF',
        'lines': (6712, 6712),
        'kind': 'logic task query',
        'note': "Blank between 'P' and the number (unlike '?sVxxx').",
    },
    {
        'printed': 'Psxxxx_dddddddd_$hh CR LF',
        'lines': (6718, 6718),
        'kind': 'logic task reply',
    },
    {
        'printed': '#sPx xx_x_d d d d d d d d_$h h C R L F',
        'lines': (6729, 6729),
        'kind': 'logic task write',
        'note': "Garbled: '#sPx xx_x_d d d d d d d d_$h h C R L F' (spaced glyphs).",
    },
    {
        'printed': '?sX__00_ CR LF',
        'lines': (6772, 6772),
        'kind': 'status query',
        'note': "Two blanks after 'X' ('?sX__00_'); the TXT examples L2791/L2801 use one.",
    },
    {
        'printed': 'Xs00_evmmmmm.mmm_evnnnnnn.nnn_$hh CR LF',
        'lines': (6778, 6778),
        'kind': 'status reply',
    },
    {
        'printed': 'Xs01_ff_tttttttttttttttttt_$hh CR LF',
        'lines': (6796, 6796),
        'kind': 'status reply',
        'note': (
            "Status 01 is sent unsolicited; text 'always 20 characters' (L6802) but only 18 't' are "
            'printed.'
        ),
    },
    {
        'printed': '?sX__02_ CR LF',
        'lines': (6830, 6830),
        'kind': 'status query',
    },
    {
        'printed': 'Xs02_nnnn_uuuu_$hh CR LF',
        'lines': (6836, 6836),
        'kind': 'status reply',
    },
    {
        'printed': '?sX__03_ CR LF',
        'lines': (6849, 6849),
        'kind': 'status query',
    },
    {
        'printed': 'Xs03_000C14FA_000A39CD_$$$$$$ $hh CR LF',
        'lines': (6855, 6855),
        'kind': 'status reply',
        'note': "Printed '_$$$$$$ $hh': '$' runs are extraction noise for blanks/placeholders.",
    },
    {
        'printed': '?sX__04_nnnn_CR LF',
        'lines': (6896, 6896),
        'kind': 'status query',
        'note': 'Query carries the counter instruction number nnnn.',
    },
    {
        'printed': 'Xs04_nnnn_iiii_zzzzzz_____ $hh CR LF',
        'lines': (6900, 6900),
        'kind': 'status reply',
        'note': (
            '4-digit actual count although COU targets have 6 digits (errata 1.11); blank before '
            "'$hh'."
        ),
    },
    {
        'printed': '?sX__05_CR LF',
        'lines': (6914, 6914),
        'kind': 'status query',
    },
    {
        'printed': 'Xs05__vvvvvvvvvvvvvvvvvvvv_ $hh CR LF',
        'lines': (6918, 6918),
        'kind': 'status reply',
        'note': "Two blanks after '05' and a blank before '$hh'.",
    },
    {
        'printed': '?sX__08_CR LF',
        'lines': (6929, 6929),
        'kind': 'status query',
    },
    {
        'printed': 'Xs08_aaaa_bbbb_cccc_dddd_eeee_fff_$hh CR LF',
        'lines': (6935, 6935),
        'kind': 'status reply',
    },
    {
        'printed': '?sX__09_CR LF',
        'lines': (6956, 6956),
        'kind': 'status query',
    },
    {
        'printed': 'Xs09__evmmmmm.mmm_vnnnnnn.nnn_$hh CR LF',
        'lines': (6962, 6962),
        'kind': 'status reply',
        'note': "Two blanks after '09'.",
    },
    {
        'printed': '?sX__10_CR LF',
        'lines': (6980, 6980),
        'kind': 'status query',
    },
    {
        'printed': 'Xs10_vmmmmm.mmm_vnnnnnn.nnn_$hh CR LF',
        'lines': (6986, 6986),
        'kind': 'status reply',
    },
    {
        'printed': '?sX__19_CR LF',
        'lines': (7000, 7000),
        'kind': 'status query',
    },
    {
        'printed': 'Xs19_CLM01.4-P-E-4-BCLM1.4-LAP-01V08$hh CR LF',
        'lines': (7006, 7006),
        'kind': 'status reply',
        'note': "Concrete example reply (hardware + firmware version) but checksum only as 'hh'.",
    },
    {
        'printed': '?sX__39_CR LF',
        'lines': (7024, 7024),
        'kind': 'status query',
    },
    {
        'printed': 'Xs39_aaaa_bbbb_cccc_dddd_$hh CR LF',
        'lines': (7030, 7030),
        'kind': 'status reply',
    },
    {
        'printed': '?sX__40_ CR LF',
        'lines': (7049, 7049),
        'kind': 'status query',
    },
    {
        'printed': 'Xs40_000C14FA_000A39CD_$$$$$hh CR LF',
        'lines': (7055, 7055),
        'kind': 'status reply',
        'note': "Printed '_$$$$$hh'.",
    },
    {
        'printed': '?sX__41_ CR LF',
        'lines': (7071, 7071),
        'kind': 'status query',
    },
    {
        'printed': 'Xs41_evmmmmm.mmm_$$$$$hh CR LF',
        'lines': (7077, 7077),
        'kind': 'status reply',
        'note': "Printed '_$$$$$hh'.",
    },
    {
        'printed': '?sX__42_CR LF',
        'lines': (7102, 7102),
        'kind': 'status query',
    },
    {
        'printed': 'Xs42_1_+1234.56_1_+1234.56_$hh CR LF',
        'lines': (7108, 7108),
        'kind': 'status reply',
    },
    {
        'printed': '?sX__43_CR LF',
        'lines': (7120, 7120),
        'kind': 'status query',
    },
    {
        'printed': 'Xs43_vmmmmm.mmm_vnnnnnn.nnn_$hh CR LF',
        'lines': (7126, 7126),
        'kind': 'status reply',
    },
    {
        'printed': '?sX__44_CR LF',
        'lines': (7140, 7140),
        'kind': 'status query',
    },
    {
        'printed': 'Xs44_evmmmmm.mmm_evnnnnnn.nnn_$hh CR LF',
        'lines': (7146, 7146),
        'kind': 'status reply',
    },
    {
        'printed': '?sX__45_CR LF',
        'lines': (7162, 7162),
        'kind': 'status query',
    },
    {
        'printed': 'Xs45_+12345_+12345_$hh CR LF',
        'lines': (7168, 7168),
        'kind': 'status reply',
    },
    {
        'printed': '?sX__47_CR LF',
        'lines': (7180, 7180),
        'kind': 'status query',
    },
    {
        'printed': 'Xs47_0_+1234.56_$hh CR LF',
        'lines': (7186, 7186),
        'kind': 'status reply',
    },
    {
        'printed': '?sX__48_CR LF',
        'lines': (7200, 7200),
        'kind': 'status query',
    },
    {
        'printed': 'Xs48_1_+1234.56_1_+1234.56_$hh CR LF',
        'lines': (7206, 7206),
        'kind': 'status reply',
    },
    {
        'printed': '?sX__49_CR LF',
        'lines': (7218, 7218),
        'kind': 'status query',
    },
    {
        'printed': 'Xs49_+12345_+12345_$hh CR LF',
        'lines': (7224, 7224),
        'kind': 'status reply',
    },
    {
        'printed': '?sX__53_CR LF',
        'lines': (7236, 7236),
        'kind': 'status query',
    },
    {
        'printed': 'Xs53_nn_tttttttttttttt_$hh CR LF',
        'lines': (7242, 7242),
        'kind': 'status reply',
    },
    {
        'printed': '?sX__54_ CR LF',
        'lines': (7256, 7256),
        'kind': 'status query',
    },
    {
        'printed': 'Xs54_vmmmmmmmm_vpppppppp_$hh CR LF',
        'lines': (7262, 7262),
        'kind': 'status reply',
    },
    {
        'printed': '?sX__60_a_ CR LF',
        'lines': (7278, 7278),
        'kind': 'status query',
    },
    {
        'printed': 'Xs60_a_nnnn_$hh CR LF',
        'lines': (7284, 7284),
        'kind': 'status reply',
    },
    {
        'printed': '?sX__61_mt.nn_ CR LF',
        'lines': (7301, 7301),
        'kind': 'status query',
    },
    {
        'printed': 'Xs61_mt.nn_bbbbbbbb_$hh CR LF',
        'lines': (7307, 7307),
        'kind': 'status reply',
    },
    {
        'printed': '?sX__63_vb_ CR LF',
        'lines': (7322, 7322),
        'kind': 'status query',
    },
    {
        'printed': 'Xs63_tttttttt. . . tttttttt_$hh CR LF',
        'lines': (7328, 7328),
        'kind': 'status reply',
    },
    {
        'printed': '!sSTART_$$hh CR LF',
        'lines': (7344, 7344),
        'kind': 'interface command',
        'note': "Printed with a doubled '$$hh' (presumably '$hh').",
    },
    {
        'printed': '!sSTOP_$$hh CR LF',
        'lines': (7352, 7352),
        'kind': 'interface command',
        'note': "Printed with a doubled '$$hh' (presumably '$hh').",
    },
    {
        'printed': '!sCLEAR_$$hh CR LF',
        'lines': (7360, 7360),
        'kind': 'interface command',
        'note': "Printed with a doubled '$$hh' (presumably '$hh').",
    },
    {
        'printed': '!sCCLVAR0019$$hh CR LF',
        'lines': (7368, 7368),
        'kind': 'interface command',
        'note': "Printed with a doubled '$$hh' (presumably '$hh').",
    },
    {
        'printed': '!sCL0_$$hh CR LF',
        'lines': (7376, 7376),
        'kind': 'interface command',
        'note': "Printed with a doubled '$$hh' (presumably '$hh').",
    },
    {
        'printed': '!sCLL1_$$hh CR LF',
        'lines': (7384, 7384),
        'kind': 'interface command',
        'note': "Printed with a doubled '$$hh' (presumably '$hh').",
    },
    {
        'printed': '!sCLL2_$$hh CR LF',
        'lines': (7392, 7392),
        'kind': 'interface command',
        'note': "Printed with a doubled '$$hh' (presumably '$hh').",
    },
    {
        'printed': '!sMxON_$hh CR LF',
        'lines': (7405, 7405),
        'kind': 'interface command',
    },
    {
        'printed': '!sMxOFF_$hh CR LF',
        'lines': (7409, 7409),
        'kind': 'interface command',
    },
    {
        'printed': '!sCSETPA_$hh CR LF',
        'lines': (7424, 7424),
        'kind': 'interface command',
    },
    {
        'printed': '!sCNOPNC$hh CR LF',
        'lines': (7430, 7430),
        'kind': 'interface command',
    },
    {
        'printed': '!sCNOPNCvvvvbbbb_$hh CR LF',
        'lines': (7434, 7434),
        'kind': 'interface command',
    },
    {
        'printed': '!sCNOPLT$hh CR LF',
        'lines': (7447, 7447),
        'kind': 'interface command',
    },
    {
        'printed': '!sCNOPLTvvvvbbbb_$hh CR LF',
        'lines': (7455, 7455),
        'kind': 'interface command',
    },
    {
        'printed': '!sCCLVAR$hh CR LF',
        'lines': (7469, 7469),
        'kind': 'interface command',
    },
    {
        'printed': '!sCCLVARvvvvbbbb_$hh CR LF',
        'lines': (7475, 7475),
        'kind': 'interface command',
    },
    {
        'printed': ':s CR LF',
        'lines': (7491, 7491),
        'kind': 'polling query',
    },
    {
        'printed': ':snn CR LF',
        'lines': (7497, 7497),
        'kind': 'polling reply',
        'note': 'nn = fault code in HEX (B018 list).',
    },
    {
        'printed': '!sMxOFF_\\$hhCrLf',
        'lines': (8935, 8935),
        'kind': 'interface command (in text)',
    },
]


# Fig. 9-13 'data formats' for program telegrams (only ACC..CPS survive in the source). Verbatim,
# '_' = blank. No checksum, so their blank counts are NOT verified. Compare the verified BPA telegram
# L6548, which needs 6 blanks where 5 are printed: the 5-blank BPA form here (L6564) has probably
# lost one too. The BCE form's 4 blanks after I1.00.3 put the state digit in the same column as the
# 6-blank BPA mask.
PROGRAM_DATA_FORMATS = [
    {
        'command': 'ACC',
        'constant_form': 'ACC_1____234_567_',
        'variable_form': 'ACC_V602_V600_V601_',
        'lines': (6554, 6554),
    },
    {
        'command': 'AEA',
        'constant_form': 'AEA_Q1.01.1_1_',
        'variable_form': 'AEA_Q1.01.0_V600_',
        'lines': (6555, 6555),
    },
    {
        'command': 'AEO',
        'constant_form': 'AEO_1____1_1_500____100_',
        'variable_form': 'AEO_V600_1_1_V601_V602_',
        'lines': (6556, 6556),
    },
    {
        'command': 'AKN',
        'constant_form': 'AKN_M2.02.3_1_',
        'variable_form': 'AKN_M2.02.3_V600_',
        'lines': (6557, 6557),
    },
    {
        'command': 'AKP',
        'constant_form': 'AKP_M2.02_01201201_',
        'variable_form': 'AKP_M2.02_01201201_',
        'lines': (6558, 6558),
    },
    {
        'command': 'APE',
        'constant_form': 'APE_Q1.01_01201201_',
        'variable_form': 'APE_Q1.01_01201201_',
        'lines': (6559, 6559),
    },
    {
        'command': 'BAC',
        'constant_form': 'BAC_1234_-5678_98765_',
        'variable_form': 'BAC_V600_-5678_V601_',
        'lines': (6560, 6560),
    },
    {
        'command': 'BCE',
        'constant_form': 'BCE_0234_I1.00.3____1_',
        'variable_form': 'BCE_V601_I1.01.3____V600_',
        'lines': (6561, 6561),
    },
    {
        'command': 'BIC',
        'constant_form': 'BIC_0234_56_____M0.12.3_0_1_',
        'variable_form': 'BIC_V601_V600_____M0.12.3_0_1_',
        'lines': (6562, 6562),
    },
    {
        'command': 'BIO',
        'constant_form': 'BIO_0234_M2.03_Q0.00_01201201_',
        'variable_form': 'BIO_V600_M2.03_Q0.01_01201201_',
        'lines': (6563, 6563),
    },
    {
        'command': 'BPA',
        'constant_form': 'BPA_0234_M2.02_____01201201_',
        'variable_form': 'BPA_V600_M2.02_____01201201_',
        'lines': (6564, 6564),
    },
    {
        'command': 'CID',
        'constant_form': 'CID_V600_1_____+12345.678_',
        'variable_form': 'CID_V600_1_____+V601_',
        'lines': (6565, 6565),
    },
    {
        'command': 'CIO',
        'constant_form': 'CIO_M2.02.3_Q1.01.1_08_',
        'variable_form': 'CIO_M2.02.3_Q1.01.1_V600_',
        'lines': (6566, 6566),
    },
    {
        'command': 'CLC',
        'constant_form': 'CLC_0234_',
        'variable_form': 'CLC_V600_',
        'lines': (6567, 6567),
    },
    {
        'command': 'CON',
        'constant_form': 'CON_1____1____+234_',
        'variable_form': 'CON_V602_V600_+V601_',
        'lines': (6568, 6568),
    },
    {
        'command': 'COU',
        'constant_form': 'COU_+12345_Q1.01.1_654321_',
        'variable_form': 'COU_+12345_Q1.01.1_V600_',
        'lines': (6569, 6569),
    },
    {
        'command': 'CPJ',
        'constant_form': 'CPJ_V600>=+12345.678_1234.56_1234_',
        'variable_form': 'CPJ_V604_>=+V600_____V601____V603_',
        'lines': (6570, 6570),
    },
    {
        'command': 'CPL',
        'constant_form': 'CPL_1_',
        'variable_form': 'CPL_V600_',
        'lines': (6571, 6571),
    },
    {
        'command': 'CPS',
        'constant_form': 'CPS_V602<=+12345.678_1234.56_Q1.01.1_',
        'variable_form': 'CPS_V602_<+V600_____V601____Q1.01.1_',
        'lines': (6572, 6572),
    },
]


# Unnumbered instruction examples at the command headings of section 5.7 (the 'with variables' /
# 'with constants' pairs, L1193). Verbatim, including leading blanks. Many headings' syntax lines were
# lost (ACC, AEA, AEO, BAC, BCE, BPA, CID, CON, COU, CPL, CPS, FAK, FOL, FUN, LMK, MLO, MLT, PSI, REP,
# RMI, SRM, SRP, VCC).
SYNTAX_EXAMPLES = [
    {
        'lines': (1472, 1472),
        'text': 'AKN M2.02.2 V600 or',
    },
    {
        'lines': (1473, 1473),
        'text': ' AKN M2.02.2 1',
    },
    {
        'lines': (1506, 1506),
        'text': 'APE M2.02 21022001',
    },
    {
        'lines': (1628, 1628),
        'text': 'BIO V600 M2.02 Q1.06 01201201 or',
    },
    {
        'lines': (1629, 1629),
        'text': ' BIO 0123 M2.02 Q1.06 01201201',
    },
    {
        'lines': (1677, 1677),
        'text': 'CIO M2.02.3 Q1.01.3 V123 or',
    },
    {
        'lines': (1678, 1678),
        'text': ' CIO M2.02.3 Q1.01.3 07',
    },
    {
        'lines': (1704, 1704),
        'text': 'CLC V661 or',
    },
    {
        'lines': (1705, 1705),
        'text': ' CLC 0123',
    },
    {
        'lines': (1786, 1786),
        'text': 'Example: CPJ V600 >= +V601 0000.00 0400',
        'note': (
            'Worked: V600 = 100.000, V601 = 090.000 -> jumps to 0400 (L1788-1792). Blank-separated '
            "operator here; Fig. 9-13 writes 'CPJ_V600>=+12345.678_...' with no blank before '>='."
        ),
    },
    {
        'lines': (1820, 1820),
        'text': 'CST 1 1',
        'note': "CST t l: '1 1' = task 1, correct the stack by 1 level.",
    },
    {
        'lines': (1846, 1846),
        'text': 'CVT V601 M2.02 1 1',
    },
    {
        'lines': (1869, 1869),
        'text': 'CVT V600 M2.00 0 0',
        'note': (
            'Worked: V600 = -87654321.654321 -> M2.00..M2.07 = 21 43 65 21 43 65 87 FF (hex), see '
            'OTHER_NUMERIC_EXAMPLES.'
        ),
    },
    {
        'lines': (1907, 1907),
        'text': 'EOS',
    },
    {
        'lines': (1999, 1999),
        'text': 'HOM V600 or',
    },
    {
        'lines': (2000, 2000),
        'text': ' HOM 1',
        'note': "Followed by box-drawing rows L2001-2002 ('Axes 1 to 4').",
    },
    {
        'lines': (2030, 2030),
        'text': 'JMP V601 or',
    },
    {
        'lines': (2031, 2031),
        'text': 'JMP 0123',
    },
    {
        'lines': (2047, 2047),
        'text': 'JSR V601 or',
    },
    {
        'lines': (2048, 2048),
        'text': 'JSR 0123',
    },
    {
        'lines': (2066, 2066),
        'text': 'JST V611 or',
    },
    {
        'lines': (2067, 2067),
        'text': 'JST 0123',
    },
    {
        'lines': (2085, 2085),
        'text': 'JTK V611 1 or',
    },
    {
        'lines': (2086, 2086),
        'text': 'JTK 0123 1',
    },
    {
        'lines': (2097, 2097),
        'text': 'JTK_0100_2',
        'note': "Serial-style ('_' = blank), in Task 1: Task 2 continues at 0100.",
    },
    {
        'lines': (2099, 2099),
        'text': 'JTK_0100_1',
        'note': "Same as 'JMP_0100' (L2099) when in Task 1.",
    },
    {
        'lines': (2099, 2099),
        'text': 'JMP_0100',
    },
    {
        'lines': (2121, 2121),
        'text': 'LML V601 V600 or',
    },
    {
        'lines': (2122, 2122),
        'text': 'LML 1 123456.789',
        'note': 'LML length is unsigned 6.3.',
    },
    {
        'lines': (2175, 2175),
        'text': 'MAT V600 = V601 - + V602 or',
        'note': "'V601 - + V602': operator then a separately printed sign.",
    },
    {
        'lines': (2176, 2176),
        'text': 'MAT V600 = V601 - +123456.987654',
    },
    {
        'lines': (2207, 2207),
        'text': 'NOP',
    },
    {
        'lines': (2215, 2215),
        'text': 'PBK V600 or',
    },
    {
        'lines': (2216, 2216),
        'text': 'PBK 1',
    },
    {
        'lines': (2239, 2239),
        'text': 'POA V600 + V601 V602 or',
        'note': "The sign is printed separated from the variable ('+ V601').",
    },
    {
        'lines': (2240, 2240),
        'text': ' POA 1 +123456.789 999',
    },
    {
        'lines': (2282, 2282),
        'text': 'POI V600 + V601 V602 or',
    },
    {
        'lines': (2283, 2283),
        'text': ' POI 1 +123456.789 999',
    },
    {
        'lines': (2302, 2302),
        'text': 'PSA V600 + V601 V602 or',
    },
    {
        'lines': (2303, 2303),
        'text': 'PSA 1 +123456.789 999',
    },
    {
        'lines': (2437, 2437),
        'text': 'RSV 1 V600 1 0 0 1 1 or',
        'note': 'Flags blank-separated here, a joined 5-digit block in the RSV listings.',
    },
    {
        'lines': (2438, 2438),
        'text': ' RSV 1 0000 1 0 0 1 1',
    },
    {
        'lines': (2470, 2470),
        'text': 'RTM V601 V600 or',
    },
    {
        'lines': (2471, 2471),
        'text': 'RTM 1 0',
    },
    {
        'lines': (2490, 2490),
        'text': 'RTS',
    },
    {
        'lines': (2504, 2504),
        'text': 'SAC V601 0 +V600 or',
    },
    {
        'lines': (2506, 2506),
        'text': 'SAC 1 0 +123456.789',
    },
    {
        'lines': (2588, 2588),
        'text': 'SET V600 = + V601 or',
        'note': "Sign separated from the variable ('+ V601').",
    },
    {
        'lines': (2589, 2589),
        'text': 'SET V600 = +12345678.123456',
    },
    {
        'lines': (2739, 2739),
        'text': 'TXT 0 ABCDEFGHIJKLMNOP',
        'note': '16-character text.',
    },
    {
        'lines': (2863, 2863),
        'text': 'VEO V601 1 0 V600 1 or',
    },
    {
        'lines': (2864, 2864),
        'text': ' VEO 1 1 0 500 1',
    },
    {
        'lines': (2948, 2948),
        'text': 'WAI V600 or',
    },
    {
        'lines': (2949, 2949),
        'text': 'WAI 00.500',
    },
]


# 5. The variable fit example of section 5.6 (L1283-1343).
VARIABLE_FIT = {
    'lines': (1283, 1343),
    'variable_format': '+12345678.123456',
    'constant_example': {
        'text': 'POI 1 +123456.123 111',
        'lines': (1305, 1315),
        'length_range': ('-999999.999', '+999999.999'),
        'velocity_range': ('000', '999'),
    },
    'variables': {
        'V600': '+00123456.123456',
        'V601': '+999.9999',
        'V602': '+01234567.123456',
        'V603': '-999.99999',
        'V604': '-1234.123456',
    },
    'variable_lines': {
        'V600': 1317,
        'V601': 1319,
        'V602': 1321,
        'V603': 1323,
        'V604': 1325,
    },
    'cases': [
        {
            'instruction': 'POI 1 +V600 V601',
            'lines': (1327, 1331),
            'error': None,
            'length': '+123456.123',
            'velocity': '999',
            'length_inferred': False,
            'why': (
                'V600 is cut to the 6.3 length field (+123456.123, L1329). V601 = +999.9999 is cut to'
                ' the 3-digit velocity field: 999 (L1331). Rounding would give 1000 and overflow, so '
                "the fit truncates. The fraction does not trip the error-32 'integer value' check."
            ),
        },
        {
            'instruction': 'POI 1 +V602 V603',
            'lines': (1333, 1337),
            'error': 32,
            'length': None,
            'velocity': None,
            'length_inferred': False,
            'why': (
                'V602 = +1234567.123456 has 7 integer digits, too large for the 6.3 length field '
                '(L1335). V603 = -999.99999 is negative, but the velocity field has no sign (L1337). '
                "The manual says each one raises an error. That error is 32 'Variable value' "
                '(L8578-8585: too large / operational sign / integer value). Status 60 gives the NC '
                'instruction number.'
            ),
        },
        {
            'instruction': 'POI 1 -V604 V601',
            'lines': (1339, 1341),
            'error': None,
            'length': '+001234.123',
            'velocity': '999',
            'length_inferred': True,
            'why': (
                "V604 = -1234.123456 times the command sign '-' gives a positive feed length (L1341)."
                ' The manual prints no number. +001234.123 follows from the truncation rule. V601 -> '
                '999 as in case 1.'
            ),
        },
    ],
    'note': (
        "L1295: only the digits of the constant's field are used, and a variable that does not fit "
        "raises an error. L1297: the variable's sign always counts. The errata (1.9, 3.7) reads this "
        'as truncate, then check range and sign, then multiply the two signs.'
    ),
}


# 6. BAC / COU counting examples and the actual-count offset rules.
COUNTER_EXAMPLES = [
    {
        'name': 'bac_a_count_after_event',
        'lines': (1546, 1553),
        'listing': 'bac_example_a',
        'target': '00010',
        'positionings': 10,
        'end': 'JST 0000: waits for Start, count back at 0',
        'note': (
            'Increment first, then compare. Below the target, jump to 0000. At the target, reset to '
            'zero and go on to 0003.'
        ),
    },
    {
        'name': 'bac_b_count_prior_to_event',
        'lines': (1555, 1563),
        'listing': 'bac_example_b',
        'target': '00010',
        'positionings': 9,
        'end': 'JST 0000 (instruction 0001), reached on the 10th BAC execution',
        'note': 'One fewer than a): the BAC runs before the PSI, so its 10th execution skips the PSI.',
    },
    {
        'name': 'cou_q1_00_4',
        'lines': (1739, 1751),
        'listing': 'cou_example',
        'target': '000010',
        'positionings': 10,
        'bit': 'Q1.00.4',
        'end': 'Q1.00.4 = 1, then JST 0001 waits for Start. 0001 clears the bit again after Start.',
        'note': 'COU only sets the bit; clearing it is up to the program (L1735).',
    },
    {
        'name': 'offset_table',
        'lines': (1753, 1766),
        'cases': [
            {
                'offset': '+00000',
                'effect': 'none',
            },
            {
                'offset': '-00000',
                'effect': 'none',
            },
            {
                'offset': '+02345',
                'effect': 'add +2345 to the actual count',
            },
            {
                'offset': '-02345',
                'effect': 'add -2345 to the actual count',
            },
            {
                'offset': '000000',
                'effect': "sign position '0': actual count := 0",
            },
        ],
        'note': (
            "COU offset = sign + 5 digits (L1758-1760). 'With the BAC command, the offset has one "
            "less digit' (L1755): sign + 4, e.g. '+0000'. The offset counts only when the instruction"
            " is read in (keypad or serial, L1762). It is then rewritten to '+00000' (L1766), so "
            "reading the same instruction back shows '+00000'. The offset means nothing at run time."
        ),
    },
    {
        'name': 'variable_target_mirror',
        'lines': (1770, 1770),
        'examples': {
            'COU_+12345_Q1.01.1_V600_': 'actual count mirrored into V601',
            'BAC_V600_-5678_V601_': 'actual count mirrored into V602 (target V601)',
        },
        'note': (
            'A target given as Vn receives the count in Vn+1 (L1770). Both examples are Fig. 9-13 '
            'data formats (L6560, L6569). In the BAC one the jump target is V600 and the target count'
            ' is V601.'
        ),
    },
    {
        'name': 'field_widths_fig9_13',
        'lines': (6560, 6569),
        'examples': {
            'BAC_1234_-5678_98765_': 'jump 1234, offset -5678 (sign+4), target 98765 (5 digits)',
            'COU_+12345_Q1.01.1_654321_': 'offset +12345 (sign+5), bit Q1.01.1, target 654321 (6)',
        },
        'note': (
            "Status 04 reports the actual count with only 4 digits ('Xs04_nnnn_iiii_zzzzzz', L6900; "
            'errata 1.11).'
        ),
    },
    {
        'name': 'persistence_and_clc',
        'lines': (1702, 1768),
        'note': (
            'Counts are keyed by instruction number and survive faults, E-stop, mode changes and '
            'power off (L1768). CLC nnnn zeroes the count of instruction nnnn and does nothing if '
            "nnnn holds no BAC/COU (L1709). Status 04 '?sX__04_nnnn_' returns blanks for i and z when"
            ' nnnn holds no counter (L6908).'
        ),
    },
    {
        'name': 'task1_cou_100',
        'lines': (3416, 3422),
        'listing': 'task1_example',
        'target': '000100',
        'bit': 'Q1.00.0',
        'note': '100 cycles set Q1.00.0.',
    },
    {
        'name': 'task2_cou_10',
        'lines': (3433, 3443),
        'listing': 'task2_example',
        'target': '000010',
        'bit': 'Q1.00.7',
        'note': '10 cycles set Q1.00.7.',
    },
    {
        'name': 'flying_cutoff_batches',
        'lines': (3873, 3921),
        'listing': 'flying_cutoff_fig7_20',
        'counts': {
            '0003': ('BAC 0000 +0000 00100', 100),
            '0008': ('BAC 0005 +0000 00200', 200),
        },
        'note': (
            'Each BAC loops back to the start of its own 5-instruction group until the count is '
            'reached. The program then cuts 100 x 1000 and 200 x 2000, and repeats.'
        ),
    },
]


# Other numeric worked examples on program data, bit masks, checksums and status/fault codes.
OTHER_NUMERIC_EXAMPLES = [
    {
        'name': 'bic_binary_1',
        'lines': (1590, 1599),
        'instruction': 'BIC 0500 11 M2.02.4 5 0',
        'M2.03_bits_2_1_0': '011',
        'M2.02_bits_7_0': '01101011',
        'selected_bits': '10110',
        'value': 22,
        'target': '0742',
        'note': (
            'Bits are taken from the start bit upwards (M2.02.4 = 2^0 ... M2.03.0 = 2^4). Target = '
            'offset + value x interval = 500 + 22 x 11.'
        ),
    },
    {
        'name': 'bic_binary_2',
        'lines': (1601, 1606),
        'instruction': 'BIC 0300 02 M2.02.2 8 0',
        'M2.03_bits_2_1_0': '011',
        'M2.02_bits_7_0': '01101011',
        'selected_bits': '11011010',
        'value': 218,
        'target': '0736',
    },
    {
        'name': 'bic_bcd_1',
        'lines': (1608, 1616),
        'instruction': 'BIC 0500 11 M2.02.4 5 1',
        'M2.03_bits_2_1_0': '101',
        'M2.02_bits_7_0': '01100111',
        'selected_bits': '10110',
        'scaling': (10, 8, 4, 2, 1),
        'value': 16,
        'target': '0676',
    },
    {
        'name': 'bic_bcd_2',
        'lines': (1618, 1622),
        'instruction': 'BIC 0300 02 M2.02.2 8 1',
        'M2.03_bits_2_1_0': '101',
        'M2.02_bits_7_0': '01100111',
        'selected_bits': '01011001',
        'scaling': (80, 40, 20, 10, 8, 4, 2, 1),
        'value': 59,
        'target': '0418',
        'note': "BCD digit > 9 -> 'BCD Input Error' (L1582); target > 2999 -> 'Invalid Block #' (L1580).",
    },
    {
        'name': 'akp_mask',
        'lines': (1495, 1500),
        'mask': '21001220',
        'must_be_0': (0, 4, 5),
        'must_be_1': (3, 6),
        'ignored': (1, 2, 7),
    },
    {
        'name': 'ape_a',
        'lines': (1520, 1525),
        'mask': '21002210',
        'set_0': (0, 4, 5),
        'set_1': (1, 6),
        'unchanged': (2, 3, 7),
    },
    {
        'name': 'ape_b',
        'lines': (1529, 1534),
        'mask': '21110002',
        'set_0': (1, 2, 3),
        'set_1': (4, 5, 6),
        'unchanged': (0, 7),
    },
    {
        'name': 'bio',
        'lines': (1645, 1651),
        'mask': '11110000',
        'byte1': '11100010',
        'byte2': '11000010',
        'result': '11XX00X0',
        'jump': False,
    },
    {
        'name': 'cio',
        'lines': (1687, 1698),
        'instruction': 'CIO I1.01.0 M2.02.0 5',
        'I1.01': '10101011',
        'M2.02_before': '00000000',
        'M2.02_after': '00001011',
    },
    {
        'name': 'cvt_v600_to_bcd',
        'lines': (1865, 1881),
        'instruction': 'CVT V600 M2.00 0 0',
        'V600': '-87654321.654321',
        'markers_hex': {
            'M2.00': '21',
            'M2.01': '43',
            'M2.02': '65',
            'M2.03': '21',
            'M2.04': '43',
            'M2.05': '65',
            'M2.06': '87',
            'M2.07': 'FF',
        },
        'note': (
            'BCD: 3 bytes after the point (low digit in the low nibble), 4 before, then the sign byte'
            ' (1-FF = negative). Format digit 0 = BCD, last digit 0 = variable -> markers.'
        ),
    },
    {
        'name': 'cpj',
        'lines': (1786, 1792),
        'instruction': 'CPJ V600 >= +V601 0000.00 0400',
        'V600': '100.000',
        'V601': '090.000',
        'jump_to': '0400',
    },
    {
        'name': 'fak',
        'lines': (1939, 1947),
        'results': {
            '0000': 100.0,
            '0003': 123.45,
            '0006': 100.03,
        },
        'note': 'Each FAK replaces the factor (1.2345, then 1.0003); it does not multiply the old one.',
    },
    {
        'name': 'checksum_sums_fig9_12',
        'lines': (6471, 6518),
        'sums': {
            '# N0000 POI 1    +123456.789 123 ': (1590, 60, 'C4'),
            '#5N0123 NOP  ': (697, 187, '45'),
        },
        'note': (
            '(raw byte sum, high byte + low byte, checksum). Every running sum in the table was '
            'checked.'
        ),
    },
    {
        'name': 'station_codes',
        'lines': (6271, 6285),
        'codes': {
            1: '1',
            2: '2',
            9: '9',
            10: 'A',
            11: 'B',
            12: 'C',
            13: 'D',
            14: 'E',
            15: 'F',
            32: 'W',
        },
        'note': "chr(ord('A') + n - 10) for n >= 10. RS232 uses a blank.",
    },
    {
        'name': 'status03_incremental',
        'lines': (6855, 6875),
        'hex': '000C14FA',
        'increments': 791802,
        'A119': '01500_0000',
        'A101': '0010.00000',
        'position_iu': 1319.67,
        'note': "791802 x 10 / (1500 x 4). The manual prints '1319,67'.",
    },
    {
        'name': 'status03_absolute',
        'lines': (6877, 6890),
        'hex': '000A39CD',
        'increments': 670157,
        'A119': '04096_0512',
        'A101': '0020.00000',
        'position_iu': 3272.25,
        'note': '670157 x 20 / 4096 = 3272.251..., printed 3272.25.',
    },
    {
        'name': 'b018_fault_code_output',
        'lines': (5438, 5452),
        'B018': '3 xxxxxx',
        'fault': 'Position lag (following error), Axis 2',
        'code_hex': '73',
        'Q1.02_bits_7_0': '01110011',
        'note': 'The fault codes of the B018 list (L5311-5436) are HEX. Code 73 = L5383.',
    },
    {
        'name': 'profibus_error_0x010C',
        'lines': (7987, 8008),
        'word': 268,
        'serial_error': 12,
        'note': '0x01nn carries the serial (Status 01) error number, which is DECIMAL: 12 -> 0x0C.',
    },
]


# Parameter values used in worked examples outside the sample table.
PARAMETER_INPUT_EXAMPLES = [
    {
        'parameter': 'Ax24',
        'value': 'M2.02.0 +100 0',
        'lines': (2018, 2018),
        'note': (
            "Homing example for HOM. The homed output is M2.02.0. Compare sample A124 'Q1.00.0 -100 "
            "0'."
        ),
    },
    {
        'parameter': 'B016',
        'value': '2000',
        'lines': (2444, 2444),
        'note': 'Restart vector for the RSV programs.',
    },
    {
        'parameter': 'A106',
        'value': '000500.000',
        'lines': (3322, 3322),
        'note': 'Gray override example: Vmax 500 mm/s.',
    },
    {
        'parameter': 'B014',
        'value': 'I1.01.0 0 0400',
        'lines': (3389, 3389),
        'note': (
            "Manual vector input I1.01.0, start 0400. L3383: '00.00.0 1 xxxx' = start only on a mode "
            'change.'
        ),
    },
    {
        'parameter': 'B011',
        'value': '0200 0000 0',
        'lines': (3428, 3428),
        'note': 'Task 2 starts at 0200, Task 3 off.',
    },
    {
        'parameter': 'B011',
        'value': '0000 0800 0',
        'lines': (3455, 3455),
        'note': 'Task 3 starts at 0800.',
    },
    {
        'parameter': 'A119',
        'value': '01024\t0256',
        'lines': (3531, 3531),
        'note': 'Absolute rotary table, 1024 lines, gear 256:1. Printed with a TAB between the fields.',
    },
    {
        'parameter': 'A119',
        'value': '01024\t0128',
        'lines': (3536, 3536),
        'note': 'Gear 128:1. 512:1 is not allowed with a 256-revolution encoder (L3539-3541).',
    },
    {
        'parameter': 'A125',
        'value': '+ 00010.000',
        'lines': (3556, 3556),
        'note': (
            'Printed with a blank after the sign. The IU is degrees, so the zero point is at 10 '
            "degrees. The value must not exceed IUT, else 'Invalid Input'."
        ),
    },
    {
        'parameter': 'Ax02',
        'value': '5:2',
        'lines': (4268, 4276),
        'note': (
            'Input revolutions 5, output revolutions 2. Each value is 1..9999. Only used for a rotary'
            ' table with an incremental encoder.'
        ),
    },
    {
        'parameter': 'A101/A102',
        'value': '360 IU per table revolution, 590:1',
        'lines': (3585, 3591),
        'note': 'Internal feed constant = 360/590 = 0.610169491 (printed). Use exact arithmetic.',
    },
    {
        'parameter': 'A101',
        'value': '14.0625',
        'lines': (3621, 3628),
        'note': (
            '3600 IU / 256. The table data: A112 = 4800 RPM (L3632), A106 = 1125 IU/s (L3643, the '
            'maximum allowed input), A108 = 10027 IU/s^2 (L3653).'
        ),
    },
    {
        'parameter': 'A119/A101',
        'value': ('01500_0000', '0010.00000'),
        'lines': (6864, 6865),
        'note': "Status 03 incremental example. '_' = blank.",
    },
    {
        'parameter': 'A119/A101',
        'value': ('04096_0512', '0020.00000'),
        'lines': (6879, 6880),
        'note': 'Status 03 absolute example.',
    },
    {
        'parameter': 'B018',
        'value': '3 xxxxxx',
        'lines': (5440, 5440),
        'note': 'Fault code output on Q1.02, see OTHER_NUMERIC_EXAMPLES.',
    },
]
