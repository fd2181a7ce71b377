"""Attacks on alpha(H) block by block (linalg.largest_real_root) and on the kernel's balanced line,
reason bernstein-root, and alpha(H) block by block.

Finding 1 (kernel-alpha, a genuine certificate REJECTED): linalg.largest_real_root isolated the positive roots of
the squarefree q without its root at 0 (polys.positive_roots strips it) and then built the Real from q itself on
that interval, which starts at 0: "an end of the interval is a root".  Every H with a strongly connected block
whose characteristic polynomial has roots 0 and > 0 (e.g. the path graph 0 - 1 - 2: x^3 - 2x) was rejected.  Fix:
the Real is made from q with its root at 0 stripped.
"""


from fractions import Fraction as F

import pytest
import sympy

from exactinv_check import check
from exactinv_check.linalg import largest_real_root

pytestmark = pytest.mark.workload  # the kernel's own workload: left out at the lowest versions (.ci/run stage 3)


def _path_certificate(alpha=None):
    """x' = Ax with A the adjacency matrix of the path 0 - 1 - 2 on P = {x <= -1} (G = I, b = -1), backward Euler:
    H = A (HG = GA, Hb = (-1, -2, -1) <= 0, off-diagonal >= 0), gamma* = 0 (the dual of row 0), rho = oo, z_p = 1,
    alpha(H) = sqrt 2 (x^3 - 2x, one strongly connected block), and the threshold min(z_p/alpha, the singular point
    of I - hA) = 1/sqrt 2, not attained (the engine's certificate, as written)."""
    return {"format": "exactinv-certificate", "version": 3,
            "problem": {"A": [["0", "1", "0"], ["1", "0", "1"], ["0", "1", "0"]],
                        "G": [["1", "0", "0"], ["0", "1", "0"], ["0", "0", "1"]], "b": ["-1", "-1", "-1"],
                        "method": {"name": "backward_euler", "numerator": ["1"], "denominator": ["1", "-1"]}},
            "claims": [{"type": "gamma_star", "value": "0",
                        "H": {"sparse": [[[1, "1"]], [[0, "1"], [2, "1"]], [[1, "1"]]]},
                        "binding_row": 0, "dual": {"y": ["1", "0", "0"], "lambda": "0"}},
                       {"type": "absolute_monotonicity_radius", "value": "oo", "reason": "product", "attained": True,
                        "pole": "1"},
                       {"type": "rational_threshold", "attained": False, "rho": "oo", "pole": "1", "alpha": alpha,
                        "value": {"poly": ["-1", "0", "2"],
                                  "interval": ["353553390593/500000000000", "707106781187/1000000000000"]}}]}


# ------------------------------------------------------------------ soundness

def test_path_graph_truth():
    """Independently: the characteristic polynomial of A is x^3 - 2x (sympy), its largest real root sqrt 2, so
    z_p/alpha = 1/sqrt 2; I - hA is singular first at h = 1/sqrt 2 too (eigenvalue sqrt 2)."""
    x = sympy.Symbol("x")
    A = sympy.Matrix([[0, 1, 0], [1, 0, 1], [0, 1, 0]])
    assert sympy.expand(A.charpoly(x).as_expr() - (x ** 3 - 2 * x)) == 0
    assert max(sympy.Poly(x ** 3 - 2 * x).real_roots()) == sympy.sqrt(2)
    lo, hi = F(353553390593, 500000000000), F(707106781187, 1000000000000)
    assert lo * lo * 2 < 1 < hi * hi * 2  # the recorded threshold interval holds 1/sqrt 2


def test_a_block_with_eigenvalues_zero_and_positive_is_certified():
    """Finding 1: was '[REJECTED] rational_threshold: largest eigenvalue: an end of the interval is a root'."""
    report = check(_path_certificate())
    assert report.ok, str(report)
    assert check(_path_certificate(alpha={"poly": ["-2", "0", "1"], "interval": ["1", "2"]})).ok
    for wrong in ("1", "2", {"poly": ["-3", "0", "1"], "interval": ["1", "2"]}, "0"):
        assert not check(_path_certificate(alpha=wrong)).ok, wrong
    bad = _path_certificate()
    bad["claims"][2]["value"] = {"poly": ["-1", "0", "3"], "interval": ["1/2", "1"]}  # 1/sqrt 3: not the threshold
    assert not check(bad).ok


def test_seeded_mutation_fuzz_of_the_balanced_line_and_bernstein_root():
    """Genuine balanced-line structures (B >= 0 touching 0, real poles off the line, pairs further right), one field
    mutated by 10^-60 or a little more; every proof of f >= 0 the kernel accepts is checked by mpmath at 200 digits
    (f at B's zeros out to t ~ 10^7), every accepted radius claim by the exact c_j.  The budget is deterministic
    (no clock), so the slice is the same on every run; it must both accept and reject something."""
    import fuzz_radius3

    stats, per = fuzz_radius3.run(float("inf"), seed=5, log=lambda *_: None, cases=6, limit=2 * 10 ** 8,
                                  claims_share=1.0)
    assert stats["cases"] == 6 and stats["accepted"] == stats["verified"]
    assert stats["accepted"] > 0 and stats["rejected"] > 0 and stats["claims_accepted"] > 0


def test_bernstein_root_claims_and_their_mutants_on_hand_structures():
    """c < 0 beside a balanced line (p* = 1, 3/4 with a pair at height 2, 1/2 touching B = 1 + cos 2t, a real pole at
    2 or 7/4): the genuine algebraic root is accepted (and checked by the exact c_j at its enclosure's ends); the
    rational 10^-70 approximations, +-10^-60, oo, attained false, reason bernstein: rejected (reason coefficient may
    prove the same rho; every accept is checked by the exact c_j and would raise if false)."""
    import fuzz_radius3

    stats = {}
    for p, q in ((F(1), F(2)), (F(3, 4), F(7, 4))):
        terms = [((p, F(0)), (F(1), F(0))), ((p, F(2)), (F(1, 2), F(0))), ((p, F(-2)), (F(1, 2), F(0))),
                 ((q, F(0)), (F(1), F(0)))]
        fuzz_radius3.check_claims(terms, stats)
    assert stats["roots_accepted"] == stats["claims_accepted"] >= 2  # bernstein-root (and coefficient: also true)


# ------------------------------------------------------------------ resource

def test_largest_real_root_with_a_root_at_zero():
    """x^k (x^2 - 2)(x + 3) and friends: the largest real root by sympy, the kernel's enclosure holds it."""
    x = sympy.Symbol("x")
    for expr in (x * (x ** 2 - 2), x ** 2 * (x ** 2 - 2) * (x + 3), x * (x - F(1, 3)) * (x ** 2 + 1), -x * (x ** 2 - 5),
                 x * (x + 1), x ** 3 * (x ** 2 + 2), x * (x - 7) ** 2):
        p = [F(int(c.p), int(c.q)) for c in reversed(sympy.Poly(expr, x).all_coeffs())]
        root = largest_real_root(p)
        truth = max(sympy.Poly(expr, x).real_roots())
        lo, hi = root.bounds()
        assert sympy.Rational(lo.numerator, lo.denominator) <= truth <= sympy.Rational(hi.numerator, hi.denominator)
