"""exactinv_check.line_poles and .balanced_tie (issue 22): the kernel's own proofs for poles on Re z = p* and for
balanced ties of several poles -- genuine certificates accepted, forged ones rejected."""


import copy
from fractions import Fraction as F

import pytest
from radius_reference import from_partial_fractions, product

import exactinv as ei
from exactinv.monotonicity.radius import absolute_monotonicity_radius
from exactinv_check import check
from exactinv_check.bernstein import prove_completely_monotone
from exactinv_check.failure import CheckFailure
from exactinv_check.line_poles import disk_on_line, line_gcd, rational_root, single_pair

BOTH = product([1, -1], [1, -1, F(1, 2)])  # poles 1, 1 +- i


def _certificate(g, h):
    return absolute_monotonicity_radius(ei.methods.rational(g, h)).certificate


def _balanced():
    u = (F(3, 5), F(4, 5))
    terms = [((F(4), F(0)), (F(2), F(0))), ((F(-6), F(0)), (F(1), F(0))),
             ((F(2), F(4)), (u[0] / 2, u[1] / 2)), ((F(2), F(-4)), (u[0] / 2, -u[1] / 2))]
    return from_partial_fractions(terms)


# ------------------------------------------------------------------ soundness

def test_line_gcd_and_disks():
    G = line_gcd([F(2), F(-4), F(3), F(-1)], F(1))
    assert G == [0, -1, 0, 1]
    assert disk_on_line(G, (F(1), F(1), F(1, 100)), F(1))            # holds 1 + i
    assert not disk_on_line(G, (F(1), F(1, 2), F(1, 100)), F(1))     # no root of G in its chord
    assert not disk_on_line(G, (F(2), F(1), F(1, 100)), F(1))        # does not meet the line
    assert rational_root([F(-1), F(3)], F(0), F(1)) == F(1, 3)
    assert rational_root([F(-2), F(0), F(1)], F(1), F(2)) is None     # sqrt 2


def test_the_kernel_proves_the_issue_example_and_refuses_its_tipped_variant():
    assert "one pair on its line" in prove_completely_monotone([F(1)], BOTH)  # the closed form runs first
    with pytest.raises(CheckFailure, match="negative somewhere"):
        prove_completely_monotone([F(1), F(1, 4)], BOTH)
    assert single_pair([F(1)], product([1, -1], [1, F(-2, 3), F(1, 3)]), F(1)) == (F(3, 2), F(9, 16))


def test_a_line_pair_of_higher_multiplicity_than_p_star_is_refused():
    """(1 - z)(1 - z + z^2/2)^2: the pair's t e^(-t) terms outweigh p*'s e^(-t); rho = oo would be false."""
    with pytest.raises(CheckFailure):
        prove_completely_monotone([F(1)], product([1, -1], [1, -1, F(1, 2)], [1, -1, F(1, 2)]))


def test_a_pair_just_left_of_the_line_is_not_taken_for_on_it():
    """Poles 1 and 1 - 10^-30 +- i: the pair ties with p* at kappa near 10^30, so rho < oo; a bernstein claim
    (rho = oo) must be rejected (the line proof finds no root of gcd(U, V))."""
    a = 1 - F(1, 10 ** 30)
    h = product([1, -1], [a * a + 1, -2 * a, 1])
    h = [c / h[0] for c in h]
    with pytest.raises(CheckFailure):
        prove_completely_monotone([F(1)], h)
    cert = _certificate([F(1)], BOTH)
    cert["problem"]["method"]["denominator"] = [str(c) for c in h]
    assert not check(cert).ok


def test_the_balanced_tie_certificate_verifies_and_forgeries_are_rejected():
    g, h = _balanced()
    cert = _certificate(g, h)
    claim = cert["claims"][0]
    assert claim["reason"] == "balanced-tie" and claim["value"] == "1" and len(claim["poles"]) == 4
    assert check(cert).ok
    forged = copy.deepcopy(cert)
    forged["claims"][0]["poles"][2] = ["2", "5"]                       # not a root of h
    assert not check(forged).ok
    forged = copy.deepcopy(cert)
    forged["claims"][0]["poles"] = forged["claims"][0]["poles"][:3]     # one pole missing
    assert not check(forged).ok
    forged = copy.deepcopy(cert)
    forged["claims"][0]["value"] = "11/10"                             # not the tie
    assert not check(forged).ok
    forged = copy.deepcopy(cert)
    forged["version"] = 1                                              # 'poles' is a version-2 key
    assert not check(forged).ok


def test_outweighing_residues_cannot_be_passed_off_as_a_balanced_tie():
    """b_(-6) = 3/2: sum |b| = 5/2 > b_* = 2; the genuine rho is below 1, a balanced-tie claim of 1 is refused."""
    u = (F(3, 5), F(4, 5))
    terms = [((F(4), F(0)), (F(2), F(0))), ((F(-6), F(0)), (F(3, 2), F(0))),
             ((F(2), F(4)), (u[0] / 2, u[1] / 2)), ((F(2), F(-4)), (u[0] / 2, -u[1] / 2))]
    g2, h2 = from_partial_fractions(terms)
    g, h = _balanced()
    cert = _certificate(g, h)
    cert["problem"]["method"]["numerator"] = [str(c) for c in g2]
    cert["problem"]["method"]["denominator"] = [str(c) for c in h2]
    verdict = check(cert)
    assert not verdict.ok


# ------------------------------------------------------------------ resource
# No test here is about this module's work limits: the certificate's account is tested in test_budget.py.
