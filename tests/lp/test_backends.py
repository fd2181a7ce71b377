"""The float-hint backends of the exact LP engine (exactinv/lp/hint.py).

The hint is never trusted: HiGHS (the default), any solver through cvxpy, or a
backend that lies all give the same exact results, and certificates the
kernel accepts."""

from __future__ import annotations

import importlib.util
import random
from fractions import Fraction

import flint
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import exactinv as ei
from exactinv.lp import ExactLPSolver, hint, hint_types
from exactinv.lp import solver as lp
from exactinv.lp.exact import ppl_maximize
from exactinv_check import check

needs_cvxpy = pytest.mark.skipif(importlib.util.find_spec("cvxpy") is None, reason="cvxpy (optional) is not installed")

BACKENDS = [
    pytest.param(("highs", {}), id="highs"),
    pytest.param(("cvxpy", {"solver": "HIGHS"}), id="cvxpy-highs", marks=needs_cvxpy),
    pytest.param(("cvxpy", {"solver": "CLARABEL"}), id="cvxpy-clarabel", marks=needs_cvxpy),
]


def _problems():
    rng = random.Random(7)
    out = [
        ("rotation box", ei.LinearSystem([[-1, 1], [-1, -1]]), ei.Polyhedron.box([-1, -1], [1, 1])),
        ("3-box", ei.LinearSystem([[-3, 1, Fraction(1, 2)], [0, -2, 1], [1, Fraction(-1, 3), -4]]),
         ei.Polyhedron.box([-1, -1, -1], [1, 1, 1])),
        ("octagon", ei.LinearSystem([[-1, Fraction(1, 2)], [Fraction(-1, 2), -1]]),
         ei.Polyhedron([[1, 0], [0, 1], [-1, 0], [0, -1], [1, 1], [1, -1], [-1, 1], [-1, -1]], [1, 1, 1, 1, 2, 2, 2, 2])),
        ("not invariant", ei.LinearSystem([[1, 0], [0, -1]]), ei.Polyhedron.box([-1, -1], [1, 1])),
    ]
    n, G = 4, []
    G += [[int(i == k) for k in range(n)] for i in range(n)] + [[-int(i == k) for k in range(n)] for i in range(n)]
    while len(G) < 14:
        row = [rng.randint(-5, 5) for _ in range(n)]
        if any(row):
            G.append(row)
    A = [[Fraction(rng.randint(-50, 50), 50 * 18 * n * n) - (Fraction(1, 2) if i == j else 0) for j in range(n)]
         for i in range(n)]
    out.append(("polytope", ei.LinearSystem(A), ei.Polyhedron(G, [1] * len(G))))
    return out


PROBLEMS = _problems()


def _gamma(S, P, backend):
    name, options = backend
    with ei.lp.hint_backend(name, **options):
        return ei.optimal_gamma(S, P)


@pytest.mark.parametrize("backend", BACKENDS)
@pytest.mark.parametrize("name,S,P", PROBLEMS, ids=[p[0] for p in PROBLEMS])
def test_gamma_is_the_same_with_every_backend(name, S, P, backend):
    ref = ei.optimal_gamma(S, P)
    g = _gamma(S, P, backend)
    assert g.value == ref.value
    assert (g.witness is None) == (ref.witness is None)
    assert check(g.certificate).ok  # where an LP has several optimal vertices, H may differ


def _strip(claims, *keys):
    return [{k: v for k, v in c.items() if k not in ("paths", *keys)} for c in claims]


@pytest.mark.parametrize("backend", BACKENDS)
def test_certificates_identical_where_the_optima_are_unique(backend):
    """Where every row LP has a unique optimal vertex and dual (the 3-box), the
    certificate is the same whichever solver gave the hint (up to the routes
    taken); on the rotation box the binding row's dual is not unique, the rest is."""
    _, S, P = PROBLEMS[1]
    assert _strip(_gamma(S, P, backend).claims()) == _strip(ei.optimal_gamma(S, P).claims())
    _, S, P = PROBLEMS[0]
    assert _strip(_gamma(S, P, backend).claims(), "dual") == _strip(ei.optimal_gamma(S, P).claims(), "dual")


@pytest.mark.parametrize("backend", BACKENDS)
@pytest.mark.parametrize("name,S,P", PROBLEMS, ids=[p[0] for p in PROBLEMS])
def test_discrete_invariance_is_the_same_with_every_backend(name, S, P, backend):
    method = ei.methods.taylor(2)
    for dt in (Fraction(1, 8), Fraction(1, 2), Fraction(3, 2)):
        ref = ei.discrete_invariance(S, P, method, dt)
        with ei.lp.hint_backend(backend[0], **backend[1]):
            d = ei.discrete_invariance(S, P, method, dt)
        assert d.holds == ref.holds
        assert check(d.certificate_json).ok
        if d.holds and name != "octagon":  # unique duals: the same H~, the same certificate
            assert d.certificate_json == ref.certificate_json


class _Liar(hint.HintBackend):
    """A backend whose every answer is wrong: random points and duals, a random
    basis, a false status, or a malformed answer."""

    name = "liar"

    def __init__(self, seed=0):
        self.rng = np.random.default_rng(seed)

    def model(self, A, equality):
        liar = self

        class Model(hint_types.HintModel):
            def solve(self, cost, rhs, nonneg):
                R, N = A.shape
                kind = liar.rng.integers(0, 6)
                if kind == 5:  # malformed: NaN, infinities, wrong lengths, out-of-range basis
                    if liar.rng.integers(0, 2):
                        return hint_types.Hint(hint_types.LPStatus.OPTIMAL, np.zeros(N), np.zeros(R), ((N + 3, -1), (R, R)))
                    return hint_types.Hint(hint_types.LPStatus.OPTIMAL, np.full(N, np.nan), np.full(R + 1, np.inf))
                if kind == 0:
                    return hint_types.Hint(hint_types.LPStatus.INFEASIBLE)
                if kind == 1:
                    return hint_types.Hint(hint_types.LPStatus.UNBOUNDED)
                if kind == 2:
                    return hint_types.Hint(hint_types.LPStatus.UNKNOWN)
                basis = None
                if kind == 3:
                    k = int(liar.rng.integers(0, min(R, N) + 1))
                    basis = (tuple(sorted(liar.rng.choice(N, k, replace=False).tolist())),
                             tuple(sorted(liar.rng.choice(R, k, replace=False).tolist())))
                return hint_types.Hint(hint_types.LPStatus.OPTIMAL, liar.rng.normal(size=N) * 3, liar.rng.normal(size=R), basis)

        return Model()


@pytest.mark.parametrize("seed", range(3))
@pytest.mark.parametrize("name,S,P", PROBLEMS, ids=[p[0] for p in PROBLEMS])
def test_a_lying_hint_still_ends_in_the_exact_answer(name, S, P, seed):
    ref = ei.optimal_gamma(S, P)
    with ei.lp.hint_backend(_Liar(seed)):
        g = ei.optimal_gamma(S, P)
        d = ei.discrete_invariance(S, P, ei.methods.taylor(2), Fraction(1, 2))
    assert g.value == ref.value and check(g.certificate).ok
    assert d.holds == ei.discrete_invariance(S, P, ei.methods.taylor(2), Fraction(1, 2)).holds
    assert check(d.certificate_json).ok


small = st.integers(-4, 4)


@needs_cvxpy
@settings(max_examples=40, deadline=None)
@given(st.integers(1, 4).flatmap(lambda n: st.tuples(
    st.lists(st.lists(small, min_size=n, max_size=n), min_size=1, max_size=5),
    st.lists(small, min_size=n, max_size=n),
    st.lists(st.booleans(), min_size=n, max_size=n),
)), st.data(), st.sampled_from(["cvxpy", "liar"]))
def test_random_lps_match_exact_ppl_with_other_backends(data, draw, backend):
    A, c, nonneg = data
    b = draw.draw(st.lists(small, min_size=len(A), max_size=len(A)))
    eq = draw.draw(st.lists(st.booleans(), min_size=len(A), max_size=len(A)))
    chosen = hint.CvxpyHint("CLARABEL") if backend == "cvxpy" else _Liar(len(A))
    res = lp.solve_lp(flint.fmpq_mat(A), eq, b, c, nonneg, hint=chosen)
    status, x = ppl_maximize(flint.fmpq_mat(A), eq, flint.fmpq_mat(len(b), 1, b), flint.fmpq_mat(len(c), 1, c), nonneg)
    assert res.status == status
    if status == "optimal":
        assert res.value == sum(ci * Fraction(int(xi.p), int(xi.q)) for ci, xi in zip(c, x.entries()))
        assert res.value == sum(ci * xi for ci, xi in zip(c, res.x)) == sum(bi * yi for bi, yi in zip(b, res.y))


@needs_cvxpy
def test_selection_global_context_and_per_solver():
    assert isinstance(ei.lp.get_hint_backend(), hint.HighsHint)
    with ei.lp.hint_backend("cvxpy", solver="CLARABEL") as chosen:
        assert ei.lp.get_hint_backend() is chosen and chosen.solver == "CLARABEL"
        assert ExactLPSolver(flint.fmpq_mat([[1]]), [False]).hint_backend is chosen
        assert isinstance(ExactLPSolver(flint.fmpq_mat([[1]]), [False], "highs").hint_backend, hint.HighsHint)
    assert isinstance(ei.lp.get_hint_backend(), hint.HighsHint)
    previous = ei.lp.set_hint_backend("cvxpy")
    try:
        assert isinstance(ei.lp.get_hint_backend(), hint.CvxpyHint)
        assert ei.optimal_gamma(*PROBLEMS[0][1:]).value == 1
    finally:
        ei.lp.set_hint_backend(previous)
    assert ei.lp.get_hint_backend() is previous
    with pytest.raises(ValueError, match="unknown hint backend"):
        ei.lp.set_hint_backend("gurobi-direct")


@needs_cvxpy
def test_a_cvxpy_hint_reaches_an_exact_vertex_without_a_basis():
    """An interior-point hint (no basis) on a degenerate LP: the engine guesses an
    active set from the float point and the exact answer follows from it, not from PPL."""
    _, S, P = PROBLEMS[0]
    g = _gamma(S, P, ("cvxpy", {"solver": "CLARABEL"}))
    assert "exact-ppl" not in g.paths
