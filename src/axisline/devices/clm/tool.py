"""The `axisline clm` commands: check, convert, checksum (bytes and files in, text and exit codes out)."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

from .check import check_files, exit_status
from .files import KINDS, read_file, write_file
from .telegram import checksum

__all__ = ["check_command", "checksum_command", "convert_command"]

Print = Callable[[str], None]


def check_command(program: Path, params: Path | None, logic: Path | None, variables: Path | None, say: Print) -> int:
    """Print every finding; 0 clean, 1 warnings only, 2 errors."""
    findings = check_files(program, params, logic, variables)
    for f in findings:
        say(str(f))
    status = exit_status(findings)
    errors = sum(f.is_error for f in findings)
    say({0: "clean: no findings", 1: f"{len(findings)} warning(s), no errors"}.get(status, f"{errors} error(s), {len(findings) - errors} warning(s)"))
    return status


def convert_command(source: Path, target: Path, form: str, kind: str | None, say: Print) -> int:
    """Convert a program / parameter / Logic Task / variable file; nothing is written on errors."""
    if form not in ("transfer", "listing"):
        say(f"--to = {form!r}: transfer or listing")
        return 2
    if kind is not None and kind not in KINDS:
        say(f"--kind = {kind!r}: one of {', '.join(KINDS)}")
        return 2
    loaded = read_file(source, kind)
    for f in loaded.findings:
        say(str(f))
    if not loaded.ok:
        say(f"{target}: not written ({source} has errors)")
        return 2
    try:
        write_file(target, loaded, form)
    except OSError as e:
        say(f"{target}: cannot be written ({e.strerror})")
        return 2
    say(f"{target}: {loaded.kind} written as {form}")
    return 0


def checksum_command(telegram: str, say: Print) -> int:
    """Print the checksum of a telegram; with a `$hh`, say whether it is right (exit 1 if not)."""
    text = telegram.rstrip("\r\n")
    if " " not in text and "_" in text:
        text = text.replace("_", " ")  # the manual's notation
    given = None
    if "$" in text:
        text, given = text[: text.rindex("$")], text[text.rindex("$") + 1 :].strip().upper()
    if not text or not text.isascii():
        say("a telegram is ASCII text from the control character (?, #, !, :) to the last character before $")
        return 2
    computed = checksum(text)
    if given is None:
        say(computed)
        return 0
    if given == computed:
        say(f"{computed}: ${given} is right")
        return 0
    say(f"{computed}: ${given} is wrong (X01:04 RS Checksum Error)")
    return 1
