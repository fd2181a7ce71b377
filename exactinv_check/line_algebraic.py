"""Poles on the line Re z = p* for an IRRATIONAL algebraic p* (issue 22, item 4), proved exactly.

:mod:`exactinv_check.line_poles` proves a non-real pole z = p* + iy to lie on the vertical line through the
smallest positive pole p* when p* is rational.  Here p* = alpha is a real algebraic number: the root of a
squarefree rational polynomial m (the factor of h that carries p*) in an isolating interval
(:class:`exactinv_check.reals.Real`).  Its Galois conjugates are roots of h too, so h has poles off p*'s line.

The proof.  For a squarefree factor f of h write f(x + iy) = U(x, y) + i V(x, y), U, V in Q[x, y] (the Taylor
shift f(x + w) = sum_k s_k(x) w^k, then w^k = (iy)^k as in line_poles).  At x = alpha the coefficients
U_k(alpha), V_k(alpha) lie in the field Q(alpha) = Q[x]/(m) -- computed here by *dynamic evaluation*: m need not
be irreducible; an element a(x) is zero at alpha iff alpha.sign_of(a) = 0 (an exact sign, reals.Real), and
before an inversion m is replaced by m/gcd(a, m), which still has alpha as a root and is coprime to a (m is
squarefree), so a is invertible modulo the new m.  Euclid's algorithm in Q(alpha)[y] gives the monic
G = gcd(U(alpha, .), V(alpha, .)); for real y, f(alpha + iy) = 0 iff G(y) = 0, and G has real coefficients (alpha
is real).  A pole in an inclusion disk (re, im, rad) (exactinv_check.disks: one root of f in it) is proved to be
alpha + iy when G(alpha, y_lo) and G(alpha, y_hi) have opposite signs or one is 0 (exact signs of elements of
Q(alpha)), where [y_lo, y_hi] = [im - w, im + w] is a chord of the disk at Re z = alpha (w^2 <= rad^2 -
(alpha - re)^2 for every alpha in its rational enclosure) not containing 0: by the intermediate value theorem G
has a real root y there, alpha + iy is a root of f in the disk, hence the disk's root.  Nothing else is claimed:
a disk that fails the test is simply not proved on the line.

Standard library only; every Euclid step is priced (exactinv_check.budget) before it runs.
"""

from __future__ import annotations

from fractions import Fraction
from math import comb
from typing import Sequence

from .budget import MAX_LINE_DEGREE, charge, fraction_products_cost
from .disks import sqrt_bounds
from .failure import require
from .poly_arithmetic import derivative, divmod_, gcd, monic, mul, sub, trim
from .polys import positive_roots
from .reals import Real

__all__ = ["AlgebraicLine", "MAX_LINE_DEGREE", "lines_nonnegative"]


def _bits(p: Sequence[Fraction]) -> int:
    return max((abs(c.numerator).bit_length() + c.denominator.bit_length() for c in p), default=1)


class AlgebraicLine:
    """The line Re z = alpha for one irrational real algebraic alpha (a :class:`Real` with an isolating interval)
    and the squarefree rational polynomial m with m(alpha) = 0 (module docstring)."""

    def __init__(self, alpha: Real, m: Sequence[Fraction]) -> None:
        require(not alpha.inf, "line: alpha must be a finite real")
        require(2 <= len(trim(m)) <= MAX_LINE_DEGREE + 1, "line: the polynomial of p* has an unsupported degree")
        require(alpha.sign_of(list(m)) == 0, "line: p* is not a root of its polynomial (internal)")
        self.alpha = alpha
        self.m = monic(list(m))

    # ------------------------------------------------------------- Q(alpha)
    def _reduce(self, a: Sequence[Fraction]) -> list[Fraction]:
        b: list[Fraction] = trim(list(a))
        if len(b) < len(self.m):
            return b
        return list(divmod_(b, self.m)[1])

    def _mul(self, a: Sequence[Fraction], b: Sequence[Fraction]) -> list[Fraction]:
        if not a or not b:
            return []
        charge(fraction_products_cost(len(a) * len(b) + len(self.m) ** 2, _bits(a) + _bits(b) + _bits(self.m)),
               "arithmetic in Q(p*) for the line Re z = p*")
        return self._reduce(mul(a, b))

    def is_zero(self, a: Sequence[Fraction]) -> bool:
        """a(alpha) = 0, exactly."""
        a = self._reduce(a)
        return not a or self.alpha.sign_of(a) == 0

    def sign(self, a: Sequence[Fraction]) -> int:
        """The exact sign of a(alpha)."""
        a = self._reduce(a)
        return 0 if not a else int(self.alpha.sign_of(a))

    def _inverse(self, a: Sequence[Fraction]) -> list[Fraction]:
        """b with a b = 1 modulo m (after m is replaced by m/gcd(a, m), which keeps alpha); a(alpha) != 0."""
        g = gcd(list(a), self.m)
        if len(g) > 1:
            self.m = monic(divmod_(self.m, g)[0])
            require(self.alpha.sign_of(self.m) == 0, "line: the factor of p*'s polynomial lost p* (internal)")
        a = self._reduce(a)
        s0: list[Fraction] = []
        r0, r1, s1 = list(self.m), a, [Fraction(1)]  # invariant: r_i = s_i a (mod m)
        while len(r1) > 1:
            # charged step by step, by the sizes of the numbers as they are (the former price, 4 n^3 products of
            # 4 (bits of a and m) bits up front, ran 30 times high: a genuine degree-12 rho = oo went over budget)
            charge(fraction_products_cost((len(r0) - len(r1) + 1) * (len(r1) + len(s1)) + len(s0),
                                          max(_bits(r0), _bits(r1), _bits(s1))),
                   "a step of an inversion in Q(p*) (the extended Euclid algorithm)")
            q, r = divmod_(r0, r1)
            r0, r1, s0, s1 = r1, list(r), s1, trim(sub(s0, mul(q, s1)))
        require(len(r1) == 1 and r1[0] != 0, "line: an element of Q(p*) is not invertible (internal)")
        inverse: list[Fraction] = self._reduce([c / r1[0] for c in s1])
        return inverse

    # ------------------------------------------------------------- Q(alpha)[y]
    def _trim(self, P: list[list[Fraction]]) -> list[list[Fraction]]:
        """P with its leading coefficients that vanish at alpha removed."""
        P = [self._reduce(c) for c in P]
        while P and self.is_zero(P[-1]):
            P.pop()
        return P

    def parts(self, f: Sequence[Fraction]) -> tuple[list[list[Fraction]], list[list[Fraction]]]:
        """(U, V): f(alpha + iy) = U(y) + i V(y), coefficients in Q(alpha) as polynomials in x modulo m."""
        n = len(f)
        require(n - 1 <= MAX_LINE_DEGREE, f"line: deg f > {MAX_LINE_DEGREE}")
        charge(fraction_products_cost(n * n * n, _bits(list(f)) + n), "the Taylor shift to the line Re z = p*")
        s = [self._reduce(_shift_coefficient(f, i)) for i in range(n)]
        U = [[c * (-1) ** (k // 2) for c in s[k]] if k % 2 == 0 else [] for k in range(n)]
        V = [[c * (-1) ** ((k - 1) // 2) for c in s[k]] if k % 2 else [] for k in range(n)]
        return self._trim(U), self._trim(V)

    def _monic(self, P: list[list[Fraction]]) -> list[list[Fraction]]:
        inv = self._inverse(P[-1])
        return [self._mul(c, inv) for c in P[:-1]] + [[Fraction(1)]]

    def _remainder(self, A: list[list[Fraction]], B: list[list[Fraction]]) -> list[list[Fraction]]:
        """A mod B for B monic (leading coefficient 1) in Q(alpha)[y]."""
        A = [list(c) for c in A]
        while A and len(A) >= len(B):
            shift, c = len(A) - len(B), A[-1]
            for k, bk in enumerate(B):
                A[k + shift] = self._reduce(sub(A[k + shift], self._mul(c, bk)))
            A[-1] = []
            A = self._trim(A)
        return A

    def line_gcd(self, f: Sequence[Fraction]) -> list[list[Fraction]]:
        """The monic G = gcd(U(alpha, .), V(alpha, .)) in Q(alpha)[y] ([[1]] when coprime): its real roots y are
        exactly the roots alpha + iy of f on the line."""
        U, V = self.parts(f)
        if not U or not V:
            G = U or V
            return self._monic(G) if G else [[Fraction(1)]]
        A, B = U, V
        while B:
            B = self._monic(B)
            A, B = B, self._remainder(A, B)
        return self._monic(A)

    def real_root_count(self, G: list[list[Fraction]]) -> int:
        """The number of distinct real roots of G(alpha, .) (coefficients in Q(alpha)), by Sturm's theorem over the
        ordered field Q(alpha): S_0 = G, S_1 = G', S_(k+1) = -rem(S_(k-1), S_k), each kept as sign(lc) times its monic
        part (a positive multiple: the sign changes are unchanged), and the count is V(-oo) - V(+oo), the sign
        changes of the leading coefficients' signs (times (-1)^degree at -oo).  Every sign is exact
        (:meth:`sign`); every product and inversion is charged (:meth:`_mul`, :meth:`_inverse`)."""
        A = self._trim([list(c) for c in G])
        if len(A) <= 1:
            return 0
        dA = self._trim([[k * x for x in c] for k, c in enumerate(A)][1:])
        seq = [(self.sign(A[-1]), len(A) - 1), (self.sign(dA[-1]), len(dA) - 1)]
        A, B = self._monic(A), self._monic(dA)
        s_a, s_b = seq[0][0], seq[1][0]
        while len(B) > 1:
            R = self._remainder(A, B)  # rem(S_(k-1), S_k) = s_(k-1) rem(A, B): S_(k+1) = -s_(k-1) R
            if not R:
                break
            s_r = -s_a * self.sign(R[-1])
            seq.append((s_r, len(R) - 1))
            A, s_a, B, s_b = B, s_b, self._monic(R), s_r
        return _changes([s * (-1) ** d for s, d in seq]) - _changes([s for s, _ in seq])

    def value_sign(self, G: list[list[Fraction]], y: Fraction) -> int:
        """The exact sign of G(alpha, y) for rational y."""
        value: list[Fraction] = []
        charge(fraction_products_cost(len(G) * len(self.m), sum(_bits(c) for c in G) + len(G) * _bits([y])),
               "a value of the line polynomial G(p*, y)")
        for c in reversed(G):
            value = trim([v * y for v in value])
            value = trim([(value[i] if i < len(value) else Fraction(0)) + (c[i] if i < len(c) else Fraction(0))
                          for i in range(max(len(value), len(c)))])
        return self.sign(value)

    def disk_on_line(self, G: list[list[Fraction]], disk: tuple[Fraction, Fraction, Fraction]) -> bool:
        """True when the root of f in the inclusion disk (re, im, rad) is proved to be alpha + iy, y != 0 real
        (module docstring: a sign change of G(alpha, .) on a chord of the disk at Re z = alpha avoiding 0)."""
        re, im, rad = disk
        if len(G) <= 1 or rad <= 0:
            return False
        self.alpha.refine_below(rad / 64)
        lo, hi = self.alpha.bounds()
        d2 = max((lo - re) ** 2, (hi - re) ** 2)
        if d2 >= rad * rad:
            return False
        w = sqrt_bounds(rad * rad - d2)[0]
        y_lo, y_hi = im - w, im + w
        if w <= 0 or y_lo <= 0 <= y_hi:
            return False
        return self.value_sign(G, y_lo) * self.value_sign(G, y_hi) <= 0


def _changes(signs: Sequence[int]) -> int:
    """Sign changes of a sequence of nonzero signs."""
    return sum(1 for a, b in zip(signs, signs[1:]) if a != b)


def _shift_coefficient(f: Sequence[Fraction], i: int) -> list[Fraction]:
    """[w^i] f(x + w) as a polynomial in x: sum_k f_k C(k, i) x^(k - i)."""
    out = [Fraction(0)] * max(len(f) - i, 1)
    for k in range(i, len(f)):
        out[k - i] += f[k] * comb(k, i)
    shifted: list[Fraction] = trim(out)
    return shifted



def _norm_at_pair(line: AlgebraicLine, P: Sequence[Fraction], Y: list[Fraction]) -> list[Fraction]:
    """|P(x + iy)|^2 at x = alpha, y^2 = Y (Y in Q(alpha)): P(x + iy) = A + i y B with A, B polynomials in Y
    (U is even, V odd in y), so |P|^2 = A^2 + Y B^2, an element of Q(alpha)."""
    U, V = line.parts(P)
    A: list[Fraction] = []
    B: list[Fraction] = []
    for k in reversed(range(len(U))):
        if k % 2 == 0:
            A = line._reduce(_add(line._mul(A, Y), U[k]))
    for k in reversed(range(len(V))):
        if k % 2 == 1:
            B = line._reduce(_add(line._mul(B, Y), V[k]))
    return line._reduce(_add(line._mul(A, A), line._mul(Y, line._mul(B, B))))


def _add(a: Sequence[Fraction], b: Sequence[Fraction]) -> list[Fraction]:
    n = max(len(a), len(b))
    out: list[Fraction] = trim([(a[i] if i < len(a) else Fraction(0)) + (b[i] if i < len(b) else Fraction(0)) for i in range(n)])
    return out


def lines_nonnegative(g: Sequence[Fraction], h: Sequence[Fraction], squarefree_h: bool) -> str | None:
    """A sentence proving f >= 0 on (0, oo) line by line, or None (no claim).  Requires h squarefree (every pole
    simple; the caller says so from its squarefree decomposition) and, for every positive real root x_j of h
    (rational or algebraic: a Real isolated by positive_roots, m = h), G_j = gcd(U, V) of h on Re z = x_j equal
    to y or with no other real root (x_j alone on its line: G's real roots y are exactly the poles x_j + iy, counted
    by :meth:`AlgebraicLine.real_root_count`; a pole x_j + s with x_j - s a pole too, s real or not, makes a
    non-real root of G: the rational pole 3 midway between 3 +- sqrt 2 has G = y(y^2 + 2)) or to y^3 - Y_j y with
    Y_j(x_j) > 0 (one pair x_j +- i sqrt(Y_j)), the counts 1 or 3 adding up to deg h (so every pole lies on one of
    these lines, all with Re z > 0), and every line part
    B_j(t) = b_j + 2 Re(beta_j e^(-i y_j t)) >= 0: b_j = -g(x_j)/h'(x_j) > 0 and b_j^2 >= 4|beta_j|^2, i.e.
    E = g^2 |h'(z)|^2 - 4 |g(z)|^2 h'^2 >= 0 at x_j (exact signs in Q(x_j)).  Then
    f(t) = sum_j e^(-x_j t) B_j(t) >= 0, also where f touches 0."""
    if not squarefree_h or len(h) - 1 > MAX_LINE_DEGREE:
        return None
    dh = derivative(list(h))
    count, parts = 0, []
    for lo, hi in positive_roots(list(h)):
        x = Real.root_in(list(h), lo, hi)
        line = AlgebraicLine(x, list(h))
        G = line.line_gcd(h)
        signs = line.sign(list(g)) * line.sign(dh)
        if signs >= 0:  # b_j = -g(x_j)/h'(x_j) <= 0
            return None
        if not line.is_zero(G[0]):  # (internal: x_j is a root of h, so y = 0 is a root of G)
            return None
        if len(G) == 2 or line.real_root_count(G) == 1:  # G = y, or G's other roots are not real (e.g. G = y(y^2 + 2)
            count += 1                                    # on Re z = 3 for the poles 3, 3 +- sqrt 2): x_j alone
            parts.append(f"{x}: b > 0")
            continue
        if len(G) != 4 or not line.is_zero(G[2]) or G[3] != [Fraction(1)]:
            return None
        Y = line._reduce([-c for c in G[1]])
        if line.sign(Y) <= 0:
            return None
        n, d = line._reduce(list(g)), line._reduce(dh)
        E = _add(line._mul(line._mul(n, n), _norm_at_pair(line, dh, Y)),
                 [-4 * c for c in line._mul(_norm_at_pair(line, g, Y), line._mul(d, d))])
        if line.sign(E) < 0:
            return None
        count += 3
        parts.append(f"{x} +- i y: b^2 >= 4|beta|^2")
    if count != len(h) - 1:
        return None
    return "every pole on a line Re z = x_j through a positive real pole, each line part B_j >= 0 (" + "; ".join(parts) + ")"
