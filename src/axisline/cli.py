"""The `axisline` command: run, serve, check, plot.

Exit codes: 0 the run completed; 1 a runtime fault (an axis went to ERROR_STOP, a job
step failed); 2 a bad machine file (the message names the key, value and range).

Help is plain text (`rich_markup_mode=None` on every Typer, see `_typer`): help texts name
TOML tables such as `[[cam]]` and `[device]`, which rich markup would swallow, and typer's
rich panels show a flag as `--quiet <bool>`. `-h` is `--help` everywhere; `--version` prints
the installed version. `run --json -` writes the summary JSON to standard output, and then
nothing else goes there (the table goes to standard error).
"""

from __future__ import annotations

import json
import os
import signal
import sys
from pathlib import Path
from typing import Annotated, Optional

import typer
from rich.console import Console
from rich.markup import escape
from rich.progress import BarColumn, Progress, TextColumn, TimeElapsedColumn
from rich.table import Table

from .configerrors import ConfigError

def _typer(help: str) -> typer.Typer:
    """A command group with plain-text help (module docstring) and -h as well as --help (the
    sub-commands inherit help_option_names from the group's context)."""
    return typer.Typer(add_completion=False, no_args_is_help=True, rich_markup_mode=None,
                       context_settings={"help_option_names": ["-h", "--help"]}, help=help)


app = _typer("axisline: an open-source motion controller.")
console = Console(stderr=True)
out = Console()


def _version(value: bool) -> None:
    if not value:
        return
    from importlib.metadata import PackageNotFoundError, version

    from . import __version__

    try:
        v = version("axisline")
    except PackageNotFoundError:  # run from a source tree that was never installed
        v = __version__
    print(f"axisline {v}")
    raise typer.Exit(0)


@app.callback()
def _main(
    version: bool = typer.Option(False, "--version", callback=_version, is_eager=True, help="print the version and exit"),
) -> None:
    """axisline: an open-source motion controller."""


def _bad_file(e: ConfigError) -> typer.Exit:
    console.print(f"[red]bad machine file[/red] {escape(e.source)}:", highlight=False)
    for p in e.problems:
        console.print(f"  - {p}", markup=False, highlight=False, soft_wrap=True)  # a line each, for grep
    return typer.Exit(2)


def _load(machine: Path, **kw):
    from .machine import Machine

    try:
        return Machine.from_file(machine, **kw)
    except ConfigError as e:
        raise _bad_file(e) from None


def _machine_value(value, option: str, key: str):
    """A command-line value that stands in for the machine file's machine.<key>: it gets the
    key's own type and range (one rule for both), or exit 2 naming the option."""
    if value is None:
        return None
    from pydantic import TypeAdapter, ValidationError

    from .config import MachineSection
    from .configerrors import allowed_range, shown

    info = MachineSection.model_fields[key]
    try:
        return TypeAdapter(Annotated[info.annotation, *info.metadata]).validate_python(value)
    except ValidationError as e:
        why = e.errors(include_url=False)[0]["msg"]
        console.print(f"[red]{option}[/red] = {escape(shown(value))}: {escape(why)} (allowed: {allowed_range(info)}, as machine.{key})")
        raise typer.Exit(2) from None


def _writable(outputs: dict[str, Path | None]) -> None:
    """Exit 2 for an output that cannot be written, before the run (not after it, with a traceback)."""
    from .kernel.atomic import unwritable_reason

    for option, path in outputs.items():
        reason = unwritable_reason(path) if path is not None else None
        if reason is not None:
            shown_path = path.parent if option in ("--plot", "--report") else path
            console.print(f"[red]{option}[/red] = {escape(str(shown_path))}: cannot be written ({escape(reason)})")
            raise typer.Exit(2)


def _endpoint(value: str | None, option: str) -> tuple[str, int] | None:
    if value is None:
        return None
    host, sep, port = value.rpartition(":")
    if not sep:
        host, port = "127.0.0.1", value
    try:
        p = int(port)
        if not 0 <= p <= 65535:
            raise ValueError
    except ValueError:
        console.print(f"[red]{option}[/red] = {escape(repr(value))}: expected HOST:PORT with a port in 0..65535")
        raise typer.Exit(2) from None
    return (host or "127.0.0.1", p)


@app.command()
def run(
    machine: Path = typer.Argument(..., help="machine file (TOML)"),
    duration: Optional[float] = typer.Option(None, "--duration", help="longest simulated time, s (default: the file's)"),
    seed: Optional[int] = typer.Option(None, "--seed", help="seed of the simulated plant (default: the file's)"),
    json_out: Optional[Path] = typer.Option(None, "--json", help="write the run summary as JSON (- for standard output: then the table goes to standard error)"),
    trace_out: Optional[Path] = typer.Option(None, "--trace", help="write the scope trace (.npz; .csv beside it)"),
    plot_dir: Optional[Path] = typer.Option(None, "--plot", help="write plots (PNG) into this folder"),
    report_dir: Optional[Path] = typer.Option(None, "--report", help="write report.md, summary.json, the trace and plots into this folder"),
    quiet: bool = typer.Option(False, "--quiet", help="no progress bar"),
) -> None:
    """Run the machine on the embedded simulated plant (as fast as possible, exact time)."""
    duration = _machine_value(duration, "--duration", "duration")
    seed = _machine_value(seed, "--seed", "seed")
    json_stdout = json_out is not None and str(json_out) == "-"
    if json_stdout:  # the report folder still gets its summary.json
        json_out = None
    _writable({"--json": json_out, "--trace": trace_out, "--plot": plot_dir and plot_dir / "axis.png",
               "--report": report_dir and report_dir / "report.md"})
    m = _load(machine, seed=seed, duration=duration)
    if quiet or not sys.stderr.isatty():
        result = m.run(duration)
    else:
        with Progress(TextColumn("[bold]simulating"), BarColumn(), TextColumn("{task.percentage:>5.1f} %"), TimeElapsedColumn(), console=console, transient=True) as bar:
            task = bar.add_task("run", total=1.0)
            result = m.run(duration, progress=lambda f: bar.update(task, completed=f))
    from .report.outputs import write_outputs

    summary = write_outputs(m, result, json_out=json_out, trace_out=trace_out, plot_dir=plot_dir, report_dir=report_dir)
    from .report.console import print_summary

    print_summary(summary, len(m.config.job.steps), m.config.machine.personality if m.device is not None else None,
                  console if json_stdout else out)
    if json_stdout:
        sys.stdout.write(json.dumps(summary, indent=2) + "\n")
        sys.stdout.flush()
    raise typer.Exit(0 if result.completed else 1)


@app.command()
def check(machine: Path = typer.Argument(..., help="machine file (TOML)")) -> None:
    """Validate a machine file: exit 0 if it is usable, 2 with the bad keys named."""
    m = _load(machine)
    steps = len(m.config.job.steps)
    driver = (f"job of {steps} steps" if steps or m.device is None
              else f"driven by the {m.config.machine.personality} personality")
    out.print(f"{escape(str(machine))}: OK ({len(m.units)} axes, cycle {m.clock.period_us} us, {driver})")


@app.command()
def plot(
    trace: Path = typer.Argument(..., help="trace written by run --trace FILE: FILE (npz) or the FILE.csv beside it; or a run --report folder"),
    out_dir: Optional[Path] = typer.Option(None, "--out", help="folder for the PNGs (default: beside the trace)"),
) -> None:
    """Draw position, velocity, acceleration, jerk and following error of each axis (PNG)."""
    from .report.plots import plot_trace
    from .report.tracefile import load_trace

    if trace.is_dir() and (trace / "trace.npz").is_file():  # the folder of run --report
        trace = trace / "trace.npz"
    try:
        rec = load_trace(trace)
    except (OSError, ValueError) as e:
        reason = e.strerror if isinstance(e, OSError) and e.strerror else str(e)
        if trace.is_dir():
            from .report.tracefile import ACCEPTED

            reason = f"a folder without a trace.npz; expected {ACCEPTED}, or the folder of run --report"
        console.print(f"[red]cannot read trace[/red] {escape(str(trace))}: {escape(reason)}", highlight=False)
        raise typer.Exit(2) from None
    files = plot_trace(rec.data(), rec.units, out_dir or trace.with_suffix(""), title=trace.stem)
    for f in files:
        out.print(str(f), markup=False, highlight=False)
    if not files:
        console.print("no axis channels in this trace (an axis is drawn from its <axis>.command_position channel)")
        raise typer.Exit(1)


@app.command()
def cam(
    machine: Path = typer.Argument(..., help="machine file (TOML) with the [[cam]]"),
    name: str = typer.Argument(..., help="the cam's name"),
    master_speed: float = typer.Option(..., "--master-speed", help="constant master speed, master units/s"),
    axis: Optional[str] = typer.Option(None, "--axis", help="check against this axis' v_max, a_max, j_max"),
    plot_file: Optional[Path] = typer.Option(None, "--plot", help="draw the cam at that speed (PNG)"),
) -> None:
    """Cam check: the slave's largest velocity, acceleration and jerk at a master speed (exit 1 if over the limits)."""
    from .motion.cam import check, plot_cam

    m = _load(machine)
    if name not in m.cams:
        console.print(f"[red]no cam {escape(repr(name))}[/red] (cams: {', '.join(m.cams) or 'none'})")
        raise typer.Exit(2)
    limits = {}
    if axis is not None:
        if axis not in m.units:
            console.print(f"[red]no axis {escape(repr(axis))}[/red] (axes: {', '.join(m.units)})")
            raise typer.Exit(2)
        c = m.units[axis].axis.config
        limits = {"v_max": c.v_max, "a_max": c.a_max, "j_max": c.j_max}
    curve = m.cams[name]
    r = check(curve, master_speed, **limits)
    t = Table(title=f"cam {name} at master speed {master_speed:g}/s")
    for col in ("", "maximum", "at master position", "limit", "ok"):
        t.add_column(col)
    for label, value, at, lim, over in (
        ("velocity", r.max_velocity, r.max_velocity_at, limits.get("v_max"), r.velocity_exceeded),
        ("acceleration", r.max_acceleration, r.max_acceleration_at, limits.get("a_max"), r.acceleration_exceeded),
        ("jerk", r.max_jerk, r.max_jerk_at, limits.get("j_max"), r.jerk_exceeded),
    ):
        t.add_row(label, f"{value:.6g}", f"{at:.6g}", "" if lim is None else f"{lim:g}", "NO" if over else "yes")
    out.print(t)
    out.print(f"largest master speed within the limits: {r.max_master_speed:.6g}/s")
    if plot_file is not None:
        unit = m.units[axis].config.unit if axis is not None else ""
        plot_cam(curve, master_speed, plot_file, title=f"cam {name}", limits=limits, unit=unit)
        out.print(str(plot_file), markup=False, highlight=False)
    raise typer.Exit(0 if r.within_limits else 1)


fs701_app = _typer("motrona FS701 flying shear tools.")
app.add_typer(fs701_app, name="fs701")


@fs701_app.command("envelope")
def fs701_envelope(
    params: Path = typer.Argument(..., help="FS701 parameter file (TOML)"),
    png: Optional[Path] = typer.Option(None, "--png", help="write the envelope plot here"),
    cut_time: Optional[float] = typer.Option(None, "--cut-time", help="s from Ready to Cut to Cut completed"),
    speeds: Optional[str] = typer.Option(None, "--speeds", help="line speeds LU/min, comma separated"),
) -> None:
    """Shortest cut length per line speed for the configured ramps and cut time (manual §10)."""
    from .devices.fs701.envelope import envelope_command

    raise typer.Exit(envelope_command(params, png, cut_time, speeds))


compax_app = _typer("COMPAX XX70 tools.")
app.add_typer(compax_app, name="compax")


@compax_app.command("plot")
def compax_plot(
    curves: Path = typer.Argument(..., help="saved cam memory (.json) or a master,slave CSV (not the machine file)"),
    curve: int = typer.Argument(..., help="curve number 1 ... 100 (SETC n); a CSV holds one curve, drawn as this number"),
    master_speed: float = typer.Option(..., "--master-speed", help="master speed, master units/s"),
    out_file: Path = typer.Option(..., "--out", help="PNG to write"),
    p36: float = typer.Option(1.0, "--p36", help="slave factor P36"),
) -> None:
    """Draw a COMPAX curve with the slave's velocity and acceleration at a master speed."""
    from .devices.compax import CompaxError
    from .devices.compax.cammemory import MAX_CURVES
    from .devices.compax.report import plot_curve

    def refuse(why: str) -> typer.Exit:
        console.print(f"[red]cannot plot curve {curve}[/red] of {escape(str(curves))}: {escape(why)}", highlight=False)
        return typer.Exit(2)

    if not 1 <= curve <= MAX_CURVES:  # a CSV takes any number; the COMPAX stores curves 1 ... 100
        raise refuse(f"a curve number is 1 ... {MAX_CURVES} (SETC n)")
    machine = _machine_file_curves(curves)
    if machine is not None:
        raise refuse(machine)
    try:
        out.print(str(plot_curve(curves, curve, master_speed, out_file, p36=p36)), markup=False, highlight=False)
    except (CompaxError, OSError, ValueError) as e:
        raise refuse(str(e)) from None


def _machine_file_curves(path: Path) -> str | None:
    """None unless `path` is a machine file (TOML with a [machine] or [device] table); then
    what to give instead, with the curve CSVs that machine file names."""
    import tomllib

    try:
        with open(path, "rb") as f:
            head = f.read(1 << 20)
        doc = tomllib.loads(head.decode("utf-8"))
    except (OSError, UnicodeDecodeError, tomllib.TOMLDecodeError):
        return None  # not TOML: the curve reader says what it is
    if not isinstance(doc, dict) or not ({"machine", "device"} & set(doc)):
        return None
    device = doc.get("device") if isinstance(doc.get("device"), dict) else {}
    entries = device.get("curves") if isinstance(device.get("curves"), list) else []
    csvs = [f"curve {c.get('number')}: {path.parent / c['csv']}" for c in entries
            if isinstance(c, dict) and isinstance(c.get("csv"), str)]
    memory = device.get("memory_file")
    hint = f"; its cam memory is saved to {path.parent / memory} by `axisline serve`" if isinstance(memory, str) else ""
    named = f"; the CSVs it names: {', '.join(csvs)}" if csvs else ""
    return ("this is a machine file; give a saved cam memory (.json, the file device.memory_file names) "
            f"or a master,slave CSV{named}{hint}")


clm_app = _typer("Rexroth CLM1.4 tools: program, parameter, Logic Task and variable files.")
app.add_typer(clm_app, name="clm")


@clm_app.command("check")
def clm_check(
    program: Path = typer.Argument(..., help="program file (telegrams #_N... or a listing 0000 POI ...)"),
    params: Optional[Path] = typer.Option(None, "--params", help="parameter file (#_K... or B000 ...)"),
    logic: Optional[Path] = typer.Option(None, "--logic", help="Logic Task file (#_P... or 0000 LD ...)"),
    variables: Optional[Path] = typer.Option(None, "--variables", help="variable file (#_V... or V600 ...)"),
) -> None:
    """Check CLM files as the CLM would: every finding as WHERE CODE TEXT; exit 0 clean, 1 warnings, 2 errors."""
    from .devices.clm.tool import check_command

    raise typer.Exit(check_command(program, params, logic, variables, lambda s: out.print(s, markup=False, highlight=False, soft_wrap=True)))


@clm_app.command("convert")
def clm_convert(
    source: Path = typer.Argument(..., help="CLM file to read (any of the four kinds, either form)"),
    target: Path = typer.Argument(..., help="file to write (atomically; not written when SOURCE has errors)"),
    to: str = typer.Option(..., "--to", help="transfer (the serial telegrams, CR LF) or listing"),
    kind: Optional[str] = typer.Option(None, "--kind", help="program, parameters, logic or variables (default: detected)"),
) -> None:
    """Convert a CLM file between the transfer form (telegrams with checksums) and the listing form."""
    from .devices.clm.tool import convert_command

    raise typer.Exit(convert_command(source, target, to, kind, lambda s: out.print(s, markup=False, highlight=False, soft_wrap=True)))


@clm_app.command("checksum")
def clm_checksum(telegram: str = typer.Argument(..., help="telegram from its control character, e.g. '# N0101 AEA Q1.00.3 1 $C0' (_ for blanks allowed)")) -> None:
    """Print the CLM checksum of a telegram; with $hh given, say whether it is right (exit 1 if wrong)."""
    from .devices.clm.tool import checksum_command

    raise typer.Exit(checksum_command(telegram, lambda s: out.print(s, markup=False, highlight=False, soft_wrap=True)))


@clm_app.command("save")
def clm_save(
    directory: Path = typer.Argument(..., help="directory for program.txt, parameters.txt, logic.txt, variables.txt"),
    connect: str = typer.Option(..., "--connect", help="the CLM's serial endpoint HOST:PORT (axisline serve --serial-tcp)"),
    station: int = typer.Option(0, "--station", min=0, max=32, help="B003 station number (0 = RS232)"),
) -> None:
    """Back up a running CLM: read program, parameters, Logic Task and V600-V999 into transfer files."""
    from .devices.clm.client import ClmClient, parse_address
    from .devices.clm.errors import ClmError

    try:
        host, port = parse_address(connect)
        with ClmClient(host, port, station) as clm:
            files = clm.save(directory)
    except (ClmError, OSError, ValueError) as e:
        console.print(f"[red]clm save failed[/red]: {escape(str(e))}", markup=True, highlight=False)
        raise typer.Exit(2) from None
    for kind, path in files.items():
        out.print(f"{path}: {kind}", markup=False, highlight=False)


@clm_app.command("display")
def clm_display(
    connect: str = typer.Option(..., "--connect", help="the CLM's serial endpoint HOST:PORT (axisline serve --serial-tcp)"),
    screen: str = typer.Option("position", "--screen", help="position, io, variables, counters, tasks or error"),
    once: bool = typer.Option(False, "--once", help="print the screen once and exit"),
    station: int = typer.Option(0, "--station", min=0, max=32, help="B003 station number (0 = RS232)"),
    variable: int = typer.Option(600, "--variable", min=0, max=999, help="variables screen: the variable number"),
    counter: int = typer.Option(0, "--counter", min=0, max=2999, help="counters screen: the COU/BAC instruction"),
    io_bytes: str = typer.Option("I0.00,I1.00,Q1.00", "--bytes", help="io screen: bytes, comma-separated"),
    interval: float = typer.Option(0.5, "--interval", min=0.05, max=60.0, help="refresh period, s"),
) -> None:
    """Show a CTA screen of a running CLM as text, refreshed until Ctrl-C (status queries)."""
    import time

    from rich.live import Live
    from rich.text import Text

    from .devices.clm.client import SCREENS, ClmClient, parse_address
    from .devices.clm.errors import ClmError

    if screen not in SCREENS:
        console.print(f"[red]--screen[/red] = {escape(repr(screen))}: one of {', '.join(SCREENS)}")
        raise typer.Exit(2)
    wanted = tuple(b.strip() for b in io_bytes.split(",") if b.strip())
    try:
        host, port = parse_address(connect)
        with ClmClient(host, port, station) as clm:
            def lines() -> str:
                return "\n".join(clm.screen(screen, variable=variable, counter=counter, io_bytes=wanted))

            if once:
                out.print(lines(), markup=False, highlight=False)
                return
            with Live(Text(lines()), console=out, auto_refresh=False) as live:
                while True:
                    time.sleep(interval)
                    live.update(Text(lines()), refresh=True)
    except KeyboardInterrupt:
        return
    except (ClmError, OSError, ValueError) as e:
        console.print(f"[red]clm display failed[/red]: {escape(str(e))}", markup=True, highlight=False)
        raise typer.Exit(2) from None


@app.command()
def schema(out_file: Optional[Path] = typer.Option(None, "--out", help="write to this file instead of printing")) -> None:
    """Print the machine-file reference (every key: type, default, allowed range, meaning)."""
    from .schema_doc import render

    text = render()
    if out_file is None:
        print(text)
    else:
        from .kernel import atomic_write_text

        atomic_write_text(out_file, text)


@app.command()
def serve(
    machine: Path = typer.Argument(..., help="machine file (TOML)"),
    modbus: Optional[str] = typer.Option(None, "--modbus", help="Modbus TCP endpoint HOST:PORT"),
    serial_tcp: Optional[str] = typer.Option(None, "--serial-tcp", help="serial protocol over TCP HOST:PORT"),
    serial_pty: bool = typer.Option(False, "--serial-pty", help="serial protocol on a pseudo-terminal (path printed)"),
    http: Optional[str] = typer.Option(None, "--http", help="web HMI HOST:PORT (overview, scope, I/O, device, events)"),
    allow_writes: bool = typer.Option(False, "--allow-writes", help="accept writes from the network (the operator's explicit enable)"),
    token: Optional[str] = typer.Option(None, "--token", envvar="AXISLINE_HMI_TOKEN", help="the token HMI writes must send (default: a new one, printed at start)"),
    log: Optional[Path] = typer.Option(None, "--log", help="append the event log to this file as JSON lines"),
    trace_out: Optional[Path] = typer.Option(None, "--trace", help="write the scope ring when stopped (.npz; .csv beside it)"),
    report_dir: Optional[Path] = typer.Option(None, "--report", help="write the usual report (report.md, summary.json, trace, plots) when stopped"),
    duration: Optional[float] = typer.Option(None, "--duration", help="stop by itself after this many seconds"),
) -> None:
    """Run the machine on the wall clock (soft real time) with its protocol endpoints.

    The cycle runs in a process of its own; the endpoints, the web HMI and the event log run
    in a second one, so clients cannot stall the cycle. Endpoints bind to 127.0.0.1 unless a
    host is given. Writes from the network are refused unless --allow-writes is given (the
    HMI's writes also need the token). Ctrl-C or SIGTERM stops the axes with their stop
    ramps, saves what must persist and exits 0; another Ctrl-C or SIGTERM meanwhile does not
    cut the ramps short (kill -9 is the hard stop).
    """
    from .config import load_machine_file
    from .kernel import WallClock
    from .machine import Machine
    from .serve.run import ServeError, ServeOptions, offered_endpoints, serve_machine

    duration = _machine_value(duration, "--duration", "duration")
    if token is not None and not (8 <= len(token) <= 200 and token.isprintable() and " " not in token):
        console.print(f"--token: {len(token)} characters; allowed is 8..200 printable characters without spaces", markup=False)
        raise typer.Exit(2)
    _writable({"--log": log, "--trace": trace_out, "--report": report_dir and report_dir / "report.md"})
    try:
        cfg = load_machine_file(machine)
        cfg.trace.mode = "ring"  # serving has no end: the scope keeps the newest samples
        m = Machine(cfg, clock=WallClock(cfg.machine.cycle_us, busy_wait_us=cfg.realtime.busy_wait_us), source=str(machine))
    except ConfigError as e:
        raise _bad_file(e) from None
    wanted = {"modbus": _endpoint(modbus, "--modbus"), "serial-tcp": _endpoint(serial_tcp, "--serial-tcp"), "http": _endpoint(http, "--http")}
    offered = offered_endpoints(m)
    if serial_pty:
        wanted["serial-pty"] = ("pty", 0)  # checked like serial-tcp, then served by the spec's flag
    for kind, ep in wanted.items():
        base_kind = "serial-tcp" if kind == "serial-pty" else kind
        if ep is not None and base_kind not in offered:
            console.print(f"[red]--{kind}[/red]: this machine (personality {escape(repr(cfg.machine.personality))}) offers no such endpoint")
            raise typer.Exit(2)
    wanted.pop("serial-pty", None)
    if m.device is not None:
        m.device.network_writes = allow_writes
        _remove_stale_temporaries(m.device.store_paths())
    opts = ServeOptions(wanted=wanted, serial_pty=serial_pty, allow_writes=allow_writes, token=token, duration=duration,
                        log_path=log, trace_out=trace_out, report_dir=report_dir)

    def stdout(line: str) -> None:
        print(line, flush=True)

    try:
        code = serve_machine(m, str(machine), opts, say=lambda text: console.print(text, markup=False, highlight=False, soft_wrap=True), stdout=stdout)
    except ServeError as e:
        console.print(f"cannot serve: {e}", markup=False)
        raise typer.Exit(e.code) from None
    raise typer.Exit(code)


def _remove_stale_temporaries(paths: list[Path]) -> None:
    """Remove the temporary files that saves interrupted by a kill left beside the stores."""
    from .kernel.atomic import remove_stale_temporaries

    for path in paths:
        for tmp in remove_stale_temporaries(path):
            console.print(f"removed {tmp} (a save interrupted before its rename; {path} is whole)", markup=False)


from .sweep.cli import sweep as _sweep  # noqa: E402  (docs/sweep.md; dask is imported only when a sweep runs)
from .drives.cli import drives_app  # noqa: E402  (docs/drives.md)

app.command("sweep")(_sweep)
app.add_typer(drives_app, name="drives")


def main() -> None:  # pragma: no cover
    app()


if __name__ == "__main__":  # pragma: no cover
    main()
