"""exactinv_check.tail: the kernel's exact proof that the Taylor-coefficient tail c_j(kappa), j >= N, is positive.

Every claim prove_tail makes is re-checked here independently: c_j(kappa) = [w^j] g(w - kappa)/h(w - kappa) by
exact series division with Fractions, for j from N to well past it, at several rational kappa in [0, K].
"""


import ast
import random
import re
import sys
from fractions import Fraction as F
from pathlib import Path

import pytest
from radius_reference import coefficients_at

from exactinv_check import budget
from exactinv_check.failure import CheckFailure
from exactinv_check.tail import prove_tail


def P(*cs):
    return [F(c) for c in cs]


def pmul(p, q):
    out = [F(0)] * (len(p) + len(q) - 1)
    for i, a in enumerate(p):
        for j, b in enumerate(q):
            out[i + j] += a * b
    return out


def coefficients(g, h, kappa, n):
    """c_0(kappa) .. c_{n-1}(kappa), exactly (the slow reference of tests/radius_reference.py)."""
    return coefficients_at(g, h, kappa, n)


def timed(g, h, K, N_hint=0):
    """prove_tail, its charged work bounded (no clock: the charges are calibrated against CPU time by
    benchmarks/kernel_cost_model.py, RATE word operations per second, so this is about half a second)."""
    with budget.account(limit=10**12, time_limit=None) as acc:
        N = prove_tail(g, h, K, N_hint)
    assert 0 < acc.spent <= budget.RATE // 2, f"prove_tail charged {acc.spent:.3g} word operations"
    return N


def assert_tail_positive(g, h, K, N, extra=120):
    kappas = [F(0), F(1), F(10), F(1000)] if K is None else sorted({F(0), K / 3, K / 2, K})
    for kappa in kappas:
        c = coefficients(g, h, kappa, N + extra)
        bad = [j for j in range(N, N + extra) if not c[j] > 0]
        assert not bad, f"c_j({kappa}) <= 0 for j = {bad[:5]} although N = {N}"


# (name, g, h, K, largest acceptable N)
BACKWARD_EULER = (P(1), P(1, -1))


DOUBLE_POLE = (P(1), P(1, -1, F(1, 4)))  # 1/(1 - z/2)^2: b_1 = 0 exactly, b_2 = 4


TRAPEZOID = (P(1, F(1, 2)), P(1, F(-1, 2)))


THETA = (P(1, F(2, 3)), P(1, F(-1, 3)))


DOUBLE_WITH_ZERO = (P(1, F(1, 2)), pmul(P(1, F(-1, 4)), P(1, F(-1, 4))))  # 8/(z-4) + 48/(z-4)^2: b_1 = -8


PRODUCT = (P(1), pmul(pmul(P(1, F(-1, 2)), P(1, F(-1, 2))), P(1, F(-1, 3))))  # b_{2,1} = -12 but a product


FAR_PAIR = (P(1), pmul(P(1, -1), P(1, F(-4, 5), F(1, 5))))  # poles 1 and 2 +- i: Re > p*, always farther


LEFT_PAIR = (P(1), pmul(P(1, -1), P(1, F(2, 5), F(1, 5))))  # poles 1 and -1 +- 2i: farther only for kappa < 1


PAIR_DOUBLE_STAR = (P(1, F(1, 2)), pmul(pmul(P(1, -1), P(1, -1)), P(1, 0, F(1, 4))))  # 1 (mu=2), +-2i; kappa < 3/2


DOUBLE_PAIR = (P(1), pmul(P(1, -1), pmul(P(1, 0, F(1, 9)), P(1, 0, F(1, 9)))))  # 1, +-3i double; kappa < 4


CANCELLING = (pmul(P(1, 1), P(1, F(-1, 3))), pmul(P(1, -1), P(1, F(-1, 3))))  # (1+z)/(1-z) after cancellation


NUMERATOR_HIGHER = (P(1, 1, 1), P(1, F(-1, 2)))  # -2z - 6 + 7/(1 - z/2): c_j = 14 (2+kappa)^-(j+1), j >= 2


CLOSE_POLES = (P(1, F(1, 2)), pmul(P(1, -1), P(1, -1 / (1 + F(1, 10**9)))))  # poles 1, 1 + 10^-9; b_2 < 0


CLOSE_PAIRS = (P(1, F(1, 3)), pmul(P(1, -1), pmul(P(1, F(-1, 2), F(1, 8)), P(1, F(-1, 2) * (1 + F(1, 10**8)),
                                                                           F(1, 8) * (1 + F(1, 10**8))))))


PADE_13 = (P(1, F(1, 4)), P(1, F(-3, 4), F(1, 4), F(-1, 24)))  # complex pair ties with p* at kappa = 1.19582...


DEGREE_15 = (P(1, F(1, 3)), [F(1), F(-1)])


for _k in range(1, 8):  # pole 1 and seven complex pairs (2 + k) +- (k/2) i
    _n = F(2 + _k) ** 2 + F(_k, 2) ** 2
    DEGREE_15 = (DEGREE_15[0], pmul(DEGREE_15[1], [F(1), -2 * F(2 + _k) / _n, 1 / _n]))


POSITIVE = [
    ("backward Euler", *BACKWARD_EULER, None, 1),
    ("1/(1-z/2)^2", *DOUBLE_POLE, None, 1),
    ("trapezoid K=2", *TRAPEZOID, F(2), 1),
    ("trapezoid K=oo", *TRAPEZOID, None, 1),
    ("theta 1/3", *THETA, F(3, 2), 1),
    ("(1+z/2)/(1-z/4)^2 K=10", *DOUBLE_WITH_ZERO, F(10), 2),
    ("(1+z/2)/(1-z/4)^2 K=100", *DOUBLE_WITH_ZERO, F(100), 17),
    ("product", *PRODUCT, None, 0),
    ("(1+2z)/(1-z)", P(1, 2), P(1, -1), None, 1),
    ("far complex pair K=5", *FAR_PAIR, F(5), 60),
    ("far complex pair K=50", *FAR_PAIR, F(50), 2000),
    ("left complex pair K=1/2", *LEFT_PAIR, F(1, 2), 60),
    ("left complex pair K=9/10", *LEFT_PAIR, F(9, 10), 400),
    ("double p*, complex pair", *PAIR_DOUBLE_STAR, F(1), 60),
    ("double complex pair", *DOUBLE_PAIR, F(2), 60),
    ("cancelling factor", *CANCELLING, None, 1),
    ("deg g > deg h", *NUMERATOR_HIGHER, F(3), 2),
    ("deg g > deg h, K=oo", *NUMERATOR_HIGHER, None, 2),
    ("close real poles", *CLOSE_POLES, F(1, 10), 5),
    ("close complex poles", *CLOSE_PAIRS, F(1), 60),
    ("degree 15", *DEGREE_15, F(3), 100),
    ("Pade(0,3) K=1/2", P(1), P(1, -1, F(1, 2), F(-1, 6)), F(1, 2), 10),
    ("Pade(1,3) near the tie", *PADE_13, F(1195, 1000), 60),
]


NEGATIVE = [
    ("1/(1+z): no positive pole", P(1), P(1, 1), None, "no positive real pole"),
    ("1/(1+z) K=1", P(1), P(1, 1), F(1), "no positive real pole"),
    ("(1-2z)/(1-z): b < 0", P(1, -2), P(1, -1), F(1), "wrong sign"),
    ("1/(1-z+z^2/2): no real pole", P(1), P(1, -1, F(1, 2)), F(1), "no positive real pole"),
    ("Pade(1,2): complex poles", P(1, F(1, 3)), P(1, F(-2, 3), F(1, 6)), F(1), "no positive real pole"),
    ("(1-z)(1+z+z^2): tie at kappa=0", P(1), pmul(P(1, -1), P(1, 1, 1)), F(0), "does not dominate"),
    ("(1-z)(1+z+z^2) K=1", P(1), pmul(P(1, -1), P(1, 1, 1)), F(1), "does not dominate"),
    ("left pair, K at the tie", *LEFT_PAIR, F(1), "does not dominate"),
    ("Pade(1,3) beyond the tie 1.19582", *PADE_13, F(1196, 1000), "does not dominate"),
    ("left pair, K beyond the tie", *LEFT_PAIR, F(2), "does not dominate"),
    ("left pair K=oo", *LEFT_PAIR, None, "K = oo"),
    ("far pair K=oo", *FAR_PAIR, None, "K = oo"),
    ("(1+z/2)/(1-z/4)^2 K=oo", *DOUBLE_WITH_ZERO, None, "K = oo"),
    ("polynomial after cancellation", P(1, -1), P(1, -1), F(1), "polynomial"),
    ("h(0) < 0", P(-1), P(-1, 1), F(1), "h(0) > 0"),
    ("r(0) != 1", P(2), P(1, -1), F(1), "r(0)"),
    ("negative K", P(1), P(1, -1), F(-1), "K must be"),
    ("float K", P(1), P(1, -1), 0.5, "K must be"),
    ("float coefficient", [F(1), 0.5], P(1, -1), F(1), "exact rationals"),
]


# ------------------------------------------------------------------ soundness

@pytest.mark.parametrize("name,g,h,K,N_max", POSITIVE, ids=[c[0] for c in POSITIVE])
def test_proved_tails_are_positive(name, g, h, K, N_max):
    N = timed(g, h, K)
    assert isinstance(N, int) and 0 <= N <= N_max
    assert_tail_positive(g, h, K, N)


def test_index_is_sharp_for_a_double_pole():
    # c_j(kappa) = 8 (4+kappa)^-(j+2) (6(j+1) - (4+kappa)) > 0 iff j > (kappa-2)/6: at K = 10, c_1 < 0 < c_2
    g, h = DOUBLE_WITH_ZERO
    assert timed(g, h, F(10)) == 2
    assert coefficients(g, h, F(10), 3)[1] < 0


def test_hint_is_a_lower_bound_of_the_index():
    assert prove_tail(*TRAPEZOID, F(2), N_hint=7) == 7
    assert prove_tail(*BACKWARD_EULER, None, N_hint=5) == 5
    assert prove_tail(*FAR_PAIR, F(5), N_hint=3) >= prove_tail(*FAR_PAIR, F(5))
    g, h = FAR_PAIR
    N = prove_tail(g, h, F(5), N_hint=100)
    assert N == 100
    assert_tail_positive(g, h, F(5), N, extra=20)


def test_polynomial_part_only_delays_the_tail():
    g, h = NUMERATOR_HIGHER
    assert timed(g, h, None) == 2
    assert coefficients(g, h, F(1), 2)[1] < 0  # c_1(1) = -2 + 14/9


def test_random_methods_soundness():
    """Whatever prove_tail claims for random methods (real, complex and multiple poles) holds exactly."""
    rng = random.Random(20240601)
    proved = 0
    for _ in range(120):
        h = [F(1)]
        for _ in range(rng.randint(1, 3)):
            if rng.random() < 0.55:
                f = [F(1), -1 / F(rng.randint(1, 48), 8)]
            else:
                a, b = F(rng.randint(-24, 48), 8), F(rng.randint(1, 32), 8)
                f = [F(1), -2 * a / (a * a + b * b), 1 / (a * a + b * b)]
            for _ in range(rng.choice([1, 1, 1, 2])):
                h = pmul(h, f)
        g = [F(1)] + [F(rng.randint(-16, 16), 8) for _ in range(rng.randint(0, len(h)))]
        K = rng.choice([None, F(0), F(1, 2), F(1), F(3), F(10)])
        try:
            N = timed(g, h, K)
        except CheckFailure:
            continue
        proved += 1
        assert_tail_positive(g, h, K, N, extra=40)
    assert proved >= 25


def test_integer_K_is_accepted():
    assert prove_tail(*THETA, 1) == prove_tail(*THETA, F(1))


@pytest.mark.parametrize("name,g,h,K,reason", NEGATIVE, ids=[c[0] for c in NEGATIVE])
def test_unprovable_tails_are_rejected(name, g, h, K, reason):
    with budget.account(limit=10**12, time_limit=None) as acc, pytest.raises(CheckFailure, match=re.escape(reason)):
        prove_tail(g, h, K)
    assert acc.spent <= budget.RATE // 2  # charged work, not a clock (see timed)


def test_rejections_are_necessary():
    # 1/(1+z): c_j(0) = (-1)^j;  (1-2z)/(1-z): c_j(0) = -1 for j >= 1
    assert coefficients(P(1), P(1, 1), F(0), 6)[1::2] == [-1, -1, -1]
    assert all(c == -1 for c in coefficients(P(1, -2), P(1, -1), F(0), 10)[1:])
    # (1+z/2)/(1-z/4)^2: for every j, c_j(kappa) < 0 once kappa > 6j + 2, so no N works for K = oo
    assert coefficients(*DOUBLE_WITH_ZERO, F(6 * 30 + 3), 31)[30] < 0
    # left pair: beyond kappa = 1 the complex pair is nearer than p*, and c_j changes sign infinitely often
    c = coefficients(*LEFT_PAIR, F(2), 200)
    assert any(x < 0 for x in c[100:])


@pytest.mark.parametrize("module", ["tail.py", "disks.py"])
def test_kernel_imports_only_the_standard_library(module):
    source = Path(__file__).resolve().parents[2] / "exactinv_check" / module
    tree = ast.parse(source.read_text())
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for alias in node.names:
                assert alias.name.split(".")[0] in sys.stdlib_module_names, alias.name
        elif isinstance(node, ast.ImportFrom):
            if node.level == 0:
                assert node.module.split(".")[0] in sys.stdlib_module_names, node.module
            else:
                # reals: a type, under TYPE_CHECKING
                allowed = {"rationals", "failure", "poly_arithmetic", "polys", "tie", "disks", "reals", "format", "budget"}
                assert node.level == 1 and node.module in allowed, node.module


# ------------------------------------------------------------------ resource
# No test here is about this module's work limits: the certificate's account is tested in test_budget.py.
