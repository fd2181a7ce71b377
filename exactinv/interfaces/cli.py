"""The ``exactinv`` command: parses arguments and prints what the pipeline,
the kernel, the oracle and the explainer return.

    exactinv certify PROBLEM.json [--method SPEC] [-o CERT.json] [--no-check] [--json | --latex | --quiet]
    exactinv check CERT.json
    exactinv explain CERT.json
    exactinv oracle RESULTS.csv [--tolerance 1e-9]
    exactinv batch INPUT... --out RESULTS.jsonl [--cert-dir DIR] [--workers N | --scheduler ADDRESS]
                   [--timeout S] [--memory MB] [--check/--no-check] [--tolerance 1e-9]
    exactinv --version

Exit codes: one rule for every sub-command, :mod:`exactinv.interfaces.exit_codes`
(0 proved, 1 refuted, 2 bad input, 3 undecided, 4 error; the highest of
several; 130 interrupted).  No traceback reaches the user: an unexpected
exception is reported in one line as an internal error (exit 4).  No output
file is ever one of the inputs (refused, exit 2, before any work), and every
file is written atomically (:mod:`exactinv.interfaces.files`).
"""

from __future__ import annotations

import argparse
import json
import os
import sys
from typing import Sequence

import exactinv_check
import exactinv_check.format
from exactinv_check.kernel import BadInput
from exactinv_check.kernel import load as _load_certificate

from ..core.encode import dumps
from ..errors import ExactinvException, InvalidInput, Undecided, VerificationFailed
from ..model.methods import PRESETS
from .batch import BatchInterrupted, run_batch
from .exit_codes import CODES, EXIT_CODES, INTERRUPTED, PIPE_CLOSED, exit_code
from .explain import explain
from .files import atomic_write, check_writable, is_certificate, refuse_foreign, refuse_inputs
from .method_format import method_from_text
from .oracle import judge_batch
from .pipeline import certify, stages
from .problem import load_problem
from .report_output import report_json, report_latex

__all__ = ["main"]

FORMAT_BRIEF = """\
problem file (JSON; full format: docs/problem-format.md, schema: docs/problem.schema.json):
  {"system":     {"A": [["-1", "1"], ["-1", "-1"]]}            or {"A0": .., "B": .., "F": ..} (A = A0 + B F)
   "polyhedron": {"G": [[1, 0], [-1, 0], [0, 1], [0, -1]], "b": [1, 1, 1, 1]}
                                             or {"vertices": [..], "rays": [..], "lines": [..]}
   "method":     {"taylor": 4}                                 optional, one of:
       {"taylor": p}  {"polynomial": [s0, s1, ..]}  {"rational": {"num": [..], "den": [..]}}
       {"theta": "1/2"}  {"pade": [k, l]}  {"butcher": {"A": [[..]], "b": [..], "c": [..]}}
       {"ssprk_s1": s}  {"preset": NAME} or just "NAME"
   "name": "..", "description": ".."}                          optional
  numbers are integers or strings: "3/4", "-2", "0.1" (exactly 1/10); JSON floats are refused.
  Unknown keys are refused.  --method takes the same JSON or a preset name, e.g. --method rk4.
presets: {presets}
"""


class _Progress:
    """Stage-by-stage progress on a terminal (stderr); silent when piped."""

    def __init__(self, total: int, active: bool = True):
        self.total, self.done = total, 0
        self.active = active and sys.stderr.isatty()

    def step(self, what: str) -> None:
        self.done += 1
        if self.active:
            bar = "#" * self.done + "." * max(self.total - self.done, 0)
            print(f"\r[{bar}] {what:<40}", end="", file=sys.stderr, flush=True)

    def close(self) -> None:
        if self.active:
            print("\r" + " " * (self.total + 45) + "\r", end="", file=sys.stderr, flush=True)


def _input_file(path: str, what: str) -> None:
    if os.path.isdir(path):
        raise InvalidInput(f"{path}: is a directory, not a {what}")
    if not os.path.exists(path):
        raise InvalidInput(f"{path}: no such file")


def _certify(args) -> int:
    _input_file(args.problem, "problem file")
    if args.output:  # refused before any work: never an input, never a file exactinv did not write
        check_writable(args.output, "-o", "cert.json")
        refuse_inputs(args.output, "-o", [args.problem])
        refuse_foreign(args.output, "-o", is_certificate, "an exactinv certificate")
    problem = load_problem(args.problem)
    method = method_from_text(args.method) if args.method else None
    progress = _Progress(stages(method or problem.method, not args.no_check), active=not args.quiet)
    try:
        report = certify(problem, method, check=not args.no_check, progress=progress.step)
    finally:
        progress.close()
    written = None
    if report.outcome == "error":  # the kernel rejected the engine's certificate: never written
        print(report.check, file=sys.stderr)
        print("exactinv: the kernel rejected the certificate (an engine bug: please report it)"
              + (f"; {args.output} was NOT written" if args.output else ""), file=sys.stderr)
    elif args.output:
        try:
            atomic_write(args.output, dumps(report.certificate))
        except OSError as exc:
            raise InvalidInput(f"-o {args.output}: cannot write ({exc.strerror or exc})") from None
        written = args.output
    if args.json:
        print(json.dumps(report_json(report, written), indent=1))
    elif args.latex:
        print(report_latex(report))
    elif not args.quiet:
        print(report.text)
        if written:
            print(f"certificate written to {written}")
    for what, why in report.undecided:  # a partial answer: every decided claim certified, this question open
        print(f"exactinv: undecided: {what}: {why}", file=sys.stderr)
    return CODES[report.outcome]


def _load_cert(path: str) -> dict:
    """The certificate in ``path``, or InvalidInput naming the file and what it is instead."""
    _input_file(path, "certificate")
    try:
        cert = _load_certificate(path)
    except BadInput as exc:
        raise InvalidInput(f"{path}: {str(exc).replace(repr(path), 'the file')}") from None
    if cert.get("format") != exactinv_check.format.FORMAT:
        if {"system", "polyhedron", "ellipsoid"} & set(cert):
            raise InvalidInput(f"{path}: this is a problem file, not a certificate (run `exactinv certify {path} -o CERT.json`)")
        raise InvalidInput(f"{path}: not an exactinv certificate (the \"format\" key is missing or wrong)")
    return cert


def _check(args) -> int:
    cert = _load_cert(args.certificate)
    report = exactinv_check.check(cert)
    print(report, file=sys.stderr if report.bad_input else sys.stdout)
    return 2 if report.bad_input else (0 if report.ok else 1)


def _oracle(args) -> int:
    _input_file(args.results, "results file")
    rows = judge_batch(args.results, args.tolerance)
    print(f"{'#':>3}  {'problem':<28}{'quantity':<11}{'method':<16}{'claimed':<22}verdict")
    for r in rows:
        print(f"{r.row:>3}  {r.name[:27]:<28}{r.quantity[:10]:<11}{r.method[:15]:<16}{r.claimed[:21]:<22}{r.status.upper()}")
        if r.verdict is None:
            print(f"     {r.error}")
        elif r.verdict.status != "tight":
            print(f"     {r.verdict.message}")
    invalid = sum(r.status == "invalid" for r in rows)
    errors = sum(r.verdict is None for r in rows)
    print(f"{len(rows)} result{'' if len(rows) == 1 else 's'} judged: {invalid} invalid"
          + (f", {errors} could not be judged (bad input)" if errors else ""))
    for r in rows:
        if r.verdict is None:
            print(f"exactinv: {args.results}: {r.error}", file=sys.stderr)
    return exit_code("bad_input" if r.verdict is None else "refuted" if r.status == "invalid" else "proved"
                     for r in rows)


def _batch(args) -> int:
    def notice(line: str) -> None:
        print(f"exactinv: {line}", file=sys.stderr, flush=True)

    summary = run_batch(args.inputs, args.out, workers=args.workers, scheduler=args.scheduler,
                        timeout=args.timeout, memory_mb=args.memory, check=args.check,
                        tolerance=args.tolerance, cert_dir=args.cert_dir, notice=notice)
    print(summary.table())
    return summary.exit_code


def _explain(args) -> int:
    cert = _load_cert(args.certificate)
    report = exactinv_check.check(cert)
    if report.bad_input:
        raise InvalidInput(f"{args.certificate}: {report.verdicts[0][2]}")
    if not report.ok:
        print(report, file=sys.stderr)
        print(f"exactinv: {args.certificate}: the kernel REJECTED this certificate; it is not explained "
              "(a rejected argument proves nothing)", file=sys.stderr)
        return 1
    print(explain(cert, verified=True))
    return 0


def _version() -> str:
    # the package's own __version__ (the top package is always imported before this module;
    # reading it here keeps the import graph pointing down)
    return f"exactinv {sys.modules[__name__.split('.')[0]].__version__}"


def _parser() -> argparse.ArgumentParser:
    fmt = argparse.RawDescriptionHelpFormatter
    parser = argparse.ArgumentParser(prog="exactinv", description="Exact steplength thresholds with certificates.",
                                     epilog=EXIT_CODES, formatter_class=fmt)
    parser.add_argument("--version", action="version", version=_version())
    sub = parser.add_subparsers(dest="command", required=True, metavar="{certify,check,explain,oracle,batch}")
    p = sub.add_parser("certify", help="compute and certify everything that applies to a problem file",
                       description="Compute gamma*, the forward-Euler step, the paper's threshold, the exact valid "
                                   "steplengths and the largest threshold of a problem, and certify them.",
                       epilog=FORMAT_BRIEF.replace("{presets}", ", ".join(sorted(PRESETS))) + "\n" + EXIT_CODES,
                       formatter_class=fmt)
    p.add_argument("problem", help="problem JSON file")
    p.add_argument("--method", help='method as JSON, e.g. \'{"taylor": 4}\', or a preset name such as rk4 '
                                    '(overrides the file)')
    p.add_argument("-o", "--output", help="write the certificate to this JSON file, atomically (not if the kernel "
                                          "rejects it; never over an input or a file that is not a certificate)")
    p.add_argument("--no-check", action="store_true", help="skip the built-in run of the trusted kernel")
    shown = p.add_mutually_exclusive_group()
    shown.add_argument("--json", action="store_true", help="print the report as JSON (exact numbers as strings, "
                                                           "as in the certificate) instead of text")
    shown.add_argument("--latex", action="store_true", help="print the results as a LaTeX tabular (needs amsmath)")
    shown.add_argument("-q", "--quiet", action="store_true", help="print nothing but errors; the exit code tells")
    p.set_defaults(run=_certify)
    for name, run, what, description in (
            ("check", _check, "re-verify a certificate with the trusted kernel (exactinv_check)", None),
            ("explain", _explain, "check a certificate, then print its argument in words",
             "Run the trusted kernel on a certificate and, if it verifies, explain every claim in words.  "
             "A rejected certificate is not explained (exit 1).")):
        c = sub.add_parser(name, help=what, description=description, epilog=EXIT_CODES, formatter_class=fmt)
        c.add_argument("certificate", help="certificate JSON file")
        c.set_defaults(run=run)
    o = sub.add_parser("oracle", help="judge float results (CSV: problem,quantity,method,claimed; or .jsonl)",
                       description="Judge claimed float results against the exact values.  Each row is judged on "
                                   "its own; a row that cannot be judged is reported with its row number.",
                       epilog="columns: problem (a problem file, relative to the results file), quantity "
                              "(threshold, gamma or radius; default threshold), method (JSON or a preset name; "
                              "default: the problem's), claimed (a float such as 1.5, 1e-3 or inf).\n"
                              "each row is one outcome: proved (valid or tight), refuted (invalid) or bad input "
                              "(the row cannot be judged).\n\n" + EXIT_CODES, formatter_class=fmt)
    o.add_argument("results", help="CSV or JSON-lines file of float results")
    o.add_argument("--tolerance", default="1e-9", help="relative tolerance for 'tight' (default 1e-9)")
    o.set_defaults(run=_oracle)
    _batch_parser(sub, fmt)
    return parser


BATCH_EPILOG = """\
inputs: a directory (every *.json problem file below it), a .json problem file, a .jsonl file
(one problem object per line) or an oracle .csv (problem,quantity,method,claimed: each row judged).
In a directory, .jsonl and .csv files, certificates and results files are not read: each is named
on stderr with the reason (give a .jsonl or .csv as an INPUT to read it).
ids: the path below the directory, the file as given, a line's "name" (else FILE:LINE), FILE:ROW.
each record (one JSON line): id, kind, status (ok, rejected, error, timeout, memory), outcome
(proved, refuted, bad_input, undecided, error), exact values as strings (values / verdict),
seconds, peak_mb, error, certificate (with --cert-dir).  A run skips ids already in --out.
--out is appended to (one whole line per record, never rewritten) and is never an input;
--cert-dir gets one certificate per problem, named after its id, each written atomically.
The summary and the exit code cover every record in --out, earlier runs' included.
Ctrl-C stops the batch with one line "interrupted: N done, resumable" (exit 130).
"""


def _batch_parser(sub, fmt) -> None:
    b = sub.add_parser("batch", help="certify or judge a corpus on Dask (local cores or a cluster); resumable",
                       description="Certify every problem (judge every oracle row) of a corpus on Dask distributed, "
                                   "each under a time and memory limit, streaming one JSON record per problem to "
                                   "--out.  Needs the batch extra: pip install \"exactinv[batch]\".",
                       epilog=BATCH_EPILOG + "\n" + EXIT_CODES, formatter_class=fmt)
    b.add_argument("inputs", nargs="+", metavar="INPUT", help="problem directory, .json, .jsonl or oracle .csv")
    b.add_argument("-o", "--out", required=True, help="results file (JSON lines); appended to, done ids skipped")
    b.add_argument("--cert-dir", metavar="DIR", help="keep each problem's certificate in DIR (created if missing): "
                                                     "ID.cert.json, written once the kernel verified it "
                                                     "(with --no-check: unverified, as asked)")
    where = b.add_mutually_exclusive_group()
    where.add_argument("--workers", type=_positive(int), metavar="N", help="local worker processes (default: every core)")
    where.add_argument("--scheduler", metavar="ADDRESS", help="an existing Dask scheduler, e.g. tcp://10.0.0.1:8786")
    b.add_argument("--timeout", type=_positive(float), metavar="S", help="wall-clock seconds per problem (default: none)")
    b.add_argument("--memory", type=_positive(float), metavar="MB",
                   help="megabytes per problem beyond the worker's own footprint (default: none)")
    b.add_argument("--check", action=argparse.BooleanOptionalAction, default=True,
                   help="run the trusted kernel on each certificate (default; --no-check skips it)")
    b.add_argument("--tolerance", default="1e-9", help="the oracle's relative tolerance for 'tight' (default 1e-9)")
    b.set_defaults(run=_batch)


def _positive(kind):
    def parse(text: str):
        try:
            value = kind(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"expected a positive {kind.__name__}, got {text!r}") from None
        if not value > 0 or value != value or value == float("inf"):
            raise argparse.ArgumentTypeError(f"expected a positive {kind.__name__}, got {text!r}")
        return value
    parse.__name__ = kind.__name__
    return parse


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line; returns the exit code (:mod:`exactinv.interfaces.exit_codes`).

    The paper's box example: A = [[-1, 1], [-1, -1]] on [-1, 1]^2 has gamma* = 1
    (row 1: max h_1 s.t. h^T G = g_1^T A = (-1, 1), h^T b <= 0 is h = (-1, 0, 1, 0)),
    and Taylor(4) keeps the box up to the root 1.7496... of x^4 - 6x^2 + 12x - 12.

    >>> import contextlib, io, pathlib, exactinv
    >>> examples = pathlib.Path(exactinv.__file__).parents[1] / "examples"
    >>> out = io.StringIO()
    >>> with contextlib.redirect_stdout(out):
    ...     code = main(["certify", str(examples / "paper_box_taylor4.json")])
    >>> lines = out.getvalue().splitlines()
    >>> code, [line.split("[")[0] for line in lines if line.startswith(("gamma*", "independent"))]
    (0, ['gamma*: 1   ', 'independent check: VERIFIED (5 claims)'])
    >>> "the root of x^4 - 6x^2 + 12x - 12" in out.getvalue()
    True
    >>> err = io.StringIO()
    >>> with contextlib.redirect_stderr(err):
    ...     code = main(["certify", str(examples / "missing.json")])
    >>> code, err.getvalue().endswith("missing.json: no such file\\n")
    (2, True)
    """
    args = _parser().parse_args(argv)
    try:
        code = args.run(args)
        sys.stdout.flush()  # here, not at exit: a closed pipe is then caught below
        return code
    except VerificationFailed as exc:
        print(f"exactinv: internal verification failed: {exc}", file=sys.stderr)
        return CODES["error"]
    except Undecided as exc:
        print(f"exactinv: undecided: {exc}", file=sys.stderr)
        return CODES["undecided"]
    except ExactinvException as exc:
        print(f"exactinv: {exc}", file=sys.stderr)
        return CODES["bad_input"]
    except BatchInterrupted as stop:
        print(f"interrupted: {stop.done} done, resumable", file=sys.stderr)
        return INTERRUPTED
    except KeyboardInterrupt:
        print("exactinv: interrupted", file=sys.stderr)
        return INTERRUPTED
    except BrokenPipeError:
        _drop_stdout()
        return PIPE_CLOSED
    except RecursionError:
        print("exactinv: input nested too deeply", file=sys.stderr)
        return CODES["bad_input"]
    except Exception as exc:  # never a traceback: a one-line report of an engine bug
        print(f"exactinv: internal error (a bug; please report it): {type(exc).__name__}: {exc}", file=sys.stderr)
        return CODES["error"]

def _drop_stdout() -> None:
    """Point stdout at /dev/null: the reader is gone, and Python's flush at exit must not fail."""
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        os.close(devnull)
    except (OSError, ValueError):
        pass


if __name__ == "__main__":
    sys.exit(main())
