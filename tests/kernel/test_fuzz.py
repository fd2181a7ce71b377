"""Fuzz: random problems through the whole certify pipeline; the kernel must
accept every certificate the engine writes (0 rejections)."""


import random
from fractions import Fraction

import pytest
from test_certificate_schema import assert_valid

import exactinv as ei
from exactinv.certificates import certificate
from exactinv_check import check

pytestmark = pytest.mark.workload  # the kernel's own workload: left out at the lowest versions (.ci/run stage 3)


PROBLEMS = 300


def _method(rng):
    M = ei.methods
    choice = rng.randrange(9)
    if choice == 0:
        return M.taylor(rng.randint(1, 4))
    if choice == 1:
        return M.backward_euler()
    if choice == 2:
        return M.trapezoid()
    if choice == 3:
        return M.theta(Fraction(rng.randint(1, 4), 4))
    if choice == 4:
        return M.rk4()
    if choice == 5:
        return M.polynomial([1] + [Fraction(rng.randint(-1, 3), rng.randint(1, 3)) for _ in range(rng.randint(1, 3))])
    if choice == 6:  # a rational r with a positive real pole p: g / (1 - z/p)^k
        p = Fraction(rng.randint(1, 4), rng.randint(1, 2))
        k = rng.randint(1, 2)
        den = [1, -1 / p] if k == 1 else [1, -2 / p, 1 / p**2]
        num = [1] + [Fraction(rng.randint(-1, 2), rng.randint(1, 4)) for _ in range(rng.randint(0, k))]
        return M.rational(num, den)
    if choice == 7:
        return M.pade(rng.randint(0, 2), rng.randint(1, 2))
    return M.ssprk_s1(rng.randint(2, 3))


def _polyhedron(rng, n):
    kind = rng.randrange(4)
    if kind == 0:
        return ei.Polyhedron.box([-rng.randint(1, 2)] * n, [rng.randint(1, 2)] * n)
    if kind == 1:  # random vertices (a polytope)
        pts = [[rng.randint(-3, 3) for _ in range(n)] for _ in range(n + 2)]
        pts.append([0] * n)
        try:
            return ei.Polyhedron.from_vertices(pts)
        except ei.ExactinvError:
            return ei.Polyhedron.box([-1] * n, [1] * n)
    if kind == 2:  # a cone (orthant in other coordinates)
        return ei.Polyhedron([[-int(i == j) for j in range(n)] for i in range(n)], [0] * n)
    rows = [[rng.randint(-2, 2) for _ in range(n)] for _ in range(rng.randint(1, n + 2))]
    rows = [r for r in rows if any(r)] or [[1] + [0] * (n - 1)]
    return ei.Polyhedron(rows, [rng.randint(0, 3) for _ in rows])  # contains 0: never empty


def _system(rng, n):
    """Mostly systems that leave a set containing 0 invariant: A = -cI + (small perturbation)."""
    c = Fraction(rng.randint(1, 4), rng.randint(1, 2))
    scale = rng.choice([0, Fraction(1, 8), Fraction(1, 4), 1])
    return ei.LinearSystem([[(-c if i == j else 0) + scale * rng.randint(-2, 2) for j in range(n)] for i in range(n)])


def _results(S, P, m):
    g = ei.optimal_gamma(S, P)
    out = [g]
    if g.value == ei.INF:
        return out
    out.append(ei.forward_euler_threshold(S, P))
    out.append(ei.steplength_threshold(S, P, m))
    out.append(ei.largest_threshold(S, P, m))
    out.append(ei.valid_steplengths(S, P, m))
    return out


# ------------------------------------------------------------------ soundness

@pytest.mark.heavy
def test_the_kernel_accepts_every_certificate_the_engine_writes(capsys):
    rng = random.Random(7)
    written = undecided = 0
    kinds = {}
    rejected = []
    for k in range(PROBLEMS):
        n = rng.randint(1, 3)
        S = _system(rng, n)
        P = _polyhedron(rng, n)
        m = _method(rng)
        try:
            cert = certificate(S, P, m, _results(S, P, m))
        except ei.Undecided:
            undecided += 1
            continue
        written += 1
        assert_valid(cert, what=f"the certificate of fuzz problem {k}")  # every one matches the documented schema
        for c in cert["claims"]:
            kinds[c["type"]] = kinds.get(c["type"], 0) + 1
        report = check(cert)
        if not report.ok:
            rejected.append(f"problem {k}: A={S.A}, G={P.G}, b={P.b}, method={m.name}\n{report}")
    with capsys.disabled():
        print(f"\nkernel fuzz: {PROBLEMS} problems, {written} certificates written, {undecided} undecided, "
              f"{len(rejected)} rejected by the kernel; claims: {kinds}")
    assert not rejected, "\n\n".join(rejected[:5])
    assert written >= PROBLEMS * 3 // 4


# ------------------------------------------------------------------ resource
# No test here is about this module's work limits: the certificate's account is tested in test_budget.py.
