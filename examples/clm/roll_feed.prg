; Roll feed with a press (Rexroth CLM1.4 program, listing form).
; Axis 1 feeds the strip by the length in V600 at V601 per mille of Ax06. After each feed
; the press strokes: valve Q1.00.0 on until the ram reaches bottom dead centre (I1.00.1),
; then off, and the ram returns. The Logic Task (roll_feed.lt) allows a feed only while the
; ram is at top dead centre with the guard closed (M5.00.0). COU counts the parts (target
; V602, the count mirrored into V603) and sets Q1.00.1 at the end of the batch.
0000 CLC 0007                   - new batch: clear the part counter
0001 AEA Q1.00.1 0              - batch-done lamp off
0002 AKN M5.00.0 1              - wait: press at top dead centre, guard closed
0003 PSI 1 +V600 V601           - feed one length and wait until in position
0004 AEA Q1.00.0 1              - press stroke: valve on
0005 AKN I1.00.1 1              - wait for bottom dead centre
0006 AEA Q1.00.0 0              - valve off: the ram returns
0007 COU +00000 Q1.00.1 V602    - count the part; the batch is done at V602
0008 BCE 0002 Q1.00.1 0         - batch not done: next feed
0009 JST 0000                   - batch done: stop, wait for Start
