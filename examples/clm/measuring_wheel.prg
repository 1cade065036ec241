; Feed to length with a measuring wheel (Rexroth CLM1.4 program, listing form).
; Axis 1 is a feed roll in measuring wheel mode Version 1 (A100 mode 3): the position loop
; closes through the measuring wheel (master encoder 1, C000-C002) rolling on the strip, so
; the 2 % the strip slips on the roll does not shorten the pieces. Each piece of 500 mm is
; followed by the cut signal Q1.00.0 for 100 ms; COU counts the pieces and ends the batch of
; 10 on Q1.00.1.
0000 CLC 0005                   - new batch: clear the piece counter
0001 AEA Q1.00.1 0              - batch-done lamp off
0002 PSI 1 +000500.000 999      - feed one piece, in position on the measuring wheel
0003 AEA Q1.00.0 1              - cut signal on
0004 WAI 00.100                 - the cut takes 100 ms
0005 COU +00000 Q1.00.1 000010  - count the piece; the batch is done at 10
0006 AEA Q1.00.0 0              - cut signal off
0007 BCE 0002 Q1.00.1 0         - batch not done: next piece
0008 JST 0000                   - batch done: stop, wait for Start
