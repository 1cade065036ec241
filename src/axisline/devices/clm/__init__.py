"""The Rexroth CLM1.4 personality (spec clm.md, errata clm-errata.md).

Part 1 (offline): the program language and its checker, the parameters, the Logic Task, and
the serial transfer format of the files (`telegram`, `operands`, `fields`, `commands`,
`program`, `parameters`, `logic`, `variables`, `files`, `check`).
"""
