"""The results file of ``exactinv batch``: JSON lines, appended to, never rewritten.

Appends are safe: the file is opened with ``O_APPEND`` and locked
(``flock``, so a second batch on the same file is refused instead of
interleaving); each record is one complete line, and the records of a chunk are
handed to the operating system together in one ``write`` (the engine holds Ctrl-C back meanwhile:
:class:`.signals.CtrlC`), so an interruption never tears a line; a crash of the machine can tear at most
the last line, which a reader ignores (and a re-run redoes: it starts on a
fresh line).  The file is fsync'ed when the batch ends.  Existing lines are
never changed.

>>> import os, tempfile
>>> out = os.path.join(tempfile.mkdtemp(), "r.jsonl")
>>> with open(out, "w") as fh:
...     _ = fh.write('{"id": "a", "status": "ok"}\\n{"id": "b", "sta')
>>> with ResultsFile(out) as sink:
...     sink.append({"id": "b", "status": "error"})
>>> sorted(read_records(out).items())
[('a', {'id': 'a', 'status': 'ok'}), ('b', {'id': 'b', 'status': 'error'})]
"""

from __future__ import annotations

import contextlib
import fcntl
import json
import os

from ...errors import InvalidInput

__all__ = ["ResultsFile", "read_records"]


class ResultsFile:
    """``out`` opened for appending records (see the module docstring); a context manager."""

    def __init__(self, out: str):
        self.out = out
        self.fd = os.open(out, os.O_WRONLY | os.O_APPEND | os.O_CREAT, 0o666)
        try:
            fcntl.flock(self.fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError:
            os.close(self.fd)
            raise InvalidInput(f"--out {out}: another exactinv batch is writing to this file") from None
        with open(out, "rb") as fh:  # a torn last line (an interrupted write): start on a fresh line
            fh.seek(0, os.SEEK_END)
            if fh.tell() > 0:
                fh.seek(-1, os.SEEK_END)
                if fh.read(1) != b"\n":
                    self._write(b"\n")

    def _write(self, data: bytes) -> None:
        view = memoryview(data)
        while view:
            view = view[os.write(self.fd, view):]

    def append(self, record: dict) -> None:
        """One record, as one whole line.

        >>> import os, tempfile
        >>> out = os.path.join(tempfile.mkdtemp(), "r.jsonl")
        >>> with ResultsFile(out) as sink:
        ...     sink.append({"id": "a", "status": "ok"})
        >>> open(out).read()
        '{"id": "a", "status": "ok"}\\n'
        """
        self._write((json.dumps(record) + "\n").encode())

    def extend(self, records: list[dict]) -> None:
        """Several records, each one whole line, handed to the operating system in one ``write``
        (a chunk's records: one system call per chunk, not per record).

        >>> import os, tempfile
        >>> out = os.path.join(tempfile.mkdtemp(), "r.jsonl")
        >>> with ResultsFile(out) as sink:
        ...     sink.extend([{"id": "a"}, {"id": "b"}]); sink.extend([])
        >>> open(out).read()
        '{"id": "a"}\\n{"id": "b"}\\n'
        """
        if records:
            self._write("".join(json.dumps(record) + "\n" for record in records).encode())

    def close(self) -> None:
        """Flush to disk (fsync) and close, releasing the lock; a second close does nothing.

        >>> import os, tempfile
        >>> sink = ResultsFile(os.path.join(tempfile.mkdtemp(), "r.jsonl"))
        >>> sink.close(); sink.close(); sink.fd
        -1
        """
        if self.fd >= 0:
            with contextlib.suppress(OSError):
                os.fsync(self.fd)
            os.close(self.fd)  # releases the lock
            self.fd = -1

    def __enter__(self) -> "ResultsFile":
        return self

    def __exit__(self, *exc) -> None:
        self.close()


def read_records(out: str) -> dict[str, dict]:
    """Every record of ``out`` by id (the last one of an id wins); torn lines and lines that are
    not records are skipped; an absent file has none.

    >>> import os, tempfile
    >>> out = os.path.join(tempfile.mkdtemp(), "r.jsonl")
    >>> _ = open(out, "w").write('{"id": "a", "status": "error"}\\n[1]\\n{"id": "a", "status": "ok"}\\n{"id": "b"')
    >>> read_records(out), read_records(out + ".absent")
    ({'a': {'id': 'a', 'status': 'ok'}}, {})
    """
    records: dict[str, dict] = {}
    try:
        with open(out, encoding="utf-8") as fh:
            for line in fh:
                try:
                    record = json.loads(line)
                except (ValueError, RecursionError):
                    continue
                if isinstance(record, dict) and isinstance(record.get("id"), str):
                    records[record["id"]] = record
    except FileNotFoundError:
        pass
    except (OSError, UnicodeDecodeError) as exc:
        raise InvalidInput(f"--out {out}: cannot read the results file ({exc})") from None
    return records
