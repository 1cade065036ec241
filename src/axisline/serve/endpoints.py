"""The endpoint process of `axisline serve`: protocol servers, the web HMI, the event log.

Forked by the cycle process before it starts cycling (serve/run.py). Everything here that
touches the machine goes through the link (serve/link.py): the servers are the same classes
as in one process (fieldbus/), given remote stand-ins for the device's endpoints and for the
command queue. The process runs at a lower priority (nice 5) than the cycle, so on a loaded
machine the scheduler prefers the cycle (with `[realtime]` measures), and on the CPUs the
cycle does not use when `[realtime] cpus` pins it.

It ignores Ctrl-C and SIGTERM (they go to the whole process group): the cycle process
decides when to stop, stops the axes with their ramps, and then sends "shutdown"; if the
cycle process dies (kill -9), the link reaches end-of-file and this process ends too.

Decisions (issue 17 point -> choice, why):

1. "An event log ... on the console in readable form" -> on standard error; standard output
   keeps the machine-readable lines that scripts and tests parse ("modbus HOST:PORT",
   "ready", "stopped"). Test: tests/serve/test_serve.py::test_the_event_log_names_who_wrote_what_old_to_new_and_the_refusals.
2. With `[realtime]` measures switched on, the endpoint process runs at nice 5 and, with
   `[realtime] cpus`, on the CPUs the cycle does not use: under load the OS prefers the cycle.
   Without measures both processes have the same priority: on a machine loaded by other work a
   nice endpoint process got too little CPU and its clients' requests timed out (seen in a
   loaded test run), which a machine nobody tuned must not do. Test: the serve lateness bench
   (`make bench`) runs both ways.
3. kill -9 of the cycle process ends the endpoint process (end-of-file on the link), so no
   orphan keeps the ports. Test: test_the_endpoint_process_ends_when_the_cycle_process_is_killed.
"""

from __future__ import annotations

import os
import signal
import sys
from dataclasses import dataclass, field
from typing import Any

from .events import EventLog
from .link import EndpointLink, RemoteCommands, RemoteEndpoint

__all__ = ["EndpointSpec", "endpoint_main"]

NICE = 5


@dataclass
class EndpointSpec:
    """What the endpoint process serves (from serve's command line)."""

    wanted: dict[str, tuple[str, int] | None] = field(default_factory=dict)  # kind -> (host, port)
    serial_pty: bool = False
    writes_allowed: bool = False
    token: str | None = None
    log_path: str | None = None
    cpus: set[int] | None = None
    nice: int = 0  # NICE with [realtime] measures, else 0 (decision 2)


def _console(line: str) -> None:
    # stderr: stdout carries serve's machine-readable lines ("modbus HOST:PORT", "ready")
    try:
        sys.stderr.write(line + "\n")
        sys.stderr.flush()
    except (OSError, ValueError):
        pass


def endpoint_main(replies: Any, requests: Any, spec: EndpointSpec, parent_ends: tuple = ()) -> None:
    for end in parent_ends:
        # the fork copied the cycle process's ends of the pipes too: closed here, so that the
        # cycle process's death (kill -9) is an end-of-file on the link and this process ends
        end.close()
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, signal.SIG_IGN)
    if spec.nice:
        try:
            os.nice(spec.nice)
        except OSError:
            pass
    if spec.cpus:
        try:
            os.sched_setaffinity(0, spec.cpus)
        except OSError:
            pass
    try:
        log = EventLog(console=_console, json_path=spec.log_path)
    except OSError as e:
        requests.send(("failed", f"--log {spec.log_path}: cannot open it: {e.strerror or e}"))
        return
    link = EndpointLink(replies, requests, on_event=lambda kind, message, fields: log.emit(kind, message, **fields))
    link.start()  # before the servers: the pty bridge opens its session as it is made
    servers: list[Any] = []
    try:
        _start(link, log, spec, servers)
    except (OSError, ValueError, RuntimeError) as e:
        link.send(("failed", str(e)))
        for srv in servers:
            srv.stop()
        log.close()
        return
    link.send(("started",))
    link.shutdown.wait()
    for srv in servers:
        try:
            srv.stop()
        except Exception:
            pass
    log.close()


def _start(link: EndpointLink, log: EventLog, spec: EndpointSpec, servers: list[Any]) -> None:
    from ..fieldbus.serial_tcp import PtyBridge, SerialTcpServer

    wanted = spec.wanted
    ep = wanted.get("serial-tcp")
    if ep is not None:
        srv = SerialTcpServer(RemoteEndpoint(link, "byte", "serial-tcp"), RemoteCommands(link, "serial-tcp"),
                              ep[0], ep[1], events=log).start()
        servers.append(srv)
        link.send(("listening", "serial-tcp", f"{srv.address[0]}:{srv.address[1]}"))
    if spec.serial_pty:
        bridge = PtyBridge(RemoteEndpoint(link, "byte", "serial-pty"), RemoteCommands(link, "serial-pty")).start()
        servers.append(bridge)
        link.send(("listening", "serial-pty", bridge.path))
    ep = wanted.get("modbus")
    if ep is not None:
        from ..fieldbus.modbus import ModbusServer

        allowed = spec.writes_allowed
        srv = ModbusServer(RemoteEndpoint(link, "register", "modbus"), RemoteCommands(link, "modbus"), ep[0], ep[1],
                           writes_allowed=lambda: allowed, events=log).start()
        servers.append(srv)
        link.send(("listening", "modbus", f"{srv.address[0]}:{srv.address[1]}"))
    ep = wanted.get("http")
    if ep is not None:
        from ..hmi.server import HmiServer

        def call(method: str, args: dict, who: str) -> Any:
            return link.call("hmi", "call", (method, args, who), who, "http")

        srv = HmiServer(call, log, ep[0], ep[1], writes_allowed=spec.writes_allowed, token=spec.token).start()
        servers.append(srv)
        link.send(("listening", "http", f"{srv.address[0]}:{srv.address[1]}"))
