"""Issue 20: where the kernel offers vcan, the positioning example runs the same over socketcan.

The simulated drive sits on its own socket of the same vcan interface (a second node on the
bus, as a real drive would be); the trace must agree with the embedded plant's within one
encoder count, as on the virtual bus (test_positioning.py). Skipped, with the reason, where
there is no vcan interface (creating one needs root: `modprobe vcan; ip link add dev vcan0
type vcan; ip link set up vcan0`).
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

import numpy as np
import pytest

from axisline.config import load_machine_file
from axisline.drives import close_drives
from axisline.drives.simulated import SimulatedDrive
from axisline.machine import Machine

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
VCAN = os.environ.get("AXISLINE_VCAN", "vcan0")


def _vcan_missing() -> str | None:
    if not sys.platform.startswith("linux"):
        return "socketcan is Linux only"
    flags = Path(f"/sys/class/net/{VCAN}/flags")
    if not flags.exists():
        return f"no {VCAN} interface here (needs root: modprobe vcan; ip link add dev {VCAN} type vcan; ip link set up {VCAN})"
    if not int(flags.read_text(), 16) & 0x1:
        return f"{VCAN} is down (ip link set up {VCAN})"
    return None


pytestmark = pytest.mark.skipif(_vcan_missing() is not None, reason=str(_vcan_missing()))


def test_positioning_over_socketcan_agrees_with_the_embedded_plant():
    config = load_machine_file(EXAMPLES / "positioning_cia402.toml")
    data = config.model_dump()
    x = data["axis"][0]
    servo_cfg = config.axis[0].drive.simulated
    x["drive"].update(interface="socketcan", channel=VCAN, simulated=None)
    entry = config.axis[0]
    servo = servo_cfg.build()
    encoder = entry.encoder.build(servo)
    sim = SimulatedDrive(1, servo, encoder, kv=entry.kv, feed_forward=entry.velocity_feed_forward,
                         interface="socketcan", channel=VCAN)
    from axisline.config import parse_machine

    m = Machine(parse_machine(data, "positioning over socketcan"))
    try:
        result = m.run()
    finally:
        close_drives(m)
        sim.close()
    embedded = Machine.from_file(EXAMPLES / "positioning.toml")
    embedded.run()
    assert result.completed, result.faults
    a, b = embedded.trace.data()["x.actual_position"], m.trace.data()["x.actual_position"]
    n = min(len(a), len(b))
    assert np.abs(a[:n] - b[:n]).max() <= 1.0 / 2000.0 + 1e-12
