"""Dotted machine-file keys: `axis.carriage.kv`, `material.profile[0].speed`, `device.parameters.cutting_length`.

A key walks the machine file's data as TOML read it (tables are dicts, arrays of tables are
lists). A part after a list of tables that is not an [index] picks the entry by its `name`
(`axis.carriage` is the [[axis]] with name = "carriage"), as a commissioning engineer names
it. A table on the way that the base file leaves out is created (`device.parameters` when the
file sets no parameter); whether the key exists at all is then the machine-file model's
judgement (parse_machine), which names the key, the value and the allowed range.

    parts = parse_key("material.profile[0].speed")   # ["material", "profile", 0, "speed"]
    set_key(data, "axis.carriage.kv", 40.0)          # KeyError naming the key if it cannot be placed
    get_key(data, "axis.carriage.kv")
"""

from __future__ import annotations

import re
from typing import Any

__all__ = ["KeyPathError", "parse_key", "set_key", "get_key", "walk"]

_PART = re.compile(r"([^.\[\]]+)|\[(\d+)\]")


class KeyPathError(ValueError):
    """A key that does not lead to a place in the machine file (the message names it)."""


def parse_key(key: str) -> list[str | int]:
    """The parts of a dotted key; [n] becomes the int n."""
    parts: list[str | int] = []
    for name, index in _PART.findall(key):
        parts.append(int(index) if index else name)
    return parts


def _names(entries: list[Any]) -> str:
    named = [e.get("name") for e in entries if isinstance(e, dict) and isinstance(e.get("name"), str)]
    return ", ".join(map(repr, named)) or "none with a name"


def _step(node: Any, part: str | int, key: str, done: str, create: bool) -> Any:
    """The child of `node` at `part` (creating a missing table when `create`)."""
    if isinstance(part, int):
        if not isinstance(node, list):
            raise KeyPathError(f"{key}: {done or 'the file'} is not a list ([{part}] indexes a list)")
        if not 0 <= part < len(node):
            raise KeyPathError(f"{key}: {done} has {len(node)} entries (allowed index: 0 .. {len(node) - 1})" if node
                               else f"{key}: {done} is empty in the base file")
        return node[part]
    if isinstance(node, list):  # a list of tables: the entry by its name
        found = [e for e in node if isinstance(e, dict) and e.get("name") == part]
        if not found:
            raise KeyPathError(f"{key}: no entry of {done} has name = {part!r} (names: {_names(node)})")
        return found[0]
    if not isinstance(node, dict):
        raise KeyPathError(f"{key}: {done} is a value ({node!r}), not a table")
    if part not in node:
        if not create:
            raise KeyPathError(f"{key}: {done + '.' if done else ''}{part} is not in the base file")
        node[part] = {}
    return node[part]


def _joined(done: str, part: str | int) -> str:
    return f"{done}[{part}]" if isinstance(part, int) else (f"{done}.{part}" if done else part)


def set_key(data: dict[str, Any], key: str, value: Any) -> None:
    """Put `value` at `key` in the machine-file data (in place)."""
    parts = parse_key(key)
    node: Any = data
    done = ""
    for part in parts[:-1]:
        node = _step(node, part, key, done, create=True)
        done = _joined(done, part)
    last = parts[-1]
    if isinstance(last, int):
        if not isinstance(node, list) or not 0 <= last < len(node):
            _step(node, last, key, done, create=False)  # raises, naming the list
        node[last] = value
    elif isinstance(node, list):
        raise KeyPathError(f"{key}: {done} is a list of tables; name an entry's key (as {done}.NAME.KEY or {done}[0].KEY)")
    elif isinstance(node, dict):
        node[last] = value
    else:
        raise KeyPathError(f"{key}: {done} is a value ({node!r}), not a table")


def walk(data: Any, key: str) -> Any:
    """The value at `key` (KeyPathError if it is not there); lists of dicts by index or name."""
    node = data
    done = ""
    for part in parse_key(key):
        node = _step(node, part, key, done, create=False)
        done = _joined(done, part)
    return node


def get_key(data: Any, key: str, default: Any = None) -> Any:
    try:
        return walk(data, key)
    except KeyPathError:
        return default
