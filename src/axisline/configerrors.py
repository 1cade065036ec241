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


def _models_in(annotation: Any) -> list[type[BaseModel]]:
    if isinstance(annotation, type) and issubclass(annotation, BaseModel):
        return [annotation]
    out: list[type[BaseModel]] = []
    for arg in typing.get_args(annotation):
        out.extend(_models_in(arg))
    return out


def _tag_of(model: type[BaseModel]) -> str | None:
    """The value of a discriminator field such as type: Literal["servo"]."""
    f = model.model_fields.get("type")
    if f is not None and typing.get_origin(f.annotation) is typing.Literal:
        return str(typing.get_args(f.annotation)[0])
    return None


def _walk(model: type[BaseModel], loc: tuple[Any, ...]):
    """(FieldInfo, clean key parts) at a location, following nested models, lists and
    discriminated unions (pydantic puts the union tag, e.g. 'servo', into the location)."""
    info = None
    parts: list[Any] = []
    candidates = [model]
    for part in loc:
        if isinstance(part, int):
            parts.append(part)
            continue
        tagged = [m for m in candidates if _tag_of(m) == part]
        if tagged and len(candidates) > 1:
            candidates = tagged
            continue
        owner = next((m for m in candidates if part in m.model_fields), None)
        parts.append(part)
        if owner is None:
            info, candidates = None, []
            continue
        info = owner.model_fields[part]
        candidates = _models_in(info.annotation)
    return info, tuple(parts), candidates


def _literal_in(annotation: Any) -> tuple | None:
    """The choices of a Literal, also inside Optional[...]."""
    if typing.get_origin(annotation) is typing.Literal:
        return typing.get_args(annotation)
    for arg in typing.get_args(annotation):
        found = _literal_in(arg)
        if found is not None:
            return found
    return None


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
    literal = _literal_in(info.annotation)
    if literal is not None:
        return "one of " + ", ".join(repr(a) for a in literal)
    if lo and hi:
        return f"{lo} and {hi}"
    return lo or hi or ""


def explain(err: ValidationError, model: type[BaseModel], source: str) -> ConfigError:
    problems = []
    for e in err.errors():
        loc = tuple(e["loc"])
        info, clean, _ = _walk(model, loc)
        key = _key(clean)
        if e["type"] == "extra_forbidden":
            owners = _walk(model, loc[:-1])[2] if len(loc) > 1 else [model]
            known = ", ".join(dict.fromkeys(k for m in owners for k in m.model_fields))
            problems.append(f"{key}: unknown key (known keys here: {known})")
            continue
        if e["type"] == "value_error" and (not loc or isinstance(e.get("input"), dict)):
            # a cross-check of a whole table: the message names its keys itself
            text = str(e["msg"]).removeprefix("Value error, ")
            problems.append(f"{key}: {text}" if loc else text)
            continue
        if e["type"] == "missing":
            problems.append(f"{key}: required key is missing")
            continue
        rng = allowed_range(info)
        value = e.get("input")
        line = f"{key} = {value!r}: {e['msg']}"
        if rng:
            line += f" (allowed: {rng})"
        problems.append(line)
    return ConfigError(source, problems)
