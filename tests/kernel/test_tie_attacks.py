"""Attacks on the kernel's pruning check (exactinv_check/routes/pruning.py, claims_sets._pruned) and the
radius 'tie' reason (exactinv_check/tie.py, tail.prove_tail(tie=...), claims_radius 'tie' branch).

The HOLE sections documented holes (first as ``xfail(strict=True)``); they are fixed and the tests now guard the
fixes: a tie radius must be positive (a tie at kappa* <= 0 is refused, rho = 0 has its own reasons), the tie
polynomial and the d_j scan are priced against the kernel's work budget, the pruning horizon has at most 64-bit
numerator and denominator, and the engine certifies rho = 0 by a witness for both tie functions.  The other
tests are attacks the kernel resists, kept as regression guards.  Slow exact references (sympy Taylor
coefficients) decide the truth.
"""


import copy
import json
from fractions import Fraction
from math import factorial

import pytest
import sympy as sp
from test_kernel_attacks import _cert, _check_in_subprocess

from exactinv_check import check

pytestmark = pytest.mark.workload  # the kernel's own workload: left out at the lowest versions (.ci/run stage 3)


z = sp.symbols("z")


def _coefficients(expr, count, at=0):
    """Exact Taylor coefficients c_0 .. c_{count-1} of expr around z = at (the slow reference)."""
    s = sp.series(expr.subs(z, z + at), z, 0, count).removeO()
    return [sp.Rational(s.coeff(z, j)) for j in range(count)]


def _coeffs(p):
    return [str(c) for c in reversed(sp.Poly(sp.expand(p), z).all_coeffs())]


def _radius(num, den, **claim):
    return _cert([dict(type="absolute_monotonicity_radius", **claim)], method=(num, den))


def _accepted(cert):
    return check(json.loads(json.dumps(cert))).ok


NEG = (["1", "1/100", "4"], _coeffs((1 - z) * (1 + 4 * z**2)))


ZERO_G = sp.expand(1 + z**2 + z / 100 - 2 * z * (1 - z) * (1 + z**2))


ZERO = (_coeffs(ZERO_G), _coeffs((1 - z) * (1 + z**2)))


def _tie_dos_cert(digits=3, d=6):
    import random
    rng = random.Random(5)
    q = [1] + [rng.randint(10**(digits - 1), 10**digits) for _ in range(d - 1)]  # q(0) = 1, q(1) > 0
    h = [0] * (d + 1)
    for i, c in enumerate(q):  # h = (1 - z) q
        h[i] += c
        h[i + 1] -= c
    return _radius(["1"], [str(c) for c in h], value="1", reason="tie", attained=True)


def _horizon_dos_cert(degree=32, digits=3999):
    num = [str(Fraction(1, factorial(k))) for k in range(degree + 1)]
    claim = {"type": "largest_threshold", "value": "0", "attained": True, "vertices": [["-1"], ["1"]], "rays": [],
             "lines": [], "pruning": {"horizon": "1" + "0" * digits, "vertex": 0, "order": [0, 1]}}
    return _cert([claim], method=(num, ["1"]), A=[["-1"]], G=[["1"], ["-1"]], b=["1", "1"])


DIAMOND_PROBLEM = dict(A=[["-1", "1/4"], ["-1/4", "-1"]],
                       G=[["-7", "30"], ["-7", "-30"], ["-3", "-70"], ["-3", "70"], ["3", "-70"], ["7", "-30"],
                          ["7", "30"], ["3", "70"]], b=["70"] * 8)


DIAMOND_VERTICES = [["-10", "0"], ["-7", "-7/10"], ["-7", "7/10"], ["0", "-1"], ["0", "1"], ["7", "-7/10"],
                    ["7", "7/10"], ["10", "0"]]


TAYLOR2 = (["1", "1", "1/2"], ["1"])


VALID = {"type": "valid_steplengths",
         "intervals": [{"lo": "0", "hi": "0", "lo_closed": True, "hi_closed": True},
                       {"lo": "594/1019", "hi": "2194/1769", "lo_closed": True, "hi_closed": True}],
         "vertices": DIAMOND_VERTICES, "rays": [], "lines": [], "determinant": ["1"],
         "pruning": {"horizon": "1314003/1048576", "vertex": 0, "order": [1, 0, 3, 2, 4, 5, 7, 6]}}


def _valid(**changes):
    claim = copy.deepcopy(VALID)
    for key, value in changes.items():
        claim["pruning"][key] = value
    return _cert([claim], method=TAYLOR2, **DIAMOND_PROBLEM)


def _own_end(k):
    """Slow reference: the last end of vertex k's own valid set, by sympy roots of its conditions."""
    h = sp.symbols("h")
    A = sp.Matrix([[-1, sp.Rational(1, 4)], [sp.Rational(-1, 4), -1]])
    Ad = sp.eye(2) + h * A + h**2 * A * A / 2
    v = sp.Matrix([sp.Rational(x) for x in DIAMOND_VERTICES[k]])
    w = Ad * v
    conds = [70 - (sp.Rational(g[0]) * w[0] + sp.Rational(g[1]) * w[1]) for g in DIAMOND_PROBLEM["G"]]
    roots = sorted({r for c in conds for r in sp.Poly(c, h).real_roots() if r > 0}, key=float)
    probe = [(a + b) / 2 for a, b in zip([0] + roots, roots)] + [roots[-1] + 1]
    ok = [all(c.subs(h, x) >= 0 for c in conds) for x in probe]
    assert not ok[-1]
    return max(r for r, good in zip(roots, ok) if good) if any(ok) else 0


BOX_GAMMA = {"type": "gamma_star", "value": "1", "paths": {"float-rounded": 4},
             "H": [["-1", "1", "0", "0"], ["0", "-1", "1", "0"], ["0", "0", "-1", "1"], ["1", "0", "0", "-1"]],
             "binding_row": 0, "dual": {"y": ["0", "-1"], "lambda": "1"}}


PADE23 = (["1", "2/5", "1/20"], ["1", "-3/5", "3/20", "-1/60"])


PADE23_TIE = {"poly": ["-36", "0", "9", "2"], "interval": ["1703416266987/1000000000000", "425854066747/250000000000"]}


def _reason(cert):
    return str(check(json.loads(json.dumps(cert))))


# ------------------------------------------------------------------ soundness

def test_reference_the_negative_tie_function_has_rho_zero_not_attained():
    c = _coefficients((1 + z / 100 + 4 * z**2) / ((1 - z) * (1 + 4 * z**2)), 12)
    assert c[11] == Fraction(-719, 100) and all(x >= 0 for x in c[:11])
    assert _accepted(_radius(*NEG, value="0", reason="dominance-at-0", attained=False, witness_j=11))


def test_a_negative_tie_radius_is_rejected():
    assert not _accepted(_radius(*NEG, value="-3/8", reason="tie", attained=True))


def test_reference_the_zero_tie_function_fails_at_kappa_zero():
    c = _coefficients(ZERO_G / ((1 - z) * (1 + z**2)), 3)
    assert c[0] == 1 and c[1] == Fraction(-99, 100)  # kappa = 0 is inadmissible: rho = 0, not attained


def test_a_zero_tie_claimed_attained_is_rejected():
    assert not _accepted(_radius(*ZERO, value="0", reason="tie", attained=True))


def test_a_zero_tie_claim_is_refused_either_way():
    """The fix refuses ties at kappa* <= 0 (rho = 0 has its own reasons, with a witness c_j(0) < 0): the true
    statement rho = 0 not attained is certified by dominance-at-0 (test below), never by 'tie'."""
    assert not _accepted(_radius(*ZERO, value="0", reason="tie", attained=False))


def test_the_engine_reports_the_zero_tie_not_attained():
    import exactinv as ei
    res = ei.absolute_monotonicity_radius(ei.methods.rational(*ZERO))
    assert res.value == 0 and res.attained is False


def test_the_genuine_pruned_valid_set_verifies():
    assert _accepted(_valid())


def test_a_horizon_just_below_the_vertex_end_is_rejected():
    end = _own_end(0)
    assert Fraction(1314003, 1048576) >= end  # the genuine horizon is an upper bound
    below = sp.floor(end * 10**30) / sp.Integer(10**30)
    below = below - sp.Rational(1, 10**30) if below == end else below
    assert 0 < end - below <= sp.Rational(1, 10**30)
    for T in (below, Fraction(0), Fraction(594, 1019)):
        assert not _accepted(_valid(horizon=str(sp.Rational(T))))


@pytest.mark.parametrize("k", range(8))
def test_every_vertex_index_is_either_proved_or_rejected(k):
    """Any vertex may carry the record; it is accepted only if its own set ends by the horizon."""
    ok = _accepted(_valid(vertex=k))
    assert ok == (_own_end(k) <= Fraction(1314003, 1048576))


def test_malformed_pruning_records_are_rejected():
    for change in ({"vertex": 8}, {"vertex": -1}, {"vertex": True}, {"order": [0, 1, 2, 3, 4, 5, 6, 6]},
                   {"order": [0, 1, 2, 3, 4, 5, 6]}, {"order": [0, 1, 2, 3, 4, 5, 6, True]},
                   {"horizon": "-1"}, {"horizon": "oo"}, {"horizon": 1.5}):
        assert not _accepted(_valid(**change)), change
    cert = _valid()
    cert["claims"][0]["pruning"]["extra"] = 1
    assert not _accepted(cert)


def test_a_forged_interval_end_under_pruning_is_rejected():
    for hi in ("2194/1769", "2193/1769", "2195/1769"):
        claim = copy.deepcopy(VALID)
        claim["intervals"][1]["hi"] = hi
        ok = _accepted(_cert([claim], method=TAYLOR2, **DIAMOND_PROBLEM))
        assert ok == (hi == "2194/1769")


def test_pruning_on_a_rational_method_is_rejected():
    cert = _valid()
    cert["problem"]["method"] = {"name": "be", "numerator": ["1"], "denominator": ["1", "-1"]}
    assert not _accepted(cert)


def test_an_unbounded_polyhedron_needs_every_ray_pair():
    """P = {x >= 0} in 1-d (vertex 0, ray 1) under x' = -x: A_d(h) v = 0 for all h, so vertex 0's own set is
    [0, oo): no finite horizon is accepted; without pruning the set is where 1 - h + h^2/2 >= 0: all h."""
    claim = {"type": "valid_steplengths",
             "intervals": [{"lo": "0", "hi": "oo", "lo_closed": True, "hi_closed": False}],
             "vertices": [["0"]], "rays": [["1"]], "lines": [],
             "pruning": {"horizon": "1000", "vertex": 0, "order": [0]}}
    cert = _cert([claim], method=TAYLOR2, A=[["-1"]], G=[["-1"]], b=["0"])
    assert not _accepted(cert)
    del claim["pruning"]
    assert _accepted(cert)


def test_a_tie_one_ulp_off_is_rejected():
    """pade(2, 3) (docs: a genuine tie) with kappa* moved by 2^-200: not a root of the tie polynomial."""
    import exactinv as ei
    cert = copy.deepcopy(ei.absolute_monotonicity_radius(ei.methods.pade(2, 3)).certificate)
    claim = cert["claims"][0]
    assert claim["reason"] == "tie" and check(cert).ok
    from exactinv_check.reals import Real
    lo, hi = Real.parse(claim["value"], "rho").bounds()
    for v in (lo - Fraction(1, 2**200), hi + Fraction(1, 2**200)):
        claim["value"] = f"{v.numerator}/{v.denominator}"
        assert not check(json.loads(json.dumps(cert))).ok


def test_a_tie_whose_residues_outweigh_p_star_is_rejected():
    """Hole 1's denominator with g = 1: the pair's residues (2 |b| = 1/sqrt 5) outweigh p*'s (1/5)."""
    assert not _accepted(_radius(["1"], NEG[1], value="-3/8", reason="tie", attained=True))


def test_a_negative_rational_threshold_is_rejected():
    claims = [BOX_GAMMA, {"type": "absolute_monotonicity_radius", "value": "-3/8", "reason": "tie", "attained": True},
              {"type": "rational_threshold", "value": "-3/8", "attained": True, "rho": "-3/8", "pole": "1"}]
    cert = _cert(claims, method=NEG, A=[["-1", "1"], ["-1", "-1"]], G=[["1", "0"], ["0", "1"], ["-1", "0"], ["0", "-1"]],
                 b=["1"] * 4)
    assert not _accepted(cert)


def test_the_true_threshold_for_the_negative_tie_function_is_zero():
    claims = [BOX_GAMMA, {"type": "absolute_monotonicity_radius", "value": "0", "reason": "dominance-at-0",
                          "attained": False, "witness_j": 11},
              {"type": "rational_threshold", "value": "0", "attained": True, "rho": "0"}]
    cert = _cert(claims, method=NEG, A=[["-1", "1"], ["-1", "-1"]], G=[["1", "0"], ["0", "1"], ["-1", "0"], ["0", "-1"]],
                 b=["1"] * 4)
    assert _accepted(cert)


def test_the_genuine_pade23_tie_verifies():
    assert _accepted(_radius(*PADE23, value=PADE23_TIE, reason="tie", attained=True, tail_index=1))


def test_the_zero_tie_function_is_certified_rho_zero_not_attained_by_its_witness():
    """The correct certificate for hole 2's function: c_1(0) = -99/100 < 0 (reason dominance-at-0)."""
    assert _accepted(_radius(*ZERO, value="0", reason="dominance-at-0", attained=False, witness_j=1))
    assert not _accepted(_radius(*ZERO, value="0", reason="dominance-at-0", attained=True, witness_j=1))


def test_tie_claims_never_crash():
    """Odd tie values: a clean verdict, never an exception."""
    for value in ("-1", "-3/8", "0", "1/3", "10**5", {"poly": ["-2", "0", "1"], "interval": ["-2", "-1"]},
                  {"poly": ["-2", "0", "1"], "interval": ["1", "2"]}):
        for method in (NEG, ZERO, PADE23, (["1"], ["1", "-1"]), (["1", "1"], ["1"])):
            report = check(json.loads(json.dumps(_radius(*method, value=value, reason="tie", attained=True))))
            assert report.ok in (True, False)


def test_pruned_and_full_recomputations_agree_on_random_polygons():
    """Differential: random convex polygons (origin inside), random A, random polynomial methods; for every
    vertex k and the TIGHTEST horizon (vertex k's own end, rounded up), the kernel's pruned conditions give the
    same valid set and first interval as all pairs (1600 cases passed in a longer run; a few here)."""
    import math
    import random
    from types import SimpleNamespace

    from exactinv_check.conditions import condition_polynomials, method_matrices
    from exactinv_check.routes import pruning
    from exactinv_check.validset import first_end, valid_set

    def same(x, y):
        return len(x) == len(y) and all(a.lo.compare(b.lo) == 0 and a.hi.compare(b.hi) == 0 and a.lo_closed == b.lo_closed
                                        and a.hi_closed == b.hi_closed for a, b in zip(x, y))

    rng, cases = random.Random(7), 0
    while cases < 12:
        k = rng.randint(3, 6)
        angles = sorted(rng.random() * 2 * math.pi for _ in range(k))
        verts = [[Fraction(round(math.cos(a) * rng.randint(1, 8), 1)).limit_denominator(10),
                  Fraction(round(math.sin(a) * rng.randint(1, 8), 1)).limit_denominator(10)] for a in angles]
        G = [[q[1] - p[1], p[0] - q[0]] for p, q in zip(verts, verts[1:] + verts[:1])]
        b = [g[0] * p[0] + g[1] * p[1] for g, p in zip(G, verts)]
        if any(g == [0, 0] for g in G) or not all(
                g[0] * v[0] + g[1] * v[1] < beta for j, (g, beta) in enumerate(zip(G, b)) for v in verts
                if v not in (verts[j], verts[(j + 1) % k])):
            continue
        cases += 1
        A = [[Fraction(rng.randint(-6, 6), rng.randint(1, 4)) for _ in range(2)] for _ in range(2)]
        num = [Fraction(1)] + [Fraction(rng.randint(-6, 6), rng.randint(1, 4)) or Fraction(1) for _ in range(rng.randint(1, 4))]
        gens = SimpleNamespace(vertices=verts, rays=[], lines=[])
        D, ineq, eq = condition_polynomials(A, G, b, num, [Fraction(1)], gens)
        truth, tau = valid_set(D, list(ineq), list(eq)), first_end(D, ineq, eq)
        N = method_matrices(A, num, [Fraction(1)])[1]
        for vk in range(k):
            _, own, _ = condition_polynomials(A, G, b, num, [Fraction(1)],
                                              SimpleNamespace(vertices=[verts[vk]], rays=[], lines=[]))
            own_set = valid_set(D, list(own), [])
            for end, mode in ((own_set[-1].hi if own_set else None, "set"), (first_end(D, own, {})[0], "first")):
                if end is None or end.inf:
                    continue
                near = pruning.survivors(G, b, verts, N, end.bounds()[1])
                D2, i2, e2 = condition_polynomials(A, G, b, num, [Fraction(1)], gens,
                                                   lambda kind, i, G=G, vk=vk, near=near: range(len(G)) if i == vk else near[i])
                if mode == "set":
                    assert same(valid_set(D2, list(i2), list(e2)), truth)
                else:
                    t2 = first_end(D2, i2, e2)
                    assert t2[0].compare(tau[0]) == 0 and t2[1] == tau[1]


@pytest.mark.parametrize("method, witness", [(NEG, 11), (ZERO, 1)])
def test_the_engine_certifies_rho_zero_not_attained_for_both_tie_functions(method, witness):
    """Truth from the sympy reference: c_j(0) >= 0 below the witness and c_witness(0) < 0."""
    import exactinv as ei
    g, h = (sp.Add(*[sp.Rational(c) * z**k for k, c in enumerate(p)]) for p in method)
    c = _coefficients(g / h, witness + 1)
    assert c[witness] < 0 and all(x >= 0 for x in c[:witness])
    res = ei.absolute_monotonicity_radius(ei.methods.rational(*method))
    assert (res.value, res.attained, res.reason, res.witness_j) == (0, False, "dominance-at-0", witness)
    assert check(json.loads(json.dumps(res.certificate))).ok


def test_a_positive_tie_and_a_64_bit_horizon_still_verify():
    """The bounds are not too tight: a tail_index of 60 (the engine writes 1) and the pruned valid set with
    its horizon rewritten as an equal 64-bit fraction still verify."""
    assert _accepted(_radius(*PADE23, value=PADE23_TIE, reason="tie", attained=True, tail_index=60))
    assert _accepted(_valid(horizon=f"{1314003 * 2**43 + 1}/{2**63}"))  # 64 bits each (in lowest terms)
    assert not _accepted(_valid(horizon=f"{1314003 * 2**44 + 1}/{2**64}"))  # a 65-bit denominator


def test_a_late_witness_is_decided_exactly():
    """r = 1/(1 + z): c_j(0) = (-1)^j exactly, so index 4095 is a witness and 4094 is not."""
    for j, ok in ((4095, True), (4094, False), (1, True), (0, False)):
        assert _accepted(_radius(["1"], ["1", "1"], value="0", reason="no-positive-pole", attained=False,
                                 witness_j=j)) is ok


# ------------------------------------------------------------------ resource

def test_a_small_tie_claim_is_rejected_quickly():
    assert _check_in_subprocess(_tie_dos_cert(), 3) == "REJECTED"


def test_a_long_pruning_horizon_is_rejected_quickly():
    assert _check_in_subprocess(_horizon_dos_cert(), 3) == "REJECTED"


def test_the_largest_threshold_horizon_reused_for_the_valid_set_is_rejected():
    assert not _accepted(_valid(horizon="0"))  # vertex 0's FIRST interval ends at 0, its valid set later


def test_a_huge_tail_index_is_decided_quickly():
    cert = _radius(*PADE23, value=PADE23_TIE, reason="tie", attained=True, tail_index=4095)
    assert _check_in_subprocess(cert, 3) in ("OK", "REJECTED")  # a clean verdict either way, quickly


def test_the_dos_inputs_are_rejected_by_the_work_budget():
    # the claimed value "1" meets no pole's kappa_z enclosure: rejected before the tie polynomial is built;
    # and T itself is priced (before the price, the Sturm budget on T rejected only AFTER interpolating it:
    # d = 6 with a 60-digit q took 49 s), whatever value is claimed
    from exactinv_check.failure import CheckFailure
    from exactinv_check.tie import tie_polynomial
    assert "meets no pole's enclosure of kappa_z" in _reason(_tie_dos_cert())
    for digits, d in ((3, 6), (60, 6), (2, 7)):
        h = [Fraction(c) for c in _tie_dos_cert(digits, d)["problem"]["method"]["denominator"]]
        with pytest.raises(CheckFailure, match="over the kernel's work budget: the tie polynomial"):
            tie_polynomial(h)
    assert "over the kernel's work budget: the pruning horizon" in _reason(_horizon_dos_cert())
    huge = _radius(*PADE23, value=PADE23_TIE, reason="tie", attained=True, tail_index=4095)
    assert "over the kernel's work budget: the coefficient polynomials" in _reason(huge)


def test_a_late_witness_with_long_coefficients_is_rejected_by_the_budget():
    den = ["1", "-1/" + "7" * 300, "1/" + "3" * 300]
    cert = _radius(["1", "1/2", "1/3"], den, value="0", reason="dominance-at-0", attained=False, witness_j=4095)
    assert "over the kernel's work budget: the series coefficients" in _reason(cert)
