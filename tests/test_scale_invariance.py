"""V(cA) = V(A)/c, exactly, for every scale c > 0 (issue 22, item 1).

r(h cA) = r((hc) A), so h is a valid step for cA iff hc is one for A: the valid set and the
largest threshold scale by 1/c.  Before issue 22 the engine raised OverflowError on
A ~ 10^30 with a condition of degree >= 11 (a float of a condition coefficient); the
answers here are checked against the unscaled problem, exactly, and some certificates
against the kernel.
"""

from __future__ import annotations

from fractions import Fraction
from functools import lru_cache

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import exactinv as ei
from exactinv import methods as M

HEXAGON = ei.Polyhedron([[1, 0], [1, 1], [0, 1], [-1, 0], [-1, -1], [0, -1]], [1, 2, 1, 1, 2, 1])
LINE = ei.Polyhedron([[1], [-1]], [1, 2])  # [-2, 1]
PROBLEMS = {
    "hexagon": (HEXAGON, [[Fraction(-1), Fraction(1, 2)], [Fraction(-1, 3), Fraction(-2)]]),
    "line": (LINE, [[Fraction(-1)]]),
}
METHODS = {"taylor(12)": M.taylor(12), "pade(3,3)": M.pade(3, 3), "radau_iia2": M.radau_iia2(),
           "sdirk4": M.sdirk4(), "rk4": M.rk4()}


def _system(A, c):
    return ei.LinearSystem([[c * x for x in row] for row in A])


@lru_cache(maxsize=None)
def _unscaled(problem: str, method: str):
    P, A = PROBLEMS[problem]
    S, m = _system(A, 1), METHODS[method]
    return ei.valid_steplengths(S, P, m), ei.largest_threshold(S, P, m)


def _scaled_end(x, c):
    return x if isinstance(x, ei.Infinity) else x / c


def _assert_scaled(problem, method, c, check=False):
    P, A = PROBLEMS[problem]
    S, m = _system(A, c), METHODS[method]
    V0, L0 = _unscaled(problem, method)
    V, L = ei.valid_steplengths(S, P, m), ei.largest_threshold(S, P, m)
    assert len(V) == len(V0)
    for iv, iv0 in zip(V, V0):
        assert (iv.lo_closed, iv.hi_closed) == (iv0.lo_closed, iv0.hi_closed)
        assert iv.lo == _scaled_end(iv0.lo, c) and iv.hi == _scaled_end(iv0.hi, c), (problem, method, c)
    assert L.value == _scaled_end(L0.value, c) and L.attained == L0.attained
    if check:
        assert ei.check(V.certificate).ok and ei.check(L.certificate).ok


scales = st.one_of(
    st.integers(-60, 60).map(lambda k: Fraction(10) ** k),
    st.integers(-200, 200).map(lambda k: Fraction(2) ** k),
    st.builds(Fraction, st.integers(1, 10**40), st.integers(1, 10**40)),
)


@settings(max_examples=25, deadline=None)
@given(scales, st.sampled_from(sorted(PROBLEMS)), st.sampled_from(sorted(METHODS)))
def test_valid_set_and_largest_threshold_scale_by_one_over_c(c, problem, method):
    _assert_scaled(problem, method, c)


@pytest.mark.parametrize("method", ["taylor(12)", "pade(3,3)", "radau_iia2"])
@pytest.mark.parametrize("k", [30, -30, 60])
def test_the_issue_cases_are_answered_and_certified(method, k):
    """A ~ 10^30 with Taylor-12, Pade(3,3), Radau IIA(2): no OverflowError, the exact answer,
    and the certificate verified by the kernel."""
    _assert_scaled("hexagon", method, Fraction(10) ** k, check=True)


def test_one_dimensional_decay_at_ten_to_the_sixty():
    """x' = -10^60 x on [-2, 1] with Pade(3,3): r(-10^60 h) must stay in [-1/2, 1] (the point -2
    maps into [-2, 1], the point 1 too), i.e. V = V(-1)/10^60."""
    c = Fraction(10) ** 60
    _assert_scaled("line", "pade(3,3)", c, check=True)
    V = ei.valid_steplengths(_system([[-1]], c), LINE, M.pade(3, 3))
    for iv in V:  # spot check the exact definition inside each interval
        mid = iv.lo + 1 if isinstance(iv.hi, ei.Infinity) else None
        if mid is None:
            lo = iv.lo if isinstance(iv.lo, Fraction) else iv.lo.upper
            hi = iv.hi if isinstance(iv.hi, Fraction) else iv.hi.lower
            mid = (lo + hi) / 2
        assert ei.discrete_invariance(_system([[-1]], c), LINE, M.pade(3, 3), mid).holds


@settings(max_examples=8, deadline=None)
@given(st.integers(-60, 60), st.sampled_from(["taylor(12)", "pade(3,3)"]))
def test_the_paper_threshold_scales_too(k, method):
    """gamma*(cA) = c gamma*(A) and the paper's threshold scales by 1/c."""
    P, A = PROBLEMS["hexagon"]
    c = Fraction(10) ** k
    t0 = ei.steplength_threshold(_system(A, 1), P, METHODS[method])
    t = ei.steplength_threshold(_system(A, c), P, METHODS[method])
    assert t.gamma.value == c * t0.gamma.value
    assert t.value == _scaled_end(t0.value, c) and t.attained == t0.attained
