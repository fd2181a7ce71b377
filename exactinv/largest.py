"""The exact largest thresholds -- beyond the paper (DESIGN.md section 1).

A_d(dt) P is a subset of P iff A_d(dt) v is in P for every point v of a
minimal generator system of P, A_d(dt) r is in the recession cone for every
ray r, and A_d(dt) l is in the lineality space for every line l.  With
D(dt) = det h(dt A) (D = 1 for polynomial methods) and N(dt) = D(dt) A_d(dt),
a polynomial matrix, each condition is a polynomial sign condition:

    vertex v, facet j:  c(dt) = (b_j D(dt) - g_j N(dt) v) D(dt) >= 0,
    ray r,    facet j:  c(dt) = -(g_j N(dt) r) D(dt) >= 0,
    line l,   facet j:  e(dt) = g_j N(dt) l = 0,

and dt must avoid the roots of D (where r(dt A) is singular).  The valid set
is therefore a finite union of intervals with algebraic ends, computed
exactly from the roots (with multiplicities) of the distinct condition
polynomials: each c is negative exactly on the open segments between its own
roots where its sign, tracked from the sign right of 0 through the odd
multiplicities, is negative.

Cost: the coefficients of all vertex-facet polynomials come from the matrix
products G A^k V (FLINT); identical polynomials are merged and a polynomial
whose coefficient signs show no positive root (Descartes) never binds and is
skipped, so only pairs that can actually bind reach root isolation.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any

import flint

from .algebraic import ExactKey, RealAlgebraic
from .errors import InvalidInput, VerificationFailed
from .intervals import Interval, IntervalUnion, complement_of_open, _lt
from .invariance import optimal_gamma
from .methods import Method, forward_euler
from .model import LinearSystem, Polyhedron
from .numbers import INF, Infinity, fmpq_of, fraction_of
from .roots import _integer, nonnegative_until, real_roots, sign_right_of, sign_variations
from .results import ExactValueMixin

__all__ = [
    "Condition",
    "ValidSteplengths",
    "LargestThreshold",
    "ForwardEulerThreshold",
    "valid_steplengths",
    "largest_threshold",
    "forward_euler_threshold",
    "ThresholdComparison",
    "compare_thresholds",
]

Real = Fraction | RealAlgebraic | Infinity


@dataclass(frozen=True)
class Condition:
    """One polynomial condition: ``kind`` is "vertex", "ray" or "line";
    ``generator`` the index in P.vertices / P.rays / P.lines; ``facet`` the row
    of G; ``poly`` the coefficients (dt^0 ..) of c (>= 0 required) or e (= 0)."""

    kind: str
    generator: int
    facet: int
    p: flint.fmpq_poly = field(repr=False, compare=False)

    @property
    def poly(self) -> tuple[Fraction, ...]:
        return tuple(fraction_of(c) for c in self.p.coeffs())


@dataclass(frozen=True)
class ValidSteplengths:
    """The exact set {dt >= 0 : A_d(dt) P subset of P}.  Iterate for the
    intervals; ``dt in V`` for a rational dt."""

    intervals: IntervalUnion
    method: Method = field(repr=False)
    singular: tuple[Real, ...] = field(default=(), repr=False)
    conditions: int = field(default=0, repr=False)
    distinct: int = field(default=0, repr=False)

    system: LinearSystem | None = field(default=None, repr=False)
    polyhedron: Polyhedron | None = field(default=None, repr=False)
    determinant: tuple[Fraction, ...] = field(default=(Fraction(1),), repr=False)

    def __iter__(self):
        return iter(self.intervals)

    def __len__(self) -> int:
        return len(self.intervals)

    def _claims(self) -> list[dict]:
        from .certificates import encode_real

        return [{
            "type": "valid_steplengths",
            "intervals": [{"lo": encode_real(iv.lo), "hi": encode_real(iv.hi), "lo_closed": iv.lo_closed,
                           "hi_closed": iv.hi_closed} for iv in self.intervals],
            "vertices": [[str(x) for x in v] for v in self.polyhedron.vertices],
            "rays": [[str(x) for x in r] for r in self.polyhedron.rays],
            "lines": [[str(x) for x in l] for l in self.polyhedron.lines],
            "determinant": [str(c) for c in self.determinant],
        }]

    @property
    def certificate(self) -> dict:
        from .certificates import certificate

        return certificate(self.system, self.polyhedron, self.method, [self])

    def __contains__(self, t: Any) -> bool:
        return t in self.intervals

    def __repr__(self) -> str:
        return f"ValidSteplengths({self.intervals!r}, method={self.method.name})"

    def _repr_latex_(self) -> str:
        return self.intervals._repr_latex_()


@dataclass(frozen=True)
class LargestThreshold(ExactValueMixin):
    """The exact largest threshold: the end of the first interval of the valid
    set, ``attained`` if that end is itself valid.  ``binding`` is the
    condition (vertex/ray, facet, polynomial) whose sign change ends the
    interval, or None when a pole of r(dt A) (``singular``) ends it."""

    value: Real
    attained: bool
    method: Method = field(repr=False)
    binding: Condition | None = None
    singular: Real | None = None
    system: LinearSystem | None = field(default=None, repr=False)
    polyhedron: Polyhedron | None = field(default=None, repr=False)
    checked: tuple[Condition, ...] = field(default=(), repr=False)
    determinant: tuple[Fraction, ...] = field(default=(Fraction(1),), repr=False)



    def _claims(self) -> list[dict]:
        from .certificates import encode_real

        return [{
            "type": "largest_threshold",
            "value": encode_real(self.value),
            "attained": self.attained,
            "vertices": [[str(x) for x in v] for v in self.polyhedron.vertices],
            "rays": [[str(x) for x in r] for r in self.polyhedron.rays],
            "lines": [[str(x) for x in l] for l in self.polyhedron.lines],
            "determinant": [str(c) for c in self.determinant],
            "binding": None if self.binding is None else {
                "kind": self.binding.kind, "generator": self.binding.generator, "facet": self.binding.facet,
                "poly": [str(c) for c in self.binding.poly]},
        }]

    @property
    def certificate(self) -> dict:
        from .certificates import certificate

        return certificate(self.system, self.polyhedron, self.method, [self])

    def __repr__(self) -> str:
        return f"LargestThreshold(value={self.value}, attained={self.attained}, method={self.method.name})"


# ------------------------------------------------------------ the conditions
def _evaluate_rational(method: Method, A: flint.fmpq_mat, t: Fraction, W: flint.fmpq_mat):
    """(D(t), D(t) A_d(t) W) exactly, D = det h(t A)."""
    n = A.nrows()
    M = A * fmpq_of(t)

    def polyval(coeffs):
        out = flint.fmpq_mat(n, n)
        for c in reversed(coeffs):
            out = out * M
            for i in range(n):
                out[i, i] += fmpq_of(c)
        return out

    Hm = polyval(method.denominator)
    D = Hm.det()
    if D == 0:
        return None
    return D, Hm.solve(polyval(method.numerator) * W) * D


def _interpolate_columns(points: list[Fraction], values: list[flint.fmpq_mat]) -> list[flint.fmpq_mat]:
    """Coefficient matrices C_0..C_d with sum_d C_d t^d = values[k] at t = points[k]."""
    d = len(points)
    V = flint.fmpq_mat(d, d, [fmpq_of(p) ** e for p in points for e in range(d)])
    Vinv = V.inv()
    return [sum((values[k] * Vinv[e, k] for k in range(d)), values[0] * 0) for e in range(d)]


def _generator_matrices(P: Polyhedron):
    def mat(rows):
        if not rows:
            return None
        return flint.fmpq_mat(len(rows[0]), len(rows), [fmpq_of(rows[i][k]) for k in range(len(rows[0])) for i in range(len(rows))])

    return mat(P.vertices), mat(P.rays), mat(P.lines)


def _conditions(system: LinearSystem, P: Polyhedron, method: Method):
    """All vertex/ray inequality conditions c >= 0, line equalities e = 0, and D."""
    A, G = system.A_flint, P.G_flint
    b = [fmpq_of(x) for x in P.b]
    V, R, L = _generator_matrices(P)
    if method.is_polynomial:
        D = flint.fmpq_poly([1])

        def coefficient_blocks(W):
            blocks, Wk = [], W
            for k, s in enumerate(method.sigmas):
                if k:
                    Wk = A * Wk
                blocks.append(G * Wk * fmpq_of(s))
            return blocks
    else:
        degree_D = P.n * (len(method.denominator) - 1)
        degree_N = (P.n - 1) * (len(method.denominator) - 1) + len(method.numerator) - 1
        count = max(degree_D, degree_N) + 1
        points, Ds = [], []
        t = Fraction(0)
        while len(points) < count:
            trial = _evaluate_rational(method, A, t, flint.fmpq_mat(P.n, 1))
            if trial is not None:
                points.append(t)
                Ds.append(trial[0])
            t += 1
        Dc = _interpolate_columns(points, [flint.fmpq_mat(1, 1, [v]) for v in Ds])
        D = flint.fmpq_poly([c[0, 0] for c in Dc])

        def coefficient_blocks(W):
            values = [G * _evaluate_rational(method, A, p, W)[1] for p in points]
            return _interpolate_columns(points, values)

    Dcoeffs = [fraction_of(c) for c in D.coeffs()]
    conditions: list[Condition] = []
    equalities: list[Condition] = []
    for kind, W in (("vertex", V), ("ray", R), ("line", L)):
        if W is None:
            continue
        blocks = coefficient_blocks(W)
        entries = [blk.entries() for blk in blocks]
        cols = W.ncols()
        cheap_skip = method.is_polynomial and kind != "line"
        for j in range(P.m):
            for i in range(cols):
                idx = j * cols + i
                if cheap_skip and all(e[idx] <= 0 for e in entries[1:]) and (kind == "ray" or entries[0][idx] <= b[j]):
                    continue  # every coefficient of c is >= 0: never binds (Descartes), decided before building c
                gN = [e[idx] for e in entries]  # g_j N(dt) w, coefficients
                if kind == "line":
                    poly = flint.fmpq_poly(gN)
                    if not poly.is_zero():
                        equalities.append(Condition(kind, i, j, poly))
                    continue
                q = -flint.fmpq_poly(gN)
                if kind == "vertex":
                    q += D * b[j]
                c = q * D
                if _never_binds(c.coeffs()):
                    continue
                conditions.append(Condition(kind, i, j, c))
    return conditions, equalities, D, Dcoeffs


def _never_binds(coeffs) -> bool:
    """No sign variation and a positive coefficient: c > 0 on (0, oo) (Descartes)."""
    nonzero = [c for c in coeffs if c != 0]
    return not nonzero or (nonzero[0] > 0 and sign_variations(nonzero) == 0)


_ONE_PLUS_X = flint.fmpq_poly([1, 1])


def _no_root_below(p: flint.fmpq_poly, T: Fraction) -> bool:
    """Descartes' rule on (0, T): with g(y) = c(T y), the polynomial
    rev(g)(1 + x) = (1+x)^d g(1/(1+x)) has no sign variation, so c has no root
    in (0, T).  Exact and cheap (a Taylor shift in FLINT)."""
    Tq = fmpq_of(T)
    scaled = [c * Tq**k for k, c in enumerate(p.coeffs())]
    shifted = flint.fmpq_poly(scaled[::-1])(_ONE_PLUS_X)
    return sign_variations(shifted.coeffs()) == 0


def _positive_right_of_zero(p: flint.fmpq_poly) -> bool:
    for c in p.coeffs():
        if c != 0:
            return c > 0
    return True


def _upper(v: Real):
    return v.upper if isinstance(v, RealAlgebraic) else v


def _distinct(conditions: list[Condition]) -> dict[tuple, Condition]:
    seen: dict[tuple, Condition] = {}
    for c in conditions:
        key = _normalised(c.p)
        if key not in seen:
            seen[key] = c
    return seen


def _normalised(p: flint.fmpq_poly) -> tuple:
    return tuple(int(c) for c in _integer(p).coeffs())


def _positive_roots(p: flint.fmpq_poly) -> list[tuple[Real, int]]:
    if p.degree() < 1:
        return []
    return [(r, m) for r, m in real_roots(p) if r > 0]


def _negative_segments(p: flint.fmpq_poly) -> list[tuple[Real, Real]]:
    """Open intervals (a, b) in (0, oo) where the polynomial is negative."""
    sign = sign_right_of(p, 0)
    roots = _positive_roots(p)
    out = []
    left: Real = Fraction(0)
    for r, m in roots:
        if sign < 0:
            out.append((left, r))
        if m % 2:
            sign = -sign
        left = r
    if sign < 0:
        out.append((left, INF))
    return out


def _check_method_problem(system, polyhedron, method):
    if not isinstance(system, LinearSystem):
        raise InvalidInput(f"system: expected an exactinv.LinearSystem, got {type(system).__name__}")
    if not isinstance(polyhedron, Polyhedron):
        raise InvalidInput(f"polyhedron: expected an exactinv.Polyhedron, got {type(polyhedron).__name__}")
    if not isinstance(method, Method):
        raise InvalidInput(f"method: expected an exactinv method, got {type(method).__name__}")
    if system.n != polyhedron.n:
        raise InvalidInput(f"system/polyhedron: A is {system.n}x{system.n} but G has {polyhedron.n} columns")
    if polyhedron.is_empty:
        from .errors import EmptyPolyhedron

        raise EmptyPolyhedron("polyhedron: P = {x : Gx <= b} is empty")


# ------------------------------------------------------------------- the API
def valid_steplengths(system: LinearSystem, polyhedron: Polyhedron, method: Method) -> ValidSteplengths:
    """The exact set {dt >= 0 : A_d(dt) P subset of P} as a union of intervals
    with exact ends (open/closed marked); singular points of r(dt A) excluded."""
    _check_method_problem(system, polyhedron, method)
    conditions, equalities, D, _ = _conditions(system, polyhedron, method)
    distinct = _distinct(conditions)
    singular = [r for r, _ in _positive_roots(D)]
    # The valid set lies inside the valid set of any single generator: take the
    # conditions of the first vertex exactly, then skip every other condition
    # that Descartes' rule shows nonnegative on [0, T], T the end of that set.
    first = [c for c in distinct.values() if c.kind == "vertex" and c.generator == 0]
    bad: list[tuple[Real, Real]] = []
    for c in first:
        bad.extend(_negative_segments(c.p))
    bound = complement_of_open(bad, singular)
    T = bound.intervals[-1].hi if bound.intervals else Fraction(0)
    for c in distinct.values():
        if c.kind == "vertex" and c.generator == 0:
            continue
        if not isinstance(T, Infinity) and _positive_right_of_zero(c.p) and _no_root_below(c.p, _upper(T)):
            continue
        bad.extend(_negative_segments(c.p))
    union = complement_of_open(bad, singular)
    if equalities:  # lines: only the common roots of every e survive
        allowed = None
        for e in _distinct(equalities).values():
            roots = {r for r, _ in _positive_roots(e.p)}
            allowed = roots if allowed is None else {r for r in allowed if any(r == s for s in roots)}
        points = [Fraction(0)] + sorted((r for r in allowed or () if r in union), key=ExactKey)
        union = IntervalUnion(tuple(Interval(p, p, True, True) for p in points))
    return ValidSteplengths(union, method, tuple(singular), len(conditions), len(distinct), system, polyhedron,
                            tuple(fraction_of(c) for c in D.coeffs()))


def largest_threshold(system: LinearSystem, polyhedron: Polyhedron, method: Method) -> LargestThreshold:
    """The exact largest threshold sup{T : A_d(dt) P subset of P for all dt in [0, T)}
    -- the end of the first interval of :func:`valid_steplengths` -- computed
    directly from the first sign change of each condition and the first pole."""
    _check_method_problem(system, polyhedron, method)
    conditions, equalities, D, Dcoeffs = _conditions(system, polyhedron, method)
    distinct = list(_distinct(conditions).values())
    if equalities:
        return LargestThreshold(Fraction(0), True, method, equalities[0], None, system, polyhedron, tuple(distinct), tuple(Dcoeffs))
    best: Real = INF
    binding: Condition | None = None
    for c in sorted(distinct, key=lambda c: c.p(0)):  # the tightest pairs first
        if not isinstance(best, Infinity) and _positive_right_of_zero(c.p) and _no_root_below(c.p, _upper(best)):
            continue  # c >= 0 on [0, best]: cannot end the first interval earlier
        end = nonnegative_until(c.p)
        if _lt(end, best):
            best, binding = end, c
    poles = _positive_roots(D)
    singular = poles[0][0] if poles else None
    attained = True
    if singular is not None and not _lt(best, singular):
        best, binding, attained = singular, None, False
    if isinstance(best, Infinity):
        attained = True
    return LargestThreshold(best, attained, method, binding, singular, system, polyhedron, tuple(distinct), tuple(Dcoeffs))


# ------------------------------------------------------------- forward Euler
@dataclass(frozen=True)
class ForwardEulerThreshold(ExactValueMixin):
    """The largest forward-Euler threshold, derived twice (paper, Section 3.4):
    ``by_gamma`` = 1/gamma* (Lemma 3.14) and ``by_vertices`` = min_i eps^i with
    eps^i = max{t : x^i + t A x^i in P} (rays and lines likewise); they must agree.
    ``binding`` = (kind, generator index, facet) of the vertex ratio test that binds."""

    value: Real
    by_gamma: Real
    by_vertices: Real
    binding: tuple[str, int, int] | None
    gamma: Any = field(repr=False)
    attained: bool = True

    def _claims(self) -> list[dict]:
        from .certificates import _gamma_claim, encode_real

        P = self.gamma.polyhedron
        return [_gamma_claim(self.gamma), {
            "type": "forward_euler_threshold",
            "value": encode_real(self.value),
            "vertices": [[str(x) for x in v] for v in P.vertices],
            "rays": [[str(x) for x in r] for r in P.rays],
            "lines": [[str(x) for x in l] for l in P.lines],
        }]

    @property
    def certificate(self) -> dict:
        from .certificates import certificate

        return certificate(self.gamma.system, self.gamma.polyhedron, None, [self])


def forward_euler_threshold(system: LinearSystem, polyhedron: Polyhedron) -> ForwardEulerThreshold:
    """The largest forward-Euler steplength, exact, cross-checked: 1/gamma* from
    the verified LP and the vertex ratio tests must coincide."""
    _check_method_problem(system, polyhedron, forward_euler())
    gamma = optimal_gamma(system, polyhedron)
    g = gamma.value
    by_gamma = Fraction(0) if g == INF else (INF if isinstance(g, Infinity) or g <= 0 else 1 / g)
    A = system.A_flint
    G, b = polyhedron.G, polyhedron.b
    best: Real = INF
    binding = None
    for kind, gens in (("vertex", polyhedron.vertices), ("ray", polyhedron.rays), ("line", polyhedron.lines)):
        for i, x in enumerate(gens):
            Ax = [sum(A[r, k] * fmpq_of(x[k]) for k in range(len(x))) for r in range(len(x))]
            Ax = [fraction_of(v) for v in Ax]
            for j, row in enumerate(G):
                rate = sum(gj * v for gj, v in zip(row, Ax))
                if kind == "line":
                    eps = INF if rate == 0 else Fraction(0)
                elif rate <= 0:
                    continue
                else:
                    slack = (b[j] if kind == "vertex" else 0) - sum(gj * v for gj, v in zip(row, x))
                    eps = slack / rate
                if _lt(eps, best):
                    best, binding = eps, (kind, i, j)
    if best != by_gamma:
        raise VerificationFailed(f"forward Euler: 1/gamma* = {by_gamma} but the vertex ratio tests give {best}")
    return ForwardEulerThreshold(best, by_gamma, best, binding, gamma)


# ------------------------------------------------------- how conservative?
@dataclass(frozen=True)
class ThresholdComparison:
    """The paper's threshold (taken literally), the corrected one and the exact
    largest one for a method on a problem, with ratios corrected/largest."""

    method: str
    paper: Real
    corrected: Real
    largest: Real
    largest_attained: bool

    @property
    def ratio(self) -> Fraction | None:
        """corrected / largest as an exact rational when both are rational,
        else a float-free ``None`` (see ``ratio_interval``)."""
        if isinstance(self.corrected, Fraction) and isinstance(self.largest, Fraction) and self.largest:
            return self.corrected / self.largest
        return None

    @property
    def ratio_interval(self) -> tuple[Fraction, Fraction] | None:
        """A rational enclosure of corrected/largest (None if either is 0 or oo)."""
        lo_c, hi_c = _bounds(self.corrected)
        lo_l, hi_l = _bounds(self.largest)
        if lo_c is None or lo_l is None or lo_l <= 0:
            return None
        return lo_c / hi_l, hi_c / lo_l

    def row(self) -> dict:
        return {"method": self.method, "paper": str(self.paper), "corrected": str(self.corrected),
                "largest": str(self.largest) + ("" if self.largest_attained else " (open)"),
                "corrected/largest": _ratio_text(self)}


def _bounds(v):
    if isinstance(v, Infinity):
        return None, None
    if isinstance(v, RealAlgebraic):
        v.refine(40)
        return v.lower, v.upper
    return v, v


def _ratio_text(c: ThresholdComparison) -> str:
    """corrected/largest exactly when rational, else a certified 6-digit enclosure."""
    if c.ratio is not None:
        return str(c.ratio)
    if isinstance(c.largest, Infinity):
        return "0 (largest = oo)" if not isinstance(c.corrected, Infinity) else "1"
    interval = c.ratio_interval
    if interval is None:
        return "0" if c.corrected == 0 else "-"
    lo, hi = interval
    scale = 10**6
    return f"[{_decimal(lo, scale, floor=True)}, {_decimal(hi, scale, floor=False)}]"


def _decimal(q: Fraction, scale: int, floor: bool) -> str:
    n = q.numerator * scale // q.denominator if floor else -((-q.numerator * scale) // q.denominator)
    return f"{n // scale}.{n % scale:06d}"


def compare_thresholds(system: LinearSystem, polyhedron: Polyhedron, methods) -> list[ThresholdComparison]:
    """For each method: the paper's, the corrected and the exact largest threshold."""
    from .thresholds import steplength_threshold

    rows = []
    for m in methods:
        t = steplength_threshold(system, polyhedron, m)
        L = largest_threshold(system, polyhedron, m)
        rows.append(ThresholdComparison(m.name, t.paper, t.value, L.value, L.attained))
    return rows
