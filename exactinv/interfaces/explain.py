"""A certificate's argument in words a referee can follow (``exactinv explain``).

:func:`explain` narrates; it does not verify.  The command line runs the
trusted kernel first and refuses to narrate a certificate it rejects.
"""

from __future__ import annotations

from fractions import Fraction
from typing import Any

from exactinv_check.format import INFINITY, NEG_INFINITY, ClaimType

from ..core.digits import decimal_text, rational_text, root_text, significant_digits
from ..core.polys import poly_text

__all__ = ["explain"]


def _q(text: str) -> Fraction:
    return Fraction(text)


def _digits(poly: list, lo: Fraction, hi: Fraction) -> str | None:
    """Certified significant digits of the root of ``poly`` in (lo, hi) by exact bisection (None if p(lo) p(hi) >= 0)."""
    cs = [_q(c) for c in poly]

    def sign(x: Fraction) -> int:
        v = Fraction(0)
        for c in reversed(cs):
            v = v * x + c
        return (v > 0) - (v < 0)

    s_lo = sign(lo)
    if s_lo * sign(hi) >= 0:
        return None
    for _ in range(400):
        text = significant_digits(lo, hi, 17) if (lo > 0 or hi < 0) else None
        if text is not None:
            return text
        mid = (lo + hi) / 2
        s = sign(mid)
        if s == 0:
            return significant_digits(mid, mid, 17)
        lo, hi = (mid, hi) if s == s_lo else (lo, mid)
    return None


def _real(v: Any) -> str:
    """An exact value of a certificate in words."""
    if v is None:
        return "none"
    if isinstance(v, dict):  # the one number format (exactinv.core.digits), as reports and the kernel print
        coeffs = [_q(c) for c in v["poly"]]
        poly = poly_text(coeffs if coeffs[-1] > 0 else [-c for c in coeffs])
        lo, hi = _q(v["interval"][0]), _q(v["interval"][1])
        digits = _digits(v["poly"], lo, hi)
        if digits is None:
            return f"the root of {poly} in [{decimal_text(lo)}, {decimal_text(hi)}]"
        return root_text(digits, poly, lo, hi)
    if v in (INFINITY, NEG_INFINITY):
        return {INFINITY: "infinity", NEG_INFINITY: "minus infinity"}[v]
    return rational_text(_q(v))


def _vec(v) -> str:
    return "[" + ", ".join(v) + "]"


def _matrix(M) -> str:
    """A dense matrix as [a, b; c, d]; a version 3 sparse one by its nonzero entries (counted when many).

    >>> _matrix([["1", "0"], ["0", "2"]]), _matrix({"sparse": [[[0, "1"]], [[1, "2"]]]})
    ('[1, 0; 0, 2]', '(the 2 x 2 matrix with nonzero entries (0, 0): 1, (1, 1): 2)')
    """
    if isinstance(M, dict):
        rows = M["sparse"]
        entries = [(i, k, v) for i, row in enumerate(rows) for k, v in row]
        if len(entries) > 12:
            return f"(a {len(rows)} x {len(rows)} matrix with {len(entries)} nonzero entries)"
        listed = ", ".join(f"({i}, {k}): {v}" for i, k, v in entries)
        return f"(the {len(rows)} x {len(rows)} matrix with nonzero entries {listed})"
    return "[" + "; ".join(", ".join(row) for row in M) + "]"


def _count(n: int, word: str) -> str:
    return f"{n} {word}{'' if n == 1 else 's'}"


def _generators(c: dict) -> str:
    if "lp" in c:
        pieces = sum(len(f["bases"]) for f in c["lp"]["facets"])
        rays = sum(isinstance(b, dict) and "ray" in b for f in c["lp"]["facets"] for b in f["bases"])
        duals = sum(isinstance(b, dict) and "dual" in b for f in c["lp"]["facets"] for b in f["bases"])
        dual = (f"; on {_count(duals, 'dual piece')} the facet is far from binding and holds by the paper's "
                f"certificate y(dt) >= 0 with y^T G = g_i A_d(dt), y^T b <= b_i (Theorem 2.2) along the piece, "
                f"no condition" if duals else "")
        unbounded = (f"; on {_count(rays, 'ray piece')} the LP is unbounded along a ray of P, whose ray-facet "
                     f"condition fails there" if rays else "")
        lines = c["lp"].get("lines", [])
        lined = (f"; P has {_count(len(lines), 'line')} (a basis of ker G), each basis holds their rows l^T x <= 0 "
                 f"and every facet must satisfy g_i N(dt) l = 0 (the line equalities)" if lines else "")
        return (f"never listed: the LP route takes, per facet, the pieces of [0, oo) on which one basis of "
                f"max g_i A_d(dt) x over P is optimal ({pieces} pieces in all, each proved by weak duality), and the "
                f"vertex of each piece, which together decide every vertex{unbounded}{dual}{lined}")
    if "box" in c:
        lo, hi = c["box"]["lo"], c["box"]["hi"]
        count = 2 ** len(lo) if len(lo) <= 20 else f"2^{len(lo)}"
        return (f"the {count} vertices of the box {_vec(lo)} <= x <= {_vec(hi)}, never listed: the box route "
                f"takes, per row of N(dt), one vertex-facet pair per sign pattern of its entries between their roots, "
                f"which covers them all")
    n_v = len(c["vertices"])
    parts = [f"{n_v} {'vertex' if n_v == 1 else 'vertices'}"]
    if c.get("rays"):
        parts.append(_count(len(c["rays"]), "ray"))
    if c.get("lines"):
        parts.append(_count(len(c["lines"]), "line"))
    return ", ".join(parts)


def _interval(iv: dict) -> str:
    left = "[" if iv["lo_closed"] else "("
    right = "]" if iv["hi_closed"] else ")"
    return f"{left}{_real(iv['lo'])}, {_real(iv['hi'])}{right}"


def _gamma_star(c: dict) -> str:
    if c["value"] == INFINITY:
        w = c["witness"]
        return (f"P is not invariant: x = {_vec(w['x'])} lies in P on facet {w['facet']} (g.x = b) and "
                f"g_{w['facet']}.A x = {w['value']} > 0, so the flow leaves P there; gamma* = infinity.")
    if c["value"] == NEG_INFINITY:
        return ("gamma* = minus infinity: every row LP is unbounded; each row comes with a feasible h and a ray "
                "that increases h_jj without bound.")
    j = c["binding_row"]
    return (f"gamma* = {c['value']}.  Upper bound: the matrix H = {_matrix(c['H'])} has nonnegative off-diagonal "
            f"entries, satisfies HG = GA and Hb <= 0, and H + gamma* I >= 0, so gamma* is feasible.  Lower bound: "
            f"row {j} of any feasible H is a vector h with h_k >= 0 (k != {j}), h^T G = g_{j}^T A and h^T b <= 0; "
            f"the dual vector y = {_vec(c['dual']['y'])} and lambda = {c['dual']['lambda']} satisfy "
            f"g_k.y + lambda b_k >= 0 for k != {j}, = 1 for k = {j}, so h_{j}{j} <= (A^T g_{j}).y = -gamma*; "
            f"no gamma below {c['value']} is feasible (LP duality).  By Lemma 3.14, 1/gamma* is the largest "
            f"forward-Euler step.")


def _invariance(c: dict, kind: str) -> str:
    flow = "the flow x' = A x" if kind == ClaimType.CONTINUOUS_INVARIANCE else (
        f"the map x -> A_d x with A_d = {_matrix(c['Ad'])}" + (f" (dt = {c['dt']})" if c.get("dt") else ""))
    if c["holds"]:
        cond = ("HG = GA, Hb <= 0 and H has nonnegative off-diagonal entries" if kind == ClaimType.CONTINUOUS_INVARIANCE
                else "H >= 0, H G = G A_d and H b <= b")
        return (f"P is invariant under {flow}: the matrix H = {_matrix(c['H'])} satisfies {cond} "
                f"(Farkas' lemma; the paper's Theorems 2.1 and 2.2).")
    w = c["witness"]
    return (f"P is not invariant under {flow}: x = {_vec(w['x'])} lies in P and "
            + (f"on facet {w['facet']} the flow points out of P (g.A x = {w['value']} > 0)."
               if kind == ClaimType.CONTINUOUS_INVARIANCE else
               f"its image violates facet {w['facet']} (g.A_d x = {w['value']} exceeds b)."))


def _ellipsoid_claim(kind: str, c: dict) -> str:
    if kind in (ClaimType.ELLIPSOID_CONTINUOUS_INVARIANCE, ClaimType.ELLIPSOID_DISCRETE_INVARIANCE):
        continuous = kind == ClaimType.ELLIPSOID_CONTINUOUS_INVARIANCE
        M = "-(A^T Q + Q A)" if continuous else "Q - A_d^T Q A_d"
        flow = "the flow x' = A x" if continuous else (
            "the map x -> A_d x" + (f" with A_d = {_matrix(c['Ad'])}" if c.get("Ad") else "")
            + (f" (dt = {c['dt']})" if c.get("dt") else ""))
        if c["holds"]:
            return (f"E is invariant under {flow}: {M} is positive semidefinite (an exact L D L^T with D >= 0), "
                    f"so x^T Q x never increases.")
        w = c["witness"]
        return (f"E is not invariant under {flow}: the direction v = {_vec(w['v'])} has v^T ({M}) v < 0, so the "
                f"boundary point v/||v||_Q " + ("leaves E at once." if continuous else "is mapped outside E."))
    if kind == ClaimType.ELLIPSOID_FORWARD_EULER_THRESHOLD:
        return (f"The largest forward-Euler step on E is {_real(c['value'])}: the largest h with "
                f"-(A^T Q + Q A) - h A^T Q A >= 0, a generalised eigenvalue.")
    how = ("M(h) = H^T Q H - G^T Q G (G = g(hA), H = h(hA), congruent to Q - A_d^T Q A_d) is positive "
           "semidefinite iff every sum of its k x k principal minors is >= 0: n polynomial conditions in h")
    if kind == ClaimType.ELLIPSOID_LARGEST_THRESHOLD:
        return (f"The exact largest threshold on E is {_real(c['value'])} "
                f"({'attained' if c['attained'] else 'not attained'}).  {how}, all of which hold on [0, tau]"
                + (f"; condition {c['binding']} changes sign at tau." if c.get("binding") else "."))
    ivs = " U ".join(_interval(iv) for iv in c["intervals"]) or "the empty set"
    return f"The set of valid steplengths {{h >= 0 : A_d(h) E is inside E}} is exactly {ivs}.  {how}."


def _claim(kind: str, c: dict) -> str:
    if kind.startswith("ellipsoid_"):
        return _ellipsoid_claim(kind, c)
    if kind in (ClaimType.CONTINUOUS_INVARIANCE, ClaimType.DISCRETE_INVARIANCE):
        return _invariance(c, kind)
    explained = _EXPLAIN.get(kind)
    return explained(c) if explained else f"(no explanation for claim type {kind})"


def _forward_euler(c: dict) -> str:
    return (f"The largest forward-Euler step is {_real(c['value'])}"
            + ("" if c.get("attained", True) else " (not attained)") + ".  Two independent arguments agree: "
            f"1/gamma* (Lemma 3.14), and a ratio test at each generator of P ({_generators(c)}): x + dt A x "
            f"stays in P for every generator x and every facet exactly while dt is at most the smallest ratio "
            f"(b - g.x)/(g.A x) over the pairs with g.A x > 0.")


def _polynomial(c: dict) -> str:
    taus = "; ".join(f"tau_{e['i']} = {_real(e['tau'])}" for e in c.get("f") or [])
    return ("Theorem 3.4: with H^ = H + gamma* I >= 0, r(dt H) = sum_i f_i(dt) H^i, so r(dt H) >= 0 while "
            "every f_i >= 0.  For each i the certificate gives f_i at gamma* and tau_i = sup{T : f_i >= 0 on "
            "[0, T]} (checked by Sturm sequences of the odd-multiplicity part of f_i)"
            + (f": {taus}" if taus else "") + f".  tau = min_i tau_i = {_real(c['value'])}"
            + (f" (binding: f_{c['binding']})" if c.get("binding") is not None else "") + ".")


def _radius(c: dict) -> str:
    return (f"The radius of absolute monotonicity (with j = 0, erratum E1) is {_real(c['value'])} "
            f"({'attained' if c['attained'] else 'not attained'}); reason: {c['reason']}"
            + (f", smallest positive pole {_real(c['pole'])}" if c.get("pole") else "") + ".")


def _rational(c: dict) -> str:
    return (f"Theorem 3.12 with the convergence condition of erratum E2: tau = min(rho/gamma*, z_p/alpha(H)) = "
            f"{_real(c['value'])} (rho = {_real(c['rho'])}, smallest positive pole z_p = "
            f"{_real(c['pole']) if c.get('pole') else 'none'}, spectral abscissa alpha(H) = "
            f"{_real(c['alpha']) if c.get('alpha') else 'not needed'}); "
            f"{'attained' if c['attained'] else 'valid on [0, tau) only'}.")


def _largest(c: dict) -> str:
    b = c.get("binding")
    how = (f"the condition of {b['kind']} {b['generator']} and facet {b['facet']} changes sign at tau"
           if b else "r(dt A) becomes singular at tau")
    return (f"The exact largest threshold is {_real(c['value'])} ({'attained' if c['attained'] else 'not attained'}).  "
            f"A_d(dt) P is inside P iff each generator of P ({_generators(c)}) is mapped into P (vertices into P, "
            f"rays into its recession cone, lines into its lineality space); each generator-facet pair is a "
            f"polynomial inequality in dt, all of which hold on [0, tau], and {how}.")


def _valid(c: dict) -> str:
    ivs = " U ".join(_interval(iv) for iv in c["intervals"]) or "the empty set"
    return (f"The set of valid steplengths {{dt >= 0 : A_d(dt) P is inside P}} is exactly {ivs}.  Each generator "
            f"of P ({_generators(c)}) and each facet give a polynomial inequality in dt; the set is where all "
            f"of them hold (and r(dt A) exists), its ends are roots of these polynomials, and the sign of every "
            f"condition is constant between consecutive ends.")


def _gain(c: dict) -> str:
    if not c["holds"]:
        return ("No linear gain u = Fx makes P invariant for x' = (A + BF)x (within the input set, if any): the "
                "conditions H >= 0 off the diagonal, HG = G(A + BF), Hb <= 0 (and Lambda >= 0, Lambda G = EF, "
                "Lambda b <= e) are one linear system in (H, F, Lambda), and the certificate's Farkas vector "
                "combines them into 0 < 0.")
    return (f"The gain F = {_matrix(c['F'])} gives gamma*(A + BF) <= {_real(c['value'])} (its H satisfies the "
            f"invariance conditions with H + gamma I >= 0, and Lambda shows Fx in U on P), and the LP dual shows "
            f"that no linear gain does better: gamma = {_real(c['value'])} is the least gamma* over all gains, so "
            f"this F maximizes the paper's threshold rho/gamma of every method, and 1/gamma is the largest "
            f"forward-Euler step over all linear gains (docs/design.md).")


def _robust(c: dict) -> str:
    return (f"For every A in conv{{A_1, ..., A_{len(c['vertices'])}}} and under arbitrary switching, steps "
            f"dt in [0, {_real(c['value'])}{']' if c['attained'] else ')'} keep P invariant: each vertex A_i has a "
            f"proved gamma_i* with its H_i, so H = sum lambda_i H_i certifies A = sum lambda_i A_i with "
            f"gamma = max_i gamma_i = {_real(c['gamma'])}; tau = rho/gamma with rho = {_real(c['rho'])}"
            + ("" if c.get("beta") is None else
               f", capped by z_p/beta with the hull-wide spectral-abscissa bound beta = {_real(c['beta'])}"
               if _q(c["beta"]) > 0 else
               f" (no convergence cap: the hull-wide spectral-abscissa bound is beta = {_real(c['beta'])} <= 0)")
            + f".  The largest robust forward-Euler step is exactly 1/gamma = {_real(c['forward_euler'])}.")


_EXPLAIN = {
    ClaimType.OPTIMAL_GAIN: _gain,
    ClaimType.ROBUST_THRESHOLD: _robust,
    ClaimType.GAMMA_STAR: _gamma_star,
    ClaimType.FORWARD_EULER_THRESHOLD: _forward_euler,
    ClaimType.POLYNOMIAL_THRESHOLD: _polynomial,
    ClaimType.ABSOLUTE_MONOTONICITY_RADIUS: _radius,
    ClaimType.RATIONAL_THRESHOLD: _rational,
    ClaimType.LARGEST_THRESHOLD: _largest,
    ClaimType.VALID_STEPLENGTHS: _valid,
}


def explain(cert: dict, verified: bool = False) -> str:
    """Explain every claim of a certificate.  This does not verify: pass
    ``verified=True`` only after the kernel (``exactinv_check.check``) accepted it.

    >>> import exactinv as ei
    >>> from exactinv.model.record import certificate
    >>> S, P = ei.LinearSystem([[-1]]), ei.Polyhedron.box([-1], [1])
    >>> text = explain(certificate(S, P, None, [ei.forward_euler_threshold(S, P)]))
    >>> 'The largest forward-Euler step is 2' in text   # (1 - dt) x stays in [-1, 1] iff dt <= 2
    True
    """
    p = cert["problem"]
    lines = []
    if "Q" in p:
        lines.append(f"Problem: x' = A x with A = {_matrix(p['A'])}, E = {{x : x^T Q x <= 1}} with Q = {_matrix(p['Q'])}.")
    elif "B" in p:
        lines.append(f"Problem: x' = A x + B u with A = {_matrix(p['A'])}, B = {_matrix(p['B'])}, P = {{x : G x <= b}} "
                     f"with G = {_matrix(p['G'])}, b = {_vec(p['b'])}"
                     + (f", inputs U = {{u : E u <= e}} with E = {_matrix(p['inputs']['E'])}, e = {_vec(p['inputs']['e'])}"
                        if "inputs" in p else "") + ".")
    elif "hull" in p:
        lines.append(f"Problem: x' = A x for A in conv{{{', '.join(_matrix(A) for A in p['hull'])}}}, P = {{x : G x <= b}} "
                     f"with G = {_matrix(p['G'])}, b = {_vec(p['b'])}.")
    elif "A" in p:
        lines.append(f"Problem: x' = A x with A = {_matrix(p['A'])}, P = {{x : G x <= b}} with G = {_matrix(p['G'])}, "
                     f"b = {_vec(p['b'])}.")
    if p.get("method"):
        m = p["method"]
        lines.append(f"Method {m.get('name', '')}: r(z) = g(z)/h(z) with g(z) = {poly_text(m['numerator'], 'z')}, "
                     f"h(z) = {poly_text(m['denominator'], 'z')}.")
    for k, c in enumerate(cert["claims"], 1):
        kind = c["type"]
        lines.append("")
        lines.append(f"Claim {k} ({kind.replace('_', ' ')}).")
        lines.append(_claim(kind, c))
    lines.append("")
    if verified:
        lines.append(f"The trusted kernel (exactinv check) verified all {_count(len(cert['claims']), 'claim')} of this "
                     f"certificate.")
    else:
        lines.append("Not verified here: run `exactinv check` on this file to re-verify every claim with the "
                     "standard-library checker.")
    return "\n".join(lines)
