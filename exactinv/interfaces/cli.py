"""The ``exactinv`` command: parses arguments and prints what the pipeline,
the kernel, the oracle and the explainer return.

    exactinv certify PROBLEM.json [--method SPEC] [-o CERT.json] [--no-check]
    exactinv check CERT.json
    exactinv explain CERT.json
    exactinv oracle RESULTS.csv [--tolerance 1e-9]

Exit codes: 0 success (for ``check``: every claim verified; for ``oracle``:
no result invalid), 1 a certificate was rejected, an oracle verdict was
``invalid`` or an internal verification failed, 2 bad input (the message
names the argument).
"""

from __future__ import annotations

import argparse
import json
import sys
from typing import Sequence

import exactinv_check

from ..core.encode import dumps
from ..errors import ExactinvException, VerificationFailed
from .explain import explain
from .oracle import judge_batch
from .pipeline import certify, stages
from .problem import load_problem, parse_method

__all__ = ["main"]


class _Progress:
    """Stage-by-stage progress on a terminal (stderr); silent when piped."""

    def __init__(self, total: int):
        self.total, self.done = total, 0
        self.active = sys.stderr.isatty()

    def step(self, what: str) -> None:
        self.done += 1
        if self.active:
            bar = "#" * self.done + "." * max(self.total - self.done, 0)
            print(f"\r[{bar}] {what:<40}", end="", file=sys.stderr, flush=True)

    def close(self) -> None:
        if self.active:
            print("\r" + " " * (self.total + 45) + "\r", end="", file=sys.stderr, flush=True)


def _certify(args) -> int:
    problem = load_problem(args.problem)
    method = parse_method(json.loads(args.method)) if args.method else None
    progress = _Progress(stages(method or problem.method, not args.no_check))
    try:
        report = certify(problem, method, check=not args.no_check, progress=progress.step)
    finally:
        progress.close()
    print(report.text)
    if report.check is not None and not report.ok:
        print(report.check, file=sys.stderr)
        if args.output:
            print(f"exactinv: the kernel rejected the certificate; {args.output} was NOT written", file=sys.stderr)
        return 1
    if args.output:
        with open(args.output, "w") as fh:
            fh.write(dumps(report.certificate))
        print(f"certificate written to {args.output}")
    return 0


def _check(args) -> int:
    report = exactinv_check.check(args.certificate)
    print(report, file=sys.stderr if report.bad_input else sys.stdout)
    return 2 if report.bad_input else (0 if report.ok else 1)


def _oracle(args) -> int:
    rows = judge_batch(args.results, args.tolerance)
    print(f"{'#':>3}  {'problem':<28}{'quantity':<11}{'method':<16}{'claimed':<22}verdict")
    for k, r in enumerate(rows, 1):
        print(f"{k:>3}  {r.name:<28}{r.quantity:<11}{r.method:<16}{r.claimed:<22}{r.verdict.status.upper()}")
        if r.verdict.status != "tight":
            print(f"     {r.verdict.message}")
    invalid = sum(r.verdict.status == "invalid" for r in rows)
    print(f"{len(rows)} results judged: {invalid} invalid")
    return 1 if invalid else 0


def _explain(args) -> int:
    with open(args.certificate) as fh:
        cert = json.load(fh)
    print(explain(cert))
    return 0


def _parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="exactinv", description="Exact steplength thresholds with certificates.")
    sub = parser.add_subparsers(dest="command", required=True)
    p = sub.add_parser("certify", help="compute and certify everything that applies to a problem file")
    p.add_argument("problem", help="problem JSON file")
    p.add_argument("--method", help='method as JSON, e.g. \'{"taylor": 4}\' (overrides the file)')
    p.add_argument("-o", "--output", help="write the certificate to this JSON file (only if the kernel verifies it)")
    p.add_argument("--no-check", action="store_true", help="skip the built-in run of the trusted kernel")
    p.set_defaults(run=_certify)
    c = sub.add_parser("check", help="re-verify a certificate with the trusted kernel (exactinv_check)")
    c.add_argument("certificate", help="certificate JSON file")
    c.set_defaults(run=_check)
    e = sub.add_parser("explain", help="print the argument of a certificate in words")
    e.add_argument("certificate", help="certificate JSON file")
    e.set_defaults(run=_explain)
    o = sub.add_parser("oracle", help="judge float results (CSV: problem,quantity,method,claimed; or .jsonl)")
    o.add_argument("results", help="CSV or JSON-lines file of float results")
    o.add_argument("--tolerance", default="1e-9", help="relative tolerance for 'tight' (default 1e-9)")
    o.set_defaults(run=_oracle)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line; returns the exit code."""
    args = _parser().parse_args(argv)
    try:
        return args.run(args)
    except VerificationFailed as exc:
        print(f"exactinv: internal verification failed: {exc}", file=sys.stderr)
        return 1
    except (ExactinvException, json.JSONDecodeError) as exc:
        print(f"exactinv: {exc}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
