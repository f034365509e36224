"""Where each field of a TOML document is written: ``positions(text)`` maps field paths in
the study errors' spelling (``sampling.method``, ``parameters[2].std``,
``parameters[0].direction[1]``) to the 1-based line and column of the key (of the value,
for array items), so that an error found after parsing can point at its place in the
file (``study.toml:14:1: parameters[2].std = -1: must be > 0``), as the scene loader's
errors do. Python's ``tomllib`` keeps no positions, hence this small scanner; it only
reads text that ``tomllib`` has already accepted, so it need not diagnose anything.
"""

from __future__ import annotations

import re
from typing import Dict, List, Optional, Tuple, Union

Path = Tuple[Union[str, int], ...]
_BARE = re.compile(r"[A-Za-z0-9_-]+")


def spell(path: Path) -> str:
    """``("parameters", 2, "std")`` → ``parameters[2].std``."""
    out = ""
    for part in path:
        out += f"[{part}]" if isinstance(part, int) else (f".{part}" if out else part)
    return out


class _Scanner:
    def __init__(self, text: str):
        self.text, self.i, self.found = text, 0, {}  # type: ignore[var-annotated]
        self.line_starts = [0] + [m.end() for m in re.finditer(r"\n", text)]

    def where(self, i: int) -> Tuple[int, int]:
        lo, hi = 0, len(self.line_starts) - 1
        while lo < hi:  # last line start ≤ i
            mid = (lo + hi + 1) // 2
            if self.line_starts[mid] <= i:
                lo = mid
            else:
                hi = mid - 1
        return lo + 1, i - self.line_starts[lo] + 1

    def record(self, path: Path, i: int) -> None:
        self.found.setdefault(spell(path), self.where(i))

    def peek(self, k: int = 1) -> str:
        return self.text[self.i:self.i + k]

    def skip(self, newlines: bool) -> None:
        """Skips blanks and comments (and line breaks when ``newlines``)."""
        while self.i < len(self.text):
            c = self.text[self.i]
            if c in " \t\r" or (newlines and c == "\n"):
                self.i += 1
            elif c == "#":
                while self.i < len(self.text) and self.text[self.i] != "\n":
                    self.i += 1
            else:
                return

    def string(self) -> str:
        """A basic, literal or multi-line string starting here; returns its raw content."""
        for quote in ('"""', "'''", '"', "'"):
            if self.peek(len(quote)) == quote:
                self.i += len(quote)
                start = self.i
                while self.i < len(self.text) and self.peek(len(quote)) != quote:
                    self.i += 2 if quote[0] == '"' and self.text[self.i] == "\\" else 1
                content = self.text[start:self.i]
                self.i += len(quote)
                while quote in ('"""', "'''") and self.peek() == quote[0]:  # up to 2 quotes end it
                    self.i += 1
                return content
        raise ValueError("not a string")

    def key(self) -> List[str]:
        """A dotted key: bare or quoted parts."""
        parts: List[str] = []
        while True:
            self.skip(False)
            if self.peek() in ('"', "'"):
                parts.append(self.string())
            else:
                m = _BARE.match(self.text, self.i)
                if not m:
                    return parts
                parts.append(m.group())
                self.i = m.end()
            self.skip(False)
            if self.peek() != ".":
                return parts
            self.i += 1

    def value(self, path: Path) -> None:
        self.skip(False)
        c = self.peek()
        if c == "{":
            self.i += 1
            while True:
                self.skip(True)
                if self.peek() in ("}", ""):
                    self.i += 1
                    return
                if self.peek() == ",":
                    self.i += 1
                    continue
                start = self.i
                k = self.key()
                self.record(path + tuple(k), start)
                self.skip(False)
                self.i += 1  # '='
                self.value(path + tuple(k))
        elif c == "[":
            self.i += 1
            index = 0
            while True:
                self.skip(True)
                if self.peek() in ("]", ""):
                    self.i += 1
                    return
                if self.peek() == ",":
                    self.i += 1
                    index += 1
                    continue
                self.record(path + (index,), self.i)
                self.value(path + (index,))
        elif c in ('"', "'"):
            self.string()
        else:  # number, boolean, date: up to the next delimiter
            while self.i < len(self.text) and self.text[self.i] not in ",]}\n#":
                self.i += 1

    def document(self) -> Dict[str, Tuple[int, int]]:
        table: Path = ()
        counts: Dict[Path, int] = {}  # arrays of tables: items so far
        while True:
            self.skip(True)
            if self.i >= len(self.text):
                return self.found
            start = self.i
            if self.peek(2) == "[[" or self.peek() == "[":
                array = self.peek(2) == "[["
                self.i += 2 if array else 1
                names = self.key()
                self.skip(False)
                self.i += 2 if array else 1
                table = self._resolve(names, counts)
                if array:
                    counts[table] = counts.get(table, 0) + 1
                    table = table + (counts[table] - 1,)
                self.record(table, start)
            else:
                k = self.key()
                if not k:  # not TOML after all: give up quietly
                    return self.found
                self.record(table + tuple(k), start)
                self.skip(False)
                self.i += 1  # '='
                self.value(table + tuple(k))

    @staticmethod
    def _resolve(names: List[str], counts: Dict[Path, int]) -> Path:
        """A header's dotted name with the current item of every array of tables on it."""
        path: Path = ()
        for name in names:
            path = path + (name,)
            if path in counts:
                path = path + (counts[path] - 1,)
        # the header's own last name is resolved by the caller for [[...]]
        if names and path and isinstance(path[-1], int) and path[-2] == names[-1]:
            path = path[:-1]
        return path


def positions(text: str) -> Dict[str, Tuple[int, int]]:
    """Every field path of the TOML ``text`` → (line, column), 1-based."""
    try:
        return _Scanner(text).document()
    except (ValueError, IndexError):  # pragma: no cover - text tomllib accepted
        return {}


def locate(text: str, where: str) -> Optional[Tuple[int, int]]:
    """The position of field ``where``, or of its nearest written ancestor (a missing
    field points at the table that lacks it); ``None`` if nothing of it is written."""
    found = positions(text)
    while where:
        if where in found:
            return found[where]
        cut = max(where.rfind("."), where.rfind("["))
        where = where[:cut] if cut > 0 else ""
    return None
