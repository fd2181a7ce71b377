"""A :class:`~exactinv.interfaces.pipeline.Report` for scripts and papers:
``exactinv certify --json`` (:func:`report_json`) and ``--latex``
(:func:`report_latex`).

The JSON holds every exact value as the certificate encodes it (a rational
``"p/q"``, ``"oo"``, an algebraic number ``{"poly": [...], "interval": [lo,
hi]}``; never a float), the outcome and its exit code
(:mod:`exactinv.interfaces.exit_codes`) and the kernel's verdict per claim.
The LaTeX is a ``tabular`` that compiles with ``amsmath`` alone.
"""

from __future__ import annotations

from typing import Any

from ..control.optimal_gain import OptimalGain
from ..core.latex import latex_matrix, latex_real, latex_text
from ..invariance.gamma_star import OptimalGamma
from ..thresholds.polynomial import SteplengthThreshold
from ..validset.results import LargestThreshold, ValidSteplengths
from .exit_codes import CODES
from .pipeline import Report

__all__ = ["report_json", "report_latex", "REPORT_FORMAT"]

REPORT_FORMAT = "exactinv-report"


def report_json(report: Report, certificate: str | None = None) -> dict[str, Any]:
    """The report as a JSON-able dict: ``format`` (``"exactinv-report"``), ``version`` (1),
    ``problem``, ``method``, ``outcome`` and ``exit_code``, ``invariant`` (and the exact
    ``witness`` when the set is not invariant), ``values`` (exact, as the certificate
    encodes them; a gain design has ``gain`` and ``closed_loop``), ``undecided`` (each open question
    and why: ``{"question", "why"}``), ``check`` (the kernel's verdict per claim; ``verified`` None
    when skipped; a gain design also has ``closed_loop_check``, the verdict on the closed loop's own
    certificate) and ``certificate`` (the file it was written to, or None).

    >>> import exactinv as ei
    >>> from exactinv.interfaces.pipeline import certify
    >>> from exactinv.interfaces.problem import Problem
    >>> report = certify(Problem(ei.LinearSystem([[-1]]), ei.Polyhedron.box([-1], [1]), name="decay"), ei.methods.taylor(1))
    >>> out = report_json(report)
    >>> out["outcome"], out["exit_code"], out["values"]["gamma_star"], out["values"]["largest_threshold"]
    ('proved', 0, '1/2', '2')
    >>> out["check"]["verified"], [v["claim"] for v in out["check"]["verdicts"]][:2]
    (True, ['gamma_star', 'forward_euler_threshold'])
    """
    witness = next((claim["witness"] for claim in report.certificate.get("claims", ())
                    if isinstance(claim, dict) and claim.get("witness") is not None), None)
    out: dict[str, Any] = {
        "format": REPORT_FORMAT, "version": 1,
        "problem": report.problem.name, "method": report.method.name if report.method is not None else None,
        "outcome": report.outcome, "exit_code": CODES[report.outcome],
        "invariant": not report.refuted,
    }
    if report.refuted:
        out["witness"] = witness
    out["values"] = report.values()
    out["undecided"] = [{"question": what, "why": why} for what, why in report.undecided]
    out["check"] = _check_json(report)
    if report.closed_loop is not None:  # a gain design: the closed loop's certificate is checked on its own
        out["closed_loop_check"] = _check_json(report.closed_loop)
    out["certificate"] = certificate
    return out


def _check_json(report: Report) -> dict[str, Any]:
    check = report.check
    return {"verified": None if check is None else bool(check.ok),
            "kind": None if check is None else str(check.kind),  # accepted, rejected, over-budget, kernel-fault
            "claims": len(report.certificate.get("claims", ())),
            "verdicts": [] if check is None else
            [{"claim": kind, "ok": bool(ok), "message": str(message)} for kind, ok, message in check.verdicts]}


def report_latex(report: Report) -> str:
    """The results as a LaTeX ``tabular`` (math in ``$...$``, needs ``amsmath`` only), with
    comment lines naming the problem and the kernel's verdict; exact values as
    :func:`exactinv.core.latex.latex_real` writes them (fractions, the certified
    digits and the polynomial of an algebraic number).

    >>> import exactinv as ei
    >>> from exactinv.interfaces.pipeline import certify
    >>> from exactinv.interfaces.problem import Problem
    >>> report = certify(Problem(ei.LinearSystem([[-1]]), ei.Polyhedron.box([-1], [1]), name="decay"), ei.methods.taylor(1))
    >>> print(report_latex(report))  # doctest: +NORMALIZE_WHITESPACE
    % exactinv certify: problem decay, method taylor(1)
    % the trusted kernel VERIFIED the certificate (5 claims); needs \\usepackage{amsmath}
    \\begin{tabular}{ll}
    \\hline
    quantity & exact value \\\\
    \\hline
    continuous invariance & holds \\\\
    $\\gamma^*$ & $\\frac{1}{2}$ \\\\
    largest forward-Euler step & $2$ \\\\
    threshold of the paper, $\\text{taylor(1)}$ & $2$ \\\\
    valid steplengths, $\\text{taylor(1)}$ & $[0, 2]$ \\\\
    largest threshold, $\\text{taylor(1)}$ & $2$ \\\\
    \\hline
    \\end{tabular}
    """
    check = report.check
    verdict = ("the check was skipped (--no-check)" if check is None else
               f"the trusted kernel {'VERIFIED' if check.ok else 'REJECTED'} the certificate "
               f"({len(report.certificate.get('claims', ()))} claims)")
    name = report.problem.name.replace("\n", " ")
    lines = [f"% exactinv certify: problem {name}, method {report.method.name if report.method else 'none'}",
             f"% {verdict}; needs \\usepackage{{amsmath}}",
             r"\begin{tabular}{ll}", r"\hline", r"quantity & exact value \\", r"\hline"]
    lines += [f"{what} & {value} \\\\" for what, value in _latex_rows(report)]
    lines += [r"\hline", r"\end{tabular}"]
    return "\n".join(lines)


def _latex_rows(report: Report) -> list[tuple[str, str]]:
    """(quantity, value) rows in the order of the paper; a gain design's rows, then its closed loop's."""
    if report.closed_loop is not None or any(isinstance(r, OptimalGain) for r in report.results):
        rows = []
        for r in report.results:
            if isinstance(r, OptimalGain) and r.holds:
                rows += [("optimal gain $F$", f"${latex_matrix(r.F)}$"),
                         (r"$\gamma = \min_F \gamma^*(A + BF)$", f"${latex_real(r.gamma)}$"),
                         ("largest forward-Euler step over all gains", f"${latex_real(r.forward_euler_step)}$")]
            elif isinstance(r, OptimalGain):
                rows.append(("optimal gain $F$", "none: no linear gain keeps the set invariant"))
        if report.closed_loop is not None:
            rows += [(f"closed loop: {what}", value) for what, value in _latex_rows(report.closed_loop)]
        return rows
    method = f", ${latex_text(report.method.name)}$" if report.method is not None else ""
    rows = [(0, "continuous invariance", "holds" if not report.refuted else "fails (an exact witness leaves the set)")]
    for r in report.results:
        if isinstance(r, OptimalGamma):
            rows.append((1, r"$\gamma^*$", f"${latex_real(r.value)}$"))
        elif type(r).__name__.endswith("ForwardEulerThreshold"):
            rows.append((2, "largest forward-Euler step", f"${latex_real(r.value)}$"))
        elif isinstance(r, SteplengthThreshold):
            rows.append((3, f"threshold of the paper{method}",
                         f"${latex_real(r.value)}$" + ("" if r.attained else " (not attained)")))
        elif isinstance(r, ValidSteplengths):
            rows.append((4, f"valid steplengths{method}", r.intervals._repr_latex_()))
        elif isinstance(r, LargestThreshold):
            rows.append((5, f"largest threshold{method}",
                         f"${latex_real(r.value)}$" + ("" if r.attained else " (not attained)")))
    rows += [(6, f"undecided: ${latex_text(what)}$", "not in the certificate") for what, _ in report.undecided]
    rows.sort(key=lambda row: row[0])
    return [(what, value) for _, what, value in rows]
