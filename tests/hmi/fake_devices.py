"""A device-view module with every section type (the contract of axisline.hmi.devices), for
the browser test of the device page's generic renderer; the harness puts it in place of the
real module with --fake-device."""

from __future__ import annotations

from typing import Any


class FakeDevice:
    """Stands for a personality on a machine that has none."""

    name = "demo"

    def __init__(self) -> None:
        self.length = 1000
        self.error = True


def device_view(p: FakeDevice) -> dict[str, Any]:
    status = (1 << 0) | (1 << 3) | ((1 << 7) if p.error else 0)
    names = ["ready", "enabled", "moving", "in position", "homed", "limit", "warning", "error"]
    return {"title": "demo device (every section type)", "sections": [
        {"type": "parameters", "title": "Parameters", "rows": [
            {"name": "cutting_length", "label": "Cutting length", "value": p.length, "unit": "mm", "min": 10, "max": 10000, "writable": True},
            {"name": "line_speed", "label": "Line speed", "value": 1000.0, "unit": "mm/s", "min": None, "max": None, "writable": False},
        ]},
        {"type": "bits", "title": "Status word", "words": [
            {"name": "status", "value": status, "bits": [{"bit": i, "name": n, "set": bool(status >> i & 1)} for i, n in enumerate(names)]}]},
        {"type": "table", "title": "Cut table", "columns": ["cut", "length mm", "error mm"],
         "rows": [[1, 1000.02, 0.02], [2, 999.97, -0.03], [3, 1000.01, 0.01]]},
        {"type": "plot", "title": "Cam curve", "x_label": "master", "y_label": "slave",
         "series": [{"name": "curve", "x": [i / 20 for i in range(21)], "y": [(i / 20) ** 2 * (3 - 2 * i / 20) for i in range(21)]}]},
        {"type": "diagnostics", "title": "Diagnostics", "rows": [
            {"code": "E07", "text": "following error too large", "active": p.error},
            {"code": "E12", "text": "encoder signal lost", "active": False}]},
        {"type": "text", "title": "Display", "lines": ["LEN  1000.0 mm", "RUN  ready"]},
    ]}


def device_write(p: FakeDevice, name: str, value: Any) -> tuple[Any, Any]:
    if name != "cutting_length":
        raise ValueError(f"{name}: not a writable parameter (writable: cutting_length)")
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not 10 <= value <= 10000:
        raise ValueError(f"cutting_length = {value!r}: allowed 10..10000 mm")
    old, p.length = p.length, value
    return old, value


def device_acknowledge(p: FakeDevice) -> str:
    was, p.error = p.error, False
    return "E07 cleared" if was else "no device error"
