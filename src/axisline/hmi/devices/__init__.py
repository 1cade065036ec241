"""The device views of the web HMI: one module per personality, dispatched by its `name`.

    device_view(personality) -> {"title": str, "sections": [section, ...]}
    device_write(personality, name, value) -> (old, new)     # ValueError when refused
    device_acknowledge(personality) -> str                    # what was acknowledged ("" if nothing)

The sections are plain JSON (`_sections`: parameters, table, bits, plot, diagnostics, text);
the HMI page renders them without knowing the device. Each module reads the personality's own
tables and codecs and writes through the checked path its protocol endpoint uses, so a value
the device refuses over the wire is refused here with the same message and changes nothing.
The HMI core (`hmi/view.py`) checks the operator's write enable and token before a write and
calls these at a cycle boundary, so they keep their work small (no file I/O beyond what the
device's own write stores, bounded tables and plots).

    fs701     motrona FS701: register cards, process data, command / output / error words,
              errors 00..05, the cut table, Clear Error
    compax    Parker COMPAX XX70: parameters P.. (written / valid), status values S.., I/O,
              errors, the cam curves in memory as plots, Quit
    wago672   WAGO 750-672: per module the process image decoded, the mailbox, the
              configuration table, the error memory, Error_Quit
    clm       Rexroth CLM1.4: parameters B000..C008 field by field, the task display, the
              program and Logic Task, the CTA screens, the system inputs / outputs, CL key
"""

from __future__ import annotations

import importlib
from typing import Any

from ._sections import clean

__all__ = ["device_view", "device_write", "device_acknowledge", "device_faults", "MODULES"]

#: personality name -> module of this package
MODULES = {"fs701": "fs701", "compax": "compax", "wago672": "wago672", "clm": "clm"}


def _module(personality: Any) -> Any:
    name = getattr(personality, "name", None)
    module = MODULES.get(name) if isinstance(name, str) else None
    if module is None:
        raise ValueError(f"personality {name!r} has no device view (views: {', '.join(sorted(MODULES))})")
    return importlib.import_module(f"{__name__}.{module}")


def device_view(personality: Any) -> dict[str, Any]:
    """The device's page: its title and sections, plain JSON (the section builders clean
    every value they take, so the page is not walked a second time)."""
    return _module(personality).view(personality)


def device_write(personality: Any, name: str, value: Any) -> tuple[Any, Any]:
    """Write one row of the view through the device's own validation; (old, new) as shown.
    Raises ValueError naming the field, the value and what is allowed; a refused write
    changes nothing."""
    if not isinstance(name, str) or not name.strip():
        raise ValueError(f"name: {name!r} is not a parameter name (a row of the device view)")
    old, new = _module(personality).write(personality, name.strip(), value)
    return clean(old), clean(new)


def device_acknowledge(personality: Any) -> str:
    """The device's own fault reset (what its panel's clear does); what it acknowledged,
    "" when nothing was active."""
    return str(_module(personality).acknowledge(personality))


def device_faults(personality: Any) -> dict[str, str]:
    """The device's active faults, source -> text (cheap: `serve` compares them every 10 ms and
    logs a fault when one appears and "cleared" when it goes)."""
    return {str(k): str(v) for k, v in _module(personality).faults(personality).items()}
