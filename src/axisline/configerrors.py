"""Machine-file errors that name the key, the value and the allowed range.

pydantic reports a location tuple and a message; a commissioning engineer wants
"axis[1].drive.tau = -0.01: must be > 0 (allowed: > 0)". The allowed range is read
from the field's own constraints, so the schema stays the single source of truth.
"""

from __future__ import annotations

import typing
from typing import Any

import annotated_types as at
from pydantic import BaseModel, ValidationError


class ConfigError(ValueError):
    """A machine file that cannot be used; `problems` lists one line per bad key."""

    def __init__(self, source: str, problems: list[str]) -> None:
        self.source = source
        self.problems = problems
        super().__init__(f"{source}: " + "; ".join(problems))


def _key(loc: tuple[Any, ...]) -> str:
    out = ""
    for part in loc:
        if isinstance(part, int):
            out += f"[{part}]"
        else:
            out += ("." if out else "") + str(part)
    return out or "(top level)"


def _model_in(annotation: Any) -> type[BaseModel] | None:
    """The pydantic model inside an annotation such as list[AxisConfig] | None."""
    if isinstance(annotation, type) and issubclass(annotation, BaseModel):
        return annotation
    for arg in typing.get_args(annotation):
        found = _model_in(arg)
        if found is not None:
            return found
    return None


def _field(model: type[BaseModel], loc: tuple[Any, ...]):
    """FieldInfo at a location, following nested models and lists; None if unknown."""
    info = None
    for part in loc:
        if isinstance(part, int):
            continue
        if model is None or part not in model.model_fields:
            return None
        info = model.model_fields[part]
        model = _model_in(info.annotation)
    return info


def allowed_range(info) -> str:
    """Human form of a field's numeric constraints and choices, '' if it has none."""
    if info is None:
        return ""
    lo = hi = None
    for m in info.metadata:
        if isinstance(m, at.Ge):
            lo = f">= {m.ge}"
        elif isinstance(m, at.Gt):
            lo = f"> {m.gt}"
        elif isinstance(m, at.Le):
            hi = f"<= {m.le}"
        elif isinstance(m, at.Lt):
            hi = f"< {m.lt}"
    args = typing.get_args(info.annotation)
    if typing.get_origin(info.annotation) is typing.Literal:
        return "one of " + ", ".join(repr(a) for a in args)
    if lo and hi:
        return f"{lo} and {hi}"
    return lo or hi or ""


def explain(err: ValidationError, model: type[BaseModel], source: str) -> ConfigError:
    problems = []
    for e in err.errors():
        loc = tuple(e["loc"])
        key = _key(loc)
        if e["type"] == "extra_forbidden":
            parent = _field(model, loc[:-1]) if len(loc) > 1 else None
            owner = _model_in(parent.annotation) if parent is not None else model
            known = ", ".join(owner.model_fields) if owner is not None else ""
            problems.append(f"{key}: unknown key (known keys here: {known})")
            continue
        if e["type"] == "value_error" and not loc:  # a cross-check of the whole file
            problems.append(str(e["msg"]).removeprefix("Value error, "))
            continue
        if e["type"] == "missing":
            problems.append(f"{key}: required key is missing")
            continue
        rng = allowed_range(_field(model, loc))
        value = e.get("input")
        line = f"{key} = {value!r}: {e['msg']}"
        if rng:
            line += f" (allowed: {rng})"
        problems.append(line)
    return ConfigError(source, problems)
