; Indexing table (Rexroth CLM1.4 program, listing form; parameters rotary_table.par).
; Homes the table (HOM + AKN on the Homed output, L2018-2022), visits stations by absolute
; positioning the shortest way (A105 = 1, RTM 1), then indexes 8 x 45 degrees forward.
; At each station the tool signal Q1.00.0 pulses for 100 ms; the report records the index
; position error then.
0000 HOM 1                      - home the table: option 1, cam I1.00.0 and marker pulse
0001 AKN M2.02.0 1              - wait until homing is completed
0002 RTM 1 1                    - shortest way (as A105)
0003 PSA 1 +000090.000 999      - station 90 degrees: +100 from the home position 350
0004 JSR 0100                   - work the station
0005 PSA 1 +000045.000 999      - 45: the shortest way is back, -45
0006 JSR 0100
0007 PSA 1 +000315.000 999      - 315: the shortest way is back through 0, -90
0008 JSR 0100
0009 PSA 1 +000000.000 999      - 0: the shortest way is forward through 360, +45
0010 JSR 0100
0011 PSI 1 +000045.000 999      - index 45 degrees forward
0012 JSR 0100
0013 BAC 0011 +0000 00008       - 8 indexes: one table revolution
0014 JST 0000                   - done: stop, wait for Start
0100 AEA Q1.00.0 1              - tool signal on (the report records the index error)
0101 WAI 00.100                 - 100 ms
0102 AEA Q1.00.0 0              - tool signal off
0103 RTS
