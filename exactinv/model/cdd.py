"""cdd files (cddlib, lrs, Sage, pycddlib, Polymake): H-representations (``.ine``)
and V-representations (``.ext``), read and written exactly.

The format (cddlib manual, Section 1)::

    * comments start with '*' (lines before "begin" that are not keywords are ignored too)
    H-representation                 (or V-representation; H is the default)
    linearity 2 1 3                  (optional: the rows that are equalities / lines)
    begin
     m  d+1  rational                (number type: integer, rational or real)
     b_1  -a_11 ... -a_1d            (H: the row says b_1 - a_1 x >= 0)
     ...
    end
    (options after "end", such as "incidence" or "minimize", are ignored)

In a V-representation a row ``1 v_1 ... v_d`` is a point and ``0 r_1 ... r_d``
a ray, or a line when its index is listed in ``linearity``; with no point at all
the origin is implied (cdd's convention for cones).

Entries are read exactly: ``integer`` files take integers, ``rational`` files
integers and ``p/q``.  ``real`` files hold floats and are refused unless the
caller passes ``allow_float=True``; each entry is then the exact value of the
double it denotes (:func:`~exactinv.exact_from_float`), which is what a float
backend would compute with.  Every error names the source, the line and what
is wrong.  This module knows no :class:`~exactinv.Polyhedron`; it turns text
into rows and rows into text (``Polyhedron.from_cdd`` / ``to_cdd`` use it).
"""

from __future__ import annotations

import os
import re
from dataclasses import dataclass
from fractions import Fraction
from typing import Any, Sequence

from ..core.scalars import Matrix, Vector, exact_from_float
from ..errors import InvalidInput

__all__ = ["CddData", "read_cdd", "parse_cdd", "ine_text", "ext_text"]

NUMBER_TYPES = ("integer", "rational", "real")
_INTEGER = re.compile(r"[+-]?\d+\Z")
_RATIONAL = re.compile(r"[+-]?\d+/\d+\Z")
_REAL = re.compile(r"[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?\Z")


@dataclass(frozen=True)
class CddData:
    """The content of a cdd file, exact.

    ``kind`` is ``"H"`` or ``"V"``.  For ``"H"``: the inequalities G x <= b
    (``G``, ``b``) and the equalities E x = e (``E``, ``e``).  For ``"V"``:
    ``points``, ``rays`` and ``lines`` (``points`` may be empty: then the origin
    is implied).  ``number_type`` is the file's declared number type.
    """

    kind: str
    dimension: int
    number_type: str
    G: Matrix = ()
    b: Vector = ()
    E: Matrix = ()
    e: Vector = ()
    points: Matrix = ()
    rays: Matrix = ()
    lines: Matrix = ()


def read_cdd(source: Any, *, allow_float: bool = False) -> CddData:
    """Parse a cdd file given as a path (``str`` or ``os.PathLike``) or as its text.

    A string that spans several lines is the text; a one-line string is a path.  Errors from a file name it.

    >>> d = read_cdd("H-representation\\nbegin\\n 2 2 rational\\n 1 -1\\n 1/2 1\\nend\\n")
    >>> d.kind, d.G, d.b                           # x <= 1, -x <= 1/2
    ('H', ((Fraction(1, 1),), (Fraction(-1, 1),)), (Fraction(1, 1), Fraction(1, 2)))
    """
    if isinstance(source, os.PathLike) or (isinstance(source, str) and "\n" not in source.strip()):
        path = os.fspath(source)
        if os.path.isdir(path):
            raise InvalidInput(f"{path}: is a directory, not a cdd file")
        try:
            with open(path, encoding="utf-8") as fh:
                text = fh.read()
        except OSError as exc:
            raise InvalidInput(f"{path}: cannot read the cdd file ({exc.strerror or exc})") from None
        except UnicodeDecodeError:
            raise InvalidInput(f"{path}: not a text file (a cdd file is plain text)") from None
        return parse_cdd(text, path, allow_float=allow_float)
    if not isinstance(source, str):
        raise InvalidInput(f"cdd: expected a path or the text of a cdd file, got {type(source).__name__}")
    return parse_cdd(source, "cdd text", allow_float=allow_float)


def parse_cdd(text: str, where: str = "cdd text", *, allow_float: bool = False) -> CddData:
    """Parse the text of a cdd file; ``where`` (a path) prefixes every error.

    >>> d = parse_cdd("V-representation\\nlinearity 1 2\\nbegin\\n2 3 integer\\n1 0 0\\n0 1 -1\\nend")
    >>> d.kind, d.points, d.lines                  # the origin and the line through (1, -1)
    ('V', ((Fraction(0, 1), Fraction(0, 1)),), ((Fraction(1, 1), Fraction(-1, 1)),))
    >>> parse_cdd("begin\\n1 2 real\\n1 -0.5\\nend", "box.ine")
    Traceback (most recent call last):
    ...
    exactinv.errors.InvalidInput: box.ine, line 2: the number type is 'real' (floats, not exact); ...
    """
    lines = text.splitlines()
    kind = "H"
    linearity: list[int] | None = None
    linearity_line = 0
    k = 0
    while k < len(lines):  # the preamble
        words = _words(lines[k])
        k += 1
        if not words:
            continue
        head = words[0].lower()
        if head == "begin":
            break
        if head == "h-representation":
            kind = "H"
        elif head == "v-representation":
            kind = "V"
        elif head == "linearity":
            linearity, linearity_line = _linearity(words, where, k), k
    else:
        raise InvalidInput(f"{where}: no 'begin' line; a cdd file holds its rows between 'begin' and 'end'")
    while k < len(lines) and not _words(lines[k]):
        k += 1
    if k == len(lines):
        raise InvalidInput(f"{where}: nothing after 'begin'; expected the size line 'm d+1 number_type'")
    header, header_line = _words(lines[k]), k + 1
    k += 1
    m, width, number_type = _header(header, where, header_line, allow_float)
    rows: list[tuple[Fraction, ...]] = []
    row_lines: list[int] = []
    entries: list[str] = []
    start = 0
    while k < len(lines):
        words = _words(lines[k])
        k += 1
        if words and words[0].lower() == "end":
            if entries:
                raise InvalidInput(f"{where}, line {start}: the row has {len(entries)} entries, expected {width}")
            break
        for w in words:
            if not entries:
                start = k
            entries.append(w)
            if len(entries) == width:
                rows.append(tuple(_number(x, number_type, where, start) for x in entries))
                row_lines.append(start)
                entries = []
    else:
        raise InvalidInput(f"{where}: no 'end' line after the rows")
    if len(rows) != m:
        raise InvalidInput(f"{where}, line {header_line}: the size line announces {m} rows but {len(rows)} "
                           f"rows of {width} entries follow")
    lin = set()
    for i in linearity or ():
        if i > m:
            raise InvalidInput(f"{where}, line {linearity_line}: linearity names row {i} but there are only {m} rows")
        lin.add(i - 1)
    d = width - 1
    if kind == "H":
        return _h_data(rows, row_lines, lin, d, number_type, where)
    return _v_data(rows, row_lines, lin, d, number_type, where)


def _words(line: str) -> list[str]:
    cut = line.find("*")
    return (line if cut < 0 else line[:cut]).split()


def _linearity(words: list[str], where: str, line: int) -> list[int]:
    try:
        values = [int(w) for w in words[1:]]
    except ValueError:
        raise InvalidInput(f"{where}, line {line}: 'linearity k i_1 ... i_k' takes integers, "
                           f"got {' '.join(words[1:])!r}") from None
    if not values or values[0] != len(values) - 1:
        raise InvalidInput(f"{where}, line {line}: 'linearity k i_1 ... i_k' must list k = {values[0] if values else '?'} "
                           f"row indices, got {max(len(values) - 1, 0)}")
    if any(i < 1 for i in values[1:]):
        raise InvalidInput(f"{where}, line {line}: linearity row indices start at 1, got {values[1:]}")
    return values[1:]


def _header(words: list[str], where: str, line: int, allow_float: bool) -> tuple[int, int, str]:
    if len(words) != 3:
        raise InvalidInput(f"{where}, line {line}: expected the size line 'm d+1 number_type', got {' '.join(words)!r}")
    try:
        m, width = int(words[0]), int(words[1])
    except ValueError:
        raise InvalidInput(f"{where}, line {line}: the size line 'm d+1 number_type' needs two integers, "
                           f"got {words[0]!r} and {words[1]!r}") from None
    if m < 0 or width < 2:
        raise InvalidInput(f"{where}, line {line}: the size line needs m >= 0 rows and d+1 >= 2 columns, got {m} {width}")
    number_type = words[2].lower()
    if number_type not in NUMBER_TYPES:
        raise InvalidInput(f"{where}, line {line}: unknown number type {words[2]!r} (cdd has integer, rational, real)")
    if number_type == "real" and not allow_float:
        raise InvalidInput(f"{where}, line {line}: the number type is 'real' (floats, not exact); exactinv does not "
                           f"guess which rationals were meant. Write the file as 'rational', or pass "
                           f"allow_float=True to read each entry as the exact value of its double")
    return m, width, number_type


def _number(word: str, number_type: str, where: str, line: int) -> Fraction:
    if _INTEGER.match(word):
        return Fraction(int(word))
    if _RATIONAL.match(word) and number_type != "integer":
        num, den = word.split("/")
        if int(den) == 0:
            raise InvalidInput(f"{where}, line {line}: {word!r} divides by zero")
        if number_type == "real":  # what a float backend computes: the double nearest p/q
            return exact_from_float(int(num) / int(den))
        return Fraction(int(num), int(den))
    if number_type == "real" and _REAL.match(word):
        try:
            return exact_from_float(float(word))
        except InvalidInput:
            raise InvalidInput(f"{where}, line {line}: {word!r} overflows a double") from None
    expected = {"integer": "an integer", "rational": "an integer or p/q",
                "real": "a number"}[number_type]
    hint = ""
    if number_type != "real" and _REAL.match(word):
        hint = " (a decimal: declare the number type 'real' and pass allow_float=True, or write it as p/q)"
    raise InvalidInput(f"{where}, line {line}: {word!r} is not {expected}, as the number type "
                       f"{number_type!r} requires{hint}")


def _h_data(rows, row_lines, lin, d, number_type, where) -> CddData:
    G, b, E, e = [], [], [], []
    for i, row in enumerate(rows):
        beta, g = row[0], tuple(-x for x in row[1:])  # beta - a.x >= 0, i.e. g.x <= beta with g = a
        if not any(g):
            if beta < 0 or (i in lin and beta != 0):
                raise InvalidInput(f"{where}, line {row_lines[i]}: the row reads {'0 = ' if i in lin else '0 <= '}"
                                   f"{beta}, so the polyhedron is empty")
            continue  # 0 <= beta: void (cdd writes it for unbounded sets)
        if i in lin:
            E.append(g)
            e.append(beta)
        else:
            G.append(g)
            b.append(beta)
    return CddData("H", d, number_type, G=tuple(G), b=tuple(b), E=tuple(E), e=tuple(e))


def _v_data(rows, row_lines, lin, d, number_type, where) -> CddData:
    points, rays, lines = [], [], []
    for i, row in enumerate(rows):
        t, v = row[0], row[1:]
        if t == 1:
            if i in lin:
                raise InvalidInput(f"{where}, line {row_lines[i]}: linearity names row {i + 1}, a point; "
                                   f"only rays (leading 0) can be lines")
            points.append(v)
        elif t == 0:
            if not any(v):
                raise InvalidInput(f"{where}, line {row_lines[i]}: the ray is the zero vector")
            (lines if i in lin else rays).append(v)
        else:
            raise InvalidInput(f"{where}, line {row_lines[i]}: a V-representation row starts with 1 (a point) "
                               f"or 0 (a ray or line), got {t}")
    return CddData("V", d, number_type, points=tuple(points), rays=tuple(rays), lines=tuple(lines))


# ---------------------------------------------------------------- writing
def _number_type(rows: Sequence[Sequence[Fraction]]) -> str:
    return "integer" if all(x.denominator == 1 for r in rows for x in r) else "rational"


def _block(header: str, rows: list[tuple[Fraction, ...]], linearity: Sequence[int], width: int) -> str:
    out = [header]
    if linearity:
        out.append("linearity " + " ".join(str(x) for x in [len(linearity), *linearity]))
    out += ["begin", f"{len(rows)} {width} {_number_type(rows)}"]
    out += [" ".join(str(x) for x in r) for r in rows]
    out.append("end")
    return "\n".join(out) + "\n"


def ine_text(G: Matrix, b: Vector, E: Matrix = (), e: Vector = ()) -> str:
    """The cdd H-representation of {x : Gx <= b, Ex = e} (equalities as ``linearity``).

    >>> print(ine_text(((Fraction(1),), (Fraction(-1),)), (Fraction(1), Fraction(1, 2))), end="")
    H-representation
    begin
    2 2 rational
    1 -1
    1/2 1
    end
    """
    n = len(G[0]) if G else len(E[0])
    rows = [(beta, *(-x for x in g)) for g, beta in zip(G, b)]
    rows += [(beta, *(-x for x in g)) for g, beta in zip(E, e)]
    lin = list(range(len(G) + 1, len(G) + len(E) + 1))
    return _block("H-representation", rows, lin, n + 1)


def ext_text(points: Matrix, rays: Matrix = (), lines: Matrix = ()) -> str:
    """The cdd V-representation conv(points) + cone(rays) + span(lines).

    >>> print(ext_text(((Fraction(0), Fraction(0)),), lines=((Fraction(1), Fraction(-1)),)), end="")
    V-representation
    linearity 1 2
    begin
    2 3 integer
    1 0 0
    0 1 -1
    end
    """
    n = len(points[0])
    one, zero = Fraction(1), Fraction(0)
    rows = [(one, *p) for p in points] + [(zero, *r) for r in rays] + [(zero, *l) for l in lines]
    lin = list(range(len(points) + len(rays) + 1, len(rows) + 1))
    return _block("V-representation", rows, lin, n + 1)
