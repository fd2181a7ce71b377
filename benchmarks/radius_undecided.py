"""The Undecided rate of the radius of absolute monotonicity over a random family of rational functions.

The family (seeded, reproducible): r = g/h of degree <= 4 with r(0) = 1 and a positive real pole, in three
equal parts --
  * generic:   h = (1 - z/p) q(z), deg q <= 3, q(0) = 1, small random rational coefficients;
  * repeated:  h = (1 - z/p)^m q(z), m = 2..4, deg h <= 4 (a repeated real pole, any numerator);
  * bernstein: h = (1 - z/p) ((1 - z/a)^2 + (z/b)^2)-type, a complex pair with real part beyond p*
               (the class where no tail index is uniform in kappa), numerator random;
the numerator g has g(0) = 1 and degree <= 4.  Each radius runs under an alarm of --cap seconds (the
engine only; a time-out is counted apart from Undecided).  For every decided case the
certificate is checked by the trusted kernel (``--no-check`` skips it); a rejected certificate is counted.

``--family ties`` (issue 22, the gap it left): in two equal parts --
  * line:      p* and a pair p* +- iy on its vertical line (random residues b_*, u +- iv; half of them with a
               farther real pole), built from partial fractions (r(0) = 1);
  * balanced:  p* and tied poles on the circle |w| = R around -kappa* (Gaussian rationals: a pair, a negative
               pole and a pair, or two pairs) whose residues' moduli add up to b_* exactly.

``--family line-balance`` (line-balance, issue 22): the family of tests/monotonicity/test_line_poles.py's random tie test, in two
equal parts --
  * pair:      p* and a pair p* +- iy on its line, p*, y, b_*, u, v random with denominators <= 4 (as the test
               draws them), half of them with a farther real pole p* + 2 (b = 1);
  * balanced:  the same with b_* = 2|b| exactly (b = m (c + is), (c, s) a rational point of the unit circle), every
               one with the farther real pole: the line part B >= 0 touches 0 (the CI failures of line-balance).

``--family line-irrational`` (issue 22 item 4): an IRRATIONAL p* = a - sqrt d (a^2 > d) with a pair p* +- iy on its
line (the Galois conjugates a + sqrt d +- iy are poles too), in three equal parts --
  * pair:      r = C + (1 - C) S/S(0), S = sum over both conjugates p of 1/(p - z) + beta/(p + iy - z) + conj,
               beta = u + iv random (f = sum_p e^(-pt)(1 + 2 Re(beta e^(-iyt))): rho = oo iff 4|beta|^2 <= 1, C >= 0);
  * touching:  the same with 4|beta|^2 = 1 exactly (a rational point of the circle): f >= 0 touches 0;
  * numerator: h = (u^2 - d)((u^2 + d + y^2)^2 - 4 d u^2), u = z - a, and a random numerator g (g(0) = 1, deg <= 4).
It is built with sympy (exact).

Run:  python benchmarks/radius_undecided.py [--count 300] [--seed 1] [--cap 20] [--no-check]
                                           [--family ties | line-balance | line-irrational]
"""

from __future__ import annotations

import argparse
import random
import signal
import time
from collections import Counter
from fractions import Fraction

import exactinv as ei
from exactinv import methods as M


def _small(rng: random.Random) -> Fraction:
    return Fraction(rng.randint(-12, 12), rng.choice([1, 2, 3, 4, 6]))


def _numerator_coefficient(rng: random.Random) -> Fraction:
    return Fraction(rng.randint(-4, 4), rng.choice([1, 2, 3, 4, 6, 8]))


def _mul(a: list, b: list) -> list:
    out = [Fraction(0)] * (len(a) + len(b) - 1)
    for i, x in enumerate(a):
        for j, y in enumerate(b):
            out[i + j] += x * y
    return out


def family(count: int, seed: int) -> list[tuple[str, list, list]]:
    """count (kind, numerator, denominator) triples, low to high, h(0) = g(0) = 1."""
    rng = random.Random(seed)
    out = []
    while len(out) < count:
        kind = ("generic", "repeated", "bernstein")[len(out) % 3]
        p = Fraction(rng.randint(1, 16), rng.choice([2, 4, 8]))
        factor = [Fraction(1), -1 / p]
        if kind == "generic":
            den = _mul(factor, [Fraction(1)] + [_small(rng) for _ in range(rng.randint(0, 3))])
        elif kind == "repeated":
            m = rng.randint(2, 4)
            den = [Fraction(1)]
            for _ in range(m):
                den = _mul(den, factor)
            if m < 4 and rng.random() < 0.5:
                den = _mul(den, [Fraction(1)] + [_small(rng) for _ in range(rng.randint(1, 4 - m))])
        else:  # 1/((1 - z/w)(1 - z/w-bar)) with Re w > p
            re = p + Fraction(rng.randint(1, 12), 4)
            im = Fraction(rng.randint(1, 12), 4)
            n2 = re * re + im * im
            den = _mul(factor, [Fraction(1), -2 * re / n2, 1 / n2])
        num = [Fraction(1)] + [_numerator_coefficient(rng) for _ in range(rng.randint(0, 4))]
        while len(num) > 1 and num[-1] == 0:
            num.pop()
        if len(den) > 5 or len(num) > 5:
            continue
        try:
            method = M.rational(num, den, name=f"r{len(out)}")
        except ei.ExactinvError:
            continue
        if method.is_polynomial:
            continue
        out.append((kind, method))
    return out


_UNITS = [(Fraction(3, 5), Fraction(4, 5)), (Fraction(-3, 5), Fraction(4, 5)), (Fraction(5, 13), Fraction(12, 13)),
          (Fraction(-8, 17), Fraction(15, 17)), (Fraction(0), Fraction(1)), (Fraction(4, 5), Fraction(3, 5))]


def _from_partial_fractions(terms) -> tuple[list, list]:
    """(g, h), h(0) = 1 and r(0) = 1, for r = c + sum -b_k/(z - z_k) (simple poles, conjugate pairs both listed)."""
    def mul(a, b):
        out = [(Fraction(0), Fraction(0))] * (len(a) + len(b) - 1)
        for i, x in enumerate(a):
            for j, y in enumerate(b):
                out[i + j] = (out[i + j][0] + x[0] * y[0] - x[1] * y[1], out[i + j][1] + x[0] * y[1] + x[1] * y[0])
        return out
    zs = [z for z, _ in terms]
    h = [(Fraction(1), Fraction(0))]
    for z in zs:
        h = mul(h, [(-z[0], -z[1]), (Fraction(1), Fraction(0))])
    num = [(Fraction(0), Fraction(0))] * len(h)
    for k, (_, b) in enumerate(terms):
        q = [(Fraction(1), Fraction(0))]
        for i, w in enumerate(zs):
            if i != k:
                q = mul(q, [(-w[0], -w[1]), (Fraction(1), Fraction(0))])
        for i, c in enumerate(q):
            num[i] = (num[i][0] - b[0] * c[0] + b[1] * c[1], num[i][1] - b[0] * c[1] - b[1] * c[0])
    h, num = [c[0] for c in h], [c[0] for c in num]
    c = 1 - num[0] / h[0]
    g = [(c * h[i] + num[i]) / h[0] for i in range(len(h))]
    while len(g) > 1 and g[-1] == 0:
        g.pop()
    return g, [x / h[0] for x in h]


def family_ties(count: int, seed: int) -> list:
    """count (kind, method): line-pole and balanced-tie cases (module docstring)."""
    rng = random.Random(seed)
    out = []
    while len(out) < count:
        kind = ("line", "balanced")[len(out) % 2]
        if kind == "line":
            p = Fraction(rng.randint(1, 16), 4)
            y = Fraction(rng.randint(1, 12), 4)
            u, v = Fraction(rng.randint(-8, 8), 4), Fraction(rng.randint(-8, 8), 4)
            if u == 0 and v == 0:
                continue
            terms = [((p, Fraction(0)), (Fraction(rng.randint(1, 16), 4), Fraction(0))), ((p, y), (u, v)), ((p, -y), (u, -v))]
            if rng.random() < 0.5:
                terms.append(((p + 2, Fraction(0)), (Fraction(1), Fraction(0))))
        else:
            R, kappa = rng.randint(2, 9), Fraction(rng.randint(1, 6), 4)
            p, b_star = R - kappa, Fraction(rng.randint(2, 12), 4)
            split = Fraction(rng.randint(1, 7), 8)

            def pair(modulus, R=R, kappa=kappa):
                w, ph = _UNITS[rng.randrange(len(_UNITS))], _UNITS[rng.randrange(len(_UNITS))]
                b = (modulus * ph[0], modulus * ph[1])
                return [((R * w[0] - kappa, R * w[1]), b), ((R * w[0] - kappa, -R * w[1]), (b[0], -b[1]))]

            terms = [((p, Fraction(0)), (b_star, Fraction(0)))]
            shape = rng.randrange(3)
            if shape == 0:
                terms += pair(b_star / 2)
            elif shape == 1:
                terms += [((-R - kappa, Fraction(0)), (b_star * split * rng.choice([1, -1]), Fraction(0)))]
                terms += pair(b_star * (1 - split) / 2)
            else:
                terms += pair(b_star * split / 2) + pair(b_star * (1 - split) / 2)
            if len({z for z, _ in terms}) != len(terms):
                continue
        num, den = _from_partial_fractions(terms)
        out.append((kind, M.rational(num, den, name=f"r{len(out)}")))
    return out


def family_line_balance(count: int, seed: int) -> list:
    """count (kind, method): the random tie test's family and its exactly balanced part (module docstring)."""
    rng = random.Random(seed)
    out = []

    def q4(lo, hi):  # a random fraction in [lo, hi] with denominator <= 4
        d = rng.choice([1, 2, 3, 4])
        return Fraction(rng.randint(int(lo * d), int(hi * d)), d)

    while len(out) < count:
        kind = ("pair", "balanced")[len(out) % 2]
        p, y = q4(Fraction(1, 4), 4), q4(Fraction(1, 4), 3)
        if p <= 0 or y <= 0:
            continue
        if kind == "pair":
            b_star, u, v = q4(Fraction(1, 4), 4), q4(-2, 2), q4(-2, 2)
            if b_star <= 0 or (u == 0 and v == 0):
                continue
            extra = rng.random() < 0.5
        else:
            m = q4(Fraction(1, 4), 2)
            c, s_ = _UNITS[rng.randrange(len(_UNITS))]
            sign = rng.choice([1, -1])
            u, v, b_star, extra = m * c * sign, m * s_, 2 * m, True
            if m <= 0:
                continue
        terms = [((p, Fraction(0)), (b_star, Fraction(0))), ((p, y), (u, v)), ((p, -y), (u, -v))]
        if extra:
            terms.append(((p + 2, Fraction(0)), (Fraction(1), Fraction(0))))
        num, den = _from_partial_fractions(terms)
        out.append((kind, M.rational(num, den, name=f"r{len(out)}")))
    return out


def family_line_irrational(count: int, seed: int) -> list:
    """count (kind, method): p* = a - sqrt d irrational with a pair on its line (module docstring)."""
    import sympy as sp

    rng = random.Random(seed)
    z = sp.symbols("z")
    circle = [(Fraction(3, 10), Fraction(2, 5)), (Fraction(-5, 26), Fraction(6, 13)), (Fraction(1, 2), Fraction(0)),
              (Fraction(-1, 2), Fraction(0)), (Fraction(0), Fraction(1, 2)), (Fraction(-4, 10), Fraction(3, 10))]
    out: list = []

    def exact(e):
        num, den = sp.fraction(sp.cancel(sp.together(e)))
        g = [Fraction(str(sp.nsimplify(x))) for x in reversed(sp.Poly(sp.expand(num), z).all_coeffs())]
        h = [Fraction(str(sp.nsimplify(x))) for x in reversed(sp.Poly(sp.expand(den), z).all_coeffs())]
        return [x / h[0] for x in g], [x / h[0] for x in h]

    while len(out) < count:
        kind = ("pair", "touching", "numerator")[len(out) % 3]
        a, d = rng.randint(2, 5), rng.choice([2, 3, 5, 6, 7])
        y = sp.Rational(rng.randint(1, 8), rng.choice([1, 2, 4]))
        if a * a <= d:
            continue
        if kind == "numerator":
            u = z - a
            h = sp.expand((u ** 2 - d) * ((u ** 2 + d + y ** 2) ** 2 - 4 * d * u ** 2))
            g = 1 + sum(sp.Rational(rng.randint(-4, 4), rng.choice([1, 2, 4, 8])) * z ** k
                        for k in range(1, rng.randint(1, 4) + 1))
            num, den = exact(g / (h / h.subs(z, 0)))
        else:
            if kind == "pair":
                bu, bv = Fraction(rng.randint(-4, 4), 4), Fraction(rng.randint(-4, 4), 4)
                if bu == 0 and bv == 0:
                    continue
            else:
                bu, bv = circle[rng.randrange(len(circle))]
            C = sp.Rational(str(rng.choice([Fraction(0), Fraction(1, 4), Fraction(-1, 2)])))
            S = 0
            for sgn in (1, -1):
                p = a - sgn * sp.sqrt(d)
                S += 1 / (p - z) + (2 * sp.Rational(str(bu)) * (p - z) + 2 * sp.Rational(str(bv)) * y) / ((p - z) ** 2 + y ** 2)
            S = sp.together(sp.expand(S))
            num, den = exact(C + (1 - C) * S / sp.nsimplify(S.subs(z, 0)))
        try:
            out.append((kind, M.rational(num, den, name=f"r{len(out)}")))
        except ei.ExactinvError:
            continue
    return out


class _Timeout(Exception):
    pass


def _alarm(*_):
    raise _Timeout


def run(count: int, seed: int, cap: float, check: bool, ties: bool | str = False) -> None:
    kinds = {"line-balance": ("pair", "balanced"), "line-irrational": ("pair", "touching", "numerator"),
             True: ("line", "balanced")}.get(ties, ("generic", "repeated", "bernstein"))
    cases = family_line_balance(count, seed) if ties == "line-balance" else \
        family_line_irrational(count, seed) if ties == "line-irrational" else family_ties(count, seed) if ties \
        else family(count, seed)
    signal.signal(signal.SIGALRM, _alarm)
    outcome: dict[str, Counter] = {}
    reasons: Counter = Counter()
    rejected, kernel_max, engine_max = 0, 0.0, 0.0
    start = time.perf_counter()
    for kind, method in cases:
        signal.setitimer(signal.ITIMER_REAL, cap)
        r = None
        try:
            t = time.perf_counter()
            r = ei.absolute_monotonicity_radius(method)
            engine_max = max(engine_max, time.perf_counter() - t)
            verdict = "decided"
            reasons[str(r.reason)] += 1
        except ei.Undecided:
            verdict = "undecided"
        except _Timeout:
            verdict = "timeout"
        finally:
            signal.setitimer(signal.ITIMER_REAL, 0)
        if r is not None and check:  # the kernel is timed apart (the cap is the engine's)
            t = time.perf_counter()
            ok = ei.check(r.certificate).ok
            rejected += not ok
            verdict = verdict if ok else "rejected"
            kernel_max = max(kernel_max, time.perf_counter() - t)
        outcome.setdefault(kind, Counter())[verdict] += 1
    total = Counter()
    for c in outcome.values():
        total.update(c)
    print(f"{count} random r = g/h, degree <= 4, seed {seed}, cap {cap:g} s, {time.perf_counter() - start:.1f} s")
    print(f"{'family':<10} {'cases':>6} {'decided':>8} {'undecided':>10} {'timeout':>8} {'rejected':>9} "
          f"{'undecided rate':>15}")
    for kind in kinds:
        c = outcome.get(kind, Counter())
        n = sum(c.values())
        print(f"{kind:<10} {n:>6} {c['decided']:>8} {c['undecided']:>10} {c['timeout']:>8} {c['rejected']:>9} "
              f"{(c['undecided'] + c['timeout']) / max(n, 1):>14.1%}")
    n = sum(total.values())
    print(f"{'all':<10} {n:>6} {total['decided']:>8} {total['undecided']:>10} {total['timeout']:>8} "
          f"{total['rejected']:>9} {(total['undecided'] + total['timeout']) / max(n, 1):>14.1%}")
    print("reasons of the decided:", dict(sorted(reasons.items())))
    print(f"slowest decided radius: engine {engine_max:.2f} s")
    if check:
        print(f"certificates rejected by the kernel: {rejected} (slowest kernel check {kernel_max:.2f} s)")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--count", type=int, default=300)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--cap", type=float, default=20.0)
    parser.add_argument("--no-check", action="store_true")
    parser.add_argument("--family", choices=["default", "ties", "line-balance", "line-irrational"], default="default")
    args = parser.parse_args()
    run(args.count, args.seed, args.cap, not args.no_check,
        args.family if args.family in ("line-balance", "line-irrational") else args.family == "ties")


if __name__ == "__main__":
    main()
