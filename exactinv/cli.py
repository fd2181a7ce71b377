"""The ``exactinv`` command.

    exactinv certify PROBLEM.json [--method SPEC] [-o CERT.json]
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

from .errors import ExactinvError, VerificationFailed

__all__ = ["main"]


def _fmt(v) -> str:
    from .algebraic import RealAlgebraic

    if isinstance(v, RealAlgebraic):
        v.tidy()
        return f"{v}  (root of {v.poly} in ({v.lower}, {v.upper}))"
    return str(v)


_VERTEX_LIMIT = 12  # dimension above which the vertex enumeration is not attempted by default


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


def _forward_euler(S, P, out):
    from .largest import forward_euler_threshold

    if P.n > _VERTEX_LIMIT:
        out("largest forward-Euler step 1/gamma* (Lemma 3.14): see gamma* above")
        return None
    fe = forward_euler_threshold(S, P)
    out(f"largest forward-Euler step: {fe.value}  (1/gamma* and the vertex ratio tests agree)")
    return fe


def _largest(S, P, method, out):
    from .largest import largest_threshold, valid_steplengths

    V = valid_steplengths(S, P, method)
    L = largest_threshold(S, P, method)
    out(f"exact valid steplengths for {method.name}: {V.intervals!r}")
    out(f"exact largest threshold: {_fmt(L.value)}" + ("" if L.attained else "  (not attained)"))
    return [L, V]


def _certify(args) -> int:
    from . import certificates
    from exactinv_check import check

    from .invariance import optimal_gamma
    from .problem import load_problem, parse_method
    from .thresholds import steplength_threshold

    problem = load_problem(args.problem)
    method = parse_method(json.loads(args.method)) if args.method else problem.method
    S, P = problem.system, problem.polyhedron
    out = print
    out(f"problem {problem.name}: n = {S.n}, m = {P.m} inequalities" + (f", method {method.name}" if method else ""))
    results = []
    progress = _Progress((5 if method is not None else 3) - args.no_check)
    progress.step("gamma* (verified row LPs)")
    gamma = optimal_gamma(S, P)
    results.append(gamma)
    if gamma.witness is not None:
        w = gamma.witness
        out(f"continuous invariance: FAILS -- x = [{', '.join(map(str, w.x))}] lies on facet {w.facet} "
            f"and g_{w.facet}.Ax = {w.value} > 0")
        out("gamma*: oo (no steplength threshold exists)")
    else:
        out("continuous invariance: holds (certificate H with HG = GA, Hb <= 0, off-diagonal >= 0)")
        out(f"gamma*: {gamma.value}   [row LPs verified in Q; routes: {gamma.paths}]")
        progress.step("forward Euler (vertex ratio tests)")
        fe = _forward_euler(S, P, out)
        if fe is not None:
            results.append(fe)
        if method is not None:
            progress.step(f"paper's threshold for {method.name}")
            t = steplength_threshold(S, P, method)
            results.append(t)
            out(f"paper's threshold for {method.name} ({t.theorem}): {_fmt(t.value)}"
                + ("" if t.attained else "  (not attained: valid on [0, tau))"))
            if t.paper != t.value:
                out(f"  the paper, taken literally, gives {_fmt(t.paper)}")
            for note in t.notes:
                out(f"  note: {note}")
    if method is not None and P.n <= _VERTEX_LIMIT:
        progress.step("exact valid steplengths")
        results.extend(_largest(S, P, method, out))
    cert = certificates.certificate(S, P, method, results)
    if args.no_check:
        progress.close()
        out(f"independent check: skipped (--no-check); run `exactinv check` on the certificate ({len(cert['claims'])} claims)")
    else:
        progress.step("independent check (the trusted kernel)")
        progress.close()
        report = check(cert)
        out(f"independent check: {'VERIFIED' if report.ok else 'REJECTED'} ({len(cert['claims'])} claims)")
        if not report.ok:
            print(report, file=sys.stderr)
            if args.output:
                print(f"exactinv: the kernel rejected the certificate; {args.output} was NOT written", file=sys.stderr)
            return 1
    if args.output:
        with open(args.output, "w") as fh:
            fh.write(certificates.dumps(cert))
        out(f"certificate written to {args.output}")
    return 0


def _check(args) -> int:
    from exactinv_check import check

    report = check(args.certificate)
    print(report, file=sys.stderr if report.bad_input else sys.stdout)
    return 2 if report.bad_input else (0 if report.ok else 1)


def _oracle(args) -> int:
    """Judge a batch of float results: CSV (problem,quantity,method,claimed) or JSON lines."""
    import csv
    import os

    from . import oracle
    from .problem import load_problem, parse_method

    base = os.path.dirname(os.path.abspath(args.results))
    with open(args.results) as fh:
        if args.results.endswith(".jsonl"):
            rows = [json.loads(line) for line in fh if line.strip()]
        else:
            rows = list(csv.DictReader(fh))
    invalid = 0
    print(f"{'#':>3}  {'problem':<28}{'quantity':<11}{'method':<16}{'claimed':<22}verdict")
    for k, row in enumerate(rows, 1):
        source = row["problem"]
        prob = load_problem(source if isinstance(source, dict) else os.path.join(base, source))
        method_spec = row.get("method") or None
        method = parse_method(json.loads(method_spec) if isinstance(method_spec, str) else method_spec) if method_spec else prob.method
        claimed = float(row["claimed"])
        quantity = row.get("quantity", "threshold")
        if quantity == "threshold":
            v = oracle.judge_threshold(prob.system, prob.polyhedron, method, claimed, args.tolerance)
        elif quantity == "gamma":
            v = oracle.judge_gamma(prob.system, prob.polyhedron, claimed, args.tolerance)
        elif quantity == "radius":
            v = oracle.judge_radius(method, claimed, args.tolerance)
        else:
            raise ExactinvError(f"row {k}: unknown quantity {quantity!r} (threshold, gamma, radius)")
        invalid += v.status == "invalid"
        name = prob.name if isinstance(source, dict) else os.path.basename(str(source))
        print(f"{k:>3}  {name:<28}{quantity:<11}{(method.name if method else '-'):<16}{row['claimed']:<22}{v.status.upper()}")
        if v.status != "tight":
            print(f"     {v.message}")
    print(f"{len(rows)} results judged: {invalid} invalid")
    return 1 if invalid else 0


def _explain(args) -> int:
    from .explain import explain

    with open(args.certificate) as fh:
        cert = json.load(fh)
    print(explain(cert))
    return 0


def main(argv: Sequence[str] | None = None) -> int:
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
    args = parser.parse_args(argv)
    try:
        return args.run(args)
    except VerificationFailed as exc:
        print(f"exactinv: internal verification failed: {exc}", file=sys.stderr)
        return 1
    except (ExactinvError, json.JSONDecodeError) as exc:
        print(f"exactinv: {exc}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
