"""The pipe between serve's cycle process and its endpoint process (serve/link.py), here with
both ends in one process: the cycle end is pumped by the test, as the WallClock's idle does."""

from __future__ import annotations

import multiprocessing
import threading
import time

import pytest

from axisline.fieldbus.modbus import RegisterRefused
from axisline.kernel import requests
from axisline.serve.audit import Audit
from axisline.serve.link import CycleLink, EndpointLink, LinkClosed, RemoteCommands, RemoteEndpoint, RemoteError


class Registers:
    def __init__(self) -> None:
        self.regs = [0] * 16
        self.calls = 0

    def read_registers(self, kind: str, address: int, count: int) -> list[int]:
        self.calls += 1
        return self.regs[address:address + count]

    def write_registers(self, address: int, values: list[int]) -> None:
        if address + len(values) > len(self.regs):
            raise RegisterRefused(f"registers {address}..{address + len(values) - 1}: the map ends at 15", 3)
        if any(v > 1000 for v in values):
            raise ValueError(f"value {max(values)} out of range 0..1000")
        self.regs[address:address + len(values)] = values


class Device:
    """A byte endpoint with a write gate, as the personalities have."""

    def __init__(self) -> None:
        self._network_writes = True
        self.params = {"speed": 10}

    @property
    def network_writes(self) -> bool:
        requests.note_write_gate()
        return self._network_writes

    def session(self):
        device = self

        class Session:
            buffer = b""

            def feed(self, data: bytes) -> bytes:
                self.buffer += data
                if b"=" in data:
                    if not device.network_writes:
                        return b"E1\r"
                    device.params["speed"] = int(data.split(b"=")[1])
                return b"ok:" + self.buffer + b"\r"

            def unpicklable(self):
                return threading.Lock()

        return Session()


@pytest.fixture
def link():
    req_in, req_out = multiprocessing.Pipe(duplex=False)
    rep_in, rep_out = multiprocessing.Pipe(duplex=False)
    regs, device, events = Registers(), Device(), []
    cycle = CycleLink(req_in, rep_out, {"register": lambda: regs, "byte": lambda: device.session.__self__})
    cycle.audit = Audit(device, cycle.emit, image=lambda: dict(device.params))
    endpoint = EndpointLink(rep_in, req_out, on_event=lambda kind, message, fields: events.append((kind, message, fields))).start()
    stop = threading.Event()

    def pump() -> None:  # the cycle process's idle time, every millisecond
        while not stop.is_set():
            cycle.pump(time.perf_counter() + 0.0005)
            time.sleep(0.001)

    pumper = threading.Thread(target=pump, daemon=True)
    pumper.start()
    yield endpoint, cycle, regs, device, events
    stop.set()
    pumper.join()
    cycle.close()


def _wait(events, n):
    deadline = time.monotonic() + 5
    while len(events) < n:
        assert time.monotonic() < deadline, events
        time.sleep(0.005)


def test_a_call_is_answered_by_the_cycle_process_object(link):
    endpoint, _, regs, _, _ = link
    regs.regs[2:4] = [7, 8]
    commands = RemoteCommands(endpoint, "modbus")
    remote = RemoteEndpoint(endpoint, "register", "modbus")
    assert commands.submit(remote.read_registers, "holding", 2, 2).result(5) == [7, 8]
    assert regs.calls == 1


def test_a_refusal_keeps_its_modbus_exception_code_across_the_link(link):
    endpoint, _, regs, _, events = link
    remote = RemoteEndpoint(endpoint, "register", "modbus")
    fut = RemoteCommands(endpoint, "modbus").submit(remote.write_registers, 15, [1, 2])
    with pytest.raises(RegisterRefused, match="the map ends at 15") as e:
        fut.result(5)
    assert int(e.value.exception_code) == 3
    assert regs.regs[15] == 0  # refused: nothing written
    _wait(events, 1)
    kind, message, fields = events[0]
    assert kind == "write" and fields["accepted"] is False and "the map ends at 15" in fields["reason"]


def test_an_accepted_register_write_is_logged_with_old_and_new(link):
    endpoint, _, regs, _, events = link
    regs.regs[4] = 5
    remote = RemoteEndpoint(endpoint, "register", "modbus")
    RemoteCommands(endpoint, "modbus").submit(remote.write_registers, 4, [9]).result(5)
    _wait(events, 1)
    kind, message, fields = events[0]
    assert kind == "write" and fields["accepted"] is True
    assert fields["changes"] == [{"what": "register 4", "old": 5, "new": 9}]


def test_byte_sessions_keep_their_own_state_and_a_write_is_audited(link):
    endpoint, _, _, device, events = link
    remote = RemoteEndpoint(endpoint, "byte", "serial-tcp")
    commands = RemoteCommands(endpoint, "serial-tcp")
    a, b = remote.session(), remote.session()
    assert commands.submit(a.feed, b"x").result(5) == b"ok:x\r"
    assert commands.submit(b.feed, b"y").result(5) == b"ok:y\r"
    assert commands.submit(a.feed, b"z").result(5) == b"ok:xz\r"
    assert events == []  # reads are not logged
    commands.submit(b.feed, b"speed=25").result(5)
    _wait(events, 1)
    kind, message, fields = events[0]
    assert fields["accepted"] is True and fields["changes"] == [{"what": "speed", "old": 10, "new": 25}]
    device._network_writes = False
    assert commands.submit(b.feed, b"speed=30").result(5) == b"E1\r"
    _wait(events, 2)
    assert events[1][2]["accepted"] is False and "--allow-writes" in events[1][2]["reason"]
    assert device.params["speed"] == 25
    a.close()
    b.close()


def test_an_unpicklable_answer_becomes_a_remote_error_not_a_hang(link):
    endpoint, _, _, _, _ = link
    s = RemoteEndpoint(endpoint, "byte", "serial-tcp").session()
    fut = endpoint.call(s.handle, "unpicklable", ())
    with pytest.raises(RemoteError, match="unsendable"):
        fut.result(5)


def test_requests_fail_with_link_closed_when_the_cycle_process_goes_away():
    req_in, req_out = multiprocessing.Pipe(duplex=False)
    rep_in, rep_out = multiprocessing.Pipe(duplex=False)
    endpoint = EndpointLink(rep_in, req_out, on_event=lambda *a: None).start()
    fut = endpoint.call("register", "read_registers", ("holding", 0, 1))
    rep_out.close()  # the cycle process died (kill -9) before answering
    req_in.close()
    with pytest.raises(LinkClosed):
        fut.result(5)
    with pytest.raises(LinkClosed):
        endpoint.call("register", "read_registers", ("holding", 0, 1)).result(5)


def test_the_pump_answers_one_waiting_request_even_without_idle_time():
    req_in, req_out = multiprocessing.Pipe(duplex=False)
    rep_in, rep_out = multiprocessing.Pipe(duplex=False)
    regs = Registers()
    cycle = CycleLink(req_in, rep_out, {"register": lambda: regs})
    for i in range(3):
        req_out.send(("call", i, "register", "read_registers", ("holding", 0, 1), "t", "modbus"))
    time.sleep(0.05)
    assert cycle.pump(until=0.0) == 1  # the deadline has passed: one, not all three
    assert cycle.pump(until=time.perf_counter() + 1.0) == 2
    cycle.close()


def test_replies_the_pipe_cannot_take_now_wait_in_the_outbox_and_the_cycle_never_blocks():
    req_in, req_out = multiprocessing.Pipe(duplex=False)
    rep_in, rep_out = multiprocessing.Pipe(duplex=False)
    cycle = CycleLink(req_in, rep_out, {})
    big = "x" * 100_000
    emitting = threading.Thread(target=lambda: [cycle.emit("note", big, i=i) for i in range(50)])
    emitting.start()  # 5 MB: far more than a pipe holds; nobody reads yet
    emitting.join(60)
    assert not emitting.is_alive()  # it returned without a reader: a blocking write never would
    assert cycle._out.waiting > 0
    got = []

    def read() -> None:
        while len(got) < 50:
            got.append(rep_in.recv())

    reader = threading.Thread(target=read)
    reader.start()
    while reader.is_alive():
        cycle.pump(time.perf_counter())  # each pump writes what the pipe takes
        time.sleep(0.001)
    assert [m[3]["i"] for m in got] == list(range(50)) and got[0][0] == "event"


def test_a_long_request_waits_for_an_idle_time_that_holds_it_and_keeps_the_order():
    req_in, req_out = multiprocessing.Pipe(duplex=False)
    rep_in, rep_out = multiprocessing.Pipe(duplex=False)
    clock = [0.0]

    class View:
        def call(self, method, args, who):
            clock[0] += 0.0008 if method == "device" else 0.00001  # the device page takes 0.8 ms
            return method

    cycle = CycleLink(req_in, rep_out, {"hmi": View})
    timer = lambda: clock[0]  # noqa: E731
    req_out.send(("call", 1, "hmi", "call", ("device", {}, "w"), "w", "http"))
    time.sleep(0.05)
    assert cycle.pump(until=1.0, timer=timer) == 1  # first time: its cost is not known yet
    req_out.send(("call", 2, "hmi", "call", ("device", {}, "w"), "w", "http"))
    req_out.send(("call", 3, "hmi", "call", ("overview", {}, "w"), "w", "http"))
    time.sleep(0.05)
    clock[0] = 0.0
    assert cycle.pump(until=0.0005, timer=timer) == 0  # 0.5 ms of idle time: the page waits, the overview behind it
    clock[0] = 0.0
    assert cycle.pump(until=0.002, timer=timer) == 2  # 2 ms: both, in order
    replies = [rep_in.recv() for _ in range(3)]
    assert [r[1] for r in replies] == [1, 2, 3]
    cycle.close()


def test_one_slow_answer_does_not_make_a_short_request_wait():
    req_in, req_out = multiprocessing.Pipe(duplex=False)
    rep_in, rep_out = multiprocessing.Pipe(duplex=False)
    clock = [0.0]
    slow = [True]

    class Regs:
        def read_registers(self, kind, address, count):
            clock[0] += 0.003 if slow[0] else 0.00002  # once preempted for 3 ms, then 20 us as always
            slow[0] = False
            return [0] * count

    cycle = CycleLink(req_in, rep_out, {"register": Regs})
    for i in range(3):
        req_out.send(("call", i, "register", "read_registers", ("holding", 0, 1), "t", "modbus"))
    time.sleep(0.05)
    assert cycle.pump(until=1.0, timer=lambda: clock[0]) == 3
    req_out.send(("call", 9, "register", "read_registers", ("holding", 0, 1), "t", "modbus"))
    time.sleep(0.05)
    clock[0] = 0.0
    assert cycle.pump(until=0.0005, timer=lambda: clock[0]) == 1  # not held: its usual cost fits
    cycle.close()
