"""The event log: JSON lines, recent events, and a console that never holds up the machine."""

from __future__ import annotations

import json
import threading

from axisline.serve.events import EventLog


def test_events_go_to_the_json_file_and_are_kept_for_the_hmi(tmp_path):
    lines: list[str] = []
    log = EventLog(console=lines.append, json_path=tmp_path / "ev.jsonl")
    log.emit("connect", "modbus 127.0.0.1:5 connected", who="modbus 127.0.0.1:5", endpoint="modbus")
    log.emit("write", "w", who="x", changes=[{"what": "r", "old": 1, "new": 2}], accepted=True, nan=float("nan"))
    log.close()
    saved = [json.loads(line) for line in (tmp_path / "ev.jsonl").read_text().splitlines()]
    assert [e["seq"] for e in saved] == [1, 2] and saved[1]["changes"][0]["new"] == 2
    assert saved[1]["nan"] is None  # strict JSON
    assert [e["kind"] for e in log.recent(after=1)] == ["write"]
    assert "connect" in lines[0] and "modbus 127.0.0.1:5 connected" in lines[0]


def test_a_console_that_does_not_read_never_holds_up_an_emit():
    stuck = threading.Event()

    def console(line: str) -> None:
        stuck.wait()  # a terminal nobody reads

    log = EventLog(console=console, keep=10)
    done = threading.Event()

    def emit_many() -> None:
        for i in range(20_000):  # more than the console backlog
            log.emit("note", f"event {i}")
        done.set()

    threading.Thread(target=emit_many, daemon=True).start()
    assert done.wait(60)  # every emit returned although the console never took a line
    assert log.dropped > 0 and log.last_seq == 20_000
    assert len(log.recent(limit=100)) == 10  # the newest `keep` are kept
    stuck.set()
    log.close()
