"""Protocol servers: byte streams over TCP or a pty, Modbus TCP. They map bytes to a
personality's typed API at cycle boundaries through the machine's command queue."""
