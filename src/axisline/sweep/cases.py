"""Cases of a sweep: the product of the parameters' values, each with its key and seed.

    grid = Grid(spec, base_text)          # values of every parameter (ranges and draws made)
    len(grid)                             # number of cases
    for case in grid.cases(): ...         # Case(index, overrides, seed, key), in a fixed order

The order is the [parameters] table's: the first parameter varies slowest. A case's `key`
is a hash of everything its result depends on (the base machine file's text, the overrides,
the machine seed, the duration), so a re-run finds the results it already has (resume) and a
changed base file or duration runs again. A random parameter's draws and a per-case machine
seed come from generators seeded by the sweep seed and the key or values (spec.py,
decisions 2 and 3): the same on any engine and in any order.
"""

from __future__ import annotations

import hashlib
import itertools
import json
import math
import zlib
from dataclasses import dataclass
from typing import Any, Iterator

import numpy as np

from .spec import RandomParameter, RangeParameter, SweepFile

__all__ = ["Case", "Grid", "parameter_values", "canonical"]


@dataclass(frozen=True)
class Case:
    index: int
    overrides: tuple[tuple[str, Any], ...]  # (dotted key, value), the [parameters] order
    seed: int | None  # the machine seed set on the case (None: the base file's)
    key: str  # hash of what the result depends on (resume)


def canonical(obj: Any) -> str:
    """JSON with a fixed form (sorted keys, shortest float repr): the input of the hashes."""
    return json.dumps(obj, sort_keys=True, separators=(",", ":"), allow_nan=True)


def _rounded(v: float, decimals: int | None) -> float | int:
    if decimals is None:
        return float(v)
    r = round(float(v), decimals)
    return int(r) if decimals == 0 else r


def _clean(v: float) -> float:
    """start + i * step without the float noise (0.1 * 3 = 0.30000000000000004 -> 0.3)."""
    return float(f"{v:.12g}") if math.isfinite(v) and v != 0.0 else float(v)


def parameter_values(key: str, p: Any, sweep_seed: int) -> list[Any]:
    """The values one parameter takes, in order."""
    if isinstance(p, list):
        return list(p)
    if isinstance(p, RangeParameter):
        if p.step is not None:
            n = math.floor((p.stop - p.start) / p.step * (1 + 1e-12)) + 1
            whole = p.round is None and all(isinstance(x, int) or float(x).is_integer() for x in (p.start, p.step))
            if whole:
                return [int(p.start) + i * int(p.step) for i in range(n)]
            return [_rounded(_clean(p.start + i * p.step), p.round) for i in range(n)]
        raw = np.geomspace(p.start, p.stop, p.num) if p.scale == "log" else np.linspace(p.start, p.stop, p.num)
        return [_rounded(_clean(float(x)), p.round) for x in raw]
    assert isinstance(p, RandomParameter)
    tag = zlib.crc32(key.encode())
    out = []
    for j in range(p.count):  # a generator per draw: more draws keep the earlier ones
        rng = np.random.default_rng([sweep_seed, tag, j])
        if p.random == "uniform":
            x: Any = rng.uniform(p.low, p.high)
        elif p.random == "loguniform":
            x = math.exp(rng.uniform(math.log(p.low), math.log(p.high)))  # type: ignore[arg-type]
        elif p.random == "normal":
            x = rng.normal(p.mean, p.std)
        else:
            x = int(rng.integers(int(p.low), int(p.high) + 1))  # type: ignore[arg-type]
        out.append(x if isinstance(x, int) else _rounded(float(x), p.round))
    return out


def _dedupe(values: list[Any], key: str) -> list[Any]:
    seen: list[str] = []
    for v in values:  # 20 and 20.0 are one value to the machine file
        same = float(v) if isinstance(v, (int, float)) and not isinstance(v, bool) else v
        c = canonical(same)
        if c in seen:
            raise ValueError(f"parameters.{key!r}: the value {v!r} comes twice (a case would run twice)")
        seen.append(c)
    return values


class Grid:
    """The values of every parameter and the cases they make (see the module docstring)."""

    def __init__(self, spec: SweepFile, base_text: str, base_duration: float) -> None:
        self.spec = spec
        self.keys = list(spec.parameters)
        self.values = {k: parameter_values(k, p, spec.sweep.seed) for k, p in spec.parameters.items()}
        for k, vs in self.values.items():
            if len(vs) <= 10_000:  # a long random draw list repeats a value only by chance
                _dedupe(vs, k)
        self.duration = spec.sweep.duration if spec.sweep.duration is not None else base_duration
        self._base_digest = hashlib.sha256(base_text.encode()).hexdigest()

    def __len__(self) -> int:
        return math.prod(len(v) for v in self.values.values())

    def seed_of(self, overrides: tuple[tuple[str, Any], ...]) -> int | None:
        if self.spec.sweep.machine_seed != "per_case":
            return None
        h = hashlib.sha256(canonical([self.spec.sweep.seed, [list(o) for o in overrides]]).encode()).digest()
        return int.from_bytes(h[:8], "big") & (2**63 - 1)

    def case(self, index: int, combo: tuple[Any, ...]) -> Case:
        overrides = tuple(zip(self.keys, combo))
        seed = self.seed_of(overrides)
        key = hashlib.sha256(canonical({
            "base": self._base_digest, "duration": self.duration, "seed": seed, "stop_on_fault": self.spec.sweep.stop_on_fault,
            "overrides": [list(o) for o in overrides],
        }).encode()).hexdigest()[:20]
        return Case(index, overrides, seed, key)

    def cases(self) -> Iterator[Case]:
        for i, combo in enumerate(itertools.product(*(self.values[k] for k in self.keys))):
            yield self.case(i, combo)

    def check_values(self) -> dict[str, list[Any]]:
        """Per parameter, the values to validate before anything runs: all of a list of up to
        50; the first, smallest and largest of a longer one, of a range and of random draws (a
        bad value in between fails its case)."""
        out: dict[str, list[Any]] = {}
        for k, vs in self.values.items():
            if len(vs) <= 50 and isinstance(self.spec.parameters[k], list):
                out[k] = list(vs)
                continue
            picks = [vs[0]]
            numeric = [v for v in vs if isinstance(v, (int, float)) and not isinstance(v, bool)]
            if numeric:
                picks += [min(numeric), max(numeric)]
            out[k] = list(dict.fromkeys(picks))
        return out
