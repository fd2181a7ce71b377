"""The exact set {h >= 0 : every inequality >= 0, every equality = 0, D(h) != 0}.

Recomputed from scratch, trusting no claimed end.  The sweep
(:func:`_valid_set`): every positive root of the given conditions and of D
is isolated (Descartes bisection), the roots are merged in exact order, the sign of each
condition on each open cell is decided at a rational sample point and
tracked across the roots, and each root itself is decided exactly (a
condition vanishes there iff the root is one of its own).  :func:`valid_set`
runs it on D and the equalities, and on each inequality alone, and
intersects the results one inequality at a time -- skipping an inequality
proved >= 0 around the current set by Descartes' rule, which leaves the set
unchanged.  The result is the list of maximal intervals, each end exact and
marked closed or open -- what a valid-set claim must equal.
"""

from __future__ import annotations

from fractions import Fraction
from functools import cmp_to_key
from typing import Any, Sequence

from . import poly_arithmetic, polys
from .budget import MEMO_MIN_DEGREE, memo
from .failure import CheckFailure, require
from .rationals import boolean
from .reals import Real, separate


class Interval:
    """[lo, hi] with open/closed ends; hi may be +infinity (then open)."""

    __slots__ = ("lo", "hi", "lo_closed", "hi_closed")

    def __init__(self, lo: Real, hi: Real | None, lo_closed: bool, hi_closed: bool) -> None:
        self.lo, self.hi, self.lo_closed, self.hi_closed = lo, hi, lo_closed, hi_closed

    def __repr__(self) -> str:
        return f"{'[' if self.lo_closed else '('}{self.lo}, {self.hi}{']' if self.hi_closed else ')'}"


def _no_positive_root(p: Sequence[int | Fraction]) -> bool:
    """Descartes: no sign variation among the coefficients means no positive root."""
    signs = [c > 0 for c in p if c != 0]
    return all(s == signs[0] for s in signs)


def breakpoints(named: Any, bounds: Any) -> list[tuple[Real, set[Any]]]:
    """Sorted distinct positive roots of the named polynomials (those of a name
    with a bound only up to that bound), each with the set of names vanishing there."""
    roots = []
    for name, p in named:
        if _no_positive_root(p):
            continue
        for lo, hi in polys.positive_roots(p, bounds.get(name)):
            real = Real.root_in(p, lo, hi)
            if real.poly is not None:  # narrow enclosures: most comparisons then need no gcd
                real.refine_below((hi - lo) / 2**24)
            roots.append((real, name))
    roots.sort(key=cmp_to_key(lambda x, y: x[0].compare(y[0])))  # type: ignore[index]
    merged: list[Any] = []
    for real, name in roots:
        if merged and merged[-1][0].compare(real) == 0:
            merged[-1][1].add(name)
        else:
            merged.append((real, {name}))
    return merged


def _tightness(p: Any) -> Fraction:
    """p(0) relative to p's size: small for a condition close to binding at h = 0."""
    return Fraction(abs(p[0]), max(abs(c) for c in p)) if p else Fraction(0)


def valid_set(D: Sequence[Fraction], inequalities: Sequence[Sequence[int | Fraction]], equalities: Sequence[Any],
              first: Sequence[Sequence[int | Fraction]] = (), start: None = None) -> Any:
    """The maximal intervals of valid h >= 0 (see the module docstring).

    Condition by condition: V starts as {h >= 0 : D(h) != 0, every equality = 0}
    (:func:`_valid_set`), and each inequality p -- those of ``first`` first (e.g.
    the conditions of one vertex, which bound V early), then the others by
    :func:`_tightness` -- replaces V by V n {p >= 0}, an exact
    identity, so the last V is the valid set whatever the order.  Each step is
    exact: V is kept when p is proved >= 0 on an interval [a, b] around V
    (:func:`_nonnegative_on`), and otherwise intersected (:func:`_intersect`) with
    p's own valid set (every positive root of p isolated).  The order only makes
    it cheap: once V is bounded, most p are proved positive around V by
    Descartes' rule, without a root isolation.

    ``start = (V0, done)``: V0 is this function's valid set of D and the
    inequalities ``done`` alone (the same D); V then starts as V0 n {every
    equality = 0} and skips ``done`` -- the same intersection, done once."""
    done: set[Any] = set(map(tuple, start[1])) if start is not None else set()
    early = [list(p) for p in first if tuple(p) not in done]
    seen = set(map(tuple, early)) | done
    rest = sorted((list(p) for p in inequalities if tuple(p) not in seen), key=_tightness)
    V, hull = _valid_set(D, [], equalities, 0, None), None
    if start is not None:
        V = _intersect(V, start[0])
    for p in early + rest:
        if not V:
            break
        hull = hull or _hull(V)
        if _nonnegative_on(poly_arithmetic.integer_coefficients(p), *hull):
            continue  # V n {p >= 0} = V
        V, hull = _intersect(V, _valid_set([Fraction(1)], [p], [], 1, None)), None
    return V


def _hull(V: Any) -> tuple[Fraction, Fraction | None]:
    """Rationals a <= b with V inside [a, b] (b short and close above V's end); b is None
    if V is unbounded."""
    end = V[-1].hi
    if end.inf:
        return V[0].lo.bounds()[0], None
    if end.poly is not None:  # a tight enclosure of the end: most tests then need no root isolation
        end.refine_below(end.hi / 2**64)
    return V[0].lo.bounds()[0], _coarse_above(end.bounds()[1])


def _nonnegative_on(ints: Sequence[int], a: Fraction, b: Fraction | None) -> Any:
    """True proves p >= 0 on [a, b] (p as integer coefficients; b = None: on [a, oo)): p(a) >= 0
    if a = b; else p positive just right of a with no root in the open (a, b) by Descartes'
    rule (then p > 0 on (a, b), and p >= 0 at the ends by continuity); for b = None, p
    positive right of 0 with no positive root at all (coefficients of one sign).  False
    says nothing."""
    if b is None:
        return polys.sign_right_of(ints, 0) > 0 and _no_positive_root(ints)
    if a == b:
        return polys.sign_at(ints, a) >= 0
    return polys.sign_right_of(ints, a) > 0 and polys.no_root_between(ints, a, b)


def _later_start(a: Interval, b: Interval) -> tuple[Real, bool]:
    c = a.lo.compare(b.lo)
    return (a.lo, a.lo_closed) if c > 0 else (b.lo, b.lo_closed) if c < 0 else (a.lo, a.lo_closed and b.lo_closed)


def _intersect(A: Any, B: Any) -> list[Interval]:
    """The intersection of two lists of maximal intervals (ordered, disjoint), as one:
    pairwise intersections, exact comparisons of the ends.  (Maximal again: two pieces
    that touched would lie in one interval of A and one of B.)"""
    out, i, j = [], 0, 0
    while i < len(A) and j < len(B):
        a, b = A[i], B[j]
        lo, lo_closed = _later_start(a, b)
        c = a.hi.compare(b.hi)
        hi, hi_closed = ((a.hi, a.hi_closed) if c < 0 else (b.hi, b.hi_closed) if c > 0
                         else (a.hi, a.hi_closed and b.hi_closed))
        k = lo.compare(hi)
        if k < 0 or (k == 0 and lo_closed and hi_closed):
            out.append(Interval(lo, hi, lo_closed, hi_closed))
        i, j = i + (c <= 0), j + (c >= 0)
    return out


def _valid_set(D: Any, inequalities: Any, equalities: Any, exact_count: Any, top: Any) -> list[Interval]:
    """The valid set; the first exact_count inequalities (and D and the
    equalities) have all their roots isolated, the others only up to top -- sound
    when those first ones already make every h > top invalid."""
    ineq = [("i", k, list(p)) for k, p in enumerate(inequalities)]
    eq = [("e", k, list(p)) for k, p in enumerate(equalities)]
    D = poly_arithmetic.trim(D)
    named = [((kind, k), p) for kind, k, p in ineq + eq]
    if len(D) > 1:
        named.append((("D", 0), D))
    polys_by_name = dict(named)
    points = [(Real.rational(0), {name for name, p in named if poly_arithmetic.evaluate(p, Fraction(0)) == 0})]
    bounds: dict[Any, Any] = {("i", k): top for k in range(exact_count, len(inequalities))} if top is not None else {}
    points += breakpoints(named, bounds)

    def cell_sample(k: int) -> Any:
        if k + 1 < len(points):
            a1, b0 = separate(points[k][0], points[k + 1][0])
            return (a1 + b0) / 2
        return points[k][0].bounds()[1] + 1

    # signs of the inequalities on the current cell; only those vanishing at a
    # breakpoint can change sign there, so only they are re-evaluated
    sample = cell_sample(0)
    negative = {("i", k) for _, k, p in ineq if poly_arithmetic.evaluate(p, sample) < 0}
    elements = []  # (kind, index, valid): ("point", k) then ("cell", k) alternately
    eq_names = {("e", k) for _, k, _ in eq}
    for k, (_real, vanishing) in enumerate(points):
        if k == 0:  # decided by evaluation: the cell signs say nothing about h = 0 itself
            point_ok = (eq_names <= vanishing and ("D", 0) not in vanishing
                        and all(poly_arithmetic.evaluate(p, Fraction(0)) >= 0 for _, _, p in ineq))
        else:  # an inequality not vanishing here has the sign of the cell on the left
            point_ok = eq_names <= vanishing and ("D", 0) not in vanishing and not (negative - vanishing)
        elements.append(("point", k, point_ok))
        sample = cell_sample(k)
        for name in vanishing:
            if name[0] == "i":
                if poly_arithmetic.evaluate(polys_by_name[name], sample) < 0:
                    negative.add(name)
                else:
                    negative.discard(name)
        elements.append(("cell", k, not negative and not eq))
    return _intervals(points, elements)


def _intervals(points: Sequence[tuple[Real, set[Any]]], elements: Sequence[tuple[str, int, bool]]) -> list[Interval]:
    out = []
    current = None
    for kind, k, ok in elements:
        if ok and current is None:
            current = Interval(points[k][0], None, kind == "point", False)
        if ok:
            end = (kind, k)
        if not ok and current is not None:
            kind_e, k_e = end
            current.hi = points[k_e][0] if kind_e == "point" else points[k_e + 1][0]
            current.hi_closed = kind_e == "point"
            out.append(current)
            current = None
    if current is not None:
        current.hi = Real(inf=1)
        out.append(current)
    return out


def _coarse_above(x: Fraction) -> Any:
    """A dyadic rational >= x with about 64 significant bits: bisection from it
    keeps short numbers, where x itself may carry thousands of bits."""
    shift = 64 - (x.numerator.bit_length() - x.denominator.bit_length())
    return Fraction(-((-x.numerator << shift) // x.denominator), 1 << shift) if shift > 0 else \
        Fraction(-(-x.numerator // (x.denominator << -shift)) << -shift)


def _first_sign_change(p: Any, upper: Any) -> Any:
    """The first root in (0, upper] where p (positive right of 0) changes sign, or None.  Remembered for the
    certificate (budget.memo): a later call for the same p whose range reaches a sign change already found, or lies
    inside a range already found free of one, is answered without a new isolation (the first sign change does not
    depend on how far one looks beyond it; a radius claim's binding d_j is isolated once, not twice: the second
    isolation of a degree-400 d_79 cost 2.4e9 of the 4e9 budget, issue 22)."""
    ints = poly_arithmetic.integer_coefficients(p)
    # {upper (None: +oo): the answer on (0, upper]}; only high degrees are remembered (a valid set's 10^6 low-degree
    # conditions would fill memory for nothing: their isolation is cheap)
    seen = memo(("first sign change", tuple(ints)), dict) if len(ints) > MEMO_MIN_DEGREE else {}
    for searched, found in seen.items():
        if found is not None and (upper is None or found.bounds()[1] <= upper):
            return found
        if found is None and (searched is None or upper is not None and upper <= searched):
            return None
    answer = None
    for lo, hi in polys.positive_roots_ascending(p, upper):  # lazily: the roots past the first are never isolated
        if lo == hi:
            if polys.sign_right_of(p, lo) < 0:
                answer = Real.rational(lo)
                break
        elif polys.sign_at(ints, hi) < 0:  # (lo, hi) isolates the root among all of p's roots
            answer = Real.root_in(p, lo, hi)
            break
    seen[upper] = answer
    return answer


def first_end(D: Any, inequalities: Any, equalities: Any, first: Any = (), start: Any = None) -> Any:
    """(tau, attained): the end of the valid interval that starts at 0.

    tau = min over the inequalities c of sup{T : c >= 0 on [0, T]} (the first
    sign change of c, or 0 if c < 0 right after 0), over the equalities (0 if
    any is not identically zero) and over the first positive root of D (not
    attained there).  ``start = (tau0, done)``: tau0 is this function's tau of D
    and the inequalities ``done`` alone (the same D); the minimum then starts
    at tau0 and skips ``done`` -- the same minimum, taken once."""
    if equalities:
        return Real.rational(0), True
    best, attained, done = Real(inf=1), True, set()
    if start is not None:
        best, done = start[0], set(map(tuple, start[1]))
        if best.is_zero():  # one of done is < 0 right after 0 (D has no root at 0)
            return best, True
    early = set(map(tuple, first))  # e.g. one vertex's conditions: a finite bound early on
    for p in sorted((list(p) for p in inequalities if tuple(p) not in done),
                    key=lambda p: (tuple(p) not in early, _tightness(p))):
        if polys.sign_right_of(p, Fraction(0)) < 0:
            return Real.rational(0), True
        if _no_positive_root(p):
            continue
        upper = None if best.inf else _coarse_above(best.bounds()[1])
        if upper is not None and tuple(p) not in early and polys.no_root_in(p, upper):
            continue  # p > 0 on (0, best]: it cannot end the interval earlier
        # (not tried on the early ones, expected to end first: for a radius's binding d_79 of degree 400 the failed
        # test's 31 Descartes nodes cost 10 s before the isolation that was needed anyway, issue 22)
        tau = _first_sign_change(p, upper)
        if tau is not None and tau.compare(best) < 0:
            best = tau
            if best.poly is not None:  # a tight enclosure: later conditions are cleared by Descartes' rule
                best.refine_below(best.hi / 2**64)
    D = poly_arithmetic.trim(D)
    if len(D) > 1:
        roots = polys.positive_roots(D)
        if roots:
            pole = Real.root_in(D, *roots[0])
            c = pole.compare(best)
            if c <= 0:
                best, attained = pole, False
    return best, attained


def require_intervals(claimed: Any, truth: Any) -> None:
    """The claim's intervals are exactly the recomputed ones: the same number,
    each end equal as a real number, each closed/open flag equal."""
    require(isinstance(claimed, list), "intervals is a list")
    # the messages that print a Real are built only on failure: printing an algebraic end costs up to
    # 400 exact bisections (text.algebraic_text), once per interval on success before
    if len(claimed) != len(truth):
        raise CheckFailure(f"the valid set has {len(truth)} intervals, the claim {len(claimed)}: {truth}")
    for k, (iv, true) in enumerate(zip(claimed, truth)):
        require(isinstance(iv, dict) and set(iv) == {"lo", "hi", "lo_closed", "hi_closed"},
                f"interval {k}: keys lo, hi, lo_closed, hi_closed")
        if Real.parse(iv["lo"], "lo").compare(true.lo) != 0:
            raise CheckFailure(f"interval {k} starts at {true.lo}")
        if Real.parse(iv["hi"], "hi").compare(true.hi) != 0:
            raise CheckFailure(f"interval {k} ends at {true.hi}")
        require(boolean(iv["lo_closed"], "lo_closed") == true.lo_closed, f"interval {k}: wrong lo_closed")
        require(boolean(iv["hi_closed"], "hi_closed") == true.hi_closed, f"interval {k}: wrong hi_closed")
