"""Output files of the command line and the batch runner: refused before any
work, written atomically, never over anything the user gave.

* :func:`check_writable` refuses an output that cannot be written;
* :func:`refuse_inputs` refuses an output that *is* one of the inputs --
  the same path, ``./x`` and ``x``, a symbolic link or a hard link to it
  (compared by device and inode where the file exists);
* :func:`refuse_foreign` refuses to replace an existing file that exactinv
  did not write (a certificate is replaced only by a certificate, a results
  file only appended to);
* :func:`atomic_write` writes a temporary file in the same directory, then
  renames it over the target (``os.replace``): a reader sees the old file or
  the new one, never half of one.
"""

from __future__ import annotations

import json
import os
import secrets
from typing import Callable, Iterable

from exactinv_check.format import FORMAT

from ..errors import InvalidInput

__all__ = ["check_writable", "same_file", "refuse_inputs", "refuse_foreign", "atomic_write", "is_certificate",
           "is_results_file"]


def check_writable(path: str, label: str, example: str) -> None:
    """Refuse an output ``path`` that cannot be written (``label`` names the argument,
    ``example`` is a file name to suggest inside a directory), before any computation.

    >>> check_writable("/", "out", "results.jsonl")
    Traceback (most recent call last):
    ...
    exactinv.errors.InvalidInput: out: / is a directory; give a file name such as /results.jsonl
    """
    if os.path.isdir(path):
        raise InvalidInput(f"{label}: {path} is a directory; give a file name such as {os.path.join(path, example)}")
    parent = os.path.dirname(os.path.abspath(path))
    if not os.path.isdir(parent):
        raise InvalidInput(f"{label}: the directory {parent} does not exist")
    if not os.access(parent, os.W_OK | os.X_OK) or (os.path.exists(path) and not os.access(path, os.W_OK)):
        raise InvalidInput(f"{label}: {path} is not writable")


def same_file(a: str | os.PathLike, b: str | os.PathLike) -> bool:
    """Whether ``a`` and ``b`` name the same file: by device and inode when both exist
    (symbolic and hard links included), else by their resolved absolute paths.

    >>> import tempfile
    >>> d = tempfile.mkdtemp(); p = os.path.join(d, "p.json"); open(p, "w").close()
    >>> os.link(p, os.path.join(d, "hard.json")); os.symlink(p, os.path.join(d, "soft.json"))
    >>> [same_file(p, os.path.join(d, x)) for x in ("hard.json", "soft.json", "./p.json", "q.json")]
    [True, True, True, False]
    """
    try:
        return os.path.samefile(a, b)
    except OSError:
        return os.path.realpath(a) == os.path.realpath(b)


def refuse_inputs(path: str, label: str, inputs: Iterable[str | os.PathLike]) -> None:
    """Raise :class:`InvalidInput` (exit 2) if the output ``path`` is the same file as one of ``inputs``.

    >>> import tempfile
    >>> d = tempfile.mkdtemp(); p = os.path.join(d, "p.json"); open(p, "w").close()
    >>> refuse_inputs(os.path.join(d, ".", "p.json"), "-o", [p])
    Traceback (most recent call last):
    ...
    exactinv.errors.InvalidInput: -o ....json: this is the input ....json; exactinv never overwrites an input (choose another file name)
    """  # noqa: E501 (doctest output)
    for given in inputs:
        if same_file(path, given):
            raise InvalidInput(f"{label} {path}: this is the input {os.fspath(given)}; exactinv never overwrites "
                               "an input (choose another file name)")


def refuse_foreign(path: str, label: str, ours: Callable[[str], bool], what: str) -> None:
    """Raise :class:`InvalidInput` if ``path`` exists, is not empty and ``ours(path)`` is false:
    exactinv replaces (or appends to) only a file of its own kind (``what`` names it).

    >>> import tempfile
    >>> d = tempfile.mkdtemp(); p = os.path.join(d, "notes.txt")
    >>> _ = open(p, "w").write("my notes")
    >>> refuse_foreign(p, "-o", is_certificate, "an exactinv certificate")
    Traceback (most recent call last):
    ...
    exactinv.errors.InvalidInput: -o ...notes.txt: the file exists and is not an exactinv certificate; exactinv does not overwrite it (delete it or choose another file name)
    """  # noqa: E501 (doctest output)
    try:
        if os.path.getsize(path) == 0:
            return
    except OSError:
        return
    if not ours(path):
        raise InvalidInput(f"{label} {path}: the file exists and is not {what}; exactinv does not overwrite it "
                           "(delete it or choose another file name)")


def is_certificate(path: str) -> bool:
    """Whether ``path`` holds an exactinv certificate (a JSON object with ``"format": "exactinv-certificate"``).

    >>> import tempfile
    >>> d = tempfile.mkdtemp(); p = os.path.join(d, "c.json")
    >>> _ = open(p, "w").write('{"format": "exactinv-certificate", "version": 2}')
    >>> is_certificate(p), is_certificate(os.path.join(d, "none.json"))
    (True, False)
    """
    try:
        with open(path, encoding="utf-8") as fh:
            head = fh.read(4096)
            if json.dumps(FORMAT) not in head:
                return False
            fh.seek(0)
            data = json.load(fh)
    except (OSError, ValueError, RecursionError):
        return False
    return isinstance(data, dict) and data.get("format") == FORMAT


def _record(line: str) -> bool:
    try:
        data = json.loads(line)
    except (ValueError, RecursionError):
        return False
    return isinstance(data, dict) and isinstance(data.get("id"), str) and "status" in data


def is_results_file(path: str) -> bool:
    """Whether ``path`` holds ``exactinv batch`` results: JSON lines of which at least one is a
    record (an object with a string ``"id"`` and a ``"status"``); torn lines are allowed.

    >>> import tempfile
    >>> d = tempfile.mkdtemp(); p = os.path.join(d, "r.jsonl")
    >>> _ = open(p, "w").write('{"id": "a.json", "status": "ok"}\\n{"id": "b.js')
    >>> is_results_file(p)
    True
    """
    try:
        with open(path, encoding="utf-8") as fh:
            return any(_record(line) for line in fh if line.lstrip().startswith("{"))
    except (OSError, UnicodeDecodeError):
        return False


def atomic_write(path: str, text: str) -> None:
    """Write ``text`` to ``path`` atomically: a temporary file in the target's own
    directory (the target of a symbolic link: the link is written through), flushed
    to disk, then renamed over it.  The file gets the mode a plain ``open(path, "w")``
    would give it (the umask's).  An error leaves ``path`` as it was and no temporary file.

    >>> import tempfile
    >>> d = tempfile.mkdtemp(); p = os.path.join(d, "c.json")
    >>> atomic_write(p, "{}"); atomic_write(p, '{"a": 1}')
    >>> open(p).read(), sorted(os.listdir(d))
    ('{"a": 1}', ['c.json'])
    """
    target = os.path.realpath(path)
    folder, name = os.path.split(target)
    temp = os.path.join(folder, f".{name}.{secrets.token_hex(6)}.tmp")
    fd = os.open(temp, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o666)
    try:
        with os.fdopen(fd, "w", encoding="utf-8") as fh:
            fh.write(text)
            fh.flush()
            os.fsync(fh.fileno())
        os.replace(temp, target)
    except BaseException:
        try:
            os.unlink(temp)
        except OSError:
            pass
        raise
