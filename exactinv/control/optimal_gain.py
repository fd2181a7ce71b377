"""The optimal gain (issue 25): the linear feedback u = Fx that minimizes gamma* of the closed loop.

gamma*(A + BF) = min{gamma : H + gamma I >= 0, HG = G(A + BF), Hb <= 0} and
the conditions are linear in (H, F) jointly, so min over F of gamma*(A + BF)
is ONE LP (:mod:`.gain_lp`), solved by the exact LP engine and verified in Q.
Its optimal F maximizes the paper's threshold rho/gamma of every method at
once, and 1/gamma is the exact largest forward-Euler step over all linear
gains (docs/design.md, "Control: the optimal gain", with proofs).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any

import flint

from exactinv_check.format import ClaimType

from ..core.encode import encode_real, envelope, mat, vec
from ..core.scalars import INF, Infinity, Matrix, to_matrix
from ..errors import ExactinvError, InvalidInput, NotInvariant, VerificationFailed
from ..invariance.gamma_star import OptimalGamma, optimal_gamma
from ..lp import INFEASIBLE, OPTIMAL, solve_lp
from ..model import LinearSystem, Method, Polyhedron
from ..model.sets import expect_set, set_family
from ..model.validate import check_method, check_polyhedron
from ..thresholds.forward_euler import ForwardEulerThreshold
from ..thresholds.polynomial import SteplengthThreshold
from ..thresholds.steplength import steplength_threshold
from ..validset.engine import forward_euler_threshold, largest_threshold, valid_steplengths
from ..validset.results import LargestThreshold, ValidSteplengths
from .gain_lp import GainLP, gain_lp

__all__ = ["OptimalGain", "optimal_gain", "gain_problem_record"]


@dataclass(frozen=True)
class OptimalGain:
    """The gain F minimizing gamma*(A + BF) over all rational p x n matrices
    (with u = Fx in U for every x in P when ``inputs`` = U is given), exactly.

    ``holds``: some gain makes P invariant.  Then ``F`` (exact), ``gamma`` (a
    Fraction, = gamma*(A + BF)), ``H`` and ``Lambda`` (the primal certificate)
    and ``dual`` (Y, mu, nu, Z, w: the LP dual proving no gain does better).
    Otherwise ``gamma`` is INF, ``F`` is None and ``farkas`` proves that no
    linear gain makes P invariant (docs/design.md).  ``path`` is the exact LP
    engine's route.
    """

    holds: bool
    F: Matrix | None
    gamma: Fraction | Infinity
    H: Matrix | None = field(repr=False)
    Lambda: Matrix | None = field(repr=False)
    dual: dict | None = field(repr=False)
    farkas: dict | None = field(repr=False)
    A: Matrix = field(repr=False)
    B: Matrix = field(repr=False)
    polyhedron: Polyhedron = field(repr=False)
    inputs: Polyhedron | None = field(repr=False)
    path: str = field(repr=False, default="")

    # ----------------------------------------------------------- the closed loop
    @property
    def system(self) -> LinearSystem:
        """The closed loop x' = (A + BF)x (raises NotInvariant when no gain exists)."""
        self._require_gain()
        return LinearSystem.closed_loop(self.A, self.B, self.F)

    @property
    def forward_euler_step(self) -> Fraction | Infinity:
        """1/gamma: the exact largest forward-Euler step of the closed loop, and the largest over
        all linear gains (INF for gamma <= 0; 0 when no gain makes P invariant)."""
        if isinstance(self.gamma, Infinity):
            return Fraction(0)
        return INF if self.gamma <= 0 else 1 / self.gamma

    def optimal_gamma(self) -> OptimalGamma:
        """gamma* of the closed loop, recomputed by :func:`exactinv.optimal_gamma` (it equals ``gamma``).

        The mass-spring-damper x1' = x2, x2' = -x1 - x2/2 + u on
        P = {-1 <= x1 <= 1, -1 <= x1 + x2 <= 1} with -2 <= u <= 2:

        >>> g = _example()
        >>> g.F, g.system.A[1], g.optimal_gamma().value
        (((Fraction(1, 1), Fraction(-1, 2)),), (Fraction(0, 1), Fraction(-1, 1)), Fraction(1, 1))
        """
        return optimal_gamma(self.system, self.polyhedron)

    def threshold(self, method: Method) -> SteplengthThreshold:
        """The paper's threshold of ``method`` for the closed loop (:func:`exactinv.steplength_threshold`).

        >>> from exactinv.model.methods import taylor
        >>> _example().threshold(taylor(2)).value     # rho/gamma = 1/1
        Fraction(1, 1)
        """
        return steplength_threshold(self.system, self.polyhedron, check_method(method))

    def largest_threshold(self, method: Method) -> LargestThreshold:
        """The closed loop's exact largest threshold of ``method`` (:func:`exactinv.largest_threshold`).

        >>> from exactinv.model.methods import taylor
        >>> _example().largest_threshold(taylor(2)).value
        Fraction(2, 1)
        """
        return largest_threshold(self.system, self.polyhedron, check_method(method))

    def valid_steplengths(self, method: Method) -> ValidSteplengths:
        """The closed loop's exact valid set of ``method`` (:func:`exactinv.valid_steplengths`).

        >>> from exactinv.model.methods import taylor
        >>> _example().valid_steplengths(taylor(2)).intervals
        [0, 2]
        """
        return valid_steplengths(self.system, self.polyhedron, check_method(method))

    def forward_euler_threshold(self) -> ForwardEulerThreshold:
        """The closed loop's largest forward-Euler step, derived two ways (it equals 1/gamma).

        >>> _example().forward_euler_threshold().value
        Fraction(1, 1)
        """
        return forward_euler_threshold(self.system, self.polyhedron)

    def _require_gain(self) -> None:
        if not self.holds:
            raise NotInvariant("no linear gain u = Fx makes P invariant" + (" with u in U" if self.inputs else "")
                               + " (a Farkas certificate proves it: .farkas)", None)

    # ----------------------------------------------------------- certificate
    def claims(self) -> list[dict]:
        """The optimal_gain claim: F, H, Lambda and the dual (or the Farkas certificate).

        >>> g = optimal_gain([[0]], [[1]], Polyhedron.box([-1], [1]))
        >>> c = g.claims()[0]
        >>> c["holds"], c["value"], c["F"]
        (True, '0', [['0']])
        """
        claim: dict[str, Any] = {"type": ClaimType.OPTIMAL_GAIN, "holds": self.holds, "value": encode_real(self.gamma)}
        if self.holds:
            claim.update(F=mat(self.F), H=mat(self.H), Lambda=mat(self.Lambda), dual=_encoded(self.dual))
        else:
            claim["farkas"] = _encoded(self.farkas)
        claim["x"] = vec(self.polyhedron.vertices[0])  # a point of P: P is nonempty (the kernel checks it)
        return [claim]

    @property
    def certificate(self) -> dict:
        """The JSON certificate (problem A, B, G, b and the inputs E, e) for :func:`exactinv.check`."""
        return envelope(gain_problem_record(self.A, self.B, self.polyhedron, self.inputs), [self])

    def __repr__(self) -> str:
        if not self.holds:
            return "OptimalGain(holds=False: no linear gain makes P invariant; see .farkas)"
        F = "[" + ", ".join("[" + ", ".join(str(v) for v in row) + "]" for row in self.F) + "]"
        return f"OptimalGain(F={F}, gamma={self.gamma}, forward_euler_step={self.forward_euler_step})"


def gain_problem_record(A: Matrix, B: Matrix, polyhedron: Polyhedron, inputs: Polyhedron | None) -> dict:
    """The problem record of a gain certificate.

    >>> gain_problem_record(((Fraction(0),),), ((Fraction(1),),), Polyhedron.box([-1], [1]), None)
    {'A': [['0']], 'B': [['1']], 'G': [['1'], ['-1']], 'b': ['1', '1']}
    """
    record = {"A": mat(A), "B": mat(B), "G": mat(polyhedron.G), "b": vec(polyhedron.b)}
    if inputs is not None:
        record["inputs"] = {"E": mat(inputs.G), "e": vec(inputs.b)}
    return record


def _example() -> OptimalGain:
    """The mass-spring-damper of the docstrings (and notebooks/06_optimal_gain.ipynb)."""
    P = Polyhedron([[1, 0], [-1, 0], [1, 1], [-1, -1]], [1, 1, 1, 1])
    return optimal_gain([[0, 1], [-1, "-1/2"]], [[0], [1]], P, inputs=Polyhedron.box([-2], [2]))


def _encoded(parts: dict) -> dict:
    return {k: (mat(v) if k in ("Y", "Z") else vec(v)) for k, v in parts.items()}


def optimal_gain(A: Any, B: Any, polyhedron: Polyhedron, inputs: Polyhedron | None = None) -> OptimalGain:
    """min over F of gamma*(A + BF), exactly: F, gamma and their certificate.

    ``A`` (n x n, or a LinearSystem) and ``B`` (n x p) are exact matrices, ``polyhedron``
    P = {x : Gx <= b} in R^n and ``inputs`` (optional) U = {u : Eu <= e} in R^p.
    One LP in (H, F, gamma, Lambda) (:mod:`exactinv.control.gain_lp`) solved by the
    exact engine: the returned F and gamma are verified in Q, with a dual proving that no
    linear gain (within U) has a smaller gamma*, or a Farkas certificate that no linear
    gain makes P invariant (``holds == False``).  Raises :class:`~exactinv.ExactinvError`
    when gamma is unbounded below (no optimum; e.g. P a cone that an input can expand).

    The double integrator x1' = x2, x2' = u on P = {-1 <= x1 <= 1, -1 <= x1 + x2 <= 1} with
    -2 <= u <= 2 (on the facet x1 + x2 = 1 the vertex (-1, 2) needs u <= -2; with -1 <= u <= 1 no gain exists):

    >>> P = Polyhedron([[1, 0], [-1, 0], [1, 1], [-1, -1]], [1, 1, 1, 1])
    >>> g = optimal_gain([[0, 1], [0, 0]], [[0], [1]], P, inputs=Polyhedron.box([-2], [2]))
    >>> g.F, g.gamma, g.forward_euler_step
    (((Fraction(0, 1), Fraction(-1, 1)),), Fraction(1, 1), Fraction(1, 1))
    >>> g.optimal_gamma().value == g.gamma
    True
    >>> optimal_gain([[0, 1], [0, 0]], [[0], [1]], P, inputs=Polyhedron.box([-1], [1])).holds
    False
    """
    A_m = A.A if isinstance(A, LinearSystem) else to_matrix(A, "A", square=True)
    n = len(A_m)
    B_m = to_matrix(B, "B", shape=(n, None))
    expect_set(polyhedron, "polyhedron", "polyhedron")
    if polyhedron.n != n:
        raise InvalidInput(f"polyhedron: A is {n}x{n} but G has {polyhedron.n} columns")
    P = check_polyhedron(polyhedron)
    p = len(B_m[0])
    U = None
    if inputs is not None:
        if set_family(inputs) != "polyhedron":
            raise InvalidInput(f"inputs: expected an exactinv.Polyhedron U = {{u : Eu <= e}}, got {type(inputs).__name__}")
        if inputs.n != p:
            raise InvalidInput(f"inputs: B has {p} columns (inputs) but U = {{u : Eu <= e}} lives in R^{inputs.n}")
        U = check_polyhedron(inputs)
    lp = gain_lp(A_m, B_m, P.G, P.b, U.G if U else (), U.b if U else ())
    res = solve_lp(lp.A_lp, lp.equality, lp.rhs, lp.cost, lp.nonnegative)
    if res.status == OPTIMAL:
        H, F, gamma, Lam = lp.primal(res.x)
        result = OptimalGain(True, F, gamma, H, Lam, lp.dual(res.y), None, A_m, B_m, P, U, str(res.path))
        _recheck(lp, result)
        return result
    if res.status == INFEASIBLE:
        return OptimalGain(False, None, INF, None, None, None, lp.dual(res.y), A_m, B_m, P, U, str(res.path))
    raise ExactinvError("optimal_gain: gamma is unbounded below over the linear gains (the LP has a verified ray), "
                        "so no gain attains the minimum; every gain with gamma*(A + BF) <= 0 gives the paper's "
                        "threshold infinity for methods with rho > 0 (docs/design.md)")


def _recheck(lp: GainLP, result: OptimalGain) -> None:
    """The closed loop's H certificate, re-checked in Q on its own terms (HG = G(A + BF), Hb <= 0,
    H off-diagonal >= 0, H + gamma I >= 0; Lambda >= 0, Lambda G = EF, Lambda b <= e)."""
    S = LinearSystem.closed_loop(result.A, result.B, result.F)
    P, U, H, m = result.polyhedron, result.inputs, result.H, lp.m
    Hq = flint.fmpq_mat([[flint.fmpq(v.numerator, v.denominator) for v in r] for r in H])
    ok = Hq * P.G_flint == P.G_flint * S.A_flint and all(v <= 0 for v in (Hq * P.b_flint).entries())
    ok = ok and all(H[i][k] >= 0 for i in range(m) for k in range(m) if i != k)
    ok = ok and all(H[i][i] + result.gamma >= 0 for i in range(m))
    if U is not None:
        L = result.Lambda
        ok = ok and all(v >= 0 for r in L for v in r)
        ok = ok and all(sum(L[j][k] * P.G[k][c] for k in range(m)) == sum(U.G[j][k] * result.F[k][c] for k in range(lp.p))
                        for j in range(lp.q) for c in range(lp.n))
        ok = ok and all(sum(L[j][k] * P.b[k] for k in range(m)) <= U.b[j] for j in range(lp.q))
    if not ok:
        raise VerificationFailed("optimal_gain: the LP's (H, F, Lambda) failed its exact re-check")
