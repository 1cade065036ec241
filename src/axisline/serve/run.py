"""`axisline serve`: the machine on the wall clock, with its endpoints in a process of their own.

This process is the cycle process: it builds the machine, forks the endpoint process
(serve/endpoints.py: protocol servers, web HMI, event log), applies the soft real-time
measures (serve/realtime.py) and runs the cycles. Between two cycles it answers the clients'
requests (serve/cycle.py). On Ctrl-C or SIGTERM it stops the axes with their ramps, saves what
must persist, writes the trace and report asked for, logs the stop with the lateness figures,
and tells the endpoint process to end.

Standard output carries machine-readable lines, in this order: one per endpoint
("modbus HOST:PORT", "serial-tcp HOST:PORT", "serial-pty PATH", "http HOST:PORT"), "token T"
when the HMI accepts writes, "ready", and at the end "stopped". The event log and the
operator's messages go to standard error.
"""

from __future__ import annotations

import multiprocessing
import os
import secrets
import signal
import time
from pathlib import Path
from typing import Any, Callable

from .cycle import CycleSide
from .endpoints import NICE, EndpointSpec, endpoint_main
from .link import CycleLink
from .realtime import apply_cycle_measures, endpoint_cpus, measures_on

__all__ = ["ServeOptions", "serve_machine", "ServeError"]

START_TIMEOUT = 30.0  # seconds the endpoint process may take to listen


class ServeError(Exception):
    """serve cannot start as asked: the message says why; the exit code is ``code``."""

    def __init__(self, message: str, code: int = 2) -> None:
        super().__init__(message)
        self.code = code


class ServeOptions:
    def __init__(self, *, wanted: dict[str, tuple[str, int] | None], serial_pty: bool = False, allow_writes: bool = False,
                 token: str | None = None, duration: float | None = None, log_path: Path | None = None,
                 trace_out: Path | None = None, report_dir: Path | None = None) -> None:
        self.wanted = wanted
        self.serial_pty = serial_pty
        self.allow_writes = allow_writes
        self.token = token
        self.duration = duration
        self.log_path = log_path
        self.trace_out = trace_out
        self.report_dir = report_dir


def offered_endpoints(machine: Any) -> set[str]:
    """What this machine can serve: its device's protocols, and the web HMI on every machine."""
    offered = set(machine.device.endpoints) if machine.device is not None else set()
    return offered | {"http"}


def serve_machine(m: Any, source: str, opts: ServeOptions, say: Callable[[str], None], stdout: Callable[[str], None]) -> int:
    """Serve the built machine `m` (on a WallClock) until stopped; returns the exit code."""
    realtime = m.config.realtime
    device = m.device
    token = opts.token
    if opts.wanted.get("http") is not None and opts.allow_writes and token is None:
        token = secrets.token_urlsafe(18)
    spec = EndpointSpec(
        wanted={k: v for k, v in opts.wanted.items() if v is not None},
        serial_pty=opts.serial_pty,
        writes_allowed=opts.allow_writes,
        token=token,
        log_path=None if opts.log_path is None else str(opts.log_path),
        cpus=endpoint_cpus(realtime),
        nice=NICE if measures_on(realtime) else 0,
    )
    ctx = multiprocessing.get_context("fork")  # before any thread of this process exists
    requests_in, requests_out = ctx.Pipe(duplex=False)  # endpoint -> cycle
    replies_in, replies_out = ctx.Pipe(duplex=False)  # cycle -> endpoint
    child = ctx.Process(target=endpoint_main, args=(replies_in, requests_out, spec, (requests_in, replies_out)),
                        name="axisline-endpoints", daemon=True)
    child.start()
    requests_out.close()
    replies_in.close()

    # only what the command line asked for: making an endpoint can be an act of the device
    # (the CLM's Profibus image checks B008 and faults 34 without a DP slave address)
    targets: dict[str, Callable[[], Any]] = {}
    if device is not None:
        if spec.wanted.get("serial-tcp") is not None or opts.serial_pty:
            targets["byte"] = device.byte_endpoint
        if spec.wanted.get("modbus") is not None:
            targets["register"] = device.register_endpoint
            # the endpoints' refusals import it on first use: 20 ms (pymodbus) in a cycle's idle time
            import axisline.fieldbus.modbus  # noqa: F401
    link: CycleLink

    def view() -> Any:
        from ..hmi.view import MachineView

        return MachineView(m, link.emit)

    if spec.wanted.get("http") is not None:
        targets["hmi"] = view
    from .audit import Audit

    link = CycleLink(requests_in, replies_out, targets)
    link.audit = Audit(device, link.emit)
    for problem in link.prepare():
        say(f"endpoint not available: {problem}")
    try:
        where = _wait_for_endpoints(link, child)
    except ServeError:
        link.close()
        child.join(5.0)
        raise
    for kind, place in where:
        stdout(f"{kind} {place}")
    if token is not None:
        stdout(f"token {token}")

    side = CycleSide(m, link, realtime)
    for note in apply_cycle_measures(realtime):
        say(note)
    m.clock.idle = side.idle

    stopping = False

    def _stop(signum: int, frame: Any) -> None:  # runs between cycles: the scheduler checks the flag
        nonlocal stopping
        if stopping:
            # scheduler.stop() now would end stop_all()'s ramps at once: axes left moving,
            # nothing saved. os.write: the handler may interrupt a console print.
            os.write(2, b"already stopping: the axes finish their stop ramps and what must persist is saved "
                        b"(kill -9 stops at once, without either)\n")
            return
        stopping = True
        m.scheduler.stop()

    signal.signal(signal.SIGINT, _stop)
    signal.signal(signal.SIGTERM, _stop)
    limit = None if opts.duration is None else max(1, round(opts.duration / m.period))
    link.emit("start", f"serving {source}: cycle {m.clock.period_us} us, writes from the network "
              f"{'enabled' if opts.allow_writes else 'refused'}", machine=source, cycle_us=m.clock.period_us,
              writes=opts.allow_writes, endpoints=[k for k, _ in where])
    say(f"serving {source} on the wall clock, cycle {m.clock.period_us} us; Ctrl-C stops")
    stdout("ready")
    t0 = time.perf_counter()
    try:
        n = m.scheduler.run(limit if limit is not None else 2**62)  # returns on stop()
    finally:
        stopping = True  # from here on a signal only says so (see _stop)
    if m.scheduler.stop_requested:  # a signal came as --duration ran out: the stop follows anyway
        m.scheduler.run(1)  # takes the request back without running a cycle
    rested = m.stop_all()  # the cycles go on answering clients while the axes ramp down
    wall = time.perf_counter() - t0
    m.clock.idle = None
    code = 0 if rested else 1
    try:
        saved = m.persist()
    except OSError as e:  # the check refused unwritable paths; this one failed since
        say(f"cannot save what must persist: {e}")
        saved, code = [], 1
    if opts.trace_out is not None or opts.report_dir is not None:
        _write_outputs(m, n, wall, rested, opts, say)
    lateness = m.clock.lateness.summary()
    late = (f"lateness p50 {lateness['p50_us']:.0f} us, p99 {lateness['p99_us']:.0f} us, "
            f"p99.9 {lateness['p99_9_us']:.0f} us, max {lateness['max_us']:.0f} us")
    link.emit("stop", f"stopped after {n} cycles; axes {'at rest' if rested else 'NOT at rest'}; "
              f"{side.overruns} overrun(s); {late}", cycles=n, at_rest=rested, saved=[str(p) for p in saved],
              overruns=side.overruns, lateness=lateness, gc_collections=side.collect.collections,
              gc_longest_ms=round(side.collect.longest_s * 1e3, 3), requests=link.answered,
              longest_cycle_ms=round(side.longest_work_s * 1e3, 3), longest_requests_ms=round(side.longest_pump_s * 1e3, 3),
              slowest_request=f"{link.slowest[1]} ({link.slowest[0] * 1e3:.3f} ms)")
    link.close()
    child.join(5.0)
    if child.is_alive():
        child.terminate()
    import gc

    gc.enable()
    say(f"stopped after {n} cycles; axes {'at rest' if rested else 'NOT at rest'}; saved {len(saved)} file(s); "
        f"worst lateness {m.clock.late_max * 1e3:.2f} ms ({late}); {side.overruns} overrun(s)")
    stdout("stopped")
    return code


def _wait_for_endpoints(link: CycleLink, child: Any) -> list[tuple[str, str]]:
    deadline = time.monotonic() + START_TIMEOUT
    while time.monotonic() < deadline:
        link.pump(time.perf_counter())
        for message in link.endpoint_messages:
            if message[0] == "failed":
                raise ServeError(message[1], 1)
            if message[0] == "started":
                return [(m[1], m[2]) for m in link.endpoint_messages if m[0] == "listening"]
        if not child.is_alive() or link.closed:
            raise ServeError("the endpoint process ended before it listened", 1)
        time.sleep(0.005)
    raise ServeError(f"the endpoints did not start within {START_TIMEOUT:g} s", 1)


def _write_outputs(m: Any, cycles: int, wall: float, rested: bool, opts: ServeOptions, say: Callable[[str], None]) -> None:
    from ..machine import RunResult
    from ..report.outputs import write_outputs

    result = RunResult(cycles, cycles * m.period, wall, rested and not m.faults, list(m.faults))
    try:
        summary = write_outputs(m, result, trace_out=opts.trace_out, report_dir=opts.report_dir)
    except OSError as e:
        say(f"cannot write the trace/report: {e}")
        return
    if opts.trace_out is not None:
        say(f"trace: {opts.trace_out} (the newest {len(m.trace) if m.trace is not None else 0} samples)")
    if "report" in summary:
        say(f"report: {summary['report']}")
