"""alpha(H) only as far as erratum E2 needs it (issue 22, item 3): thresholds/spectral.py.

The route against the old one (the largest real root of H's dense characteristic
polynomial, always), the certified bounds as theorems, the eigenvalue argument on
random problems, and the E2 threshold on polygons and cones.
"""

from __future__ import annotations

import math
from fractions import Fraction

import flint
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from strategies import metzler_cones

import exactinv as ei
from exactinv import methods as M
from exactinv.core.algebraic import ExactKey
from exactinv.core.roots import real_roots
from exactinv.core.sparse import SparseRows
from exactinv.thresholds import rational
from exactinv.thresholds.spectral import (
    abscissa_is_nonpositive,
    collatz_wielandt_upper,
    components,
    perron_lower,
    spectral_abscissa,
)


def dense_abscissa(H):
    """The definition: the largest real root of the dense characteristic polynomial."""
    return real_roots(SparseRows.of(H).to_flint().charpoly())[-1][0]


@st.composite
def metzler(draw, size=st.integers(1, 7)):  # noqa: B008 (a hypothesis strategy: immutable)
    """A Metzler matrix, often reducible (sparse off-diagonal pattern)."""
    m = draw(size)
    entries = []
    for i in range(m):
        for j in range(m):
            if i == j:
                entries.append(Fraction(draw(st.integers(-6, 3)), draw(st.integers(1, 3))))
            else:
                entries.append(Fraction(draw(st.sampled_from([0, 0, 0, 1, 2, 3])), draw(st.integers(1, 3))))
    return flint.fmpq_mat(m, m, [flint.fmpq(x.numerator, x.denominator) for x in entries])


@given(metzler())
def test_spectral_abscissa_is_the_dense_definition(H):
    assert spectral_abscissa(H) == dense_abscissa(H)


@given(metzler(), st.lists(st.integers(1, 9), min_size=7, max_size=7), st.lists(st.integers(0, 9), min_size=7, max_size=7))
def test_collatz_wielandt_bounds_enclose_alpha(H, positive, nonnegative):
    m = H.nrows()
    alpha = dense_abscissa(H)
    v = [Fraction(x) for x in positive[:m]]
    assert not ExactKey(collatz_wielandt_upper(H, v)) < ExactKey(alpha)
    w = [Fraction(x) for x in nonnegative[:m]]
    lower = perron_lower(H, w)
    if any(w):
        assert lower is not None and not ExactKey(alpha) < ExactKey(lower)
    else:
        assert lower is None


def test_components_of_a_block_triangular_matrix():
    H = flint.fmpq_mat([[-1, 1, 0, 0], [1, -1, 0, 0], [1, 0, -3, 2], [0, 0, 1, -3]])
    assert components(H) == [[0, 1], [2, 3]]
    assert spectral_abscissa(H) == 0  # blocks: eigenvalues 0, -2 and -3 +- sqrt 2


@settings(max_examples=40, deadline=None)
@given(metzler_cones())
def test_nonpositive_abscissa_is_sound(problem):
    """Where A has no positive real eigenvalue and P is full-dimensional, every certificate H
    (here the gamma*-optimal one) has alpha(H) <= 0, by the dense definition."""
    S, P = problem
    g = ei.optimal_gamma(S, P)
    assume(g.H_flint is not None and g.H_flint.nrows() > 0)
    if abscissa_is_nonpositive(S.A_flint, P.dimension == P.n):
        assert dense_abscissa(g.H_flint) <= 0


def _old_route(monkeypatch):
    """Today's path before issue 22: alpha(H) from the dense charpoly, always computed."""
    monkeypatch.setattr(rational, "_e2_may_bind", lambda H, gamma, z_p, value, nonpositive: z_p is not None and H.m > 0)
    monkeypatch.setattr(rational, "spectral_abscissa", dense_abscissa)


def ellipse_polygon(N):
    pts, k = set(), 0
    while len(pts) < N:
        theta = -math.pi + 2 * math.pi * (k + 0.5) / N
        s = Fraction(math.tan(theta / 2)).limit_denominator(10**4)
        pts.add((2 * (1 - s * s) / (1 + s * s), 2 * s / (1 + s * s)))
        k += 1
    return ei.Polyhedron.from_vertices(sorted(pts))


RATIONAL = [M.backward_euler(), M.trapezoid(), M.theta("3/4"), M.pade(1, 2), M.radau_iia2()]
POLYGONS = [(ellipse_polygon(N), A) for N in (5, 12, 24, 40)
            for A in ([[-2, 0], [0, -2]], [[-1, "1/2"], ["-1/2", -1]])]
ORTHANT = ei.Polyhedron([[-1, 0], [0, -1]], [0, 0])


@pytest.mark.parametrize("k", range(len(POLYGONS)))
@pytest.mark.parametrize("method", [M.backward_euler(), M.trapezoid(), M.radau_iia2()], ids=lambda m: m.name)
def test_polygons_agree_with_the_dense_route(k, method, monkeypatch):
    P, A = POLYGONS[k]
    S = ei.LinearSystem(A)
    new = ei.steplength_threshold(S, P, method)
    assert ei.check(new.certificate).ok
    with monkeypatch.context() as patch:
        _old_route(patch)
        old = ei.steplength_threshold(S, P, method)
    assert (new.value, new.attained, new.theorem) == (old.value, old.attained, old.theorem)
    assert old.spectral_abscissa is None or old.spectral_abscissa <= 0  # a bounded invariant P: alpha(H) <= 0


@settings(max_examples=40, deadline=None)
@given(metzler_cones(), st.sampled_from(RATIONAL))
def test_cones_agree_with_the_dense_route(problem, method):
    """On cones E2 binds (alpha(H) > 0 for an unstable A): the value, the attained flag and the
    recorded alpha agree with the dense route, and the kernel re-proves the certificate."""
    S, P = problem
    new = ei.steplength_threshold(S, P, method)
    old_bind, old_alpha = rational._e2_may_bind, rational.spectral_abscissa
    try:
        rational._e2_may_bind = lambda H, gamma, z_p, value, nonpositive: z_p is not None and H.m > 0
        rational.spectral_abscissa = dense_abscissa
        old = ei.steplength_threshold(S, P, method)
    finally:
        rational._e2_may_bind, rational.spectral_abscissa = old_bind, old_alpha
    assert (new.value, new.attained, new.theorem) == (old.value, old.attained, old.theorem)
    if "erratum E2:" in new.theorem:
        assert new.spectral_abscissa == old.spectral_abscissa > 0
    assert ei.check(new.certificate).ok


def test_the_orthant_uses_the_eigenvalue_argument(monkeypatch):
    """b = 0, so Collatz-Wielandt takes v = 1: H = A = [[-1, 2], [1, -3]] gives H1 = (1, -2),
    no decision.  A's eigenvalues -2 +- sqrt 3 are negative and the orthant is full-dimensional,
    so alpha(H) <= 0 without any characteristic polynomial of H: tau = oo for backward Euler."""
    S = ei.LinearSystem([[-1, 2], [1, -3]])
    calls = []
    monkeypatch.setattr(rational, "spectral_abscissa", lambda H: calls.append(H) or dense_abscissa(H))
    t = ei.steplength_threshold(S, ORTHANT, M.backward_euler())
    assert calls == [] and t.value == ei.INF and t.attained and t.spectral_abscissa is None
    assert dense_abscissa(t.gamma.H_flint) < 0
    assert ei.discrete_invariance(S, ORTHANT, M.backward_euler(), 1000).holds
    assert ei.check(t.certificate).ok
