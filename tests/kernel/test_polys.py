"""exactinv_check.polys: the root bound (Fujiwara's, by bit lengths) scales with the roots, so the kernel's
Descartes isolation costs the same for roots near 10^60, 1 or 10^-60 (issue 22: a Taylor-12 certificate on
10^-60 A was rejected over the certificate budget after 3.4 s of CPU time with Cauchy's bound)."""


from fractions import Fraction

from hypothesis import given, settings
from hypothesis import strategies as st
from kernel_deadline import check_within

import exactinv as ei
from exactinv_check.polys import cauchy_bound, count_roots, positive_roots


def _from_roots(roots):
    p = [Fraction(1)]
    for r in roots:
        q = [Fraction(0)] * (len(p) + 1)
        for i, c in enumerate(p):
            q[i] -= r * c
            q[i + 1] += c
        p = q
    return p


# ------------------------------------------------------------------ soundness

def test_the_bound_of_known_polynomials():
    assert cauchy_bound([-2, 0, 1]) == 4                   # +-sqrt(2) < 4 (Fujiwara: 2 * 2^1)
    assert cauchy_bound([-(2 ** 400), 0, 1]) == 2 ** 202   # +-2^200
    assert cauchy_bound([-1, 0, 2 ** 400]) == Fraction(1, 2 ** 198)   # +-2^-200
    assert cauchy_bound([Fraction(5)]) == 1


@settings(max_examples=60, deadline=None)
@given(st.lists(st.fractions(min_value=-50, max_value=50, max_denominator=50), min_size=1, max_size=6),
       st.integers(-80, 80))
def test_every_root_lies_inside_and_the_bound_scales_with_them(roots, k):
    scale = Fraction(10) ** k
    rs = [r * scale for r in roots]
    B = cauchy_bound(_from_roots(rs))
    largest = max(abs(r) for r in rs)
    assert largest < B
    if largest:  # not more than 2 * 2 * (2 * deg) times the largest root: no 10^60 overshoot
        assert B <= 16 * len(rs) * largest
    assert count_roots(_from_roots(rs), -B, B) == len(set(rs))


def test_positive_roots_of_far_and_near_roots():
    for k in (-60, 0, 60):
        s = Fraction(10) ** k
        roots = [s, 2 * s, Fraction(7, 3) * s]
        found = positive_roots(_from_roots(roots))
        assert len(found) == 3 and all(lo <= r <= hi for (lo, hi), r in zip(found, sorted(roots)))


# ------------------------------------------------------------------ resource

def test_taylor12_certificates_at_10_pm_60_verify_within_cpu_seconds():
    """V(cA) = V(A)/c exactly, and the kernel accepts both certificates in a few CPU seconds (it rejected the
    10^-60 one over the budget before)."""
    P = ei.Polyhedron.box([-1, -1], [1, 1])
    m = ei.methods.taylor(12)
    base = ei.largest_threshold(ei.LinearSystem([[-1, 1], [-1, -1]]), P, m)
    for e in (-60, 60):
        c = Fraction(10) ** e
        L = ei.largest_threshold(ei.LinearSystem([[-c, c], [-c, -c]]), P, m)
        assert L.value == base.value / c
        assert check_within(L.certificate, 20).ok
        T = ei.steplength_threshold(ei.LinearSystem([[-c, c], [-c, -c]]), P, m)
        assert check_within(T.certificate, 20).ok
