"""The one exit-code rule of the ``exactinv`` command, for every sub-command.

An *outcome* is what became of one question (one problem of ``certify`` or
of a batch, one certificate of ``check``, one row of ``oracle``):

========== ==== ==============================================================
outcome    code meaning
========== ==== ==============================================================
proved     0    every claim decided and verified; nothing refuted
refuted    1    a claim is false, shown by an exact witness: the set is not
                invariant (``certify``), the kernel rejected a claim of the
                certificate (``check``, ``explain``), a claimed float value is
                invalid (``oracle``)
bad_input  2    a missing or malformed file, key, row or argument, or an
                output that would overwrite an input
undecided  3    a question could not be decided (e.g. the radius of absolute
                monotonicity); everything else is certified and written
error      4    the engine could not finish: an internal error (a bug), a
                certificate of its own the kernel rejected, a batch task that
                timed out or ran out of memory
========== ==== ==============================================================

Several outcomes (a batch, an oracle file) exit with the **highest** code
among them -- as ``python -m exactinv_check`` does over several files.  An
interrupted run (Ctrl-C) exits 130; a batch is then resumable.

>>> exit_code(["proved", "refuted", "undecided"])
3
>>> exit_code([])
0
"""

from __future__ import annotations

from typing import Iterable

__all__ = ["CODES", "EXIT_CODES", "INTERRUPTED", "PIPE_CLOSED", "exit_code"]

CODES = {"proved": 0, "refuted": 1, "bad_input": 2, "undecided": 3, "error": 4}
"""The exit code of each outcome."""

INTERRUPTED = 130  # 128 + SIGINT, the shell's convention
PIPE_CLOSED = 141  # 128 + SIGPIPE: what `yes | head` reports for yes

EXIT_CODES = """\
exit codes (every sub-command; several outcomes -- a batch, an oracle file -- exit with the highest):
  0  proved: every claim decided and verified; nothing refuted
  1  refuted: a claim is false, shown by an exact witness -- the set is not invariant
     (certify), the kernel rejected a claim (check, explain), a claimed value is invalid (oracle)
  2  bad input: a missing or malformed file, key, row or argument, or an output that would
     overwrite an input (the one-line message names it)
  3  undecided: a question could not be decided (e.g. the radius of absolute monotonicity);
     everything else is certified and written
  4  error: the engine could not finish -- an internal error (a bug: please report it), a
     certificate of its own the kernel rejected, a batch task that timed out or ran out of memory
  130  interrupted (Ctrl-C); a batch is resumable: run the same command again
  141  the reader of the output went away (e.g. `exactinv certify P.json | head`): stops quietly
"""
"""The rule as ``exactinv --help`` prints it (README's "Command line" section quotes it verbatim)."""


def exit_code(outcomes: Iterable[str]) -> int:
    """The exit code of a run with these outcomes: the highest of their codes (0 for none).

    >>> exit_code(["proved", "proved"]), exit_code(["refuted", "bad_input"]), exit_code(["error", "undecided"])
    (0, 2, 4)
    """
    return max((CODES[o] for o in outcomes), default=0)
