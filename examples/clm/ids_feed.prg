; The manual's IDS01 example (§7.8, L3677-3685; Rexroth CLM1.4 program, listing form).
; The feed length comes from the decade switch's thumbwheels (V016: an IDS01.1-2 with two
; decimal places) at its velocity (V018: % x 10 = per mille of A106); after each feed the
; output Q1.00.0 is on for 0.5 s. A change on the switch is taken by the next feed.
0000 PSI 1 +V016 V018           - feed the switch's length at the switch's velocity
0001 AEA Q1.00.0 1              - signal on
0002 WAI 00.500                 - for 0.5 s
0003 AEA Q1.00.0 0              - signal off
0004 JMP 0000                   - next feed
