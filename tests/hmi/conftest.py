"""Fixtures of the HMI tests: a real Machine on the simulated clock behind the HMI app.

`hmi(path, writes_allowed=..., token=...)` builds the machine, its MachineView, the app and a
TestClient; `call` runs MachineView.call at once and hands back a completed Future, which is
what the cycle does at its next boundary in `serve`.
"""

from __future__ import annotations

from concurrent.futures import Future
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import pytest
from fastapi.testclient import TestClient

from axisline.config import load_machine_file
from axisline.hmi.app import create_app
from axisline.hmi.view import MachineView
from axisline.machine import Machine

from .eventlog import event_log

ROOT = Path(__file__).resolve().parents[2]
HERE = Path(__file__).resolve().parent
POSITIONING = ROOT / "examples" / "positioning.toml"
FLYING_SHEAR = ROOT / "examples" / "flying_shear.toml"
FAULT_MACHINE = HERE / "fault_machine.toml"
TOKEN = "s3cret-token"


@dataclass
class Hmi:
    machine: Machine
    view: MachineView
    events: Any
    client: TestClient

    def run(self, cycles: int) -> None:
        self.machine.scheduler.run(cycles)

    def write(self, body: Any, token: str | None = TOKEN) -> Any:
        headers = {"X-Axisline-Token": token} if token is not None else {}
        return self.client.post("/api/write", json=body, headers=headers)

    def kinds(self, kind: str) -> list[dict[str, Any]]:
        return [e for e in self.events.recent(0, 10000) if e["kind"] == kind]


def build_machine(path: Path) -> Machine:
    return Machine(load_machine_file(path), source=str(path))


def direct_call(view: MachineView):
    def call(method: str, args: dict[str, Any], who: str) -> Future:
        fut: Future = Future()
        try:
            fut.set_result(view.call(method, args, who))
        except Exception as e:
            fut.set_exception(e)
        return fut

    return call


@pytest.fixture
def hmi():
    clients = []

    def make(path: Path = POSITIONING, *, writes_allowed: bool = True, token: str | None = TOKEN) -> Hmi:
        machine = build_machine(path)
        events = event_log()
        view = MachineView(machine, events.emit)
        app = create_app(direct_call(view), events, writes_allowed=writes_allowed, token=token)
        client = TestClient(app, raise_server_exceptions=False)
        clients.append(client)
        return Hmi(machine, view, events, client)

    yield make
    for c in clients:
        c.close()
