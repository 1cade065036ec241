"""The results of the cases as they come in, kept in OUT/journal/ so a sweep resumes.

Results are written in parts, `part-000001.jsonl`, ... (one JSON object a line), each part
atomically (kernel.atomic_write_text) every FLUSH_CASES results or FLUSH_SECONDS seconds and at
the end: a sweep killed at any moment keeps every part it finished and loses at most the last
few seconds. A re-run reads all parts (a later result of a case wins) and skips the cases whose
result is there.

Decisions
1. (issue: "re-running skips cases whose result exists") a result is a case that ran: status
   "ok" or "fault" (a run that ended on a runtime fault, e.g. Error 02, is what the sweep
   measures). A "failed" case (it raised, or its worker died) runs again on a re-run: the
   cause may have been the worker, and a deterministic failure costs one case's time. A
   result that lacks a field now in `collect` runs again too. Test:
   test_sweep_run.py::test_resume_skips_done_cases_and_reruns_failed_ones.
2. (brief: "files that must persist are written atomically") parts instead of one appended
   file: each part is whole or absent, so no torn last line is ever read (and a line that is
   not a result, from a hand edit, is skipped). Test:
   test_sweep_run.py::test_journal_parts_are_whole_and_unreadable_lines_are_skipped.
"""

from __future__ import annotations

import json
import re
import time
from pathlib import Path
from typing import Any, Iterable

from axisline.kernel import atomic_write_text

__all__ = ["Journal", "is_result"]

FLUSH_CASES = 500
FLUSH_SECONDS = 10.0
_PART = re.compile(r"^part-(\d{6,})\.jsonl$")


def is_result(r: dict[str, Any], collect: Iterable[str]) -> bool:
    """A stored result that a re-run keeps (decision 1)."""
    if r.get("status") not in ("ok", "fault"):
        return False
    have = set(r.get("values", {}))
    for table, rows in (r.get("tables") or {}).items():
        for row in rows[:1]:
            have.update(f"{table}.{c}" for c in row)
    need = [f for f in collect if f not in have]
    # a per-row field of an empty table leaves no column: the table itself is there
    tables = set(r.get("tables") or {})
    return all(any(f.startswith(t + ".") for t in tables) for f in need)


class Journal:
    def __init__(self, out: Path) -> None:
        self.dir = out / "journal"
        self.pending: list[str] = []
        self._last = time.monotonic()
        self._next = 1 + max((int(m.group(1)) for p in self._parts() if (m := _PART.match(p.name))), default=0)

    def _parts(self) -> list[Path]:
        if not self.dir.is_dir():
            return []
        return sorted(p for p in self.dir.iterdir() if _PART.match(p.name))

    def load(self) -> dict[str, dict[str, Any]]:
        """Every stored result by case key (a later part wins); unreadable lines are skipped."""
        out: dict[str, dict[str, Any]] = {}
        for part in self._parts():
            try:
                text = part.read_text(encoding="utf-8")
            except (OSError, UnicodeDecodeError):
                continue
            for line in text.splitlines():
                try:
                    r = json.loads(line)
                except json.JSONDecodeError:
                    continue
                if isinstance(r, dict) and isinstance(r.get("key"), str):
                    out[r["key"]] = r
        return out

    def add(self, result: dict[str, Any]) -> None:
        self.pending.append(json.dumps(result, separators=(",", ":"), allow_nan=True))
        if len(self.pending) >= FLUSH_CASES or time.monotonic() - self._last >= FLUSH_SECONDS:
            self.flush()

    def compact(self) -> None:
        """All parts into one (the sweep has ended): written first, then the older parts go
        (the new part has the highest number, so it wins over any part left by a kill here)."""
        parts = self._parts()
        if len(parts) <= 1:
            return
        merged = self.load()
        self.pending = [json.dumps(r, separators=(",", ":"), allow_nan=True) for r in merged.values()]
        self.flush()
        for p in parts:
            p.unlink(missing_ok=True)

    def flush(self) -> None:
        self._last = time.monotonic()
        if not self.pending:
            return
        self.dir.mkdir(parents=True, exist_ok=True)
        atomic_write_text(self.dir / f"part-{self._next:06d}.jsonl", "\n".join(self.pending) + "\n")
        self._next += 1
        self.pending = []
