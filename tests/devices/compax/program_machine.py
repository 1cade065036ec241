"""Helpers for the program tests (no tests here): a COMPAX machine on the internal time base whose
program is loaded over the ASCII interface as a host would, run cycle by cycle."""

from __future__ import annotations

from typing import Any

import numpy as np

from axisline.config import parse_machine
from axisline.machine import Machine

MASTER_SPEED = 5.0  # P35: 500 master cycles of 360 per minute (120 ms per cycle)


def straight(number: int, slave_end: float, points: int = 2) -> dict:
    """A curve from 0 to `slave_end` over M_T = 360, constant gradient."""
    return {"number": number, "master_period": 360.0, "points": points,
            "segments": [{"master_end": 360.0, "slave_end": slave_end, "law": "constant_velocity"}]}


def open_segment(number: int, middle: float, end: float) -> dict:
    """An open curve with gradient 1 at both borders and a different speed in between (§15.2
    example 2: "curve segments which do not have acceleration or speed zero at the curve borders")."""
    return {"number": number, "master_period": 360.0, "points": 361, "segments": [
        {"master_end": 90.0, "slave_end": 90.0, "law": "constant_velocity"},
        {"master_end": 270.0, "slave_end": middle, "law": "auto"},
        {"master_end": 360.0, "slave_end": end, "law": "constant_velocity"}]}


def doffing(number: int, stroke: float) -> dict:
    """A curve with standstill phases at both ends moving the slave by `stroke` (§15.2 example 1)."""
    return {"number": number, "master_period": 360.0, "points": 361, "segments": [
        {"master_end": 60.0, "slave_end": 0.0, "law": "dwell"},
        {"master_end": 300.0, "slave_end": stroke, "law": "poly345"},
        {"master_end": 360.0, "slave_end": stroke, "law": "dwell"}]}


def build(curves: list[dict], parameters: dict[str, Any] | None = None, inputs: dict[str, Any] | None = None,
          io_inputs: tuple[str, ...] = (), **device: Any) -> Machine:
    """The slave "s" (deg) on the internal time base; I16 on the io input "master" (the
    master counts from its rising edge after SETC, §10.1 "Stationary master"), I13 = 1."""
    data = {
        "machine": {"personality": "compax", "duration": 60.0},
        "axis": [{"name": "s", "unit": "deg", "counts_per_unit": 100.0, "v_max": 20000.0, "a_max": 1e7,
                  "kv": 80.0, "following_error_limit": 50.0, "drive": {"type": "servo", "time_constant": 0.001}}],
        "io": {"inputs": ["master", *io_inputs], "outputs": ["o7"]},
        "device": {"slave": "s", "master": "internal",
                   "parameters": {"P35": MASTER_SPEED, "P93": 1, **(parameters or {})},
                   "inputs": {"I13": True, "I16": "master", **(inputs or {})},
                   "curves": curves, **device},
        "trace": {"enabled": False},
    }
    m = Machine(parse_machine(data, "t.toml"), source="")
    m.device.network_writes = True
    return m


def send(m: Machine, *lines: str) -> list[bytes]:
    """Lines over the device's ASCII interface (a host's session); the replies."""
    ep = m.device.byte_endpoint()
    return [ep.feed(line.encode("ascii") + b"\r") for line in lines]


def load(m: Machine, lines: list[str]) -> None:
    for line, reply in zip(lines, send(m, *lines)):
        assert reply == b"\r\n>", (line, reply)


class Run:
    """Cycles of a machine with the slave's set point and speed recorded."""

    def __init__(self, m: Machine) -> None:
        self.m = m
        self.p: list[float] = []
        self.v: list[float] = []

    def cycles(self, n: int, until: Any = None) -> None:
        ax = self.m.device.axis
        for _ in range(n):
            self.m.scheduler.run_cycle()
            self.p.append(ax.command_position)
            self.v.append(ax.command_velocity)
            if until is not None and until():
                return

    def master_on(self) -> None:
        self.m.io.set_input("master", True)

    def speed_steps(self) -> np.ndarray:
        return np.abs(np.diff(np.asarray(self.v)))

    @property
    def log(self) -> list[dict]:
        return self.m.device.run.log
