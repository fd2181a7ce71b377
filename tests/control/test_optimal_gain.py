"""optimal_gain (issue 25, part 1): min over F of gamma*(A + BF), one exact LP.

Checked against an independent float LP over (H, F, gamma) written here with
scipy's linprog (scipy comes with cvxpy in the test extra), against the closed
loop's own gamma* and forward-Euler step, against random rational gains, and
by the trusted kernel (including forged certificates and infeasibility).
"""

import copy
from fractions import Fraction

import flint
import numpy as np
import pytest
from hypothesis import assume, given
from hypothesis import strategies as st

import exactinv as ei

scipy_optimize = pytest.importorskip("scipy.optimize")

BOX2 = ei.Polyhedron.box([-1, -1], [1, 1])
SKEWED = ei.Polyhedron([[1, 0], [-1, 0], [1, 1], [-1, -1]], [1, 1, 1, 1])  # |x1| <= 1, |x1 + x2| <= 1
DOUBLE_INTEGRATOR = ([[0, 1], [0, 0]], [[0], [1]])


def float_gain_lp(A, B, G, b, E=None, e=None):
    """min gamma over (H, F, gamma, Lambda) in floats, written from the definitions
    (independent of exactinv.control.gain_lp): returns (status, gamma)."""
    A, B, G, b = (np.array(X, dtype=float) for X in (A, B, G, b))
    n, p, m = A.shape[0], B.shape[1], G.shape[0]
    q = 0 if E is None else len(E)
    E = np.zeros((0, p)) if E is None else np.array(E, dtype=float)
    e = np.zeros(0) if e is None else np.array(e, dtype=float)
    nH, nF, nL = m * m, p * n, q * m
    N = nH + nF + 1 + nL
    iH = lambda i, k: i * m + k  # noqa: E731
    iF = lambda k, c: nH + k * n + c  # noqa: E731
    ig = nH + nF
    iL = lambda j, k: ig + 1 + j * m + k  # noqa: E731
    Aeq, beq, Aub, bub = [], [], [], []
    GA, GB = G @ A, G @ B
    for i in range(m):
        for c in range(n):  # (H G - G B F)_{ic} = (G A)_{ic}
            row = np.zeros(N)
            for k in range(m):
                row[iH(i, k)] += G[k, c]
            for k in range(p):
                row[iF(k, c)] -= GB[i, k]
            Aeq.append(row), beq.append(GA[i, c])
        row = np.zeros(N)
        for k in range(m):
            row[iH(i, k)] = b[k]
        Aub.append(row), bub.append(0.0)
        row = np.zeros(N)
        row[iH(i, i)], row[ig] = -1, -1
        Aub.append(row), bub.append(0.0)
    for j in range(q):
        for c in range(n):
            row = np.zeros(N)
            for k in range(m):
                row[iL(j, k)] += G[k, c]
            for k in range(p):
                row[iF(k, c)] -= E[j, k]
            Aeq.append(row), beq.append(0.0)
        row = np.zeros(N)
        for k in range(m):
            row[iL(j, k)] = b[k]
        Aub.append(row), bub.append(e[j])
    bounds = [(0, None) if i != k else (None, None) for i in range(m) for k in range(m)]
    bounds += [(None, None)] * (nF + 1) + [(0, None)] * nL
    cost = np.zeros(N)
    cost[ig] = 1
    res = scipy_optimize.linprog(cost, A_ub=np.array(Aub), b_ub=bub, A_eq=np.array(Aeq), b_eq=beq, bounds=bounds,
                                 method="highs")
    return res.status, (res.fun if res.status == 0 else None)


def controllable(A, B):
    n = len(A)
    Aq, Bq = np.array(A, dtype=object), np.array(B, dtype=object)
    blocks, M = [], Bq
    for _ in range(n):
        blocks.append(M)
        M = Aq.dot(M)
    C = flint.fmpq_mat([[Fraction(v).numerator for v in row] for row in np.hstack(blocks).tolist()])
    return C.rank() == n


@st.composite
def gain_problems(draw, with_inputs):
    """Random controllable (A, B) with P a box or a polytope around 0 (often no gain exists:
    both engines must then say infeasible) and, if asked, an input box."""
    n = draw(st.integers(2, 3))
    p = draw(st.integers(1, 2)) if n == 3 else 1
    A = [[draw(st.integers(-3, 3)) for _ in range(n)] for _ in range(n)]
    B = [[draw(st.integers(-2, 2)) for _ in range(p)] for _ in range(n)]
    assume(controllable(A, B))
    if draw(st.booleans()):
        P = ei.Polyhedron.box([-draw(st.integers(1, 3)) for _ in range(n)], [draw(st.integers(1, 3)) for _ in range(n)])
    else:  # a polytope containing 0 in its interior: the box rows plus random cuts
        extra = [[draw(st.integers(-2, 2)) for _ in range(n)] for _ in range(draw(st.integers(1, 2)))]
        extra = [g for g in extra if any(g)]
        G = [[int(i == k) for k in range(n)] for i in range(n)] + [[-int(i == k) for k in range(n)] for i in range(n)]
        P = ei.Polyhedron(G + extra, [2] * (2 * n) + [draw(st.integers(1, 4)) for _ in extra])
    if with_inputs is None:
        with_inputs = draw(st.booleans())
    U = ei.Polyhedron.box([-draw(st.integers(1, 5)) for _ in range(p)], [draw(st.integers(1, 5)) for _ in range(p)]) \
        if with_inputs else None
    return A, B, P, U


@st.composite
def feasible_gain_problems(draw):
    """Controllable (A, B) for which some gain F0 keeps the box [-s, s]^n invariant, by construction:
    M = A + B F0 has M_ii + sum_{j != i} |M_ij| <= 0 (each facet's outward rate <= 0 at every vertex);
    the input box, if any, contains F0 P."""
    n = draw(st.integers(2, 3))
    p = draw(st.integers(1, 2)) if n == 3 else 1
    M = [[draw(st.integers(-2, 2)) if i != j else 0 for j in range(n)] for i in range(n)]
    for i in range(n):
        M[i][i] = -sum(abs(v) for v in M[i]) - draw(st.integers(0, 2))
    B = [[draw(st.integers(-2, 2)) for _ in range(p)] for _ in range(n)]
    F0 = [[draw(st.integers(-2, 2)) for _ in range(n)] for _ in range(p)]
    A = [[M[i][j] - sum(B[i][k] * F0[k][j] for k in range(p)) for j in range(n)] for i in range(n)]
    assume(controllable(A, B))
    s = draw(st.integers(1, 3))
    P = ei.Polyhedron.box([-s] * n, [s] * n)
    U = None
    if draw(st.booleans()):
        bound = [s * sum(abs(v) for v in F0[k]) + draw(st.integers(0, 2)) for k in range(p)]
        U = ei.Polyhedron.box([-max(u, 1) for u in bound], [max(u, 1) for u in bound])
    return A, B, P, U


def _check_against_float(A, B, P, U):
    g = ei.optimal_gain(A, B, P, inputs=U)
    status, value = float_gain_lp(A, B, P.G, P.b, U.G if U else None, U.b if U else None)
    if g.holds:
        assert status == 0
        assert abs(float(g.gamma) - value) <= 1e-6 * (1 + abs(value))
    else:
        assert status == 2  # infeasible
    assert ei.check(g.certificate).ok
    return g


@given(gain_problems(with_inputs=False))
def test_against_an_independent_float_lp(problem):
    _check_against_float(*problem)


@given(gain_problems(with_inputs=True))
def test_against_an_independent_float_lp_with_inputs(problem):
    _check_against_float(*problem)


@given(feasible_gain_problems(), st.data())
def test_closed_loop_gamma_and_forward_euler_and_no_random_gain_does_better(problem, data):
    A, B, P, U = problem
    g = ei.optimal_gain(A, B, P, inputs=U)
    assert g.holds  # F0 is admissible
    closed = g.optimal_gamma()
    assert closed.value == g.gamma  # the closed loop's own gamma* (its own verified LPs)
    fe = g.forward_euler_threshold()
    assert fe.value == g.forward_euler_step
    if g.gamma > 0:
        assert fe.value == 1 / g.gamma
    n, p = len(A), len(B[0])
    for _ in range(3):
        F = [[Fraction(data.draw(st.integers(-6, 6)), data.draw(st.integers(1, 3))) for _ in range(n)] for _ in range(p)]
        if U is not None:  # only admissible gains: F maps P into U (checked at the vertices)
            Fx = [[sum(F[k][c] * x[c] for c in range(n)) for k in range(p)] for x in P.vertices]
            if not all(u in U for u in Fx):
                continue
        other = ei.optimal_gamma(ei.LinearSystem.closed_loop(A, B, F), P).value
        assert not other < g.gamma  # INF (not invariant) or >= the optimum


def test_double_integrator_by_hand():
    """x1' = x2, x2' = u on P = {|x1| <= 1, |x1 + x2| <= 1}.  On the facet x1 = 1, x2 <= 0 whatever F.
    On x1 + x2 = 1 with u = f1 x1 + f2 x2: (x1 + x2)' = x2 + u; the LP's optimum is worked out
    independently by the float LP and must match the closed loop's own gamma*."""
    A, B = DOUBLE_INTEGRATOR
    U = ei.Polyhedron.box([-2], [2])
    g = ei.optimal_gain(A, B, SKEWED, inputs=U)
    assert g.holds and g.gamma == 1
    assert all(abs(sum(g.F[0][c] * x[c] for c in range(2))) <= 2 for x in SKEWED.vertices)  # |u| <= 2 on P
    # |u| <= 1 is too little: at the vertex (-1, 2) of the facet x1 + x2 = 1, x2 + u <= 0 needs u <= -2
    assert not ei.optimal_gain(A, B, SKEWED, inputs=ei.Polyhedron.box([-1], [1])).holds
    assert ei.optimal_gamma(g.system, SKEWED).value == g.gamma
    free = ei.optimal_gain(A, B, SKEWED)
    assert free.gamma <= g.gamma  # fewer constraints, no worse
    status, value = float_gain_lp(A, B, SKEWED.G, SKEWED.b, U.G, U.b)
    assert status == 0 and abs(value - float(g.gamma)) < 1e-9
    # the box [-1, 1]^2 is invariant for no gain: at (1, 1), x1' = x2 = 1 > 0
    assert not ei.optimal_gain(A, B, BOX2).holds


def test_infeasible_gain_has_a_kernel_checked_farkas_certificate():
    # x1' = x1 is not influenced by u: the facet x1 = 1 always leaves
    g = ei.optimal_gain([[1, 0], [0, 0]], [[0], [1]], BOX2)
    assert not g.holds and g.gamma == ei.INF and g.F is None and g.forward_euler_step == 0
    cert = g.certificate
    report = ei.check(cert)
    assert report.ok, str(report)
    with pytest.raises(ei.NotInvariant):
        _ = g.system
    # a controllable pair whose input limit is too tight (test_double_integrator_by_hand): |u| <= 1 on SKEWED
    A, B = DOUBLE_INTEGRATOR
    tight = ei.optimal_gain(A, B, SKEWED, inputs=ei.Polyhedron.box([-1], [1]))
    assert not tight.holds and ei.check(tight.certificate).ok
    assert tight.farkas["w"] and any(w > 0 for w in tight.farkas["w"])  # the input rows take part in the proof
    assert ei.optimal_gain(A, B, SKEWED, inputs=ei.Polyhedron.box([-2], [2])).holds


def _rejected(cert):
    return not ei.check(cert).ok


def test_forged_certificates_are_rejected():
    A, B = DOUBLE_INTEGRATOR
    g = ei.optimal_gain(A, B, SKEWED, inputs=ei.Polyhedron.box([-2], [2]))
    cert = g.certificate
    assert ei.check(cert).ok
    claim = cert["claims"][0]

    def forged(edit):
        c = copy.deepcopy(cert)
        edit(c["claims"][0])
        return c

    bump = lambda s: str(Fraction(s) + 1)  # noqa: E731
    assert _rejected(forged(lambda c: c["F"][0].__setitem__(0, bump(c["F"][0][0]))))      # perturbed F
    assert _rejected(forged(lambda c: c["H"][0].__setitem__(1, bump(c["H"][0][1]))))      # perturbed H
    assert _rejected(forged(lambda c: c["dual"]["Y"][0].__setitem__(0, bump(c["dual"]["Y"][0][0]))))  # dual
    assert _rejected(forged(lambda c: c["dual"]["w"].__setitem__(0, bump(c["dual"]["w"][0]))))
    assert _rejected(forged(lambda c: c.__setitem__("value", str(Fraction(claim["value"]) - Fraction(1, 2)))))
    assert _rejected(forged(lambda c: c.__setitem__("value", str(Fraction(claim["value"]) + Fraction(1, 2)))))
    assert _rejected(forged(lambda c: c.__setitem__("holds", False)))
    # the same F with a looser input set proved for a tighter one: the problem's inputs changed
    c = copy.deepcopy(cert)
    c["problem"]["inputs"]["e"] = ["1/2", "1/2"]
    assert _rejected(c)
    # Farkas vectors: the negated vector, the zero vector and a negative mu are no proof
    bad = ei.optimal_gain([[1, 0], [0, 0]], [[0], [1]], BOX2).certificate
    farkas = bad["claims"][0]["farkas"]
    for edit in (lambda f: f.update(Y=[[str(-Fraction(v)) for v in row] for row in f["Y"]]),
                 lambda f: f.update(Y=[["0"] * len(row) for row in f["Y"]], mu=["0"] * len(f["mu"])),
                 lambda f: f.update(mu=[str(-Fraction(v)) if Fraction(v) else "-1" for v in f["mu"]]),
                 lambda f: f.update(nu=["1"] + f["nu"][1:])):
        c = copy.deepcopy(bad)
        edit(c["claims"][0]["farkas"])
        assert c["claims"][0]["farkas"] != farkas and _rejected(c)
    c = copy.deepcopy(bad)
    c["problem"]["A"][0][0] = "-1"  # now a gain exists (x1' = -x1): the certificate proves nothing
    assert _rejected(c)


def test_the_closed_loop_results_delegate_to_the_engine():
    A, B = DOUBLE_INTEGRATOR
    g = ei.optimal_gain(A, B, SKEWED, inputs=ei.Polyhedron.box([-2], [2]))
    S = g.system
    assert S.A == ei.LinearSystem.closed_loop(A, B, g.F).A
    m = ei.methods.taylor(2)
    assert g.threshold(m).value == ei.steplength_threshold(S, SKEWED, m).value
    assert g.largest_threshold(m).value == ei.largest_threshold(S, SKEWED, m).value
    assert g.valid_steplengths(m).intervals == ei.valid_steplengths(S, SKEWED, m).intervals
    assert ei.check(g.largest_threshold(m).certificate).ok


def test_bad_input_names_the_argument():
    with pytest.raises(ei.ExactinvError, match="B"):
        ei.optimal_gain([[0, 1], [0, 0]], [[0, 1]], BOX2)
    with pytest.raises(ei.ExactinvError, match="inputs"):
        ei.optimal_gain([[0, 1], [0, 0]], [[0], [1]], BOX2, inputs=BOX2)
    with pytest.raises(ei.ExactinvError, match="polyhedron"):
        ei.optimal_gain([[0, 1], [0, 0]], [[0], [1]], ei.Polyhedron.box([-1], [1]))
    with pytest.raises(ei.ExactinvError, match="float"):
        ei.optimal_gain([[0.5, 1], [0, 0]], [[0], [1]], BOX2)
