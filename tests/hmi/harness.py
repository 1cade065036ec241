"""The HMI on a machine running on the wall clock in one process, for the browser test of the
device page's demo device (the other browser tests run `axisline serve --http`, which prints
the same lines).

    python tests/hmi/harness.py MACHINE.toml [--fake-device]

prints `http HOST:PORT`, `token TOKEN`, `ready` and serves until stdin closes or SIGTERM.
--fake-device shows tests/hmi/fake_devices.py's demo device on the device page.
"""

from __future__ import annotations

import argparse
import signal
import sys
import threading
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from eventlog import event_log  # noqa: E402

from axisline.config import load_machine_file  # noqa: E402
from axisline.hmi import view as view_module  # noqa: E402
from axisline.hmi.server import HmiServer  # noqa: E402
from axisline.hmi.view import MachineView  # noqa: E402
from axisline.kernel import WallClock  # noqa: E402
from axisline.machine import Machine  # noqa: E402


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("machine", type=Path)
    ap.add_argument("--fake-device", action="store_true")
    a = ap.parse_args()
    cfg = load_machine_file(a.machine)
    machine = Machine(cfg, clock=WallClock(cfg.machine.cycle_us), source=str(a.machine))
    if a.fake_device:
        import fake_devices

        view_module._devices_module = lambda: fake_devices
        if machine.device is None:
            machine.device = fake_devices.FakeDevice()
    events = event_log()
    view = MachineView(machine, events.emit)
    cycle = threading.Thread(target=machine.scheduler.run, args=(2**62,), name="cycle", daemon=True)
    srv = HmiServer(lambda m, args, who: machine.commands.submit(view.call, m, args, who), events, writes_allowed=True)
    srv.start()
    cycle.start()
    print(f"http {srv.address[0]}:{srv.address[1]}", f"token {srv.token}", "ready", sep="\n", flush=True)
    done = threading.Event()
    signal.signal(signal.SIGTERM, lambda *_: done.set())
    threading.Thread(target=lambda: (sys.stdin.read(), done.set()), daemon=True).start()
    done.wait()
    machine.scheduler.stop()
    srv.stop()
    cycle.join(5)


if __name__ == "__main__":
    main()
