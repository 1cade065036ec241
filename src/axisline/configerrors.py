"""Machine-file errors that name the key, the value and the allowed range.

pydantic reports a location tuple and a message; a commissioning engineer wants
"axis[1].drive.tau = -0.01: must be > 0 (allowed: > 0)". The allowed range is read
from the field's own constraints, so the schema stays the single source of truth.

An entry of a list of tables that has a name is named by it as well: the engineer's file says
`[[axis]] name = "x"`, not "axis 0", so a line reads "axis[0].v_max = -5.0 (axis 'x'): ...".
An unknown key gets the closest known key as a suggestion ("did you mean v_max?"), found with
difflib (a typo, a missing underscore, a different case).

A value is echoed shortened (`shown`): an error must stay a line, whatever the file holds.
`read_text` reads the machine file and the files it names within a size limit, and
`FilePath` is the type of a file name in it.
"""

from __future__ import annotations

import difflib
import os
import reprlib
import typing
from typing import Annotated, Any

import annotated_types as at
from pydantic import AfterValidator, BaseModel, ValidationError

#: a value is echoed in an error with at most this many characters: a 1 MB string or a list
#: of 30 000 tables must not turn one error into megabytes of output
VALUE_CHARS = 200
#: a problem line from anywhere (also device code) is cut to this length, as a backstop
LINE_CHARS = 1200
#: explain() reports this many problems and counts the rest
MAX_PROBLEMS = 50

_repr = reprlib.Repr()
_repr.maxlevel, _repr.maxdict, _repr.maxlist, _repr.maxtuple = 3, 8, 8, 8
_repr.maxstring, _repr.maxother, _repr.maxlong = VALUE_CHARS, VALUE_CHARS, 60


def shown(value: Any) -> str:
    """repr(value), shortened to about VALUE_CHARS characters (with the full length of a long
    string and the number of entries of a long list, which say what went wrong)."""
    text = _repr.repr(value)  # reprlib stops early: never builds the repr of a huge value
    if len(text) > VALUE_CHARS:
        text = text[: VALUE_CHARS - 3] + "..."
    if isinstance(value, str) and len(value) > VALUE_CHARS:
        text += f" ({len(value)} characters)"
    elif isinstance(value, (list, tuple, dict)) and len(value) > _repr.maxlist:
        text += f" ({len(value)} entries)"
    return text


def _bounded(line: str) -> str:
    if len(line) <= LINE_CHARS:
        return line
    cut = len(line) - LINE_CHARS
    return f"{line[: LINE_CHARS - 300]} ... ({cut} characters left out) ... {line[-300:]}"


class ConfigError(ValueError):
    """A machine file that cannot be used; `problems` lists one line per bad key."""

    def __init__(self, source: str, problems: list[str]) -> None:
        self.source = _bounded(source)
        self.problems = [_bounded(p) for p in problems]
        super().__init__(f"{self.source}: " + "; ".join(self.problems))


def _no_nul(path: str | None) -> str | None:
    if path is not None and "\0" in path:
        # the operating system cannot name such a file; open() would fail with a bare ValueError
        raise ValueError(f"a file path cannot contain a NUL character (at position {path.index(chr(0))})")
    return path


#: an optional file named in the machine file, e.g. `memory_file: FilePath = Field(None,
#: min_length=1, max_length=4096)`; the field's type still reads `str | None` (in the docs)
FilePath = Annotated[str | None, AfterValidator(_no_nul)]


def read_text(path: str | os.PathLike[str], limit: int) -> str:
    """The UTF-8 text of a file the machine file is or names, at most `limit` bytes.

    Raises ValueError with a one-line reason. The size is checked before the file is read
    (and no more than limit + 1 bytes are ever read, also from a pipe or a device), so a
    huge file costs nothing."""
    try:
        with open(path, "rb") as f:
            size = os.fstat(f.fileno()).st_size
            data = b"" if size > limit else f.read(limit + 1)
    except OSError as e:
        raise ValueError(f"cannot read: {e.strerror or e}") from None
    except ValueError:  # open() of a path with a NUL byte
        raise ValueError("cannot read: a file path cannot contain a NUL character") from None
    if size > limit or len(data) > limit:
        raise ValueError(f"the file is {max(size, len(data)) / 2**20:.1f} MiB; the limit is {limit / 2**20:g} MiB")
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as e:
        line = data.count(b"\n", 0, e.start) + 1
        raise ValueError(
            f"not UTF-8 text: byte 0x{data[e.start]:02x} at position {e.start} (line {line}); save the file as UTF-8"
        ) from None


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


def _singular(key: str) -> str:
    """'switches' -> 'switch', 'marks' -> 'mark', 'axis' -> 'axis': one entry of a list."""
    if key.endswith("ches") or key.endswith("shes"):
        return key[:-2]
    if key.endswith("s") and not key.endswith(("is", "ss", "us")):
        return key[:-1]
    return key


def named_entries(loc: tuple[Any, ...], data: Any) -> list[tuple[str, str]]:
    """The named list entries on the way to `loc` in the input `data`, as (kind, name) pairs:
    [("axis", "x"), ("switch", "ref")]; [] when none has a name (or data is not given).

    The data is walked along the location; parts that are not in it (the tag pydantic puts
    in for a discriminated union, such as 'servo') are skipped. An entry's own `name` key in
    error does not name it (that would only repeat the bad value)."""
    found: list[tuple[str, str]] = []
    node, last_key = data, None
    for i, part in enumerate(loc):
        if isinstance(part, int) and isinstance(node, list) and 0 <= part < len(node):
            node = node[part]
            name = node.get("name") if isinstance(node, dict) else None
            names_itself = loc[i + 1 :] == ("name",)
            if isinstance(name, str) and name and last_key is not None and not names_itself:
                found.append((_singular(last_key), name))
        elif isinstance(part, str) and isinstance(node, dict) and part in node:
            node, last_key = node[part], part
    return found


def _label(named: list[tuple[str, str]], text: str = "") -> str:
    """"axis 'x', switch 'ref'", or '' when there is nothing to add: no named entry, or a
    message (a table's cross-check) that names them itself."""
    if not named or all(repr(name) in text for _, name in named):
        return ""
    return ", ".join(f"{kind} {shown(name)}" for kind, name in named)


def closest_key(bad: Any, known: list[str]) -> str | None:
    """The known key a typo most likely meant ('vmax' -> 'v_max', 'V_Max' -> 'v_max'), or None
    when none is close (difflib's ratio >= 0.6, case ignored)."""
    if not isinstance(bad, str) or not bad or len(bad) > 200:  # no quadratic work on a huge key
        return None
    lowered = {k.lower(): k for k in known}
    found = difflib.get_close_matches(bad.lower(), list(lowered), n=1, cutoff=0.6)
    return lowered[found[0]] if found else None


def explain(err: ValidationError, model: type[BaseModel], source: str, data: Any = None) -> ConfigError:
    """The ConfigError for a ValidationError of `model`; pass the validated input as `data` so
    that named entries (an axis, a switch, a master) are named in the lines."""
    problems = []
    errors = err.errors(include_url=False)
    for e in errors[:MAX_PROBLEMS]:
        loc = tuple(e["loc"])
        info, clean, _ = _walk(model, loc)
        key = _key(clean)
        named = named_entries(loc, data)
        label = _label(named)
        where = f" ({label})" if label else ""
        if e["type"] == "extra_forbidden":
            owners = _walk(model, loc[:-1])[2] if len(loc) > 1 else [model]
            known = list(dict.fromkeys(k for m in owners for k in m.model_fields))
            guess = closest_key(loc[-1] if loc else None, known)
            hint = f"; did you mean {guess}?" if guess else ""
            problems.append(f"{key}: unknown key{where}{hint} (known keys here: {', '.join(known)})")
            continue
        if e["type"] == "value_error" and (not loc or isinstance(e.get("input"), dict)):
            # a cross-check of a whole table: the message names its keys itself
            text = str(e["msg"]).removeprefix("Value error, ")
            label = _label(named, text)  # after the message: "KEY: message" stays as it was
            problems.append((f"{key}: {text}" + (f" (in {label})" if label else "")) if loc else text)
            continue
        if e["type"] == "missing":
            problems.append(f"{key}: required key is missing{where}")
            continue
        rng = allowed_range(info)
        value = e.get("input")
        msg = e["msg"]
        if len(msg) > 2 * VALUE_CHARS:  # pydantic quotes some inputs whole (a union's tag)
            msg = msg[: 2 * VALUE_CHARS - 3] + "..."
        line = f"{key} = {shown(value)}{where}: {msg}"
        if rng:
            line += f" (allowed: {rng})"
        problems.append(line)
    if len(errors) > MAX_PROBLEMS:
        problems.append(f"... and {len(errors) - MAX_PROBLEMS} more problems")
    return ConfigError(source, problems)
