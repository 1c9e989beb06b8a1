"""The values in URDF and SDF text (numbers, vectors, whole numbers, switches): one set of checks for both.

A value that fails raises BadValue naming the Problem and the text; each reader words the message its
own way (urdf_model.UrdfError.of: the URDF is refused; sdf_elements: the SDF element is skipped with a
warning), so the rules are written once and the messages stay each format's.
"""
from __future__ import annotations

import math
from enum import Enum

__all__ = ['Problem', 'BadValue', 'number', 'numbers', 'words', 'integer', 'boolean']


class Problem(Enum):
    COUNT = 'count'      # not the number of values expected
    NUMBER = 'number'    # not a decimal number
    FINITE = 'finite'    # a number, but inf or nan
    INTEGER = 'integer'  # not a whole number
    BOOLEAN = 'boolean'  # not true, false, 1 or 0


class BadValue(ValueError):
    """`text` (the word or text at fault, as given) is unusable for `problem`; `count`: the number of values
    expected (Problem.COUNT)."""

    def __init__(self, problem: Problem, text: str | None, count: int | None = None) -> None:
        super().__init__('%s: %r' % (problem.value, text))
        self.problem, self.text, self.count = problem, text, count


def _convert(kind, problem: Problem, text):
    """kind(text) (float or int), spaces around allowed; BadValue(problem) when it is not one."""
    try:
        return kind(str(text).strip())
    except ValueError:
        raise BadValue(problem, text) from None


def number(text: str | None) -> float:
    """A finite float."""
    value = _convert(float, Problem.NUMBER, text)
    if not math.isfinite(value):
        raise BadValue(Problem.FINITE, text)
    return value


def words(text: str | None, count: int) -> list[str]:
    """The `count` whitespace-separated words of `text` (None reads as empty)."""
    parts = (text or '').split()
    if len(parts) != count:
        raise BadValue(Problem.COUNT, text, count)
    return parts


def numbers(text: str | None, count: int) -> tuple[float, ...]:
    """`count` finite floats from whitespace-separated `text`. Checked as a whole: the count, then that every
    word is a number, then that every number is finite; BadValue's text is then the whole `text`."""
    parts = words(text, count)
    try:
        values = tuple(float(p) for p in parts)
    except ValueError:
        raise BadValue(Problem.NUMBER, text) from None
    if not all(math.isfinite(v) for v in values):
        raise BadValue(Problem.FINITE, text)
    return values


def integer(text: str | None) -> int:
    return _convert(int, Problem.INTEGER, text)


def boolean(text: str | None) -> bool:
    """'true' or '1' (any case, spaces around) is True, 'false' or '0' False."""
    value = (text or '').strip().lower()
    if value in ('true', '1'):
        return True
    if value in ('false', '0'):
        return False
    raise BadValue(Problem.BOOLEAN, text)
