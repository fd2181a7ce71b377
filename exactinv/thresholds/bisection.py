"""The paper's own algorithm for the first positive zero (Section 3.1.2).

A faithful transcription of Steps 0-5 -- Sturm-sequence root counting plus
bisection -- kept as a *reference* to compare against and to reproduce
erratum E3, not as exactinv's engine (that is :func:`exactinv.roots.first_sign_change`).
It is given in two arithmetics: exact (Fractions, FLINT polynomials) and
plain floats (numpy), the way a reader of the paper would implement it.

The input is f(t) = 1 + alpha_1 t + ... + alpha_q t^q (f(0) = 1, alpha_q != 0).
Step 0 sets t* = alpha*/alpha_q + 1 from the bound lemma (Lemma 3.6), which
assumes alpha_q > 0; for alpha_q < 0 this t* is <= 0 and Step 2 returns
tau = infinity although f has a positive root (erratum E3: f(t) = 1 - t gives
infinity instead of 1).  ``repaired=True`` uses Cauchy's bound
1 + alpha*/|alpha_q| instead, which bounds every root for either sign.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction
from typing import Any, Sequence

import flint
import numpy as np

from ..core.flintq import fmpq_of
from ..core.float_hint import float_hints
from ..core.scalars import INF, Infinity, to_rational, to_vector
from ..core.tags import BisectionStep
from ..errors import InvalidInput

__all__ = ["PaperBisectionResult", "paper_bisection", "paper_bisection_float", "paper_bound"]


@dataclass(frozen=True)
class PaperBisectionResult:
    """tau as the paper's algorithm returns it, the step that terminated, the
    final bracket [t_l, t_r] and the number of Sturm evaluations."""

    tau: Fraction | float | Infinity
    terminated_by: BisectionStep
    t_l: Fraction | float
    t_r: Fraction | float
    sturm_counts: int


def _normalised(alphas: Sequence[Any]) -> tuple[Fraction, ...]:
    a = to_vector(alphas, "f")
    if a[0] != 1:
        raise InvalidInput(f"f: the paper's algorithm needs f(0) = 1, got f(0) = {a[0]}")
    while len(a) > 1 and a[-1] == 0:
        a = a[:-1]
    if len(a) < 2:
        raise InvalidInput("f: the paper's algorithm needs degree q >= 1 (alpha_q != 0)")
    return a


def paper_bound(alphas: Sequence[Any], repaired: bool = False) -> Fraction:
    """t* of the bound lemma: alpha*/alpha_q + 1 (as printed), or Cauchy's
    1 + alpha*/|alpha_q| (``repaired``), with alpha* = max(1, |alpha_1|, ..., |alpha_{q-1}|).

    >>> paper_bound([1, -3, 2])   # alpha* = max(1, |-3|) = 3: t* = 3/2 + 1
    Fraction(5, 2)
    >>> paper_bound([1, -3, -2], repaired=True)   # Cauchy: 1 + 3/|-2|
    Fraction(5, 2)
    """
    a = _normalised(alphas)
    alpha_star = max([Fraction(1)] + [abs(x) for x in a[1:-1]])
    alpha_q = a[-1]
    return alpha_star / (abs(alpha_q) if repaired else alpha_q) + 1


def paper_bisection(alphas: Sequence[Any], epsilon: Any = Fraction(1, 2**30), repaired: bool = False) -> PaperBisectionResult:
    """Steps 0-5 of the paper in exact arithmetic.  ``alphas`` = [1, alpha_1, ..., alpha_q].

    >>> res = paper_bisection([1, -3, 2])   # 1 - 3t + 2t^2 = (1 - t)(1 - 2t): first root 1/2
    >>> res.tau < Fraction(1, 2) <= res.tau + Fraction(1, 2**30), res.terminated_by   # Step 5 returns t_l
    (True, 'step 5')
    """
    a = _normalised(alphas)
    eps = to_rational(epsilon, "epsilon")
    f = flint.fmpq_poly([fmpq_of(x) for x in a])
    seq = [f, f.derivative()]
    while not seq[-1].is_zero():
        seq.append(-(seq[-2] % seq[-1]))
    seq.pop()
    zero = fmpq_of(Fraction(0))
    v0 = _variations([s(zero) for s in seq])
    counts = 0

    def count(delta: Fraction) -> int:  # #f[delta]: distinct zeros in (0, delta]
        nonlocal counts
        counts += 1
        return v0 - _variations([s(fmpq_of(delta)) for s in seq])

    return _steps(a, f=lambda t: f(fmpq_of(t)), count=count, t_star=paper_bound(a, repaired), eps=eps,
                  half=lambda t: t / 2, mid=lambda l, r: (l + r) / 2, one=Fraction(1), counts=lambda: counts)


def paper_bisection_float(alphas: Sequence[Any], epsilon: float = 2.0**-30, repaired: bool = False) -> PaperBisectionResult:
    """Steps 0-5 of the paper in double precision (numpy polynomial division
    for the Sturm sequence); what a float implementation of the paper gives.

    >>> res = paper_bisection_float([1, -3, 2])
    >>> abs(res.tau - 0.5) < 1e-8, res.terminated_by
    (True, 'step 5')
    """
    a = float_hints(_normalised(alphas)).tolist()
    if not all(math.isfinite(x) for x in a):
        raise InvalidInput("alphas: a normalised coefficient is beyond the double range; the float algorithm "
                           "cannot represent it (use paper_bisection, exact)")
    f = np.polynomial.Polynomial(a)
    seq = [f, f.deriv()]
    while seq[-1].degree() > 0 or abs(seq[-1].coef[0]) > 0:
        _, r = divmod(seq[-2], seq[-1])
        r = r.trim(tol=1e-14 * max(1.0, max(abs(c) for c in seq[-2].coef)))
        if r.degree() == 0 and r.coef[0] == 0:
            break
        seq.append(-r)
        if seq[-1].degree() == 0:
            break
    v0 = _variations([s(0.0) for s in seq])
    counts = 0

    def count(delta: float) -> int:
        nonlocal counts
        counts += 1
        return v0 - _variations([s(delta) for s in seq])

    alpha_star = max([1.0] + [abs(x) for x in a[1:-1]])
    t_star = alpha_star / (abs(a[-1]) if repaired else a[-1]) + 1
    return _steps(a, f=lambda t: f(t), count=count, t_star=t_star, eps=float(epsilon),
                  half=lambda t: t / 2, mid=lambda l, r: (l + r) / 2, one=1.0, counts=lambda: counts)


def _variations(values) -> int:
    signs = [v > 0 for v in values if v != 0]
    return sum(1 for x, y in zip(signs, signs[1:]) if x != y)


def _steps(a, *, f, count, t_star, eps, half, mid, one, counts) -> PaperBisectionResult:
    # Step 0: t° = 1, halve until #f[t°] = 0.
    t0 = one
    while count(t0) != 0:
        t0 = half(t0)
    # Step 1.
    t_l, t_r = t0, t_star
    # Step 2 [Termination 1].
    n_r = count(t_r)
    if n_r == 0:
        return PaperBisectionResult(INF, BisectionStep.STEP_2, t_l, t_r, counts())
    # Step 3 [Termination 2].
    if n_r == 1 and f(t_r) == 0:
        return PaperBisectionResult(t_star, BisectionStep.STEP_3, t_l, t_r, counts())
    # Step 4 [Bisection].
    while abs(t_l - t_r) >= eps:
        t_m = mid(t_l, t_r)
        n_m = count(t_m)
        if n_m == 1 and f(t_m) == 0:
            return PaperBisectionResult(t_m, BisectionStep.STEP_4, t_l, t_r, counts())
        if n_m >= 1:
            t_r = t_m
        else:
            t_l = t_m
    # Step 5 [Termination 4].
    return PaperBisectionResult(t_l, BisectionStep.STEP_5, t_l, t_r, counts())
