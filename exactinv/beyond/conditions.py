"""The condition polynomials of the exact valid set (DESIGN.md section 1, beyond the paper).

A_d(dt) P is a subset of P iff A_d(dt) v is in P for every point v of a
minimal generator system of P, A_d(dt) r is in the recession cone for every
ray r, and A_d(dt) l is in the lineality space for every line l.  With
D(dt) = det h(dt A) (D = 1 for polynomial methods) and N(dt) = D(dt) A_d(dt),
a polynomial matrix, each condition is a polynomial sign condition:

    vertex v, facet j:  c(dt) = (b_j D(dt) - g_j N(dt) v) D(dt) >= 0,
    ray r,    facet j:  c(dt) = -(g_j N(dt) r) D(dt) >= 0,
    line l,   facet j:  e(dt) = g_j N(dt) l = 0.

The coefficients of all vertex-facet polynomials come from the matrix
products G A^k V (FLINT); a polynomial whose coefficient signs show no
positive root (Descartes) never binds and is skipped.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from enum import StrEnum
from fractions import Fraction

import flint

from ..core.polys import integer_part, sign_variations
from ..core.scalars import fmpq_of, fraction_of
from ..model import LinearSystem, Method, Polyhedron
from ..model.methods import matrix_polynomial

__all__ = ["Kind", "Condition", "conditions_of", "distinct_conditions"]


class Kind(StrEnum):
    """Which generator of P a condition is about (equal to the old strings)."""

    VERTEX = "vertex"
    RAY = "ray"
    LINE = "line"


@dataclass(frozen=True)
class Condition:
    """One polynomial condition: ``kind`` is "vertex", "ray" or "line";
    ``generator`` the index in P.vertices / P.rays / P.lines; ``facet`` the row
    of G; ``poly`` the coefficients (dt^0 ..) of c (>= 0 required) or e (= 0)."""

    kind: Kind
    generator: int
    facet: int
    p: flint.fmpq_poly = field(repr=False, compare=False)

    @property
    def poly(self) -> tuple[Fraction, ...]:
        return tuple(fraction_of(c) for c in self.p.coeffs())


def _evaluate_rational(method: Method, A: flint.fmpq_mat, t: Fraction, W: flint.fmpq_mat):
    """(D(t), D(t) A_d(t) W) exactly, D = det h(t A)."""
    M = A * fmpq_of(t)
    Hm = matrix_polynomial(method.denominator, M)
    D = Hm.det()
    if D == 0:
        return None
    return D, Hm.solve(matrix_polynomial(method.numerator, M) * W) * D


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


def conditions_of(system: LinearSystem, P: Polyhedron, method: Method):
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
    for kind, W in ((Kind.VERTEX, V), (Kind.RAY, R), (Kind.LINE, L)):
        if W is None:
            continue
        blocks = coefficient_blocks(W)
        entries = [blk.entries() for blk in blocks]
        cols = W.ncols()
        cheap_skip = method.is_polynomial and kind != Kind.LINE
        for j in range(P.m):
            for i in range(cols):
                idx = j * cols + i
                if cheap_skip and all(e[idx] <= 0 for e in entries[1:]) and (kind == Kind.RAY or entries[0][idx] <= b[j]):
                    continue  # every coefficient of c is >= 0: never binds (Descartes), decided before building c
                gN = [e[idx] for e in entries]  # g_j N(dt) w, coefficients
                if kind == Kind.LINE:
                    poly = flint.fmpq_poly(gN)
                    if not poly.is_zero():
                        equalities.append(Condition(kind, i, j, poly))
                    continue
                q = -flint.fmpq_poly(gN)
                if kind == Kind.VERTEX:
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


def distinct_conditions(conditions: list[Condition]) -> dict[tuple, Condition]:
    """The conditions with distinct polynomials (up to a positive factor), first kept."""
    seen: dict[tuple, Condition] = {}
    for c in conditions:
        key = tuple(int(x) for x in integer_part(c.p).coeffs())
        if key not in seen:
            seen[key] = c
    return seen
