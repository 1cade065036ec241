"""motrona FS701 "Flying Shears and Saws" personality (MC700 / MC720, firmware FS701.09).

Register side (this package's data modules):

    parameters   every parameter of every block as data, `ParameterSet`, encoder scaling,
                 Error 05 ratio rule, virtual-master 1/2048 quantisation
    status       process values 0x0800.., error/status words 0x0B00..0x0B05, errors 00..05,
                 LED model, `StatusImage`
    io_assign    command inputs / output signals, hardware assignment (many-to-many)
    registers    one register map over all of the above, value formatting, write rules,
                 EEPROM store, Modbus holding-register map
    drivecom     the serial protocol (Drivecom after ISO 1745): `DrivecomEndpoint`, client helpers
    paramfile    parameter files (TOML), atomic save, validated load, compare
    lcd          the MC720 terminal's LCD windows over the process values (spec §5.4, E23)

The modules are imported on demand; importing the package itself loads nothing heavy.
"""
