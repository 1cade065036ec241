; Print-registered feed (Rexroth CLM1.4 program, listing form; SRP mode 1, Fig. 5-29, L2700-2714).
; Axis 1 feeds a printed strip 100 mm per product. The print marks (pitch 100.4 mm: the print
; is stretched) pass the contrast sensor on Raster 1 (I0.01.7). SRP measures, in every feed,
; where the mark is when the feed ends (V600) and corrects the next feed by V601 - V600, at
; most V602: the mark stops 20 mm past the sensor, the knife cuts (Q1.00.2), 12 products.
0000 SET V601 = +00000020.000000 - desired distance mark -> end of the feed
0001 SET V602 = +00000010.000000 - maximum correction
0002 SET V603 = +00000000.000000 - search from the start of the feed
0003 SET V604 = +00000000.000000 - no search monitoring
0004 SRP 1 1 0 V600 M2.02       - registration mode 1: correct the following feed
0005 WAI 00.100
0006 PSI 1 +000100.000 999      - feed one product
0007 AEA Q1.00.2 1              - knife
0008 WAI 00.050
0009 AEA Q1.00.2 0
0010 COU +00000 Q1.00.1 000012  - 12 products
0011 BCE 0006 Q1.00.1 0
0012 JST 0000
