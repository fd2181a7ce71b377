"""The radius of absolute monotonicity of rational methods with poles (exactinv.monotonicity.tail):
Pringsheim's witness, the infinite-radius certificates, the tail argument, Undecided when nothing decides."""

import pytest
import sympy

import exactinv as ei
from exactinv import methods as M
from exactinv.monotonicity.radius import absolute_monotonicity_radius


def test_zero_radius_has_a_witness():
    r = absolute_monotonicity_radius(M.lobatto_iiic2())
    assert r.reason == "no-positive-pole" and r.witness_j is not None
    z = sympy.Symbol("z")
    series = sympy.series(1 / (1 - z + z**2 / 2), z, 0, r.witness_j + 1).removeO()
    assert series.coeff(z, r.witness_j) < 0


def test_infinite_radius_certificates():
    assert absolute_monotonicity_radius(M.backward_euler()).reason == "product"
    assert absolute_monotonicity_radius(M.rational([1], [1, "-3/2", "1/2"])).reason == "product"
    termwise = absolute_monotonicity_radius(M.rational([3, -1], [3, -6, 3]))  # (3 - z)/(3 (1 - z)^2)
    assert termwise.value == ei.INF and termwise.reason == "termwise"


def test_rational_with_tail_argument():
    r = absolute_monotonicity_radius(M.rational([1, "1/2"], [1, -1, "1/4"]))  # (1 + z/2)/(1 - z/2)^2
    assert r.value == 2 and r.tail_index is not None and r.pole == 2


def test_undecided_is_raised_not_guessed():
    # p* = 2 - sqrt 2 and the pair p* +- i on its line (once Undecided as "an implementation gap"; 1/h is now
    # rho = oo, tests/monotonicity/test_line_algebraic.py).  With f = (1 + cos t)((1 + sqrt 2) e^(-p* t) + (1 - sqrt 2) e^(-q t)),
    # q = 2 + sqrt 2, p*'s line part B touches 0 and the conjugate line's is negative, so neither the march nor the
    # line-by-line proof applies: Undecided naming the open problem, never a guess (docs/design.md)
    with pytest.raises(ei.Undecided, match="continuous positivity problem"):
        absolute_monotonicity_radius(M.rational(["1", "-61/28", "53/21", "-107/84", "2/7", "-1/42"],
                                                ["1", "-58/17", "157/34", "-64/17", "28/17", "-6/17", "1/34"]))
