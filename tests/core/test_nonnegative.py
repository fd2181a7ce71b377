"""The condition-by-condition valid set (exactinv/core/nonnegative.py) against the all-at-once
reference (every negative segment removed at once), the batched Descartes test against
exact evaluation, and IntervalUnion.intersect against membership of sample points."""

from fractions import Fraction

import flint
from hypothesis import given, settings
from hypothesis import strategies as st

from exactinv.core.algebraic import ExactKey
from exactinv.core.intervals import complement_of_open
from exactinv.core.nonnegative import earliest_first, first_end, nonnegative_set, tightest_first
from exactinv.core.polys import positive_below
from exactinv.core.roots import negative_segments, nonnegative_until, positive_roots
from exactinv.core.scalars import INF

# products of linear factors (t - r) with small rational roots: many shared and touching ends
roots = st.lists(st.fractions(min_value=-2, max_value=4, max_denominator=3), min_size=0, max_size=3)
polys = st.builds(lambda rs, c: c * _product(rs), roots, st.sampled_from([-3, -1, 1, 2]))


def _product(rs):
    p = flint.fmpq_poly([1])
    for r in rs:
        p *= flint.fmpq_poly([flint.fmpq(-r.numerator, r.denominator), 1])
    return p


def _samples(ps):
    """Every positive root of the polynomials, the midpoints between them and a point beyond."""
    pts = sorted({r for p in ps for r, _ in positive_roots(p)})
    grid = [Fraction(0)] + pts
    return grid + [(a + b) / 2 for a, b in zip(grid, grid[1:])] + [grid[-1] + 1]


@settings(max_examples=150, deadline=None)
@given(st.lists(polys, min_size=1, max_size=6), st.lists(st.fractions(min_value=Fraction(1, 4), max_value=5,
                                                                       max_denominator=4), max_size=2))
def test_nonnegative_set_is_the_all_at_once_set(ps, points):
    """Same maximal intervals as complement_of_open of every negative segment, whatever the order."""
    reference = complement_of_open([s for p in ps for s in negative_segments(p)], points)
    start = complement_of_open([], points)
    for order in (ps, tightest_first(ps), earliest_first(ps), ps[::-1]):
        assert repr(nonnegative_set(order, start)) == repr(reference)
    for t in _samples(ps)[1:] + points:  # and the set is right pointwise on t > 0 (0 is always kept)
        inside = all(p(flint.fmpq(t.numerator, t.denominator)) >= 0 for p in ps) and t not in points
        assert (t in reference) == inside


@settings(max_examples=150, deadline=None)
@given(st.lists(polys, min_size=1, max_size=6), st.fractions(min_value=Fraction(1, 8), max_value=5,
                                                              max_denominator=8))
def test_positive_below_is_sound(ps, T):
    """True only when p > 0 at every root-free sample of (0, T), and p has no root in (0, T)."""
    for p, ok in zip(ps, positive_below(ps, T)):
        if ok:
            assert all(not (0 < r < T) for r, _ in positive_roots(p))
            assert p(flint.fmpq(T.numerator, 2 * T.denominator)) > 0
    for p, ok in zip(ps, positive_below(ps, None)):
        if ok:
            assert positive_roots(p) == [] and p(1) > 0


def test_positive_below_decides_simple_cases():
    """(t - 1)(t - 2) is positive on (0, 1) but not on (0, 3/2); -1 never; t^2 on (0, oo)."""
    p, q, r = _product([Fraction(1), Fraction(2)]), flint.fmpq_poly([-1]), flint.fmpq_poly([0, 0, 1])
    assert positive_below([p, q, r], Fraction(1)) == [True, False, True]
    assert positive_below([p, q, r], Fraction(3, 2)) == [False, False, True]
    assert positive_below([p, q, r], None) == [False, False, True]


@settings(max_examples=150, deadline=None)
@given(st.lists(polys, min_size=1, max_size=3), st.lists(polys, min_size=1, max_size=3))
def test_intersect_is_pointwise(ps, qs):
    A, B = nonnegative_set(ps), nonnegative_set(qs)
    both = A.intersect(B)
    assert repr(both) == repr(nonnegative_set(ps + qs))
    for t in _samples(ps + qs):
        assert (t in both) == (t in A and t in B)
    assert all(iv.lo_closed or iv.lo != 0 for iv in both) and (not both.intervals or both[-1].hi == INF or
                                                                   both[-1].hi_closed)


@settings(max_examples=150, deadline=None)
@given(st.lists(polys, max_size=6))
def test_first_end_is_the_least_nonnegative_end(ps):
    """first_end (skips, earliest first) equals the minimum of nonnegative_until over every p."""
    assert first_end(ps) == min((nonnegative_until(p) for p in ps), key=ExactKey, default=INF)
    assert sorted(map(str, earliest_first(ps))) == sorted(map(str, ps))   # a permutation
