"""The device guides show how to connect with ordinary tools (socat, mbpoll) with transcripts
taken from real sessions; this test keeps them true by replaying every transcript on the same
machine file, in process (issue 16).

A transcript is a ```console block whose first line is the command, preceded by a comment
naming the machine file and how the replies read on the terminal:

    <!-- transcript: examples/cam_packaging.toml prompt -->     a reply ends with the '>' prompt
    <!-- transcript: examples/roll_feed_clm.toml lines -->      one reply line per typed line
    <!-- transcript: examples/wago_stepper.toml mbpoll -->      mbpoll's "[n]: value" lines

Replies whose value changes while the machine runs are not shown in transcripts; the machine
here stands at power on (no cycle run), as `serve` does before the first client."""

from __future__ import annotations

import re
import shlex
from pathlib import Path

import pytest

from axisline.machine import Machine

ROOT = Path(__file__).resolve().parent.parent
_BLOCK = re.compile(r"<!-- transcript: (\S+) (prompt|lines|mbpoll) -->\s*```console\n(.*?)```", re.S)


def _transcripts() -> list[tuple[str, str, str, str]]:
    out = []
    for doc in sorted((ROOT / "docs").glob("*.md")):
        for m in _BLOCK.finditer(doc.read_text()):
            out.append((doc.name, m.group(1), m.group(2), m.group(3)))
    return out


TRANSCRIPTS = _transcripts()


def test_every_device_guide_has_a_transcript():
    guides = {name for name, *_ in TRANSCRIPTS}
    assert {"compax.md", "clm.md", "wago672-modbus.md", "fs701.md"} <= guides


def _exchanges_prompt(lines: list[str]) -> list[tuple[str, list[str]]]:
    """Typed line, reply lines, '>' + the next typed line, ... (socat with crnl)."""
    out: list[tuple[str, list[str]]] = []
    typed: str | None = lines[0]
    reply: list[str] = []
    for line in lines[1:]:
        if line.startswith(">"):
            out.append((typed or "", reply))
            typed, reply = line[1:], []
        else:
            reply.append(line)
    return out


@pytest.mark.parametrize("doc, machine, style, body", TRANSCRIPTS, ids=[f"{t[0]}:{i}" for i, t in enumerate(TRANSCRIPTS)])
def test_transcript_replays(doc, machine, style, body):
    lines = body.rstrip("\n").split("\n")
    command, lines = lines[0], lines[1:]
    assert command.startswith("$ ")
    m = Machine.from_file(ROOT / machine)
    if style == "mbpoll":
        args = shlex.split(command[2:])
        reference = int(args[args.index("-r") + 1])
        count = int(args[args.index("-c") + 1])
        kind = {"3": "input", "4": "holding"}[args[args.index("-t") + 1]]
        base = 0 if "-0" in args else 1
        shown = [tuple(map(int, re.match(r"\[(\d+)\]:\s+(\d+)", line).groups())) for line in lines if line.startswith("[")]
        assert len(shown) == count
        values = m.device.register_endpoint().read_registers(kind, reference - base, count)
        assert shown == [(reference + i, v) for i, v in enumerate(values)]
        return
    session = m.device.byte_endpoint().session()
    if style == "prompt":  # socat crnl: a typed line goes out with CR LF, CR LF comes back as LF
        for typed, reply in _exchanges_prompt(lines):
            got = session.feed(typed.encode() + b"\r\n").decode("ascii")
            assert got.replace("\r\n", "\n") == "".join(r + "\n" for r in reply) + ">"
    else:  # one reply line per typed line
        for typed, reply in zip(lines[0::2], lines[1::2]):
            got = session.feed(typed.encode() + b"\r\n").decode("ascii")
            assert got.replace("\r\n", "\n") == reply + "\n"
