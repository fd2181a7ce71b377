"""The paper's pipeline implemented in floating point -- the kind of code the oracle judges.

gamma* from a float LP (cvxpy + HiGHS), the f_i of Theorem 3.4 in floats,
tau_i by the paper's float Sturm-bisection algorithm (Section 3.1.2, as printed),
tau = min_i tau_i.  Writes paper_float_results.csv next to this file; then

    exactinv oracle examples/oracle/paper_float_results.csv

judges every row against the exact largest thresholds (the float gamma* LP
itself is judged here too, by ``exactinv.oracle.judge_lp``: its exact optimum
with a certificate, and whether cvxpy's value is tight).  Because of erratum E3
(t* = alpha*/alpha_q + 1 <= 0 when alpha_q < 0) the float pipeline returns
tau = inf for Taylor methods of order >= 2, and the oracle catches it with an
exact counterexample.
"""

from __future__ import annotations

import csv
import json
import math
import os
import sys
from math import comb

import cvxpy as cp
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", ".."))

from exactinv.interfaces.oracle import judge_lp  # noqa: E402
from exactinv.interfaces.problem import load_problem  # noqa: E402
from exactinv.thresholds.bisection import paper_bisection_float  # noqa: E402

PROBLEMS = ["../paper_box_taylor4.json", "../octagon_heun.json"]
METHODS = [{"taylor": 1}, {"taylor": 2}, {"taylor": 3}, {"taylor": 4}]


def float_gamma(S, P) -> float:
    G = np.array([[float(v) for v in r] for r in P.G])
    A = np.array([[float(v) for v in r] for r in S.A])
    b = np.array([float(v) for v in P.b])
    m = len(b)
    H, gamma = cp.Variable((m, m)), cp.Variable()
    problem = cp.Problem(cp.Minimize(gamma), [H + gamma * np.eye(m) >= 0, H @ G == G @ A, H @ b <= 0])
    problem.solve(solver=cp.HIGHS)
    print(f"  the float gamma* LP: {judge_lp(problem)}")
    return float(gamma.value)


def float_threshold(sigmas: list[float], gamma: float) -> float:
    """min_i tau_i with f_i / (sigma_i dt^i) = 1 + sum_{k>i} (-1)^(k-i) sigma_k C(k,i) gamma^(k-i)/sigma_i dt^(k-i)."""
    if gamma <= 0:
        return math.inf
    taus = []
    p = len(sigmas) - 1
    for i in range(p + 1):
        alphas = [1.0] + [(-1) ** (k - i) * sigmas[k] * comb(k, i) * gamma ** (k - i) / sigmas[i] for k in range(i + 1, p + 1)]
        while len(alphas) > 1 and alphas[-1] == 0:
            alphas.pop()
        if len(alphas) == 1:
            taus.append(math.inf)
            continue
        taus.append(float(paper_bisection_float([repr(a) for a in alphas], repaired=False).tau))
    return min(taus)


def main():
    rows = []
    for rel in PROBLEMS:
        prob = load_problem(os.path.join(HERE, rel))
        g = float_gamma(prob.system, prob.polyhedron)
        rows.append({"problem": rel, "quantity": "gamma", "method": "", "claimed": repr(g)})
        for spec in METHODS:
            p = spec["taylor"]
            sigmas = [1.0 / math.factorial(k) for k in range(p + 1)]
            tau = float_threshold(sigmas, g)
            rows.append({"problem": rel, "quantity": "threshold", "method": json.dumps(spec), "claimed": repr(tau)})
    out = os.path.join(HERE, "paper_float_results.csv")
    with open(out, "w", newline="") as fh:
        writer = csv.DictWriter(fh, fieldnames=["problem", "quantity", "method", "claimed"])
        writer.writeheader()
        writer.writerows(rows)
    print(f"wrote {len(rows)} float results to {out}")


if __name__ == "__main__":
    main()
