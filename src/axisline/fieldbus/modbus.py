"""A personality's register image served over Modbus TCP (pymodbus).

The device decides what every register means (`RegisterEndpoint`: read_registers(kind,
address, count), write_registers(address, values)); this module only carries requests to
it. Every request goes through the machine's command queue, so registers are read and
written at a cycle boundary, as a fieldbus coupler exchanges its process image between
scans; the event loop awaits the queue without blocking other clients.

Function codes: 3 (read holding registers) and 4 (read input registers) read, 6 and 16
write. Writes are refused with exception code 01 (illegal function) unless the operator
enabled them (`serve --allow-writes`), and with 02 (illegal address) when the device
refuses the address or value; a refused write changes nothing.

pymodbus 3.16 serves a `SimDevice` whose `action` hook sees every request with the
registers of the addressed block: the hook fills them from the device before a read and
hands the values to the device on a write. The block spans all 65536 addresses; the device
refuses the ones it does not have.
"""

from __future__ import annotations

import asyncio
import threading
from typing import Any

from pymodbus.constants import ExcCodes
from pymodbus.server import ModbusTcpServer
from pymodbus.simulator import DataType, SimData, SimDevice

_READ = {3: "holding", 4: "input"}
_WRITE = (6, 16)
_SPAN = 0x10000


class RegisterRefused(ValueError):
    """Raised by a register endpoint for an address or value it does not accept."""


class ModbusServer:
    """Serve `endpoint` (read_registers / write_registers) on host:port; port 0: a free port."""

    def __init__(self, endpoint: Any, commands: Any, host: str = "127.0.0.1", port: int = 502, *, writes_allowed=None) -> None:
        self.endpoint = endpoint
        self.commands = commands
        self.host, self.port = host, port
        # a callable, so the operator's enable is read at each write (serve --allow-writes)
        self.writes_allowed = writes_allowed or (lambda: bool(getattr(endpoint, "network_writes", False)))
        self._loop: asyncio.AbstractEventLoop | None = None
        self._server: ModbusTcpServer | None = None
        self._ready = threading.Event()
        self._thread = threading.Thread(target=self._run, name="modbus", daemon=True)
        self._error: BaseException | None = None

    @property
    def address(self) -> tuple[str, int]:
        return self.host, self.port

    async def _action(self, function_code, start_address, address, count, registers, values):
        offset = address - start_address
        try:
            if function_code in _READ:
                fut = self.commands.submit(self.endpoint.read_registers, _READ[function_code], address, count)
                regs = await asyncio.wrap_future(fut)
                registers[offset : offset + count] = [int(r) & 0xFFFF for r in regs]
                return None
            if function_code in _WRITE:
                if values is None:
                    return None  # the echo a write-single answers with: the values just written
                if not self.writes_allowed():
                    return ExcCodes.ILLEGAL_FUNCTION
                fut = self.commands.submit(self.endpoint.write_registers, address, [int(v) for v in values])
                await asyncio.wrap_future(fut)
                return None
        except (RegisterRefused, ValueError, IndexError):
            return ExcCodes.ILLEGAL_ADDRESS
        return ExcCodes.ILLEGAL_FUNCTION

    def _run(self) -> None:
        async def main() -> None:
            self._loop = asyncio.get_running_loop()
            try:
                regs = [SimData(0, count=_SPAN, values=0, datatype=DataType.REGISTERS)]
                bits = [SimData(0, count=16, values=False, datatype=DataType.BITS)]  # unused: no coils or inputs
                device = SimDevice(0, simdata=(bits, list(bits), regs, list(regs)), action=self._action)
                self._server = ModbusTcpServer(device, address=(self.host, self.port))
                await self._server.serve_forever(background=True)
            except BaseException as e:  # could not build or listen: report to start()
                self._error = e
                self._ready.set()
                return
            transport = self._server.transport
            if transport is not None and hasattr(transport, "sockets") and transport.sockets:
                self.port = transport.sockets[0].getsockname()[1]
            self._ready.set()
            await self._server.serving

        asyncio.run(main())

    def start(self) -> "ModbusServer":
        self._thread.start()
        self._ready.wait(10.0)
        if self._error is not None:
            raise OSError(f"Modbus server cannot listen on {self.host}:{self.port}: {self._error}")
        return self

    def stop(self) -> None:
        if self._loop is not None and self._server is not None:
            asyncio.run_coroutine_threadsafe(self._server.shutdown(), self._loop).result(5.0)
        self._thread.join(5.0)
