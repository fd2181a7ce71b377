"""Balanced ties of several simple poles (exactinv/monotonicity/balanced_tie.py, issue 22): c_j(kappa) =
sum_k b_k (z_k + kappa)^-(j+1) decides the tie when the tied residues balance p*'s exactly; every certificate is
re-proved by the kernel and every radius checked against the slow exact reference (c_j at rationals)."""

from fractions import Fraction as F

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from radius_reference import admissible, coefficients_at, from_partial_fractions

import exactinv as ei
from exactinv.monotonicity.balanced_tie import balanced_tie, gaussian_poles
from exactinv.monotonicity.radius import absolute_monotonicity_radius
from exactinv_check import check

UNITS = [(F(3, 5), F(4, 5)), (F(-3, 5), F(4, 5)), (F(5, 13), F(12, 13)), (F(-8, 17), F(15, 17)), (F(0), F(1)),
         (F(-7, 25), F(24, 25)), (F(4, 5), F(3, 5))]  # points of the unit circle in Q(i), upper half plane


def _mul(x, y):
    return (x[0] * y[0] - x[1] * y[1], x[0] * y[1] + x[1] * y[0])


def _radius(g, h):
    r = absolute_monotonicity_radius(ei.methods.rational(g, h))
    verdict = check(r.certificate)
    assert verdict.ok, str(verdict)
    return r



def _beyond_fails(g, h, zs, kappa, count):
    """Past kappa* either a pole lies in [-kappa, 0] or some c_j(kappa) < 0 (j < count)."""
    if any(y == 0 and -kappa <= x <= 0 for x, y in zs):
        return True
    c = coefficients_at(g, h, kappa, count)
    return c is None or any(x < 0 for x in c)


def test_gaussian_poles_of_a_product():
    h = [F(20), F(-4), F(1)]  # z^2 - 4z + 20: 2 +- 4i
    assert sorted(gaussian_poles(h)) == [(F(2), F(-4)), (F(2), F(4))]
    assert gaussian_poles([F(3), F(0), F(1)]) is None      # +- i sqrt 3
    assert gaussian_poles([F(1), F(-2), F(1)]) is None     # a double pole


def test_four_poles_on_one_circle_with_balanced_residues():
    """Poles 4, -6, 2 +- 4i, all at distance 5 from -1: kappa* = 1 for each ((|z|^2 - 16)/(2(4 - Re z))).
    b_* = 2, b_(-6) = 1, b_(2 +- 4i) = (3 +- 4i)/10: sum |b| = 1 + 1/2 + 1/2 = 2 = b_*, so c_j >= 0 on [0, 1] for
    j > deg q and rho = 1 exactly; the reference finds c_j < 0 at kappa = 11/10."""
    u = UNITS[0]
    terms = [((F(4), F(0)), (F(2), F(0))), ((F(-6), F(0)), (F(1), F(0))),
             ((F(2), F(4)), (u[0] / 2, u[1] / 2)), ((F(2), F(-4)), (u[0] / 2, -u[1] / 2))]
    g, h = from_partial_fractions(terms)
    assert balanced_tie(g, h)[0] == 1
    r = _radius(g, h)
    assert r.value == 1 and r.reason == "balanced-tie" and r.attained
    assert admissible(g, h, F(1), 400)
    assert _beyond_fails(g, h, [z for z, _ in terms], F(11, 10), 400)


def test_outweighing_residues_are_not_a_balanced_tie():
    """The same poles with b_(-6) = 3/2: sum |b| = 5/2 > b_* = 2, so p* loses the tie and rho < 1 (the scan finds
    the coefficient that ends first)."""
    u = UNITS[0]
    terms = [((F(4), F(0)), (F(2), F(0))), ((F(-6), F(0)), (F(3, 2), F(0))),
             ((F(2), F(4)), (u[0] / 2, u[1] / 2)), ((F(2), F(-4)), (u[0] / 2, -u[1] / 2))]
    g, h = from_partial_fractions(terms)
    assert balanced_tie(g, h) is None
    r = _radius(g, h)
    assert r.value < 1 and r.reason == "coefficient"


@pytest.mark.heavy
@settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])
@given(R=st.integers(2, 9), kappa=st.fractions(min_value=F(1, 4), max_value=F(3, 2), max_denominator=4),
       shape=st.sampled_from(["pair", "negative+pair", "two pairs"]),
       units=st.lists(st.integers(0, len(UNITS) - 1), min_size=2, max_size=2, unique=True),
       phases=st.lists(st.integers(0, len(UNITS) - 1), min_size=2, max_size=2),
       split=st.fractions(min_value=F(1, 8), max_value=F(7, 8), max_denominator=8),
       b_star=st.fractions(min_value=F(1, 2), max_value=3, max_denominator=4),
       farther=st.booleans())
def test_random_three_and_four_pole_balanced_ties(R, kappa, shape, units, phases, split, b_star, farther):
    """p* = R - kappa* and tied poles w - kappa* with w on the circle |w| = R (Gaussian rational), residues whose
    moduli add up to b_* exactly (phases from the unit circle in Q(i)), optionally a farther positive real pole
    with b > 0: rho = kappa*, the kernel re-proves it, c_j(kappa*) >= 0 for j < 300 and past kappa* a pole or a
    negative c_j."""
    p = R - kappa
    if p <= 0:
        return
    terms = [((p, F(0)), (b_star, F(0)))]

    def pair(unit, phase, modulus):
        w = (R * UNITS[unit][0], R * UNITS[unit][1])
        b = (modulus * UNITS[phase][0], modulus * UNITS[phase][1])
        return [((w[0] - kappa, w[1]), b), ((w[0] - kappa, -w[1]), (b[0], -b[1]))]

    if shape == "pair":
        terms += pair(units[0], phases[0], b_star / 2)
    elif shape == "negative+pair":
        terms.append(((-R - kappa, F(0)), (b_star * split * (1 if phases[1] % 2 else -1), F(0))))
        terms += pair(units[0], phases[0], b_star * (1 - split) / 2)
    else:
        terms += pair(units[0], phases[0], b_star * split / 2) + pair(units[1], phases[1], b_star * (1 - split) / 2)
    if farther:
        terms.append(((p + 3, F(0)), (F(1, 3), F(0))))
    zs = [z for z, _ in terms]
    if len(set(zs)) != len(zs):
        return
    g, h = from_partial_fractions(terms)
    r = _radius(g, h)
    first = max(len(g) - len(h) + 1, 0)
    if r.reason != "balanced-tie":  # the polynomial part ends first: a coefficient c_j with j < first
        assert r.value < kappa and r.binding is not None and r.binding < max(first, 1)
        return
    assert r.value == kappa and r.attained
    assert admissible(g, h, kappa, 300)
    assert _beyond_fails(g, h, zs, 2 * kappa + 1, 600)
