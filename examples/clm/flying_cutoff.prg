; The typical flying cutoff of the CLM manual, Fig. 7-20 (L3896-3921), as printed except the
; two stroke constants: the manual's minimum cutoff stroke (CPJ V100 < 1000) and minimum
; carriage stroke (CPJ V100 < 2000) are longer than its 1000 mm pieces (errata: "the Fig. 7-20
; strokes"), so a carriage that waits for them could never be home before the next cut. They are
; scaled by 1/10 (100 mm and 200 mm): the punch strikes once the carriage is 100 mm out and the
; carriage leaves the material at 200 mm. Everything else is the listing: 100 pieces of 1000 mm,
; 200 pieces of 2000 mm, again; the punch Q1.00.0 and its switch I1.00.0 (both AKN wait for 1,
; as printed: the second one passes while the punch is still down).
0000 NOP                                - product 1
0001 LML 1 001000.000                   - production length 1
0002 JSR 1000                           - cutoff program
0003 BAC 0000 +0000 00100               - piece count
0004 NOP
0005 NOP                                - product 2
0006 LML 1 002000.000                   - production length 2
0007 JSR 1000                           - cutoff program
0008 BAC 0005 +0000 00200               - piece count
0009 NOP
0010 JMP 0000
1000 CPJ V100 < +00100.000 0000.00 1000 - minimum cutoff stroke (printed: +01000.000)
1001 AEA Q1.00.0 1                      - punch down
1002 AKN I1.00.0 1                      - wait until punch down
1003 AEA Q1.00.0 0                      - punch up
1004 AKN I1.00.0 1                      - wait until punch up
1005 CPJ V100 < +00200.000 0000.00 1005 - minimum carriage stroke (printed: +02000.000)
1006 EOS                                - end of processing program
1007 RTS                                - jump back
