"""exactinv/core/real_signs.py: signs at and just right of algebraic points, the next sign change,
batched Descartes signs -- against the definitions (exact roots, exact signs at rationals)."""

import math
from fractions import Fraction

import flint
from hypothesis import given, settings
from hypothesis import strategies as st

from exactinv.core.polys import count_real_roots, sign_at
from exactinv.core.real_algebraic import RealAlgebraic
from exactinv.core.real_signs import (
    interval_signs,
    narrowed,
    next_sign_change,
    rational_right_of,
    sign_change_near,
    sign_right_of_real,
)
from exactinv.core.roots import real_roots
from exactinv.core.scalars import INF

F = Fraction
SQRT2 = (-2, 0, 1)


def _sqrt2():
    return RealAlgebraic.from_isolating_interval(list(SQRT2), 1, 2)


small = st.lists(st.integers(-4, 4), min_size=1, max_size=4).filter(any)


@settings(max_examples=60, deadline=None)
@given(small, st.integers(0, 3))
def test_sign_right_of_sqrt2_of_q_to_the_k_times_r(r, k):
    """p = (x^2 - 2)^k r: right of sqrt 2, (x^2 - 2) > 0, so the sign is that of r(sqrt 2) (r(sqrt 2) != 0:
    r has integer coefficients and degree < 4, so r(sqrt 2) = 0 only if x^2 - 2 divides r) -- or, when it
    divides r, the sign just right taken from r's own factorisation; checked against a rational point
    closer to sqrt 2 than any other root of p."""
    q = flint.fmpq_poly(list(SQRT2))
    p = q ** k * flint.fmpq_poly(r)
    t = _sqrt2()
    others = [root for root, _ in real_roots(p) if root != t] if p.degree() > 0 else []
    gap = min((abs(Fraction(float(root)) - F(141421, 100000)) for root in others), default=F(1))
    s = rational_right_of(t, min(gap / 4, F(1, 10**6)))
    assert sign_right_of_real(p, t) == sign_at(p, s)


@settings(max_examples=60, deadline=None)
@given(st.lists(st.integers(-5, 5), min_size=2, max_size=6).filter(lambda c: c[-1] != 0))
def test_next_sign_change_is_the_least_odd_root_beyond(coeffs):
    p = flint.fmpq_poly(coeffs)
    for t in (_sqrt2(), F(1, 3)):
        expected = next((root for root, m in real_roots(p) if m % 2 and root > t), INF)
        assert next_sign_change(p, t) == expected


@settings(max_examples=60, deadline=None)
@given(st.lists(st.lists(st.integers(-5, 5), min_size=3, max_size=3), min_size=1, max_size=5),
       st.fractions(min_value=-2, max_value=2, max_denominator=4), st.fractions(min_value=F(1, 4), max_value=3,
                                                                             max_denominator=4))
def test_interval_signs_are_sound(rows, lo, width):
    """+1 / -1 only when the polynomial has no root in (lo, hi) and that sign there (count_real_roots)."""
    hi = lo + width
    M = flint.fmpq_mat(len(rows), 3, [v for r in rows for v in r])
    for r, sign in zip(rows, interval_signs(M, lo, hi)):
        p = flint.fmpq_poly(r)
        if sign == 0:
            continue
        if p.is_zero():
            assert sign == 1
            continue
        inside = count_real_roots(p, lo, hi) - (1 if sign_at(p, hi) == 0 else 0) if p.degree() > 0 else 0
        assert inside == 0 and sign_at(p, (lo + hi) / 2) == sign


def test_narrowed_keeps_the_number():
    for poly, lo, hi in ((SQRT2, 1, 2), ((-3, 0, 0, 1), 1, 2), ((-1, -1, 1), 1, 2)):
        a = RealAlgebraic.from_isolating_interval(list(poly), lo, hi)
        b = narrowed(a)
        assert b == a and b.upper - b.lower < F(1, 2**40)


@settings(max_examples=60, deadline=None)
@given(st.lists(st.integers(-40, 40), min_size=2, max_size=6).filter(lambda c: c[-1] != 0))
def test_narrowed_by_the_newton_hint_keeps_every_root(coeffs):
    """Every real root of a squarefree factor, narrowed (a float Newton hint proved by an exact sign
    change, or the Arb fallback): the same number, a narrow enclosure inside the old one."""
    for p, _ in flint.fmpz_poly(coeffs).factor()[1]:
        for root, _ in real_roots(flint.fmpq_poly(p)):
            if not isinstance(root, RealAlgebraic):
                continue
            old = (root.lower, root.upper)
            b = narrowed(RealAlgebraic(root.poly, root.lower, root.upper))
            assert b == root and old[0] <= b.lower < b.upper <= old[1] and b.upper - b.lower < F(1, 2**40)


def test_the_newton_hint_never_raises_and_only_helps():
    """Coefficients beyond double range, and an enclosure the float iteration leaves: no hint, no error."""
    from exactinv.core.real_signs import _newton
    assert _newton(flint.fmpz_poly([-2 * 10**400, 0, 10**400]), F(1), F(2)) is None  # overflow: no hint
    far = _newton(flint.fmpz_poly([-2, 0, 1]), F(-2), F(-1))      # the root -sqrt 2, from the midpoint
    assert far is not None and far.upper < 0 and far.upper ** 2 < 2 < far.lower ** 2


# ------------------------------------------------------------------ the end of a piece from a float bracket


def _brackets(e, rng):
    """Float brackets around the exact end e (right ones, and wrong ones: off to either side, reversed)."""
    x = float(e)
    out = [(x - 0.5, x + 0.25), (x - 1e-3, x + 1e-3), (x - 1e-9 * (1 + abs(x)), x + 1e-9 * (1 + abs(x)))]
    out += [(x + 0.1, x + 1.0), (x - 2.0, x - 0.5), (x + 1e-3, x - 1e-3), (x - 1e-30, x + 1e-30)]
    out.append((x - rng.random(), x + rng.random()))
    return out


@settings(max_examples=120, deadline=None)
@given(st.lists(st.integers(-6, 6), min_size=2, max_size=7).filter(lambda c: c[-1] != 0),
       st.lists(st.integers(-3, 3), min_size=0, max_size=3), st.integers(0, 2), st.randoms(use_true_random=False))
def test_sign_change_near_is_next_sign_change_or_nothing(coeffs, linear_roots, square, rng):
    """Against the exact root isolation (next_sign_change), from a rational t and from t = sqrt 2, with
    right and wrong float brackets: either None (the hint did not help) or the same exact number -- also
    for p with a squared factor (a tangency the piece steps over), repeated and rational roots."""
    p = flint.fmpq_poly(coeffs)
    for r in linear_roots:
        p *= flint.fmpq_poly([-r, 1])
    if square:
        p *= flint.fmpq_poly([-square, 0, 1]) ** 2  # tangent roots at +-sqrt(square): never an end
    for t in (F(-1, 3), _sqrt2()):
        if sign_right_of_real(p, t) <= 0:
            p = -p
        exact = next_sign_change(p, t)
        targets = [exact] if exact != INF else [F(5)]
        for e in targets:
            for left, right in _brackets(e, rng):
                found = sign_change_near(p, t, left, right)
                assert found is None or found == exact


def test_sign_change_near_helps_where_the_bracket_is_right():
    """A right bracket finds the end (narrow, exact) for a simple root, rational or not, also from an
    algebraic t; a bracket around a tangency or with one before it (Descartes then sees a root), a bracket
    left of t or within t's enclosure, or floats out of range give None (the exact isolation decides)."""
    q = flint.fmpq_poly([6, -5, 1]) * flint.fmpq_poly([3, 0, -1])      # (x - 2)(x - 3)(3 - x^2): ends at sqrt 3
    e = sign_change_near(q, F(0), 1.5, 1.8)
    assert isinstance(e, RealAlgebraic) and e == next_sign_change(q, F(0)) and e.upper - e.lower < F(1, 2**40)
    assert sign_change_near(flint.fmpq_poly([-2, 1]) * -1, _sqrt2(), 1.5, 2.5) is None    # t's enclosure reaches 2
    assert sign_change_near(flint.fmpq_poly([-2, 1]) * -1, narrowed(_sqrt2()), 1.5, 2.5) == 2   # 2 - x from sqrt 2
    tangent = flint.fmpq_poly([-1, 1]) ** 2 * flint.fmpq_poly([-3, 1]) * -1                 # (x-1)^2 (3-x)
    assert sign_change_near(tangent, F(0), 0.5, 1.5) is None
    assert sign_change_near(tangent, F(0), 2.5, 3.5) is None     # the tangency at 1 is before it: not proved here
    assert sign_change_near(tangent, F(3, 2), 2.5, 3.5) == 3 == next_sign_change(tangent, F(3, 2))
    assert sign_change_near(flint.fmpq_poly([2, 0, -1]), F(2), 1.0, 2.0) is None            # left of t
    assert sign_change_near(flint.fmpq_poly([2 * 10**400, 0, -(10**400)]), F(0), 1.0, 2.0) is not None
    assert sign_change_near(flint.fmpq_poly([2, 0, -1]), F(0), math.nan, 2.0) is None
    assert sign_change_near(flint.fmpq_poly([2, 0, -1]), F(0), 1.0, math.inf) is None


@settings(max_examples=60, deadline=None)
@given(st.lists(st.lists(st.integers(-5, 5), min_size=4, max_size=4), min_size=1, max_size=5),
       st.lists(st.integers(1, 9), min_size=5, max_size=5), st.integers(1, 6),
       st.fractions(min_value=-2, max_value=2, max_denominator=5),
       st.one_of(st.none(), st.fractions(min_value=F(1, 5), max_value=3, max_denominator=7)))
def test_interval_signs_on_integers_are_the_rationals(rows, dens, k, lo, width):
    """The integer form (an fmpz_mat, each row times a positive integer) gives the same signs as the rational
    rows: the transform runs on integers over one positive common denominator."""
    Mq = flint.fmpq_mat(len(rows), 4, [flint.fmpq(v, dens[j] * k) for r in rows for j, v in enumerate(r)])
    Mz = flint.fmpz_mat([[v * (math.lcm(*dens) * k // (dens[j] * k)) * (i + 1) for j, v in enumerate(r)]
                         for i, r in enumerate(rows)])
    hi = None if width is None else lo + width
    assert interval_signs(Mq, lo, hi) == interval_signs(Mz, lo, hi)
