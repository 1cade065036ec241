"""`axisline drives`: CANopen drives on a bus (the lead adds it to cli.py as a sub-app).

    axisline drives scan --interface socketcan --channel can0 [--bitrate 1000000]

Exit codes: 0 nodes listed (or none found: said so), 2 a bad option or a bus that cannot be opened.
"""

from __future__ import annotations

import json

import typer
from rich.console import Console
from rich.markup import escape

from .config import BITRATES

__all__ = ["drives_app"]

drives_app = typer.Typer(
    add_completion=False, no_args_is_help=True, rich_markup_mode=None,
    context_settings={"help_option_names": ["-h", "--help"]},
    help="CiA 402 drives over CANopen: find them on a bus.",
)
_err = Console(stderr=True)


@drives_app.callback()
def _group() -> None:
    """CiA 402 drives over CANopen: find them on a bus (a group, so `scan` stays a sub-command)."""


_out = Console()


@drives_app.command()
def scan(
    interface: str = typer.Option("socketcan", "--interface", help="python-can interface: socketcan, pcan, kvaser, virtual, ..."),
    channel: str = typer.Option("can0", "--channel", help="bus channel, e.g. can0"),
    bitrate: int = typer.Option(1_000_000, "--bitrate", help="bit rate, bit/s"),
    wait: float = typer.Option(0.5, "--wait", help="seconds to listen for answers after asking every node id"),
    as_json: bool = typer.Option(False, "--json", help="print the nodes as JSON"),
) -> None:
    """List the nodes on the bus: node id, name, profile, identity (0x1018), NMT and CiA 402 state."""
    from .bus import DriveError
    from .scan import HEADER, scan as run_scan

    if bitrate not in BITRATES:
        _err.print(f"[red]--bitrate[/red] = {bitrate}: not a CANopen bit rate (allowed: {', '.join(str(b) for b in BITRATES)})")
        raise typer.Exit(2)
    if not 0.0 < wait <= 60.0:
        _err.print(f"[red]--wait[/red] = {wait:g}: allowed 0 < wait <= 60 s")
        raise typer.Exit(2)
    try:
        nodes = run_scan(interface, channel, bitrate, wait=wait)
    except DriveError as e:
        for p in e.problems:
            _err.print(escape(p), highlight=False)
        raise typer.Exit(2) from None
    if as_json:
        _out.print_json(json.dumps([dict(zip(HEADER, n.row())) for n in nodes]))
        return
    if not nodes:
        _out.print(f"no CANopen node answered on {interface}:{channel} at {bitrate} bit/s", highlight=False)
        return
    # plain columns, one line a node (grep-able, never folded to the terminal's width)
    rows = [HEADER] + [n.row() for n in nodes]
    widths = [max(len(r[i]) for r in rows) for i in range(len(HEADER))]
    print(f"{interface}:{channel}, {bitrate} bit/s: {len(nodes)} node{'s' if len(nodes) != 1 else ''}")
    for r in rows:
        print("  ".join(cell.ljust(w) for cell, w in zip(r, widths)).rstrip())
