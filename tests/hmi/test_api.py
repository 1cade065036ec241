"""The HMI's JSON API on a real Machine (simulated clock): read-outs, the scope's sample
numbers, writes and acknowledge with their safety checks and events (issue 17)."""

from __future__ import annotations

import math
import types
from concurrent.futures import Future

import httpx
import pytest
from fastapi.testclient import TestClient
from starlette.websockets import WebSocketDisconnect

from axisline.hmi import app as app_module
from axisline.hmi import view as view_module
from axisline.hmi.app import create_app
from axisline.hmi.server import HmiServer
from axisline.hmi.view import HmiRefused

from .conftest import FAULT_MACHINE, FLYING_SHEAR, POSITIONING, TOKEN, direct_call
from .eventlog import EventLog


# -- read-outs ---------------------------------------------------------------------------


def test_overview_shows_every_axis_as_the_machine_has_it(hmi):
    h = hmi(POSITIONING)
    h.run(1500)  # the job powers both axes and starts their moves
    o = h.client.get("/api/overview").json()
    m = h.machine
    assert o["name"] == m.config.machine.name
    assert o["cycle"] == 1500 and o["time"] == pytest.approx(1.5)
    assert [a["name"] for a in o["axes"]] == list(m.units)
    for a in o["axes"]:
        ax = m.units[a["name"]].axis
        assert a["state"] == ax.state.value
        assert a["position"] == pytest.approx(ax.actual_position)
        assert a["following_error"] == pytest.approx(ax.following_error)
        assert a["unit"] == m.units[a["name"]].config.unit
    x = next(a for a in o["axes"] if a["name"] == "x")
    assert x["state"] == "DiscreteMotion" and x["velocity"] > 0


def test_channels_name_the_trace_channels_with_units(hmi):
    h = hmi(POSITIONING)
    ch = h.client.get("/api/channels").json()
    tr = h.machine.trace
    assert [c["name"] for c in ch["channels"]] == list(tr.channels)
    units = {c["name"]: c["unit"] for c in ch["channels"]}
    assert units["x.actual_position"] == "mm" and units["r.command_velocity"] == "deg/s"
    assert ch["period_s"] == pytest.approx(0.001)


def test_scope_returns_the_new_samples_and_the_next_number(hmi):
    h = hmi(POSITIONING)
    h.run(300)
    first = h.client.get("/api/scope", params={"channels": "x.command_position,r.state", "since": 0}).json()
    assert first["since"] == 0 and first["next"] == 300 and first["skipped"] == 0
    assert len(first["t"]) == 300 and len(first["data"]["x.command_position"]) == 300
    h.run(120)
    more = h.client.get("/api/scope", params={"channels": "x.command_position", "since": first["next"]}).json()
    assert more["since"] == 300 and more["next"] == 420 and len(more["t"]) == 120
    trace = h.machine.trace.data()
    assert more["data"]["x.command_position"] == trace["x.command_position"][300:420].tolist()
    assert more["t"] == pytest.approx(trace["t"][300:420].tolist())
    again = h.client.get("/api/scope", params={"channels": "x.command_position", "since": more["next"]}).json()
    assert again["t"] == [] and again["next"] == 420


def test_scope_far_behind_skips_to_the_newest(hmi):
    """view.py decision 2: a live scope gets the newest `limit` samples, not the backlog."""
    h = hmi(FAULT_MACHINE)  # a ring of 20000 samples
    h.run(500)
    block = h.client.get("/api/scope", params={"channels": "y.command_position", "since": 100, "limit": 50}).json()
    assert block["since"] == 450 and block["next"] == 500 and block["skipped"] == 350
    assert block["data"]["y.command_position"] == h.machine.trace.data()["y.command_position"][450:].tolist()


def test_scope_refuses_an_unknown_channel_naming_it(hmi):
    h = hmi(POSITIONING)
    r = h.client.get("/api/scope", params={"channels": "x.nonsense", "since": 0})
    assert r.status_code == 400
    assert "x.nonsense" in r.json()["error"] and "channels" in r.json()["error"]
    r = h.client.get("/api/scope", params={"channels": "x.command_position", "since": -1})
    assert r.status_code == 422 and "since" in r.json()["error"]


def test_io_image_lists_inputs_outputs_and_forcing(hmi):
    h = hmi(FAULT_MACHINE)
    h.machine.io.force("start", True)
    h.run(2)
    io = h.client.get("/api/io").json()
    assert [i["name"] for i in io["inputs"]] == ["door_closed", "start"]
    assert io["inputs"][1] == {"name": "start", "value": True, "forced": True}
    assert io["inputs"][0] == {"name": "door_closed", "value": False, "forced": None}
    assert io["outputs"] == [{"name": "lamp", "value": False, "forced": None}]
    assert io["sensors"] == [{"name": "x.ref", "value": h.machine.sensors["x.ref"].state}]


# -- writes ----------------------------------------------------------------------------------

FORCE_DOOR = {"target": "io", "name": "door_closed", "value": True}


def test_write_refused_without_writes_allowed(hmi):
    h = hmi(FAULT_MACHINE, writes_allowed=False, token=None)
    r = h.write(FORCE_DOOR)
    assert r.status_code == 403 and "read-only" in r.json()["error"] and "--allow-writes" in r.json()["error"]
    assert h.machine.io.forced == {}
    ev = h.kinds("write")[-1]
    assert ev["accepted"] is False and "read-only" in ev["reason"]
    # a read-only HMI says so whatever the body (app.py decision 1)
    assert h.client.post("/api/write", content=b"{nonsense").status_code == 403
    assert h.client.post("/api/acknowledge").status_code == 403


@pytest.mark.parametrize("token", [None, "wrong"])
def test_write_refused_without_the_token(hmi, token):
    h = hmi(FAULT_MACHINE)
    r = h.write(FORCE_DOOR, token=token)
    assert r.status_code == 403 and "X-Axisline-Token" in r.json()["error"]
    assert h.machine.io.forced == {}
    assert h.kinds("write")[-1]["accepted"] is False


def test_write_with_a_bad_value_is_refused_and_changes_nothing(hmi):
    h = hmi(FAULT_MACHINE)
    r = h.write({"target": "io", "name": "door_closed", "value": "maybe"})
    assert r.status_code == 400
    assert "'maybe'" in r.json()["error"] and "door_closed" in r.json()["error"]
    assert h.machine.io.forced == {}
    ev = h.kinds("write")[-1]
    assert ev["accepted"] is False and ev["name"] == "door_closed" and "maybe" in ev["reason"]
    r = h.write({"target": "io", "name": "no_such_input", "value": True})
    assert r.status_code == 404 and "no_such_input" in r.json()["error"]


def test_io_output_force_refused(hmi):
    """view.py decision 1: the HMI forces inputs only."""
    h = hmi(FAULT_MACHINE)
    r = h.write({"target": "io", "name": "lamp", "value": True})
    assert r.status_code == 400 and "lamp" in r.json()["error"] and "output" in r.json()["error"]
    assert h.machine.io.forced == {}


def test_bad_json_and_missing_fields_are_named(hmi):
    h = hmi(FAULT_MACHINE)
    headers = {"X-Axisline-Token": TOKEN}
    r = h.client.post("/api/write", content=b"{nonsense", headers=headers)
    assert r.status_code == 400 and r.json()["error"].startswith("body: not JSON")
    r = h.client.post("/api/write", json={"target": "io", "name": "door_closed"}, headers=headers)
    assert r.status_code == 422 and "value" in r.json()["error"] and "required" in r.json()["error"]
    r = h.client.post("/api/write", json={"target": "axis", "name": "x", "value": 1}, headers=headers)
    assert r.status_code == 422 and "target" in r.json()["error"] and "'axis'" in r.json()["error"]
    assert h.machine.io.forced == {}


def test_write_accepted_with_the_token_changes_the_input_and_is_an_event(hmi):
    h = hmi(FAULT_MACHINE)
    r = h.write(FORCE_DOOR)
    assert r.status_code == 200, r.text
    assert r.json()["old"] == "False" and r.json()["new"] == "forced True"
    h.run(1)  # the image takes the forced value at the next sample
    assert h.machine.io.read("door_closed") is True
    ev = h.kinds("write")[-1]
    assert ev["accepted"] is True and ev["old"] == "False" and ev["new"] == "forced True"
    assert ev["who"].startswith("hmi ") and "door_closed" in ev["message"] and "->" in ev["message"]
    r = h.write({"target": "io", "name": "door_closed", "value": None})  # release
    assert r.status_code == 200 and (r.json()["old"], r.json()["new"]) == ("forced True", "not forced")
    assert h.machine.io.forced == {}


def test_acknowledge_resets_a_tripped_axis(hmi):
    """view.py decision 3: one acknowledge resets every axis in ErrorStop."""
    h = hmi(FAULT_MACHINE)
    h.run(300)
    x = h.machine.units["x"].axis
    assert x.state.value == "ErrorStop"
    o = h.client.get("/api/overview").json()
    assert "following error" in next(a for a in o["axes"] if a["name"] == "x")["error"]
    r = h.client.post("/api/acknowledge", headers={"X-Axisline-Token": TOKEN})
    assert r.status_code == 200 and [a["axis"] for a in r.json()["axes"]] == ["x"]
    h.run(5)
    assert x.state.value == "Standstill" and x.error_id == 0
    ev = h.kinds("acknowledge")[-1]
    assert ev["axes"] == ["x"] and ev["who"].startswith("hmi ")


# -- the device view ---------------------------------------------------------------------------


def test_device_view_without_a_personality_is_empty(hmi):
    h = hmi(POSITIONING)
    assert h.client.get("/api/device").json()["sections"] == []
    r = h.write({"target": "device", "name": "anything", "value": 1})
    assert r.status_code == 404 and "no device personality" in r.json()["error"]


class _FakeDevices(types.ModuleType):
    """A device-view module with one writable parameter 0..100."""

    def __init__(self) -> None:
        super().__init__("fake_devices")
        self.values = {"length": 10}
        self.acknowledged = 0

    def device_view(self, p):
        return {"title": "fake", "sections": [{"type": "parameters", "title": "P", "rows": [
            {"name": "length", "label": "Length", "value": self.values["length"], "unit": "mm", "min": 0, "max": 100, "writable": True}]}]}

    def device_write(self, p, name, value):
        if name != "length":
            raise ValueError(f"{name}: no such parameter")
        if not isinstance(value, (int, float)) or not 0 <= value <= 100:
            raise ValueError(f"length = {value!r}: allowed 0..100 mm")
        old, self.values["length"] = self.values["length"], value
        return old, value

    def device_acknowledge(self, p):
        self.acknowledged += 1
        return "device errors cleared"


def test_device_writes_go_through_the_device_module(hmi, monkeypatch):
    fake = _FakeDevices()
    monkeypatch.setattr(view_module, "_devices_module", lambda: fake)
    h = hmi(FLYING_SHEAR)
    assert h.client.get("/api/device").json()["sections"][0]["rows"][0]["value"] == 10
    r = h.write({"target": "device", "name": "length", "value": 500})
    assert r.status_code == 400 and "0..100" in r.json()["error"]
    assert fake.values["length"] == 10
    assert h.kinds("write")[-1]["accepted"] is False
    r = h.write({"target": "device", "name": "length", "value": 42})
    assert r.status_code == 200 and r.json()["old"] == 10 and r.json()["new"] == 42
    ev = h.kinds("write")[-1]
    assert ev["accepted"] is True and (ev["old"], ev["new"]) == (10, 42)
    r = h.client.post("/api/acknowledge", headers={"X-Axisline-Token": TOKEN})
    assert r.json()["device"] == "device errors cleared" and fake.acknowledged == 1


def test_fs701_device_page_is_the_device_modules_view(hmi):
    devices = pytest.importorskip("axisline.hmi.devices")
    h = hmi(FLYING_SHEAR)
    h.run(10)
    view = h.client.get("/api/device").json()
    assert view == view_module.jsonable(devices.device_view(h.machine.device))
    assert "FS701" in view["title"] and any(s["type"] == "parameters" for s in view["sections"])


# -- the HTTP side ---------------------------------------------------------------------------


def test_unknown_pages_are_json_404(hmi):
    h = hmi(POSITIONING)
    r = h.client.get("/nowhere")
    assert r.status_code == 404 and "/nowhere" in r.json()["error"]
    assert h.client.get("/api/nothing").status_code == 404
    for page in ("/", "/scope", "/io", "/device", "/events"):
        r = h.client.get(page)
        assert r.status_code == 200 and r.headers["content-type"].startswith("text/html")
    assert h.client.get("/static/scope.js").status_code == 200


def test_no_cors_header(hmi):
    h = hmi(POSITIONING)
    evil = {"Origin": "http://evil.example"}
    r = h.client.get("/api/overview", headers=evil)
    assert r.status_code == 200 and "access-control-allow-origin" not in r.headers
    r = h.client.options("/api/write", headers={**evil, "Access-Control-Request-Method": "POST",
                                                "Access-Control-Request-Headers": "x-axisline-token"})
    assert "access-control-allow-origin" not in r.headers and "access-control-allow-headers" not in r.headers


def test_websocket_from_a_foreign_origin_is_closed(hmi):
    """app.py decision 2."""
    h = hmi(POSITIONING)
    with pytest.raises(WebSocketDisconnect) as closed:
        with h.client.websocket_connect("/ws/scope", headers={"Origin": "http://evil.example"}) as ws:
            ws.receive_json()
    assert closed.value.code == 1008


def test_scope_websocket_sends_sample_blocks(hmi):
    h = hmi(POSITIONING)
    h.run(200)
    with h.client.websocket_connect("/ws/scope", headers={"Origin": "http://testserver"}) as ws:
        ws.send_json({"channels": ["x.command_position"], "since": None, "limit": 100})
        block = ws.receive_json()
        assert block["next"] == 200 and len(block["t"]) == 100 and block["skipped"] == 100
        ws.send_json({"channels": ["x.bogus"], "since": None})
        assert "x.bogus" in ws.receive_json()["error"]
    assert [e["kind"] for e in h.events.recent()][-2:] == ["connect", "disconnect"]


def test_events_websocket_and_api(hmi):
    h = hmi(FAULT_MACHINE)
    h.write(FORCE_DOOR)
    assert h.client.get("/api/events").json()["events"][-1]["kind"] == "write"
    with h.client.websocket_connect("/ws/events") as ws:
        got = ws.receive_json()["events"]
        assert got[-1]["kind"] == "write" and got[-1]["accepted"] is True


def test_a_machine_that_does_not_answer_is_503(monkeypatch):
    monkeypatch.setattr(app_module, "REPLY_TIMEOUT", 0.05)
    pending: list[Future] = []

    def never(method, args, who):
        pending.append(Future())
        return pending[-1]

    with TestClient(create_app(never, EventLog(), writes_allowed=False, token=None)) as client:
        r = client.get("/api/overview")
    assert r.status_code == 503 and "nothing was done" in r.json()["error"]
    assert pending[0].cancelled()


def test_a_failing_machine_answer_is_json_500_without_traceback():
    def broken(method, args, who):
        fut: Future = Future()
        fut.set_exception(RuntimeError("boom"))
        return fut

    with TestClient(create_app(broken, EventLog(), writes_allowed=False, token=None), raise_server_exceptions=False) as client:
        r = client.get("/api/io")
    assert r.status_code == 500 and "boom" in r.json()["error"] and "Traceback" not in r.text


def test_refusal_crosses_a_process_boundary():
    import pickle

    e = pickle.loads(pickle.dumps(HmiRefused("name: nope", 404)))
    assert (e.message, e.status, str(e)) == ("name: nope", 404, "name: nope")


def test_view_answers_are_strict_json():
    assert view_module.jsonable({"a": math.nan, "b": [math.inf, 1.5], "c": (1, True)}) == {"a": None, "b": [None, 1.5], "c": [1, True]}


def test_server_listens_and_stops(hmi):
    h = hmi(POSITIONING)
    srv = HmiServer(direct_call(h.view), EventLog(), writes_allowed=True).start()
    try:
        host, port = srv.address
        assert host == "127.0.0.1" and port > 0 and srv.token
        r = httpx.get(f"http://{host}:{port}/api/overview", timeout=5)
        assert r.status_code == 200 and len(r.json()["axes"]) == 2
        assert httpx.get(f"http://localhost:{port}/api/info", timeout=5).status_code == 200
        # DNS rebinding: another site's page whose name now points at 127.0.0.1 sends its own Host
        rebound = httpx.get(f"http://{host}:{port}/api/overview", headers={"Host": f"evil.example:{port}"}, timeout=5)
        assert rebound.status_code == 400 and "axes" not in rebound.text
        with pytest.raises(OSError, match=f"cannot listen on 127.0.0.1:{port}"):
            HmiServer(direct_call(h.view), EventLog(), port=port).start()
    finally:
        srv.stop()
    with pytest.raises(httpx.ConnectError):
        httpx.get(f"http://{host}:{port}/api/info", timeout=2)


def test_scope_sends_a_non_finite_sample_as_null():
    from types import SimpleNamespace

    from axisline.kernel import Trace

    values = iter([1.0, math.nan, math.inf, 2.0])
    tr = Trace(8, mode="ring")
    tr.add_channel("v", lambda: next(values), unit="mm")
    for cycle in range(4):
        tr.record(cycle)
    view = view_module.MachineView(SimpleNamespace(trace=tr), lambda *a, **k: None)
    block = view.call("scope", {"channels": ["v"], "since": 0}, "test")
    assert block["data"]["v"] == [1.0, None, None, 2.0] and block["next"] == 4


def test_a_stopped_machine_is_503_not_500():
    def gone(method, args, who):
        fut: Future = Future()
        fut.set_exception(ConnectionError("the machine stopped before answering"))
        return fut

    with TestClient(create_app(gone, EventLog(), writes_allowed=False, token=None)) as client:
        r = client.get("/api/overview")
    assert r.status_code == 503 and "not running" in r.json()["error"]


def test_a_personality_without_a_device_view_says_so(hmi, monkeypatch):
    def no_view(p):
        raise ValueError("personality 'new' has no device view (views: clm, compax, fs701, wago672)")

    fake = _FakeDevices()
    fake.device_view = no_view
    monkeypatch.setattr(view_module, "_devices_module", lambda: fake)
    h = hmi(FLYING_SHEAR)
    r = h.client.get("/api/device")
    assert r.status_code == 404 and "has no device view" in r.json()["error"]
