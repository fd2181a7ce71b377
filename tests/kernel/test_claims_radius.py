"""exactinv_check.claims_radius, attacked: the kernel's new radius reasons of issue 22 -- balanced ties of several simple poles
('poles' in Q(i)), complex poles on the line Re z = p* (bernstein: dominance, trigonometric density, one pair),
and the Fujiwara root bound.

Every forgery here is rejected; every genuine certificate is accepted, and its value is checked against the
slow exact reference (c_j(kappa) at rationals, tests/radius_reference.py) and against Pringsheim's bound
rho <= kappa_z (the first kappa at which a pole z is as close to -kappa as p*), computed exactly for poles in
Q(i).  The last test is a seeded mutation fuzzer over genuine engine certificates.
"""


import json
import random
from fractions import Fraction as F
from math import comb, factorial

import pytest
from kernel_deadline import check_within
from radius_reference import coefficients_at

from exactinv_check import check
from exactinv_check.bernstein import prove_completely_monotone
from exactinv_check.failure import CheckFailure

pytestmark = pytest.mark.workload  # the kernel's own workload: left out at the lowest versions (.ci/run stage 3)


def _cmul(x, y):
    return (x[0] * y[0] - x[1] * y[1], x[0] * y[1] + x[1] * y[0])


def _cpmul(p, q):
    out = [(F(0), F(0))] * (len(p) + len(q) - 1)
    for i, a in enumerate(p):
        for j, b in enumerate(q):
            v = _cmul(a, b)
            out[i + j] = (out[i + j][0] + v[0], out[i + j][1] + v[1])
    return out


def from_poles(poles, residues, constant=True):
    """(num, den) of r = c + sum_k b_k/(z_k - z) (simple poles z_k in Q(i), b_k = -a_k, conjugate-closed), the
    constant c chosen so that r(0) = 1 (constant=False: c = 0 and every b_k scaled by one factor s > 0 instead),
    scaled to den(0) = 1."""
    one = (F(1), F(0))
    den = [one]
    for z in poles:
        den = _cpmul(den, [(-z[0], -z[1]), one])
    num = [(F(0), F(0))] * len(den)
    for k in range(len(poles)):
        rest = [one]
        for l, w in enumerate(poles):
            if l != k:
                rest = _cpmul(rest, [(-w[0], -w[1]), one])
        for i, x in enumerate(rest):
            v = _cmul((-residues[k][0], -residues[k][1]), x)
            num[i] = (num[i][0] + v[0], num[i][1] + v[1])
    assert all(x[1] == 0 for x in den + num)
    den, num = [x[0] for x in den], [x[0] for x in num]
    if not constant:
        s = den[0] / num[0]
        assert s > 0
        return [x * s / den[0] for x in num], [x / den[0] for x in den]
    c = 1 - num[0] / den[0]
    num = [num[i] + c * den[i] for i in range(len(den))]
    while num[-1] == 0:
        num.pop()
    return [x / den[0] for x in num], [x / den[0] for x in den]


def _cert(num, den, claim):
    return {"format": "exactinv-certificate", "version": 2,
            "problem": {"method": {"name": "rt-radius", "numerator": [str(c) for c in num],
                                   "denominator": [str(c) for c in den]}},
            "claims": [{"type": "absolute_monotonicity_radius", **claim}]}


def verified(num, den, **claim):
    return check(json.loads(json.dumps(_cert(num, den, claim)))).ok


def tie_kappa(p, z):
    """The exact kappa at which z = (x, y) is as far from -kappa as the real pole p (x < p)."""
    return (z[0] ** 2 + z[1] ** 2 - p * p) / (2 * (p - z[0]))


def admissible(num, den, kappa, count):
    c = coefficients_at(num, den, kappa, count)
    return c is not None and min(c) >= 0


# A balanced tie of four simple poles at kappa* = 1: p* = 1, a = -3 ((|a| - p*)/2 = 1) and the pair
# 1/5 +- 8i/5 (|z|^2 = 13/5: (13/5 - 1)/(2 (1 - 1/5)) = 1); all three are at distance 2 from -1.
P_STAR, A, Z = (F(1), F(0)), (F(-3), F(0)), (F(1, 5), F(8, 5))


POLES = [P_STAR, A, Z, (Z[0], -Z[1])]


POLES_TEXT = [[str(x), str(y)] for x, y in POLES]


def four_pole_tie(beta_a, beta_z):
    return from_poles(POLES, [(F(1), F(0)), (beta_a, F(0)), beta_z, (beta_z[0], -beta_z[1])])


def _forged_lists():
    good = [list(z) for z in POLES_TEXT]
    yield "a pole dropped", good[:3]
    yield "a pole duplicated", good + [good[1]]
    yield "p* listed twice instead of a", [good[0], good[0], good[2], good[3]]
    yield "a conjugate missing (the pole twice)", [good[0], good[1], good[2], good[2]]
    yield "a conjugate with the wrong sign of Re", [good[0], good[1], good[2], ["-1/5", "-8/5"]]
    yield "a pole moved off the circle", [good[0], good[1], ["1/5", "81/50"], ["1/5", "-81/50"]]
    yield "a non-root", [good[0], ["-3000001/1000000", "0"], good[2], good[3]]
    yield "floats", [[1.0, "0"], good[1], good[2], good[3]]
    yield "not pairs", [["1"], good[1], good[2], good[3]]
    yield "too many", good * 5


def _rand(rng, lo, hi, dens=(1, 2, 3, 4, 5, 8)):
    d = rng.choice(dens)
    return F(rng.randint(int(lo * d), int(hi * d)), d)


def _tie_family(rng):
    """p* and poles tied with it at kappa* (a negative real pole, pairs on the circle |z + kappa*| = p* + kappa*,
    parametrised rationally), residues splitting a budget sum |b_T| in {1/2, 99/100, 1, 101/100} x b_*, and
    sometimes a real pole beyond p*; degree <= 6."""
    p, k = _rand(rng, F(1, 2), 2), _rand(rng, F(1, 4), 2)
    poles, res, weights = [(p, F(0))], [(F(1), F(0))], []
    if rng.random() < .7:
        poles.append((-(p + 2 * k), F(0)))
        weights.append(1)
    for _ in range(rng.choice([0, 1, 1, 2])):
        t, R0 = _rand(rng, -3, 3), p + k
        x, y = -k + R0 * (1 - t * t) / (1 + t * t), R0 * 2 * t / (1 + t * t)
        if y != 0 and x < p and (x, y) not in poles:
            poles += [(x, y), (x, -y)]
            weights.append(2)
    if not weights:
        return None
    budget = rng.choice([F(1, 2), F(99, 100), F(1), F(1), F(101, 100)])
    parts = [rng.randint(1, 9) for _ in weights]
    for w, part in zip(weights, parts):
        m = budget * F(part, sum(parts)) / w
        if w == 1:
            res.append((m * rng.choice([1, -1]), F(0)))
        else:
            u = rng.choice([(F(1), F(0)), (F(0), F(1)), (F(3, 5), F(4, 5)), (F(-4, 5), F(3, 5))])
            res += [(m * u[0], m * u[1]), (m * u[0], -m * u[1])]
    if rng.random() < .3:
        poles.append((p + _rand(rng, F(1, 4), 2), F(0)))
        res.append((_rand(rng, F(-1, 4), 1), F(0)))
    return poles, res, k


def _line_family(rng):
    """p* and one or two pairs on Re z = p* at rational heights, random residues."""
    p = _rand(rng, F(1, 2), 2)
    poles, res = [(p, F(0))], [(F(1), F(0))]
    for _ in range(rng.choice([1, 2])):
        y = _rand(rng, F(1, 2), 3)
        if (p, y) in poles:
            continue
        b = _rand(rng, 0, F(3, 4))
        u = rng.choice([(F(1), F(0)), (F(0), F(1)), (F(3, 5), F(4, 5))])
        poles += [(p, y), (p, -y)]
        res += [(b * u[0], b * u[1]), (b * u[0], -b * u[1])]
    return poles, res


def _refuted(num, den, claim, tie=None):
    """A sentence when the slow reference refutes a verified claim; None when it agrees as far as it sees."""
    if claim["value"] == "oo":
        for kappa in (F(1, 2), F(2), F(8), F(32)):
            if not admissible(num, den, kappa, 150):
                return f"rho = oo but some c_j({kappa}) < 0"
        return None
    kappa = F(claim["value"])
    if tie is not None and kappa > tie:
        return f"rho = {kappa} beyond the tie {tie} (Pringsheim)"
    if claim["attained"] and not admissible(num, den, kappa, 300):
        return f"attained, yet some c_j({kappa}) < 0"
    if kappa > 0 and not admissible(num, den, kappa * F(999, 1000), 300):
        return f"some c_j < 0 below rho = {kappa}"
    return None


# ------------------------------------------------------------------ soundness

def test_the_four_pole_tie_is_a_tie():
    assert tie_kappa(F(1), A) == tie_kappa(F(1), Z) == 1


@pytest.mark.parametrize("beta_a, beta_z", [(F(-1, 2), (F(1, 4), F(0))), (F(1, 2), (F(0), F(1, 4))),
                                            (F(-1, 4), (F(3, 20), F(4, 20)))])
def test_a_genuine_balanced_tie_is_verified_and_true(beta_a, beta_z):
    """sum of the tied |b_k| = 1 = b_* (exact square roots: |3/20 + 4i/20| = 1/4): rho = 1, attained.  The
    reference: c_j(1) >= 0 for j < 300 (the bound is tight: the sum equals b_*), some c_j(1 + 1/100) < 0."""
    num, den = four_pole_tie(beta_a, beta_z)
    assert verified(num, den, value="1", reason="balanced-tie", attained=True, poles=POLES_TEXT)
    assert admissible(num, den, F(1), 300)
    assert not admissible(num, den, F(101, 100), 300)
    assert not verified(num, den, value="1", reason="balanced-tie", attained=False, poles=POLES_TEXT)
    for value in ("101/100", "2", "oo", "99/100"):
        assert not verified(num, den, value=value, reason="balanced-tie", attained=True, poles=POLES_TEXT)


@pytest.mark.parametrize("beta_a, beta_z", [(F(-51, 100), (F(1, 4), F(0))), (F(1, 2), (F(1, 5), F(1, 5))),
                                            (F(-1, 2), (F(1, 4), F(1, 10**30)))])
def test_outweighed_residues_are_rejected_and_rho_is_below_the_tie(beta_a, beta_z):
    """sum |b_T| > b_* (by 1/100; by sqrt(2)/5 - 1/4; by about 10^-60 through an irrational modulus whose rational
    upper bound must not be rounded down): the kernel rejects rho = 1.  For the first two the reference shows
    the claim false (some c_j(1) < 0)."""
    num, den = four_pole_tie(beta_a, beta_z)
    assert not verified(num, den, value="1", reason="balanced-tie", attained=True, poles=POLES_TEXT)
    assert not verified(num, den, value="1", reason="balanced-tie", attained=False, poles=POLES_TEXT)
    if beta_z[1] < F(1, 1000):
        return
    assert not admissible(num, den, F(1), 400)


@pytest.mark.parametrize("what, poles", list(_forged_lists()))
def test_forged_pole_lists_are_rejected(what, poles):
    num, den = four_pole_tie(F(-1, 2), (F(1, 4), F(0)))
    assert not verified(num, den, value="1", reason="balanced-tie", attained=True, poles=poles), what


def test_the_pole_order_does_not_matter():
    num, den = four_pole_tie(F(-1, 2), (F(1, 4), F(0)))
    assert verified(num, den, value="1", reason="balanced-tie", attained=True, poles=POLES_TEXT[::-1])


def test_a_double_pole_cannot_pass_as_simple_poles():
    """h = (1 - z)^2 (1 + z/3): listing 1 twice is refused (not distinct), listing it once is refused (deg h)."""
    den = [F(1)]
    for f in ([F(1), F(-1)], [F(1), F(-1)], [F(1), F(1, 3)]):
        den = [sum(den[i] * f[k - i] for i in range(len(den)) if 0 <= k - i < len(f)) for k in range(len(den) + 1)]
    num = [F(1)]
    for poles in ([["1", "0"], ["1", "0"], ["-3", "0"]], [["1", "0"], ["-3", "0"]]):
        assert not verified(num, den, value="1", reason="balanced-tie", attained=True, poles=poles)


def test_an_untied_pole_left_of_p_star_is_refused():
    """A pole with Re z < p* that is not in the tie (a negative real pole farther out, reached later) and a
    complex pole right of p* are refused: the closed-form bound does not cover their terms."""
    poles = POLES + [(F(-7), F(0))]  # kappa = (7 - 1)/2 = 3 > 1
    num, den = from_poles(poles, [(F(1), F(0)), (F(-1, 4), F(0)), (F(1, 8), F(0)), (F(1, 8), F(0)), (F(1, 8), F(0))])
    text = [[str(x), str(y)] for x, y in poles]
    assert not verified(num, den, value="1", reason="balanced-tie", attained=True, poles=text)
    poles = POLES + [(F(2), F(1)), (F(2), F(-1))]
    num, den = from_poles(poles, [(F(1), F(0)), (F(-1, 4), F(0)), (F(1, 8), F(0)), (F(1, 8), F(0)),
                                  (F(1, 100), F(0)), (F(1, 100), F(0))])
    text = [[str(x), str(y)] for x, y in poles]
    assert not verified(num, den, value="1", reason="balanced-tie", attained=True, poles=text)


def test_a_cancelled_factor_is_no_pole():
    """r = g (1 + z/5) / (h (1 + z/5)): the method is reduced first, so a list naming -5 as a pole is refused,
    and the list of the reduced poles is accepted."""
    num, den = four_pole_tie(F(-1, 2), (F(1, 4), F(0)))
    f = [F(1), F(1, 5)]
    def mul(p):
        return [sum(p[i] * f[k - i] for i in range(len(p)) if 0 <= k - i < 2) for k in range(len(p) + 1)]

    num5, den5 = mul(num), mul(den)
    assert not verified(num5, den5, value="1", reason="balanced-tie", attained=True,
                        poles=POLES_TEXT + [["-5", "0"]])
    assert verified(num5, den5, value="1", reason="balanced-tie", attained=True, poles=POLES_TEXT)


def test_one_pair_on_the_line_decided_exactly():
    """p* = 1 and 1 +- 2i: f(t) = e^(-t) (b_* + 2 Re(b e^(-2it))), nonnegative iff b_* >= 2|b|.  b = 1/2 (touching
    0) is accepted; b = 1/2 + 10^-40 is refused, and (b_* < 2|b|) rho is finite: c_j(kappa) < 0 somewhere."""
    poles = [(F(1), F(0)), (F(1), F(2)), (F(1), F(-2))]
    ok = from_poles(poles, [(F(1), F(0)), (F(1, 2), F(0)), (F(1, 2), F(0))], constant=False)
    assert verified(*ok, value="oo", reason="bernstein", attained=True)
    eps = F(1, 10**40)
    bad = from_poles(poles, [(F(1), F(0)), (F(1, 2) + eps, F(0)), (F(1, 2) + eps, F(0))], constant=False)
    assert not verified(*bad, value="oo", reason="bernstein", attained=True)
    with pytest.raises(CheckFailure):
        prove_completely_monotone(*bad)
    bad = from_poles(poles, [(F(1), F(0)), (F(3, 5), F(0)), (F(3, 5), F(0))], constant=False)
    assert not verified(*bad, value="oo", reason="bernstein", attained=True)
    assert any(not admissible(*bad, F(k), 200) for k in (1, 4, 16, 64))


def test_a_pair_just_left_of_the_line_is_not_on_it():
    """1 - 10^-30 +- 2i: its tie with p* = 1 is at kappa_z = (|z|^2 - 1)/(2 10^-30), finite, so by Pringsheim rho
    <= kappa_z < oo; the kernel must not prove the pair on the line (an enclosure cannot tell)."""
    x = 1 - F(1, 10**30)
    poles = [(F(1), F(0)), (x, F(2)), (x, F(-2))]
    num, den = from_poles(poles, [(F(1), F(0)), (F(1, 8), F(0)), (F(1, 8), F(0))], constant=False)
    assert 0 < tie_kappa(F(1), poles[1]) < 10**31
    assert not verified(num, den, value="oo", reason="bernstein", attained=True)


def test_all_poles_on_the_line_density():
    """p* = 1 and 1 +- i, 1 +- 2i, residues 1, a, a, b, b (c = 0): f(t) = e^(-t) T(t) with
    T = 1 + 2a cos t + 2b cos 2t = 1 - b + 2a x + 4b x^2 (x = cos t).  a = b = 1/8: min 3/4 - 1/32 > 0;
    a = 1/8, b = 1/4: 1/2 - 1/64 > 0 (rho = oo, accepted); a = 1/8, b = 3/4: T(pi/2) = -1/2 < 0 (refused, and
    the reference finds a c_j(kappa) < 0)."""
    poles = [(F(1), F(0)), (F(1), F(1)), (F(1), F(-1)), (F(1), F(2)), (F(1), F(-2))]

    def r(a, b):
        return from_poles(poles, [(F(1), F(0)), (a, F(0)), (a, F(0)), (b, F(0)), (b, F(0))], constant=False)

    assert verified(*r(F(1, 8), F(1, 8)), value="oo", reason="bernstein", attained=True)
    assert verified(*r(F(1, 8), F(1, 4)), value="oo", reason="bernstein", attained=True)
    bad = r(F(1, 8), F(3, 4))
    assert not verified(*bad, value="oo", reason="bernstein", attained=True)
    assert any(not admissible(*bad, F(k), 300) for k in (2, 8, 32, 128))


def test_a_line_pole_of_higher_multiplicity_than_p_star_is_refused():
    """h = (1 - z)((z - 1)^2 + 1)^2: the double pair on Re z = 1 outgrows p* (t e^(-t) against e^(-t)), so f
    changes sign for some numerators; the kernel refuses dominance by p* whatever the numerator."""
    q = [F(2), F(-2), F(1)]  # (z - 1)^2 + 1
    den = [F(1), F(-1)]
    for f in (q, q):
        den = [sum(den[i] * f[k - i] for i in range(len(den)) if 0 <= k - i < len(f)) for k in range(len(den) + 2)]
    den = [c / den[0] for c in den]
    assert not verified([F(1)], den, value="oo", reason="bernstein", attained=True)


@pytest.mark.parametrize("num, den", [([F(1)], [F(1), F(1)]),            # pole at -1 only: rho = 0 (c_1(0) < 0)
                                      ([F(1), F(1)], [F(1), F(-1)]),     # (1 + z)/(1 - z): deg g = deg h
                                      ([F(1), F(-1, 2)], [F(1), F(-1)]),  # 1 - ... : b = 1/2 > 0, c = 1/2
                                      ([F(1), F(-2)], [F(1), F(-1)])])    # c = 2 > 0 but b = -1 < 0
def test_degree_one(num, den):
    """Degree 1: r = c + b/(1 - z).  rho = oo iff b >= 0 and c >= 0 (the reference: c_j(kappa) = b/(1 + kappa)^(j+1)
    for j >= 1 and c_0 = c + b/(1 + kappa)); every other combination of (value, reason) is refused."""
    b = num[0] + num[1] if len(num) > 1 else num[0]  # r = g/(1 - z): b = g(1)
    c = -num[1] if len(num) > 1 else F(0)
    truth_oo = b >= 0 and c >= 0 and den[1] < 0
    for reason in ("bernstein", "balanced-tie"):
        for poles in (None, [["1", "0"]], [["1", "0"], ["-1", "0"]]):
            claim = dict(value="oo", reason=reason, attained=True)
            if poles is not None:
                claim["poles"] = poles
            ok = verified(num, den, **claim)
            assert not ok or (reason == "bernstein" and poles is None and truth_oo)
    if truth_oo:
        assert verified(num, den, value="oo", reason="bernstein", attained=True)
        assert all(admissible(num, den, F(k), 50) for k in (0, 1, 100))


def test_a_verified_several_pole_tie_matches_the_schema():
    """The kernel verified the v2 key 'poles' but docs/certificate.schema.json did not list it (tests/conftest.py
    validates every verified certificate against the schema: this failed before the schema was fixed)."""
    num, den = four_pole_tie(F(-1, 2), (F(1, 4), F(0)))
    assert verified(num, den, value="1", reason="balanced-tie", attained=True, poles=POLES_TEXT)


def test_seeded_mutation_fuzzer():
    """Genuine claims for the two new families (a balanced tie at kappa*, rho = oo with poles on the line), each
    with mutants: residues nudged (the function changes, the claim stays), pole lists edited, value and attained
    flipped.  Every verified claim is checked against the slow reference; a refuted one is a false accept.
    (Run for minutes with a longer loop: 0 false accepts; see CHANGELOG.md, Security.)"""
    rng = random.Random(2026)
    stats = {"claims": 0, "verified": 0, "false": []}
    for _ in range(16):
        tie_case = rng.random() < .6
        built = _tie_family(rng) if tie_case else _line_family(rng)
        if built is None:
            continue
        poles, res = built[0], built[1]
        kappa = built[2] if tie_case else None
        variants = [(res, None)]
        for _ in range(2):  # nudged residues
            i = rng.randrange(len(res))
            nudge = F(rng.choice([1, -1]), rng.choice([100, 10**6]))
            new = list(res)
            new[i] = (res[i][0] + nudge, res[i][1])
            j = next((j for j, z in enumerate(poles) if z == (poles[i][0], -poles[i][1])), i)
            new[j] = (new[i][0], -new[i][1]) if j != i else new[i]
            variants.append((new, "nudged"))
        for rs, _how in variants:
            try:
                num, den = from_poles(poles, rs, constant=rng.random() < .5)
            except (AssertionError, ZeroDivisionError):
                continue
            text = [[str(x), str(y)] for x, y in poles]
            if tie_case:
                claims = [dict(value=str(kappa), reason="balanced-tie", attained=True, poles=text),
                          dict(value=str(kappa), reason="balanced-tie", attained=False, poles=text),
                          dict(value=str(kappa), reason="balanced-tie", attained=True, poles=text[:-1]),
                          dict(value=str(kappa), reason="balanced-tie", attained=True, poles=text + text[-1:]),
                          dict(value=str(kappa + F(1, 10**9)), reason="balanced-tie", attained=True, poles=text),
                          dict(value="oo", reason="bernstein", attained=True)]
            else:
                claims = [dict(value="oo", reason="bernstein", attained=True),
                          dict(value="oo", reason="bernstein", attained=False),
                          dict(value="oo", reason="balanced-tie", attained=True, poles=text)]
            for claim in claims:
                stats["claims"] += 1
                if not verified(num, den, **claim):
                    continue
                stats["verified"] += 1
                why = _refuted(num, den, claim, kappa)
                if why:
                    stats["false"].append((why, [str(c) for c in num], [str(c) for c in den], claim))
    print(stats["claims"], "claims,", stats["verified"], "verified,", len(stats["false"]), "refuted")
    assert stats["verified"] > 0
    assert not stats["false"], stats["false"][:3]


@pytest.mark.parametrize("binding", [0, 42, 44, 77, -1, 78, True, "43", 10 ** 9])
def test_the_binding_index_only_orders_the_work(binding):
    """Pade(1,3) (rho ~ 1.1955, binding d_43, tail index 78): the claim's binding index is handed to the recomputation
    as a hint (d_binding isolated first); any other index -- another d_j, out of range, not an integer -- is still
    rejected, and the genuine one accepted."""
    import exactinv as ei
    cert = ei.absolute_monotonicity_radius(ei.methods.pade(1, 3)).certificate
    assert check(cert).ok
    cert["claims"][-1]["binding"] = binding
    assert not check(cert).ok


def test_polynomials_of_high_degree_are_verified_and_their_radius_is_exact():
    """A polynomial has no series division: its d_j are shifts of g.  The up-front gate charged the division by
    deg g all the same and refused every one of these (4e10 to 6e10 estimated; each verifies in under a second):
    (1 + z/20)^25 (rho = 20, the shape of NodePy's SSPRK3(25)), (1 + z/64)^64 (rho = 64) and Taylor-64 (rho = 1).
    Each value is checked against the exact reference: every c_j >= 0 at rho, and some c_j < 0 just beyond."""
    import exactinv as ei

    for num, rho in (([F(comb(25, k), 20 ** k) for k in range(26)], 20),
                     ([F(comb(64, k), 64 ** k) for k in range(65)], 64),
                     ([F(1, factorial(k)) for k in range(65)], 1)):
        r = ei.absolute_monotonicity_radius(ei.methods.polynomial(num))
        assert r.value == rho
        assert check(r.certificate).ok
        assert min(coefficients_at(num, [F(1)], F(rho), len(num))) >= 0
        assert min(coefficients_at(num, [F(1)], F(rho) + F(1, 10**6), len(num))) < 0


# ------------------------------------------------------------------ resource
@pytest.mark.heavy
def test_a_polynomial_with_long_coefficients_gets_a_verdict_within_the_promise():
    """The gate lets a polynomial's shifts through, so a forged degree-64 numerator with 600-digit coefficients
    reaches the series: its products are charged as they run, and the verdict (over budget) comes well inside the
    60 s promise (about 18 s of CPU here)."""
    rng = random.Random(5)
    num = [F(1)] + [F(rng.randrange(10**599, 10**600), rng.randrange(10**599, 10**600)) for _ in range(64)]
    report = check_within(json.loads(json.dumps(_cert(num, [F(1)], dict(value="1", reason="coefficient",
                                                                        attained=True, binding=0)))), 55)
    assert not report.ok and "budget" in str(report), str(report)


def test_huge_pole_coordinates_get_a_quick_verdict():
    """15 simple poles whose coordinates have about 800 bits (p* = 1, a = -3 and 13 real poles above 1 with long
    denominators): the Q(i) products are priced; the verdict comes within seconds."""
    rng = random.Random(22)
    poles = [(F(1), F(0))] + [(1 + F(rng.getrandbits(400) | 1, 2 ** 400 + rng.getrandbits(390)), F(0))
                              for _ in range(13)]
    poles = [poles[0], (F(-3), F(0))] + poles[1:]
    num, den = from_poles(poles, [(F(1), F(0))] * len(poles))
    text = [[str(x), str(y)] for x, y in poles]
    report = check(json.loads(json.dumps(_cert(num, den, dict(value="1", reason="balanced-tie", attained=True,
                                                               poles=text)))))
    assert not report.ok  # the untied real poles have b_k = 1 > 0 but 1 + ... > p*: a tie with a (b_a = 1 <= b_*)


def test_poles_belong_to_the_balanced_tie_only():
    """A 'poles' list on another reason was ignored (accepted unread); the format is strict: refused.  Backward
    Euler, rho = oo by product, with a (true) 'poles' list attached."""
    num, den = [F(1)], [F(1), F(-1)]
    assert verified(num, den, value="oo", reason="product", attained=True)
    assert not verified(num, den, value="oo", reason="product", attained=True, poles=[["1", "0"], ["2", "0"]])
    assert not verified(num, den, value="oo", reason="bernstein", attained=True, poles=[["1", "0"], ["2", "0"]])


def test_large_numbers_in_messages_do_not_crash():
    """Messages were built with str() of exact numbers, eagerly (an f-string is evaluated before require is
    called): b_* = -g(p*)/h'(p*) for 2000-bit poles and deg g = 30 has over 4300 digits, and str() raised
    ValueError (Python's int -> str limit) -- even on the path where the check passes.  Now the numbers go
    through rationals.describe: a clear CheckFailure (the claim is false: the residues do not balance)."""
    from exactinv_check.balanced_tie import prove_balanced_tie
    from exactinv_check.tail import reduced
    rng = random.Random(5)
    p = 1 + F(1, rng.getrandbits(2000) | 1 << 1999)
    a = -(3 + F(1, rng.getrandbits(2000) | 1 << 1999))
    den = [p * a, -(p + a), F(1)]
    den = [c / den[0] for c in den]
    num = [F(1)] + [F(rng.getrandbits(8)) for _ in range(30)]
    g, h = reduced(num, den)
    with pytest.raises(CheckFailure, match="residues outweigh"):
        prove_balanced_tie(g, h, [[p, F(0)], [a, F(0)]])
    report = check(json.loads(json.dumps(_cert(num, den, dict(value="1", reason="balanced-tie", attained=True,
                                                               poles=[[str(p), "0"], [str(a), "0"]])))))
    assert not report.ok and "ValueError" not in str(report)


@pytest.mark.parametrize("q", [F(1999, 1000), F(1501, 1000), F(2001, 1000)])
def test_simple_rational_poles_with_a_long_exponent_polynomial(q):
    """Poles 1 and q = n/1000, residues 1 and -1/2 (c = 0 after scaling): f(t) = e^(-t) - e^(-q t)/2 > 0, rho = oo;
    the engine certifies 'bernstein'.  The kernel's shortcut F(u) = u^1000 - u^n/2 has degree n - 1000 > 200 for
    q = 1999/1000 and 1501/1000, and its degree check raised instead of leaving the pair to the general proof
    (q = 2001/1000 passed: its exponent was over MAX_EXPONENT, so the shortcut stepped aside): a genuine
    certificate was rejected.  The reference agrees that rho = oo."""
    num, den = from_poles([(F(1), F(0)), (q, F(0))], [(F(1), F(0)), (F(-1, 2), F(0))])
    assert verified(num, den, value="oo", reason="bernstein", attained=True)
    assert all(admissible(num, den, F(k), 100) for k in (0, 1, 10, 100))


@pytest.mark.parametrize("heights", [[F(60)], [F(64)], [F(63, 2)], [F(1), F(60)]])
def test_line_poles_at_large_heights(heights):
    """p* = 1 and pairs 1 +- iy, y up to 64, residues 1/8 each (c = 0): b_* = 1 > sum |b_k| = 1/4 per pair, so p*
    dominates and rho = oo; the engine certifies 'bernstein'.  The kernel's trigonometric density had degree
    2 max|n_k| = 120..128 with ~120-bit binomials and its Sturm count was over the certificate's budget: the
    genuine certificate was rejected.  Now the one-pair closed form comes first and an unaffordable density leaves
    the poles to the dominance proof.  Residues 1/2 + 10^-9 on one pair (b_*^2 < 4|b|^2) stay refused."""
    poles, res = [(F(1), F(0))], [(F(1), F(0))]
    for y in heights:
        poles += [(F(1), y), (F(1), -y)]
        res += [(F(1, 8), F(0)), (F(1, 8), F(0))]
    num, den = from_poles(poles, res, constant=False)
    assert verified(num, den, value="oo", reason="bernstein", attained=True)
    assert all(admissible(num, den, F(k), 100) for k in (0, 1, 10))
    if len(heights) == 1:
        eps = F(1, 10**9)
        num, den = from_poles(poles, [(F(1), F(0)), (F(1, 2) + eps, F(0)), (F(1, 2) + eps, F(0))], constant=False)
        assert not verified(num, den, value="oo", reason="bernstein", attained=True)
