"""A corpus for ``exactinv batch``: the tasks in its inputs, and the ids an
output file already holds.

Inputs, each read on the machine that starts the batch (workers need no
shared file system: a task carries the text it works on):

* a directory: every ``*.json`` problem file below it; id = the path relative
  to the directory (``sub/box.json``);
* a ``.json`` file: one problem; id = the path as given;
* a ``.jsonl`` file: one problem object per line; id = its ``"name"`` if it
  has one, else ``FILE:LINE``;
* a ``.csv`` file: an oracle batch (columns problem, quantity, method,
  claimed; :func:`exactinv.interfaces.oracle.judge_batch`), one judging task
  per row; id = ``FILE:ROW``; each problem file it names is read here.

A file that cannot be read, or a line that is not JSON, still becomes a task:
its problem is recorded as an error and the batch goes on.

>>> import json, os, tempfile
>>> d = tempfile.mkdtemp()
>>> with open(os.path.join(d, "p.jsonl"), "w") as fh:
...     _ = fh.write(json.dumps({"name": "box", "system": {"A": [[-1]]}, "polyhedron": {"G": [[1], [-1]], "b": [1, 1]}})
...                  + "\\nnot json\\n")
>>> [(t.id, t.kind) for t in read_corpus([os.path.join(d, "p.jsonl")])]
[('box', 'certify'), ('p.jsonl:2', 'certify')]
"""

from __future__ import annotations

import csv
import json
import os
from dataclasses import dataclass, field
from pathlib import Path
from typing import Iterable, Sequence

from ...errors import InvalidInput

__all__ = ["Task", "read_corpus", "done_ids"]


@dataclass(frozen=True)
class Task:
    """One unit of work: ``kind`` is ``"certify"`` (``text``: a problem's JSON)
    or ``"judge"`` (``row``: an oracle row, its problem inlined as JSON text).
    ``error``: why the input could not even be read (the task is then
    recorded as an error without running); ``source``: the file it came from."""

    id: str
    kind: str
    text: str | None = field(default=None, repr=False)
    row: dict | None = field(default=None, repr=False)
    error: str | None = None
    source: str = ""


def read_corpus(inputs: Sequence[str | os.PathLike]) -> list[Task]:
    """The tasks of ``inputs`` (directories, .json, .jsonl, .csv), in order.
    Raises :class:`InvalidInput` for an input that does not exist or has an
    unknown suffix, and for two tasks with the same id.

    >>> import os, tempfile
    >>> d = tempfile.mkdtemp()
    >>> os.mkdir(os.path.join(d, "sub"))
    >>> for name in ("sub/box.json", "a.json"):
    ...     with open(os.path.join(d, name), "w") as fh:
    ...         _ = fh.write('{"system": {"A": [[-1]]}, "polyhedron": {"G": [[1], [-1]], "b": [1, 1]}}')
    >>> [(t.id, t.kind, t.error) for t in read_corpus(d)]
    [('a.json', 'certify', None), ('sub/box.json', 'certify', None)]
    >>> read_corpus([os.path.join(d, "a.txt")])
    Traceback (most recent call last):
    ...
    exactinv.errors.InvalidInput: ...a.txt: no such file or directory
    """
    if isinstance(inputs, (str, os.PathLike)):
        inputs = [inputs]
    if not inputs:
        raise InvalidInput("INPUT: give at least one directory, .json, .jsonl or .csv file")
    tasks: list[Task] = []
    for source in map(str, inputs):
        tasks.extend(_read(source))
    seen: dict[str, int] = {}
    for k, t in enumerate(tasks):
        if t.id in seen:
            raise InvalidInput(f"{t.id}: two problems have this id (give them different \"name\"s); "
                               "a resumable batch needs unique ids")
        seen[t.id] = k
    return tasks


def _read(source: str) -> list[Task]:
    if os.path.isdir(source):
        root = Path(source)
        return [_file_task(str(p), p.relative_to(root).as_posix()) for p in sorted(root.rglob("*.json"))]
    if not os.path.exists(source):
        raise InvalidInput(f"{source}: no such file or directory")
    suffix = os.path.splitext(source)[1].lower()
    if suffix == ".json":
        return [_file_task(source, source)]
    if suffix == ".jsonl":
        return list(_jsonl_tasks(source))
    if suffix == ".csv":
        return list(_csv_tasks(source))
    raise InvalidInput(f"{source}: unknown kind of input (expected a directory, .json, .jsonl or .csv)")


def _text(path: str) -> tuple[str | None, str | None]:
    """(text, None) or (None, why it cannot be read)."""
    try:
        with open(path, encoding="utf-8") as fh:
            return fh.read(), None
    except OSError as exc:
        return None, f"{path}: cannot read the problem file ({exc.strerror or exc})"
    except UnicodeDecodeError:
        return None, f"{path}: not a text file (a problem file is UTF-8 JSON)"


def _file_task(path: str, task_id: str) -> Task:
    text, error = _text(path)
    return Task(task_id, "certify", text=text, error=error, source=path)


def _jsonl_tasks(path: str) -> Iterable[Task]:
    text, error = _text(path)
    if error:
        raise InvalidInput(error.replace("problem file", "JSON-lines file"))
    base = os.path.basename(path)
    for number, line in enumerate(text.splitlines(), 1):
        if line.strip():
            yield Task(_line_name(line) or f"{base}:{number}", "certify", text=line, source=f"{path}:{number}")


def _line_name(line: str) -> str | None:
    try:
        name = json.loads(line).get("name")
    except (ValueError, AttributeError, RecursionError):
        return None
    return name if isinstance(name, str) and name else None


def _csv_tasks(path: str) -> Iterable[Task]:
    base, stem = os.path.dirname(os.path.abspath(path)), os.path.basename(path)
    try:
        with open(path, encoding="utf-8", newline="") as fh:
            reader = csv.DictReader(fh)
            rows = list(reader)
    except OSError as exc:
        raise InvalidInput(f"{path}: cannot read the results file ({exc.strerror or exc})") from None
    except (UnicodeDecodeError, csv.Error) as exc:
        raise InvalidInput(f"{path}: not a CSV text file ({exc})") from None
    if not reader.fieldnames or "problem" not in reader.fieldnames or "claimed" not in reader.fieldnames:
        raise InvalidInput(f"{path}: the CSV header must name the columns problem and claimed "
                           "(expected problem,quantity,method,claimed)")
    for k, row in enumerate(rows, 1):
        named, error = row.get("problem"), None
        problem = named
        if isinstance(named, str) and named and not named.lstrip().startswith("{"):
            problem, error = _text(os.path.join(base, named))
        yield Task(f"{stem}:{k}", "judge", row={**row, "problem": problem}, error=error, source=str(named))


def done_ids(out: str | os.PathLike) -> set[str]:
    """The ids already recorded in the results file ``out`` (none if it does
    not exist).  A line that is not a JSON object with an ``"id"`` -- such as
    the torn last line of an interrupted run -- does not count.

    >>> import os, tempfile
    >>> out = os.path.join(tempfile.mkdtemp(), "results.jsonl")
    >>> with open(out, "w") as fh:
    ...     _ = fh.write('{"id": "a.json", "status": "ok"}\\n{"id": "b.js')
    >>> done_ids(out), done_ids(out + ".none")
    ({'a.json'}, set())
    """
    ids: set[str] = set()
    try:
        with open(out, encoding="utf-8") as fh:
            for line in fh:
                try:
                    record = json.loads(line)
                except ValueError:
                    continue
                if isinstance(record, dict) and isinstance(record.get("id"), str):
                    ids.add(record["id"])
    except FileNotFoundError:
        pass
    except (OSError, UnicodeDecodeError) as exc:
        raise InvalidInput(f"--out {out}: cannot read the results file to resume ({exc})") from None
    return ids
