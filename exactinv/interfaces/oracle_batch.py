"""The oracle's batch mode: judge a CSV or JSON-lines file of float results.

Every row is judged on its own by :mod:`exactinv.interfaces.oracle_judges`; a
row that cannot be judged is returned with its error and the batch goes on.
"""

from __future__ import annotations

import csv
import json
import os
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

from ..core.scalars import to_rational
from ..errors import ExactinvException, InvalidInput
from .method_format import method_from_text, parse_method
from .oracle_judges import Verdict, judge_gamma, judge_radius, judge_threshold
from .problem import load_problem
from .strict_json import did_you_mean

__all__ = ["BatchRow", "judge_batch", "judge_row"]


@dataclass(frozen=True)
class BatchRow:
    """One row of a batch file: where it came from and its :class:`Verdict`, or,
    for a row that could not be judged (bad input), ``verdict`` None and the
    ``error`` naming the row and what is wrong."""

    name: str
    quantity: str
    method: str
    claimed: str
    verdict: Verdict | None
    error: str | None = None
    row: int = 0

    @property
    def status(self) -> str:
        """The verdict's status, or ``"error"``."""
        return self.verdict.status if self.verdict is not None else "error"


def judge_batch(path: str, tolerance: Any = "1e-9") -> list[BatchRow]:
    """Judge a batch of float results: CSV (problem,quantity,method,claimed) or
    JSON lines; problem paths are relative to the batch file.  Every row is
    judged on its own: a row that cannot be judged (bad problem, method,
    quantity or claim) is returned with its ``error`` and the batch goes on.
    A batch file that cannot be read raises :class:`InvalidInput`.

    >>> import tempfile, pathlib
    >>> d = pathlib.Path(tempfile.mkdtemp())
    >>> _ = (d / 'p.json').write_text(json.dumps({'system': {'A': [['-1']]}, 'polyhedron': {'G': [[1], [-1]], 'b': [1, 1]}}))
    >>> _ = (d / 'rows.csv').write_text('problem,quantity,method,claimed\\np.json,gamma,,0.5\\np.json,threshold,forward_euler,2\\nnope.json,gamma,,1\\n')
    >>> [row.status for row in judge_batch(d / 'rows.csv')]   # x' = -x on [-1, 1]: gamma* = 1/2, forward Euler (1 - dt) x: dt <= 2; no file nope.json
    [<Status.TIGHT: 'tight'>, <Status.TIGHT: 'tight'>, 'error']
    """  # noqa: E501 (doctest output)
    tol = to_rational(tolerance, "--tolerance")
    if tol < 0:
        raise InvalidInput(f"--tolerance: must be >= 0, got {tolerance}")
    path = os.fspath(path)
    if os.path.isdir(path):
        raise InvalidInput(f"{path}: is a directory, not a results file")
    base = os.path.dirname(os.path.abspath(path))
    try:
        with open(path, encoding="utf-8", newline="") as fh:
            if path.endswith(".jsonl"):
                rows = [_json_row(line) for line in fh if line.strip()]
            else:
                reader = csv.DictReader(fh)
                rows = list(reader)
                if not reader.fieldnames:
                    raise InvalidInput(f"{path}: empty CSV file (expected the header problem,quantity,method,claimed)")
                missing = [c for c in ("problem", "claimed") if c not in reader.fieldnames]
                if missing:
                    raise InvalidInput(f"{path}: the CSV header lacks the column(s) {', '.join(missing)} "
                                       f"(expected problem,quantity,method,claimed; got {','.join(map(str, reader.fieldnames))})")
    except OSError as exc:
        raise InvalidInput(f"{path}: cannot read the results file ({exc.strerror or exc})") from None
    except (UnicodeDecodeError, csv.Error) as exc:
        raise InvalidInput(f"{path}: not a CSV or JSON-lines text file ({exc})") from None
    return [_safe_row(k, row, base, tol) for k, row in enumerate(rows, 1)]


def _json_row(line: str) -> Any:
    try:
        return json.loads(line)
    except json.JSONDecodeError as exc:
        return InvalidInput(f"not valid JSON ({exc})")


def judge_row(row: dict, base: str = ".", tolerance: Any = "1e-9", number: int = 1) -> BatchRow:
    """Judge one row of a batch (a dict with problem, quantity, method,
    claimed; ``problem`` a file relative to ``base``, a problem dict or its
    JSON text), as :func:`judge_batch` judges row ``number``: a row that
    cannot be judged comes back with its ``error``.

    >>> box = {"system": {"A": [[-1]]}, "polyhedron": {"G": [[1], [-1]], "b": [1, 1]}}
    >>> print(judge_row({"problem": box, "quantity": "gamma", "claimed": "0.5"}).status)  # gamma* = 1/2
    tight
    """
    tol = to_rational(tolerance, "tolerance")
    if tol < 0:
        raise InvalidInput(f"tolerance: must be >= 0, got {tolerance}")
    return _safe_row(number, row, base, tol)


def _safe_row(k: int, row: Any, base: str, tolerance: Fraction) -> BatchRow:
    get = row.get if isinstance(row, dict) else (lambda key, default=None: default)
    name = get("problem")
    name = os.path.basename(str(name)) if isinstance(name, str) else ("-" if name is None else "(inline)")
    method = get("method")
    shown = [name, str(get("quantity") or "threshold"), str(method) if method else "-", str(get("claimed", ""))]
    try:
        if isinstance(row, InvalidInput):
            raise row
        if not isinstance(row, dict):
            raise InvalidInput(f"expected an object with problem, quantity, method, claimed; got {type(row).__name__}")
        return _judge_row(k, row, base, tolerance)
    except ExactinvException as exc:
        msg = str(exc)
        return BatchRow(*shown, verdict=None, error=f"row {k}: {msg}" if not msg.startswith(f"row {k}") else msg, row=k)


def _claim_of(text: Any) -> Any:
    if isinstance(text, (int, float)) and not isinstance(text, bool):
        return text
    if not isinstance(text, str) or not text.strip():
        raise InvalidInput(f"claimed: missing or not a number ({text!r})")
    try:
        return float(text)
    except ValueError:
        pass
    try:
        return to_rational(text.strip(), "claimed")
    except InvalidInput:
        raise InvalidInput(f"claimed: cannot read {text!r} as a number (write e.g. 0.5, 1e-3, 1/3 or inf)") from None


def _judge_row(k: int, row: dict, base: str, tolerance: Any) -> BatchRow:
    extra = set(row) - {"problem", "quantity", "method", "claimed"} - {None}
    if extra:
        key = sorted(extra)[0]
        raise InvalidInput(f"row {k}: unknown column {key!r}"
                           f"{did_you_mean(key, ('problem', 'quantity', 'method', 'claimed'))}")
    if None in row:
        raise InvalidInput(f"row {k}: more fields than the header has columns")
    source = row.get("problem")
    if not source:
        raise InvalidInput(f"row {k}: problem: missing")
    inline = isinstance(source, dict) or source.lstrip().startswith("{")  # the problem itself, not a file name
    prob = load_problem(source if inline else os.path.join(base, source))
    spec = row.get("method") or None
    if isinstance(spec, str):
        method = method_from_text(spec, "method")
    else:
        method = parse_method(spec) if spec else prob.method
    quantity = row.get("quantity") or "threshold"
    claimed = _claim_of(row.get("claimed"))
    if quantity in ("threshold", "radius") and method is None:
        raise InvalidInput(f"row {k}: method: a {quantity} needs a method (in the row or in the problem file)")
    if quantity == "threshold":
        v = judge_threshold(prob.system, prob.polyhedron, method, claimed, tolerance)
    elif quantity == "gamma":
        v = judge_gamma(prob.system, prob.polyhedron, claimed, tolerance)
    elif quantity == "radius":
        v = judge_radius(method, claimed, tolerance)
    else:
        raise InvalidInput(f"row {k}: quantity: unknown {quantity!r}{did_you_mean(quantity, ('threshold', 'gamma', 'radius'))} "
                           "(threshold, gamma, radius)")
    name = prob.name if inline else os.path.basename(str(source))
    return BatchRow(name, quantity, method.name if method else "-", str(row["claimed"]), v, row=k)
