"""A personality's register image served over Modbus TCP.

The device decides what every register means (`RegisterEndpoint`: read_registers(kind,
address, count), write_registers(address, values)); this module only carries requests to
it. Every request goes through the machine's command queue, so registers are read and
written at a cycle boundary, as a fieldbus coupler exchanges its process image between
scans; the event loop awaits the queue without blocking other clients.

Function codes: 3 (read holding registers) and 4 (read input registers) read, 6 and 16
write. Every other request is answered with the Modbus exception response (function code
| 0x80) and its exception code, checked in the order of the Modbus application protocol
(V1.1b3, §6 and §7):

    01 illegal function  a function code other than 3, 4, 6, 16; a write (6, 16) while the
                         operator has not enabled network writes (`serve --allow-writes`)
    03 illegal value     a quantity outside 1..125 (read) or 1..123 (FC16), a byte count
                         that is not 2 x quantity, a PDU longer or shorter than its fields
    02 illegal address   beyond the 65536 addresses, or refused by the device
                         (`RegisterRefused`, ValueError, IndexError: address or value)
    02, 03, 04           a `RegisterRefused` with that `exception_code`
    04 device failure    the device raised anything else (logged as an error, no traceback)
    06 device busy       the cycle did not take the request within `reply_timeout` (the
                         machine stopped cycling); the request is withdrawn, nothing is done

A refused request changes nothing: the device checks a multi-register write as a whole
before it applies any of it (the endpoints' write paths are all-or-nothing).

Framing: a client may pipeline requests (send several without waiting, as the Modbus TCP
implementation guide allows: that is what the transaction id is for). Each connection
reads one request (MBAP header: transaction id, protocol id 0, length, unit id), answers
it with the request's transaction and unit id, then reads the next, so replies come in
order, one per request. A header that cannot be a Modbus TCP header (protocol id not 0,
length outside 2..254) means the byte stream has lost its framing: the connection is
closed (logged as a warning), as there is no way to find the next request in it.

Why not pymodbus's server (3.16, the pinned version, still the client library here):
its request handler keeps one decoded request per connection (`last_pdu`) and answers it
later from `call_soon`, so a second request arriving first overwrites it (two replies with
the second's transaction id and the first's data) and further requests in the same segment
are dropped as "extra data"; its maintainers hold that a connection carries one request at a
time (pymodbus-dev/pymodbus#665), so that is not going to change. It also answers function
codes 7, 8, 11, 12, 17, 20, 21 (a write) and 24 itself, with no hook to refuse them, answers
undecodable requests with function code 0x80, and logs a traceback for codes 0x81..0xFF.
Serving four function codes is a few lines of struct; wrapping its handler would have meant
replacing its internals. pymodbus still provides the exception codes (`ExcCodes`).
"""

from __future__ import annotations

import asyncio
import logging
import struct
import threading
from typing import Any

from pymodbus.constants import ExcCodes

from .clients import current_client, peer_name, set_client

_log = logging.getLogger(__name__)

_READ = {3: "holding", 4: "input"}
_SPAN = 0x10000  # Modbus addresses 0..65535
_MBAP = struct.Struct(">HHHB")  # transaction id, protocol id, length (unit id + PDU), unit id
_MIN_LENGTH = 2  # the unit id and a function code
_MAX_LENGTH = 254  # the unit id and the largest PDU (253 bytes)
_MAX_READ = 125  # registers in one read: 250 data bytes fit the PDU
_MAX_WRITE = 123  # registers in one FC16: 246 data bytes + 6 header bytes
REPLY_TIMEOUT = 5.0  # seconds a request waits for the cycle to take it
_REFUSAL_CODES = (ExcCodes.ILLEGAL_ADDRESS, ExcCodes.ILLEGAL_VALUE, ExcCodes.DEVICE_FAILURE)


class RegisterRefused(ValueError):
    """Raised by a register endpoint for a request it does not accept; answered with
    `exception_code`: 02 (address or value, the default), 03 (value) or 04 (the device
    refuses it in its present state)."""

    def __init__(self, message: str = "", exception_code: int = ExcCodes.ILLEGAL_ADDRESS) -> None:
        if exception_code not in _REFUSAL_CODES:
            raise ValueError(f"exception_code must be 2, 3 or 4, got {exception_code!r}")
        super().__init__(message)
        self.exception_code = ExcCodes(exception_code)

    def __reduce__(self):  # keep the code across serve's process link
        return (type(self), (str(self), int(self.exception_code)))


class _Refuse(Exception):
    """Answer the request with this exception code."""

    def __init__(self, code: ExcCodes) -> None:
        super().__init__(code)
        self.code = code


class ModbusServer:
    """Serve `endpoint` (read_registers / write_registers) on host:port; port 0: a free port."""

    def __init__(
        self,
        endpoint: Any,
        commands: Any,
        host: str = "127.0.0.1",
        port: int = 502,
        *,
        writes_allowed=None,
        reply_timeout: float = REPLY_TIMEOUT,
        events: Any = None,
    ) -> None:
        self.endpoint = endpoint
        self.commands = commands
        self.host, self.port = host, port
        # a callable, so the operator's enable is read at each write (serve --allow-writes)
        self.writes_allowed = writes_allowed or (lambda: bool(getattr(endpoint, "network_writes", False)))
        self.reply_timeout = reply_timeout
        # serve's event log (emit(kind, message, **fields)): connects, leaves, refused writes
        self.events = events
        self._loop: asyncio.AbstractEventLoop | None = None
        self._stopping: asyncio.Event | None = None
        self._clients: set[asyncio.Task] = set()
        self._ready = threading.Event()
        self._thread = threading.Thread(target=self._run, name="modbus", daemon=True)
        self._error: BaseException | None = None

    @property
    def address(self) -> tuple[str, int]:
        return self.host, self.port

    # ------------------------------------------------------------------ one connection

    async def _serve_client(self, reader: asyncio.StreamReader, writer: asyncio.StreamWriter) -> None:
        task = asyncio.current_task()
        if task is not None:
            self._clients.add(task)
        peer = writer.get_extra_info("peername")
        who = peer_name("modbus", peer)
        set_client(who)  # this task's context: the requests it submits name their client
        if self.events is not None:
            self.events.emit("connect", f"{who} connected", endpoint="modbus", who=who)
        try:
            while True:
                header = await reader.readexactly(_MBAP.size)
                tid, protocol, length, unit = _MBAP.unpack(header)
                if protocol != 0 or not _MIN_LENGTH <= length <= _MAX_LENGTH:
                    _log.warning("Modbus client %s sent %s, not a Modbus TCP header: connection closed", peer, header.hex(" "))
                    return
                pdu = await reader.readexactly(length - 1)
                reply = await self._answer(pdu)
                writer.write(_MBAP.pack(tid, 0, len(reply) + 1, unit) + reply)
                await writer.drain()
        except asyncio.IncompleteReadError as e:
            if e.partial:
                _log.info("Modbus client %s left in the middle of a request (%d bytes)", peer, len(e.partial))
        except OSError as e:  # reset by the peer, broken pipe: the client is gone
            _log.info("Modbus client %s: %s", peer, e)
        except asyncio.CancelledError:
            # stop(): end normally, because Python 3.11's asyncio.streams calls exception()
            # on the finished handler task, which for a cancelled task logs a traceback
            pass
        finally:
            if task is not None:
                self._clients.discard(task)
            writer.close()
            if self.events is not None:
                self.events.emit("disconnect", f"{who} disconnected", endpoint="modbus", who=who)

    async def _answer(self, pdu: bytes) -> bytes:
        """The reply PDU to one request PDU (at least the function code)."""
        fc = pdu[0]
        try:
            if fc in _READ:
                return await self._read(fc, pdu)
            if fc == 6 or fc == 16:
                if not self.writes_allowed():
                    self._refused_write(fc, pdu)
                    raise _Refuse(ExcCodes.ILLEGAL_FUNCTION)
                return await (self._write_single(pdu) if fc == 6 else self._write_multiple(pdu))
            raise _Refuse(ExcCodes.ILLEGAL_FUNCTION)
        except _Refuse as r:
            return bytes((fc | 0x80, r.code))

    def _refused_write(self, fc: int, pdu: bytes) -> None:
        if self.events is None:
            return
        address = struct.unpack_from(">H", pdu, 1)[0] if len(pdu) >= 3 else None
        who = current_client()
        self.events.emit("write", f"{who}: write FC{fc} at register {address} refused: network writes are not enabled (serve --allow-writes)",
                         endpoint="modbus", who=who, what=f"FC{fc} register {address}", accepted=False,
                         reason="network writes are not enabled (serve --allow-writes)")

    async def _read(self, fc: int, pdu: bytes) -> bytes:
        if len(pdu) != 5:
            raise _Refuse(ExcCodes.ILLEGAL_VALUE)
        address, count = struct.unpack_from(">HH", pdu, 1)
        if not 1 <= count <= _MAX_READ:
            raise _Refuse(ExcCodes.ILLEGAL_VALUE)
        if address + count > _SPAN:
            raise _Refuse(ExcCodes.ILLEGAL_ADDRESS)
        regs = await self._device(self.endpoint.read_registers, _READ[fc], address, count)
        try:
            words = [int(r) & 0xFFFF for r in regs]
        except (TypeError, ValueError) as e:
            words, why = [], f"{type(e).__name__}: {e}"
        else:
            why = f"{len(words)} registers for {count}"
        if len(words) != count:
            _log.error("Modbus read FC%d of %d registers at %d: the device answered %s", fc, count, address, why)
            raise _Refuse(ExcCodes.DEVICE_FAILURE)
        return struct.pack(f">BB{count}H", fc, 2 * count, *words)

    async def _write_single(self, pdu: bytes) -> bytes:
        if len(pdu) != 5:
            raise _Refuse(ExcCodes.ILLEGAL_VALUE)
        address, value = struct.unpack_from(">HH", pdu, 1)
        await self._device(self.endpoint.write_registers, address, [value])
        return pdu  # FC6 answers with its request

    async def _write_multiple(self, pdu: bytes) -> bytes:
        if len(pdu) < 6:
            raise _Refuse(ExcCodes.ILLEGAL_VALUE)
        address, count, nbytes = struct.unpack_from(">HHB", pdu, 1)
        if not 1 <= count <= _MAX_WRITE or nbytes != 2 * count or len(pdu) != 6 + nbytes:
            raise _Refuse(ExcCodes.ILLEGAL_VALUE)
        if address + count > _SPAN:
            raise _Refuse(ExcCodes.ILLEGAL_ADDRESS)
        values = list(struct.unpack_from(f">{count}H", pdu, 6))
        await self._device(self.endpoint.write_registers, address, values)
        return pdu[:5]  # function code, address, quantity

    async def _device(self, fn: Any, *args: Any) -> Any:
        """`fn(*args)` at the next cycle boundary; its refusal as the exception to answer."""
        fut = self.commands.submit(fn, *args)
        waiter = asyncio.wrap_future(fut)
        done, _ = await asyncio.wait({waiter}, timeout=self.reply_timeout)
        # withdraw a request the cycle has not taken, so a busy answer means nothing was done;
        # once it runs it cannot be withdrawn, and its own answer is awaited
        if not done and fut.cancel():
            _log.warning("Modbus request not taken by the cycle within %.1f s: answered busy, not done", self.reply_timeout)
            raise _Refuse(ExcCodes.DEVICE_BUSY)
        try:
            return await waiter
        except asyncio.CancelledError:
            if fut.cancelled():  # withdrawn by the machine (serve is stopping), not run
                raise _Refuse(ExcCodes.DEVICE_BUSY) from None
            raise
        except (RegisterRefused, ValueError, IndexError) as e:
            _log.debug("Modbus request %s%r refused: %s", getattr(fn, "__name__", fn), args, e)
            raise _Refuse(getattr(e, "exception_code", ExcCodes.ILLEGAL_ADDRESS)) from None
        except Exception as e:  # a fault of the device, not of the request: no traceback for the network
            _log.error("Modbus request %s%r: the device failed: %s: %s", getattr(fn, "__name__", fn), args, type(e).__name__, e)
            raise _Refuse(ExcCodes.DEVICE_FAILURE) from None

    # ------------------------------------------------------------------ server thread

    def _run(self) -> None:
        async def main() -> None:
            self._loop = asyncio.get_running_loop()
            self._stopping = asyncio.Event()
            try:
                server = await asyncio.start_server(self._serve_client, self.host, self.port)
            except BaseException as e:  # could not listen: report to start()
                self._error = e
                self._ready.set()
                return
            self.port = server.sockets[0].getsockname()[1]
            self._ready.set()
            async with server:
                await self._stopping.wait()
                server.close()
                for task in list(self._clients):
                    task.cancel()
                await asyncio.gather(*self._clients, return_exceptions=True)

        asyncio.run(main())

    def start(self) -> "ModbusServer":
        self._thread.start()
        self._ready.wait(10.0)
        if self._error is not None:
            raise OSError(f"Modbus server cannot listen on {self.host}:{self.port}: {self._error}")
        return self

    def stop(self) -> None:
        loop, stopping = self._loop, self._stopping
        if loop is not None and stopping is not None and not loop.is_closed():
            try:
                loop.call_soon_threadsafe(stopping.set)
            except RuntimeError:  # the loop ended meanwhile
                pass
        self._thread.join(5.0)
