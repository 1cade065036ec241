"""Test helpers for what is served: `axisline serve` in a subprocess, and a command queue that
keeps the submissions of a protocol server (to wait until the cycle ran them)."""

from __future__ import annotations

import subprocess
import sys
import time


def serve(*args: str, cwd=None) -> tuple[subprocess.Popen, dict[str, str]]:
    """Start `axisline serve`; return it once it printed "ready", with its endpoints."""
    proc = subprocess.Popen([sys.executable, "-m", "axisline.cli", "serve", *args],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, cwd=cwd)
    endpoints = {}
    assert proc.stdout is not None
    for line in proc.stdout:
        kind, _, where = line.strip().partition(" ")
        if kind == "ready":
            return proc, endpoints
        endpoints[kind] = where
    proc.kill()
    raise AssertionError(f"serve did not start: {proc.stderr.read() if proc.stderr else ''}")


class Fed:
    """The machine's command queue, keeping the server's submissions (to wait until one ran)."""

    def __init__(self, commands) -> None:
        self.commands = commands
        self.futures: list = []

    def submit(self, fn, *args):
        future = self.commands.submit(fn, *args)
        self.futures.append(future)
        return future

    def wait(self, n: int) -> None:
        deadline = time.monotonic() + 5
        while not (len(self.futures) >= n and all(f.done() for f in self.futures)):
            assert time.monotonic() < deadline, "the cycle did not take the bytes"
            time.sleep(0.005)
