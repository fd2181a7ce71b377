"""Red-team mutation fuzzer for the kernel's balanced line, reason bernstein-root and alpha(H) by blocks.

Not a test module (no test_ prefix): tests/kernel/test_linalg_attacks.py runs a small seeded slice of it;
``python tests/fuzz_radius3.py SECONDS [SEED]`` runs it for longer and prints the counts.

Genuine structures are built from poles and residues (radius_reference.from_partial_fractions): p* with
b_* > 0, pairs on Re z = p* whose line part B(t) >= 0 touches 0 (or nearly), real poles off the line with
positive residues, sometimes a pair off the line further right.  Each mutant changes ONE field by a small or a
tiny (10^-60) amount.  The oracle is independent of the kernel:
 * f >= 0: e^(p* t) f(t) = sum_k b_k e^(-(z_k - p*) t) evaluated in mpmath at 200 digits on a grid, at the zeros
   of B (t = (2n+1) pi / y for one pair) far out, and decided exactly where a mutation makes it decidable
   (a pole with Re z < p*, or b_q < 0 beside a touching B: f < 0 at B's zeros for large t);
 * rho: radius_reference.coefficients_at (exact c_j at rationals) just below and above the accepted value.
Every accept must be true; a false accept is printed with its structure and raised.
"""

import random
import sys
import time
from fractions import Fraction as F

import mpmath
from radius_reference import coefficients_at, from_partial_fractions

from exactinv_check import bernstein, budget
from exactinv_check.failure import CheckFailure

TINY = F(1, 10 ** 60)


def _rand_q(rng, lo, hi, den=8):
    d = rng.randint(1, den)
    return F(rng.randint(int(lo * d), int(hi * d)), d)


def structure(rng):
    """A genuine balanced-line structure: [((x, y), (u, v))] with conjugates listed both, and a description."""
    p = _rand_q(rng, F(1, 4), 4, 4) or F(1)
    if p <= 0:
        p = F(1, 2)
    b_star = _rand_q(rng, F(1, 4), 3, 4) or F(1)
    terms = [((p, F(0)), (b_star, F(0)))]
    kind = rng.choice(["pair", "pair", "heights"])
    if kind == "pair":
        y = _rand_q(rng, F(1, 4), 4, 4) or F(1)
        # b = |b| e^(i phi) with |b| = b_*/2: rational points on the circle (3/5, 4/5) etc.
        u, v = rng.choice([(F(1), F(0)), (F(3, 5), F(4, 5)), (F(-4, 5), F(3, 5)), (F(5, 13), F(-12, 13)),
                           (F(-1), F(0))])
        scale = b_star / 2 if rng.random() < 0.8 else b_star / 2 * F(rng.randint(1, 9), 10)
        terms += [((p, y), (u * scale, v * scale)), ((p, -y), (u * scale, -v * scale))]
    else:
        # B = b_* (1 - cos(n1 t)) (1 - cos(n2 t)) scaled: b at heights n1, n2, n1 + n2, |n1 - n2|
        n1, n2 = rng.sample([1, 2, 3], 2)
        s = rng.choice([F(1), F(1, 2), F(2, 3)])
        coeffs = {}
        # (1 - cos a)(1 - cos b) = 1 - cos a - cos b + (cos(a+b) + cos(a-b))/2; cos(n t) = (e^{int} + e^{-int})/2
        for n, c in ((n1, F(-1)), (n2, F(-1)), (n1 + n2, F(1, 2)), (abs(n1 - n2), F(1, 2))):
            coeffs[n] = coeffs.get(n, F(0)) + c
        const = F(1) + coeffs.pop(0, F(0))
        terms[0] = ((p, F(0)), (b_star * const, F(0)))
        for n, c in coeffs.items():
            if c:
                terms += [((p, s * n), (b_star * c / 2, F(0))), ((p, -s * n), (b_star * c / 2, F(0)))]
        if terms[0][1][0] <= 0:
            return structure(rng)
    for _ in range(rng.randint(1, 2)):  # real poles off the line, positive residues
        q = p + _rand_q(rng, F(1, 4), 3, 4)
        if q <= p or any(t[0] == (q, F(0)) for t in terms):
            continue
        terms.append(((q, F(0)), (_rand_q(rng, F(1, 8), 2, 8) or F(1), F(0))))
    if rng.random() < 0.3:  # a pair off the line beyond the slowest real pole
        qs = [t[0][0] for t in terms[1:] if t[0][1] == 0 and t[0][0] > p]
        if qs:
            x = max(qs) + _rand_q(rng, F(1, 4), 2, 4) + F(1, 4)
            y = _rand_q(rng, F(1, 4), 3, 4) or F(1)
            bu, bv = _rand_q(rng, -1, 1, 4), _rand_q(rng, -1, 1, 4)
            terms += [((x, y), (bu, bv)), ((x, -y), (bu, -bv))]
    return terms


MUTATIONS = ["b_star_down", "pair_b_up", "pair_b_rotate", "pair_re_down", "pair_re_up", "q_negative", "q_zero_ish",
             "q_residue_down", "add_slow_pair", "q_to_line", "pair_height", "b_star_up", "none"]


def mutate(rng, terms, which):
    t = [list(x) for x in terms]
    eps = TINY if rng.random() < 0.6 else F(1, 10 ** rng.randint(3, 20))
    p = t[0][0][0]
    line = [i for i, x in enumerate(t) if x[0][0] == p and x[0][1] > 0]
    off = [i for i, x in enumerate(t) if x[0][1] == 0 and x[0][0] > p]

    def conj(i):
        z, b = t[i]
        j = next(k for k, x in enumerate(t) if x[0] == (z[0], -z[1]) and k != i)
        return j

    def set_pair(i, z, b):
        j = conj(i)
        t[i] = [z, b]
        t[j] = [(z[0], -z[1]), (b[0], -b[1])]

    if which == "b_star_down":
        t[0] = [t[0][0], (t[0][1][0] - eps, F(0))]
    elif which == "b_star_up":
        t[0] = [t[0][0], (t[0][1][0] + eps, F(0))]
    elif which == "pair_b_up" and line:
        i = rng.choice(line)
        z, b = t[i]
        set_pair(i, z, (b[0] + eps * (1 if b[0] >= 0 else -1), b[1]))
    elif which == "pair_b_rotate" and line:
        i = rng.choice(line)
        z, b = t[i]
        set_pair(i, z, (b[0], b[1] + eps))
    elif which == "pair_re_down" and line:
        i = rng.choice(line)
        z, b = t[i]
        set_pair(i, (z[0] - eps, z[1]), b)
    elif which == "pair_re_up" and line:
        i = rng.choice(line)
        z, b = t[i]
        set_pair(i, (z[0] + eps, z[1]), b)
    elif which == "q_negative" and off:
        i = min(off, key=lambda k: t[k][0][0])
        t[i] = [t[i][0], (-eps, F(0))]
    elif which == "q_zero_ish" and off:
        i = rng.choice(off)
        t[i] = [t[i][0], (eps, F(0))]
    elif which == "q_residue_down" and off:
        i = min(off, key=lambda k: t[k][0][0])
        t[i] = [t[i][0], (-t[i][1][0], F(0))]
    elif which == "add_slow_pair" and off:
        q = min(t[k][0][0] for k in off)
        x = p + (q - p) * rng.choice([F(1, 2), 1 - eps, F(1) + eps])
        y = F(rng.randint(1, 8), 4)
        b = (F(rng.randint(-4, 4), 8), F(rng.randint(-4, 4), 8))
        t += [[(x, y), b], [(x, -y), (b[0], -b[1])]]
    elif which == "q_to_line" and off:
        i = rng.choice(off)
        t[i] = [(p + eps, F(0)), t[i][1]]
    elif which == "pair_height" and line:
        i = rng.choice(line)
        z, b = t[i]
        set_pair(i, (z[0], z[1] + eps), b)
    else:
        which = "none"
    zs = [x[0] for x in t]
    if len(set(zs)) != len(zs):
        return None, which
    return [(tuple(x[0]), tuple(x[1])) for x in t], which


def _mp(q):
    return mpmath.mpf(q.numerator) / q.denominator


def density_negative_somewhere(terms):
    """An independent verdict on f >= 0 for f(t) = sum b_k e^(-z_k t) (simple poles): True if f < 0 is found
    (exactly decided cases, or mpmath at 200 digits), False if nothing negative is found."""
    p = min(z[0] for z, _ in terms if z[1] == 0 and z[0] > 0) if any(z[1] == 0 for z, _ in terms) else None
    lead = min(z[0] for z, _ in terms)
    if lead < p:  # a pair (or pole) strictly left of p*: e^(lead t) f is dominated by an oscillating/neg term
        slow = [(z, b) for z, b in terms if z[0] == lead]
        if all(z[1] != 0 for z, _ in slow) and any(b != (0, 0) for _, b in slow):
            return True
    with mpmath.workdps(200):
        def ef(t):  # e^(p t) f(t)
            s = mpmath.mpf(0)
            for z, b in terms:
                w = mpmath.mpc(_mp(b[0]), _mp(b[1])) * mpmath.exp(-mpmath.mpc(_mp(z[0] - p), _mp(z[1])) * t)
                s += w
            return s.real
        grid = [mpmath.mpf(k) / 16 for k in range(1, 16 * 40)]
        ys = sorted({abs(z[1]) for z, _ in terms if z[0] == p and z[1] != 0})
        far = []
        ks = list(range(0, 60)) + [10 ** k for k in range(2, 7)] + [3 * 10 ** k + 1 for k in range(2, 6)]
        for y in ys:  # zeros of 1 + cos(yt) (odd multiples of pi) and of 1 - cos(yt) (even multiples)
            for n in ks:
                for frac in (1, 2):
                    far.append(((2 * n + frac) * mpmath.pi) / _mp(y))
        for t in grid + far:
            if ef(t) < -mpmath.mpf(10) ** -180:
                return True
    return False


def check_density(terms, stats, limit=budget.CERTIFICATE_BUDGET):
    """The kernel's proof of f >= 0 inside an account of ``limit`` word operations and no clock (deterministic:
    a mutant the budget stops is counted rejected); an accept is checked by density_negative_somewhere."""
    g, h = from_partial_fractions(terms)
    if len(h) - 1 > 16:
        return
    try:
        with budget.account(limit=limit, time_limit=None):
            c, how = bernstein.prove_density_nonnegative(g, h)
    except CheckFailure:
        stats["rejected"] += 1
        return
    stats["accepted"] += 1
    if density_negative_somewhere(terms):
        raise AssertionError(f"FALSE ACCEPT: f < 0 somewhere but the kernel proved f >= 0: {terms!r} ({how})")
    stats["verified"] += 1


def _certificate(g, h, value, reason, attained=True):
    method = {"name": "fuzz", "numerator": [str(c) for c in g], "denominator": [str(c) for c in h]}
    claim = {"type": "absolute_monotonicity_radius", "value": value, "attained": attained, "reason": reason}
    return {"format": "exactinv-certificate", "version": 3, "problem": {"method": method}, "claims": [claim]}


def check_claims(terms, stats):
    """Radius claims on the structure, judged by the whole kernel (check): the one genuine claim (bernstein when
    c >= 0, bernstein-root with the root of g(-kappa) when c < 0) and its mutants (a rational 10^-60 off the
    root, another root, oo for a finite rho, the other reason, attained false).  Every accept is checked against
    the exact c_j of radius_reference at the ends of the accepted value's enclosure."""
    from exactinv_check import check
    g, h = from_partial_fractions(terms)
    if len(h) - 1 > 16:
        return
    gm = [x * (-1) ** k for k, x in enumerate(g)]
    with mpmath.workdps(80):
        roots = sorted(mpmath.re(r) for r in mpmath.polyroots([_mp(x) for x in reversed(gm)], maxsteps=200,
                                                             extraprec=200)
                       if abs(mpmath.im(r)) < mpmath.mpf(10) ** -40 and mpmath.re(r) > 0)
        roots = [F(int(mpmath.floor(x * 10 ** 70)), 10 ** 70) for x in roots]  # at 80 digits
    claims = [("oo", "bernstein", True), ("oo", "bernstein-root", True), ("oo", "bernstein", False)]
    for q in roots:
        for v in (q, q + TINY, q - TINY):
            claims.append((str(v), "bernstein-root", True))
            claims.append((str(v), "bernstein", True))
        exact = {"poly": [str(c) for c in gm], "interval": [str(q - F(1, 10 ** 40)), str(q + F(1, 10 ** 40))]}
        claims += [(exact, "bernstein-root", True), (exact, "bernstein-root", False), (exact, "coefficient", True)]
    for value, reason, attained in claims:
        report = check(_certificate(g, h, value, reason, attained))
        stats["claims"] = stats.get("claims", 0) + 1
        if not report.ok:
            continue
        stats["claims_accepted"] = stats.get("claims_accepted", 0) + 1
        if isinstance(value, dict):
            stats["roots_accepted"] = stats.get("roots_accepted", 0) + 1
        if value == "oo":  # rho = oo: c_j >= 0 at several kappa, and f >= 0 (the density oracle)
            bad = density_negative_somewhere(terms) or not all(
                all(x >= 0 for x in coefficients_at(g, h, k, 40)) for k in (F(0), F(1), F(10), F(1000)))
        elif isinstance(value, dict):  # the algebraic root accepted: c_j >= 0 at its lower end, c_0 < 0 above it
            lo, hi = (F(x) for x in value["interval"])
            below, above = coefficients_at(g, h, lo, 40), coefficients_at(g, h, hi, 1)
            bad = (below is None or any(x < 0 for x in below) or above is None or above[0] >= 0 or not attained
                   or density_negative_somewhere(terms))
        else:  # a rational rho accepted: it must be the exact root, c_0 = 0 there, c_j >= 0
            cs = coefficients_at(g, h, F(value), 40)
            bad = cs is None or cs[0] != 0 or any(x < 0 for x in cs) or density_negative_somewhere(terms)
        if bad:
            raise AssertionError(f"FALSE ACCEPT of rho = {value} ({reason}, attained {attained}) for {terms!r}")


def run(seconds, seed=0, log=print, cases=None, limit=budget.CERTIFICATE_BUDGET,
        claims_share=0.3, progress=False):
    rng = random.Random(seed)
    stats = {"cases": 0, "accepted": 0, "rejected": 0, "verified": 0}
    per = {}
    end = time.process_time() + seconds
    while time.process_time() < end and (cases is None or stats["cases"] < cases):
        base = structure(rng)
        which = rng.choice(MUTATIONS)
        terms, which = mutate(rng, base, which)
        if terms is None:
            continue
        stats["cases"] += 1
        before = dict(stats)
        t0 = time.process_time()
        check_density(terms, stats, limit)
        if stats["accepted"] > before["accepted"] and rng.random() < claims_share:
            check_claims(terms, stats)
        dt = time.process_time() - t0
        stats["max_cpu"] = max(stats.get("max_cpu", 0), dt)
        per.setdefault(which, [0, 0])
        per[which][0] += 1
        per[which][1] += stats["accepted"] - before["accepted"]
        if dt > 20:
            log(f"SLOW {dt:.1f}s: {terms!r}")
        if progress:
            log(f"{which}: {stats}")
    log(f"{stats} per mutation [cases, accepted]: {per}")
    return stats, per


if __name__ == "__main__":
    run(float(sys.argv[1]), int(sys.argv[2]) if len(sys.argv) > 2 else 0)
