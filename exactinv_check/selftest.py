"""The kernel's selftest: ``python3 -S -m exactinv_check.selftest`` (from a bare copy of the package).

A built-in suite, run with the Python standard library only (as ``python -m flint.test`` does for
python-flint):

* every genuine certificate of ``selftest_certificates/`` (small certificates made by the engine,
  covering every family of claims and the three format versions) must be accepted;
* every forgery -- a genuine certificate with one fact changed (a value, a flag, a generator, an entry
  of H, a key, the version) -- must be rejected, with the verdict kind named (``rejected``,
  ``over-budget`` or ``bad-input``): a kernel fault on a forgery fails the selftest too;
* the driver's own guarantee: a claim check that raises an unexpected exception is reported as a
  ``kernel-fault`` and never accepted.

It prints one line per case and a summary, and exits 0 if every case behaved, 1 otherwise.
"""

import copy
import json
import sys
import time
from pathlib import Path
from typing import Any, TextIO

from . import kernel
from .format import ClaimType, Verdict

DATA = Path(__file__).resolve().parent / "selftest_certificates"


def genuine() -> dict[str, dict]:
    """{name: certificate} of the built-in genuine certificates."""
    return {p.stem: json.loads(p.read_text(encoding="utf-8")) for p in sorted(DATA.glob("*.json"))}


def _set(*path_value: Any) -> Any:
    *path, value = path_value

    def mutate(cert: Any) -> Any:
        node = cert
        for key in path[:-1]:
            node = node[key]
        node[path[-1]] = value
    return mutate


def _delete(*path: Any) -> Any:
    def mutate(cert: Any) -> Any:
        node = cert
        for key in path[:-1]:
            node = node[key]
        del node[path[-1]]
    return mutate


def _claim(index: int, **fields: Any) -> Any:
    """Set several keys of one claim at once (a forgery consistent in all but the fact it forges)."""
    def mutate(cert: Any) -> Any:
        cert["claims"][index].update(copy.deepcopy(fields))
    return mutate


def _drop_vertex(claim: Any) -> Any:
    def mutate(cert: Any) -> Any:
        cert["claims"][claim]["vertices"].pop()
    return mutate


HUGE_ROOT = {"poly": ["9" * 3000] * 1000 + ["1"], "interval": ["0", "1"]}

# (name, genuine certificate, what is forged, mutation, expected verdict kind)
FORGERIES = [
    ("gamma-too-small", "box-taylor4", "gamma* = 1/2 instead of 1", _set("claims", 0, "value", "1/2"), Verdict.REJECTED),
    ("gamma-H-entry", "box-taylor4", "an entry of H changed", _set("claims", 0, "H", "sparse", 0, 0, [0, "-2"]),
     Verdict.REJECTED),
    ("gamma-dual", "box-taylor4", "the dual's lambda changed", _set("claims", 0, "dual", "lambda", "1/3"), Verdict.REJECTED),
    ("forward-euler-value", "box-taylor4", "forward Euler step 2 instead of 1", _set("claims", 1, "value", "2"),
     Verdict.REJECTED),
    ("forward-euler-vertex", "box-taylor4", "a vertex left out of the list", _drop_vertex(1), Verdict.REJECTED),
    ("paper-threshold", "box-taylor4", "the paper's threshold 3/2 instead of 1", _set("claims", 2, "value", "3/2"),
     Verdict.REJECTED),
    ("largest-other-root", "box-taylor4", "the largest threshold moved to another root of its polynomial",
     _set("claims", 3, "value", "interval", ["-3", "-2"]), Verdict.REJECTED),
    ("largest-not-attained", "box-taylor4", "attained flipped", _set("claims", 3, "attained", False), Verdict.REJECTED),
    ("largest-vertex", "box-taylor4", "a vertex left out of the list", _drop_vertex(3), Verdict.REJECTED),
    ("valid-set-longer", "box-taylor4", "the valid set extended to [0, 2]",
     _set("claims", 4, "intervals", [{"lo": "0", "hi": "2", "lo_closed": True, "hi_closed": True}]), Verdict.REJECTED),
    ("box-route-box", "box-route-rk4", "the box's corner moved", _set("claims", 0, "box", "hi", ["2", "1"]),
     Verdict.REJECTED),
    ("lp-route-basis", "lp-route-taylor2", "a basis of the LP route swapped",
     _set("claims", 0, "lp", "facets", 0, "bases", [[3, 7], [0, 4]]), Verdict.REJECTED),
    ("lp-route-end", "lp-route-taylor2", "a piece moved past the end of its basis's optimality",
     _set("claims", 0, "lp", "facets", 1, "ends", ["5/4", "3/2"]), Verdict.REJECTED),
    ("lp-route-short", "lp-route-taylor2", "the pieces stopped at 5/4, short of what the conditions allow",
     _set("claims", 0, "lp", "facets", 1, "ends", ["1", "5/4"]), Verdict.REJECTED),
    ("lp-dual-negative", "lp-dual-taylor2", "an entry of a dual piece's y_1 made negative",
     _set("claims", 0, "lp", "facets", 0, "bases", 1, "dual", 1, 0, [7, "-1"]), Verdict.REJECTED),
    ("lp-dual-identity", "lp-dual-taylor2", "a dual piece's identity G^T y(h) = D N^T g_i off in one coefficient",
     _set("claims", 0, "lp", "facets", 0, "bases", 1, "dual", 1, 0, [7, "2"]), Verdict.REJECTED),
    ("lp-lines-kernel", "lp-lines-taylor2", "a line of the LP route not in ker G",
     _set("claims", 1, "lp", "lines", [["1", "1"]]), Verdict.REJECTED),
    ("lp-lines-equalities", "lp-lines-taylor2", "the line equality ignored: the valid set {0, 1} claimed [0, 2]",
     _set("claims", 1, "intervals", [{"lo": "0", "hi": "2", "lo_closed": True, "hi_closed": True}]),
     Verdict.REJECTED),
    ("radius-value", "radius-ssprk33", "rho = 2 instead of 1", _set("claims", 0, "value", "2"), Verdict.REJECTED),
    ("radius-reason", "radius-ssprk33", "the reason all-coefficients (rho = oo)",
     _set("claims", 0, "reason", "all-coefficients"), Verdict.REJECTED),
    ("radius-tie", "radius-radau_iia3", "the tie's rho moved to 17/10",
     _set("claims", 0, "value", "17/10"), Verdict.REJECTED),
    ("radius-zero", "radius-sdirk4", "rho = 0 claimed attained", _set("claims", 0, "attained", True), Verdict.REJECTED),
    ("rational-threshold", "erratum-e2-backward-euler", "the paper's infinity for backward Euler (erratum E2)",
     _set("claims", 2, "value", "oo"), Verdict.REJECTED),
    ("rational-valid-set", "erratum-e2-backward-euler", "the valid set [0, oo) (erratum E2)",
     _set("claims", 3, "intervals", [{"lo": "0", "hi": "oo", "lo_closed": True, "hi_closed": False}]), Verdict.REJECTED),
    ("pade-radius", "octagon-pade22", "rho = 1 for Pade(2,2)", _set("claims", 1, "value", "1"), Verdict.REJECTED),
    ("ellipsoid-invariance", "ellipsoid-taylor2", "invariance denied without a witness",
     _set("claims", 0, "holds", False), Verdict.REJECTED),
    ("ellipsoid-largest", "ellipsoid-taylor2", "the largest threshold on E moved to 2",
     _set("claims", 1, "value", "2"), Verdict.REJECTED),
    ("ellipsoid-forward-euler", "ellipsoid-taylor2", "forward Euler on E 3/2 instead of 1",
     _set("claims", 3, "value", "3/2"), Verdict.REJECTED),
    ("discrete-invariance-dt", "discrete-invariance-taylor2", "invariance at dt = 3 with Ad = r(3A), where it fails",
     _claim(0, dt="3", Ad=[["-2", "-6"], ["6", "-2"]]), Verdict.REJECTED),
    ("ellipsoid-discrete-dt", "ellipsoid-discrete-taylor2", "invariance of E at dt = 3 with Ad = r(3A), where it fails",
     _claim(0, dt="3", Ad=[["-2", "-6"], ["6", "-2"]]), Verdict.REJECTED),
    ("pruning-horizon", "pruning-diamond-taylor2", "a pruning horizon 1/2 short of the bounding vertex's own set",
     _set("claims", 0, "pruning", "horizon", "1/2"), Verdict.REJECTED),
    ("gain-holds-F", "gain-holds", "a gain F = (0, 1) that makes P not invariant", _set("claims", 0, "F", [["0", "1"]]),
     Verdict.REJECTED),
    ("gain-farkas", "gain-double-integrator", "the Farkas vector changed",
     _set("claims", 0, "farkas", "mu", ["0", "1", "0", "0"]), Verdict.REJECTED),
    ("robust-value", "robust-ssprk33", "the robust threshold 1 instead of 2/3", _set("claims", 1, "value", "1"),
     Verdict.REJECTED),
    ("version-1-dt", "doc-version-1", "a version-2 key in a version-1 certificate",
     _set("claims", 0, "dt", "1/2"), Verdict.REJECTED),
    ("unknown-key", "box-taylor4", "a key the format does not have", _set("claims", 0, "trust_me", True),
     Verdict.REJECTED),
    ("missing-key", "box-taylor4", "a required key left out", _delete("claims", 1, "vertices"), Verdict.REJECTED),
    ("unknown-claim", "box-taylor4", "an unknown claim type", _set("claims", 0, "type", "gamma"), Verdict.REJECTED),
    ("version-4", "box-taylor4", "version 4", _set("version", 4), Verdict.REJECTED),
    ("float-number", "box-taylor4", "a JSON float for a number", _set("claims", 0, "value", 1.0), Verdict.REJECTED),
    ("huge-root", "box-taylor4", "a threshold of degree 1000 with 3000-digit coefficients",
     _set("claims", 2, "value", HUGE_ROOT), Verdict.OVER_BUDGET),
    ("wrong-format", "box-taylor4", "not the exactinv format", _set("format", "exactinv"), Verdict.BAD_INPUT),
]


def fault_is_never_accepted(certificate: Any) -> Any:
    """A claim check that raises TypeError (a stand-in for a kernel bug) is a kernel-fault, not accepted."""
    kind = ClaimType.GAMMA_STAR
    handler, required, optional = kernel.CLAIMS[kind]

    def broken(problem: Any, claim: Any, context: Any) -> Any:
        raise TypeError("a deliberate fault (selftest)")

    kernel.CLAIMS[kind] = (broken, required, optional)
    try:
        return kernel.check(copy.deepcopy(certificate))
    finally:
        kernel.CLAIMS[kind] = (handler, required, optional)


def run(out: TextIO = sys.stdout) -> int:
    """Run every case, print one line each and a summary; the number of cases that misbehaved."""
    certificates = genuine()
    failures, start = 0, time.process_time()

    def line(ok: Any, text: Any) -> Any:
        nonlocal failures
        failures += not ok
        print(f"  {'ok  ' if ok else 'FAIL'} {text}", file=out)

    print(f"exactinv_check selftest: {len(certificates)} genuine certificates, {len(FORGERIES)} forgeries", file=out)
    for name, cert in certificates.items():
        report = kernel.check(copy.deepcopy(cert))
        line(report.ok and report.kind == Verdict.ACCEPTED,
             f"genuine {name}: {report.kind} ({len(cert['claims'])} claims)"
             + ("" if report.ok else f" -- {report.verdicts[-1][2]}"))
    for name, base, what, mutate, expected in FORGERIES:
        if base not in certificates:
            line(False, f"forged {name}: no genuine certificate {base!r}")
            continue
        cert = copy.deepcopy(certificates[base])
        mutate(cert)
        report = kernel.check(cert)
        line(not report.ok and report.kind == expected, f"forged {name} ({what}): {report.kind}"
             + ("" if report.kind == expected else f", expected {expected}"))
    report = fault_is_never_accepted(certificates["box-taylor4"])
    line(not report.ok and report.kind == Verdict.KERNEL_FAULT, f"a fault inside the kernel: {report.kind}, not accepted")
    total = len(certificates) + len(FORGERIES) + 1
    print(f"{total - failures} of {total} cases behaved, {failures} failed "
          f"({time.process_time() - start:.1f} s of CPU time)", file=out)
    return failures


def main() -> int:
    return 1 if run() else 0


if __name__ == "__main__":
    sys.exit(main())
