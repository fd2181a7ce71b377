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

Never read as problems, each named in :attr:`Corpus.ignored` with the
reason: inside a directory, ``.jsonl`` and ``.csv`` files (give one as an
input to read it); anywhere, the batch's own results file and certificate
folder, an exactinv certificate and an ``exactinv batch`` results file.

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

from exactinv_check.format import FORMAT

from ...errors import InvalidInput
from ..files import is_results_file, same_file

__all__ = ["Task", "Corpus", "read_corpus", "scan_corpus", "done_ids"]


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


@dataclass(frozen=True)
class Corpus:
    """The tasks of a batch's inputs; ``files``: every file read for them (problem files,
    ``.jsonl``, ``.csv`` and the problem files its rows name), which no output may be;
    ``ignored``: (path, why) for every file of the inputs that was not read as a problem."""

    tasks: tuple[Task, ...]
    files: tuple[str, ...] = ()
    ignored: tuple[tuple[str, str], ...] = ()


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
    return list(scan_corpus(inputs).tasks)


def scan_corpus(inputs: Sequence[str | os.PathLike], out: str | None = None,
                cert_dir: str | None = None) -> Corpus:
    """The :class:`Corpus` of ``inputs``; ``out`` (the results file) and everything in
    ``cert_dir`` are never read as problems.

    >>> import os, tempfile
    >>> d = tempfile.mkdtemp()
    >>> for name, text in (("a.json", '{"system": {"A": [[-1]]}, "polyhedron": {"G": [[1], [-1]], "b": [1, 1]}}'),
    ...                    ("old.jsonl", ""), ("c.json", '{"format": "exactinv-certificate"}')):
    ...     with open(os.path.join(d, name), "w") as fh:
    ...         _ = fh.write(text)
    >>> c = scan_corpus([d], out=os.path.join(d, "r.jsonl"))
    >>> [t.id for t in c.tasks], [(os.path.basename(p), why[:30]) for p, why in c.ignored]
    (['a.json'], [('c.json', 'an exactinv certificate, not a'), ('old.jsonl', 'a .jsonl file inside a directo')])
    """
    if isinstance(inputs, (str, os.PathLike)):
        inputs = [inputs]
    if not inputs:
        raise InvalidInput("INPUT: give at least one directory, .json, .jsonl or .csv file")
    scan = _Scan(out, cert_dir)
    for source in map(str, inputs):
        scan.read(source)
    seen: dict[str, int] = {}
    for k, t in enumerate(scan.tasks):
        if t.id in seen:
            raise InvalidInput(f"{t.id}: two problems have this id (give them different \"name\"s); "
                               "a resumable batch needs unique ids")
        seen[t.id] = k
    return Corpus(tuple(scan.tasks), tuple(scan.files), tuple(scan.ignored))


_IN_FOLDERS = {".jsonl": "a .jsonl file inside a directory is not read (give it as an INPUT to read its problems)",
               ".csv": "a .csv file inside a directory is not read (give it as an INPUT to judge its rows)"}


class _Scan:
    """The tasks, files read and files ignored, input by input."""

    def __init__(self, out: str | None, cert_dir: str | None):
        self.out, self.cert_dir = out, cert_dir
        self.tasks: list[Task] = []
        self.files: list[str] = []
        self.ignored: list[tuple[str, str]] = []

    def _ours(self, path: str) -> str | None:
        """Why ``path`` is this batch's own output (never read), or None."""
        if self.out is not None and same_file(path, self.out):
            return "the results file of this batch (--out), not a problem"
        if self.cert_dir is not None:
            here = os.path.realpath(path)
            folder = os.path.realpath(self.cert_dir)
            if os.path.commonpath([here, folder]) == folder:
                return "inside --cert-dir (the certificates this batch writes), not a problem"
        return None

    def read(self, source: str) -> None:
        if os.path.isdir(source):
            root = Path(source)
            found = sorted(p for p in root.rglob("*") if p.suffix.lower() in (".json", ".jsonl", ".csv")
                           and not p.name.startswith(".") and p.is_file())
            for p in found:
                why = self._ours(str(p)) or _IN_FOLDERS.get(p.suffix.lower())
                if why and self.out is not None and same_file(p, self.out) and os.path.getsize(p) \
                        and not is_results_file(str(p)):
                    self.files.append(str(p))  # a file of the user's that --out names: refused by the caller
                if why:
                    self.ignored.append((str(p), why))
                else:
                    self._json_file(str(p), p.relative_to(root).as_posix())
            return
        if not os.path.exists(source):
            raise InvalidInput(f"{source}: no such file or directory")
        suffix = os.path.splitext(source)[1].lower()
        if suffix not in (".json", ".jsonl", ".csv"):
            raise InvalidInput(f"{source}: unknown kind of input (expected a directory, .json, .jsonl or .csv)")
        why = self._ours(source)
        if why:  # refused later as an output that is an input; never read here
            self.files.append(source)
            self.ignored.append((source, why))
        elif suffix == ".json":
            self._json_file(source, source)
        elif suffix == ".jsonl":
            self._jsonl(source)
        else:
            self.files.append(source)
            self.tasks.extend(_csv_tasks(source, self.files))

    def _json_file(self, path: str, task_id: str) -> None:
        text, error = _text(path)
        why = _not_a_problem(text) if text is not None else None
        self.files.append(path)
        if why:
            self.ignored.append((path, why))
        else:
            self.tasks.append(Task(task_id, "certify", text=text, error=error, source=path))

    def _jsonl(self, path: str) -> None:
        self.files.append(path)
        text, error = _text(path)
        if error:
            raise InvalidInput(error.replace("problem file", "JSON-lines file"))
        first = next((line for line in text.splitlines() if line.strip()), "")
        if _is_record(first):
            self.ignored.append((path, "an exactinv batch results file, not a file of problems"))
            return
        base = os.path.basename(path)
        for number, line in enumerate(text.splitlines(), 1):
            if line.strip():
                self.tasks.append(Task(_line_name(line) or f"{base}:{number}", "certify", text=line,
                                       source=f"{path}:{number}"))


def _is_record(line: str) -> bool:
    try:
        data = json.loads(line)
    except (ValueError, RecursionError):
        return False
    return isinstance(data, dict) and isinstance(data.get("id"), str) and "status" in data


def _not_a_problem(text: str) -> str | None:
    """Why a .json file's ``text`` is exactinv's own output rather than a problem, or None."""
    head = text.lstrip()[:1]
    if head != "{":
        return None
    if '"exactinv-certificate"' in text[:4096]:
        try:
            data = json.loads(text)
        except (ValueError, RecursionError):
            data = None
        if isinstance(data, dict) and data.get("format") == FORMAT:
            return "an exactinv certificate, not a problem"
    first = text.lstrip().split("\n", 1)[0]
    if "\n" in text.strip() and _is_record(first):
        return "an exactinv batch results file, not a problem"
    if _is_record(text):
        return "an exactinv batch results file, not a problem"
    return None


def _text(path: str) -> tuple[str | None, str | None]:
    """(text, None) or (None, why it cannot be read)."""
    try:
        with open(path, encoding="utf-8") as fh:
            return fh.read(), None
    except OSError as exc:
        return None, f"{path}: cannot read the problem file ({exc.strerror or exc})"
    except UnicodeDecodeError:
        return None, f"{path}: not a text file (a problem file is UTF-8 JSON)"


def _line_name(line: str) -> str | None:
    try:
        name = json.loads(line).get("name")
    except (ValueError, AttributeError, RecursionError):
        return None
    return name if isinstance(name, str) and name else None


def _csv_tasks(path: str, files: list[str]) -> Iterable[Task]:
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
            files.append(os.path.join(base, named))
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
