"""`axisline drives scan`: the nodes on a bus with identity and state."""

from __future__ import annotations

import json

import pytest
from typer.testing import CliRunner

from axisline.drives.cli import drives_app
from axisline.drives.scan import scan
from axisline.drives.simulated import SimulatedDrive
from axisline.plant import IncrementalEncoder, ServoDrive


@pytest.fixture
def two_drives(channel):
    drives = []
    for node_id in (3, 12):
        servo = ServoDrive()
        drives.append(SimulatedDrive(node_id, servo, IncrementalEncoder(servo, 250.0), kv=30.0, channel=channel))
    yield drives
    for d in drives:
        d.close()


def test_scan_finds_the_nodes_with_identity_and_state(two_drives, channel):
    nodes = scan("virtual", channel, wait=0.2)
    assert [n.node_id for n in nodes] == [3, 12]
    n = nodes[0]
    assert n.profile == "CiA 402" and n.product_code == 0x402 and n.name == "axisline generic CiA 402"
    assert n.drive_state.startswith("SWITCH ON DISABLED")
    assert n.nmt_state in ("PRE-OPERATIONAL", "?")  # (from its heartbeat, if it sends one)


def test_scan_command_prints_a_table(two_drives, channel):
    r = CliRunner().invoke(drives_app, ["scan", "--interface", "virtual", "--channel", channel, "--wait", "0.2", "--json"])
    assert r.exit_code == 0, r.output
    rows = json.loads(r.output)
    assert [row["node"] for row in rows] == ["3", "12"]
    assert rows[1]["CiA 402 state"].startswith("SWITCH ON DISABLED")


def test_scan_of_an_empty_bus_says_so(channel):
    r = CliRunner().invoke(drives_app, ["scan", "--interface", "virtual", "--channel", channel, "--wait", "0.05"])
    assert r.exit_code == 0
    assert "no CANopen node answered" in r.output


def test_scan_refuses_a_bad_bitrate_and_a_missing_interface(channel):
    r = CliRunner().invoke(drives_app, ["scan", "--interface", "virtual", "--channel", channel, "--bitrate", "12345"])
    assert r.exit_code == 2 and "--bitrate" in r.output and "1000000" in r.output
    r = CliRunner().invoke(drives_app, ["scan", "--interface", "nosuchbus", "--channel", "x"])
    assert r.exit_code == 2 and "nosuchbus" in r.output and "Traceback" not in r.output
