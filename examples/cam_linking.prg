# COMPAX program: the supplement's §15.2 "Program example 2: Multiple travelling of open curves",
# set by set as printed ("SETM x  Align master" with x = 0: the master starts at the curve start).
# Loaded by examples/cam_linking.toml (device.program_file); `START` in its start-up list runs it.
N001: P210=1     ; Parallel mode
N002: SETC 1     ; Select 1st curve
N003: SETM 0     ; Align master
N004: SETS       ; Align slave
N006: LOOP 1     ; Execute 1st curve
N007: SETC 2     ; Select 2nd curve
N008: LOOP 2     ; Execute 2nd curve
N009: SETC 3     ; Select 3rd curve
N010: LOOP 1     ; Execute 3rd curve
N011: SETC 1     ; Select 1st curve
N012: GOTO 6     ; return to processing the 1st curve
