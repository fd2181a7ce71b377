"""A certificate's argument in words a referee can follow (``exactinv explain``)."""

from __future__ import annotations

from typing import Any

__all__ = ["explain"]


def _real(v: Any) -> str:
    if isinstance(v, dict):
        poly = " + ".join(f"{c} t^{k}" for k, c in enumerate(v["poly"]) if c != "0")
        return f"the unique root of {poly} in ({v['interval'][0]}, {v['interval'][1]})"
    return {"oo": "infinity", "-oo": "minus infinity"}.get(v, v)


def _matrix(M) -> str:
    return "[" + "; ".join(", ".join(row) for row in M) + "]"


def explain(cert: dict) -> str:
    """Explain every claim of a certificate (no verification: run ``exactinv check``)."""
    p = cert["problem"]
    lines = [
        f"Problem: x' = A x with A = {_matrix(p['A'])}, P = {{x : G x <= b}} with G = {_matrix(p['G'])}, b = [{', '.join(p['b'])}].",
    ]
    if p.get("method"):
        m = p["method"]
        lines.append(f"Method {m['name']}: r(z) = g(z)/h(z), g = [{', '.join(m['numerator'])}], h = [{', '.join(m['denominator'])}] (coefficients from z^0).")
    for k, c in enumerate(cert["claims"], 1):
        kind = c["type"]
        lines.append("")
        lines.append(f"Claim {k} ({kind}).")
        if kind == "gamma_star" and c["value"] not in ("oo", "-oo"):
            j = c["binding_row"]
            lines.append(
                f"gamma* = {c['value']}.  Upper bound: the matrix H = {_matrix(c['H'])} has nonnegative off-diagonal "
                f"entries, satisfies HG = GA and Hb <= 0, and H + gamma* I >= 0, so gamma* is feasible.  Lower bound: "
                f"row {j} of any feasible H is a vector h with h_k >= 0 (k != {j}), h^T G = g_{j}^T A and h^T b <= 0; "
                f"the dual vector y = [{', '.join(c['dual']['y'])}] and lambda = {c['dual']['lambda']} satisfy "
                f"g_k.y + lambda b_k >= 0 for k != {j}, = 1 for k = {j}, so h_{j}{j} <= (A^T g_{j}).y = -gamma*; "
                f"no gamma below {c['value']} is feasible (LP duality).  By Lemma 3.14, 1/gamma* is the largest forward-Euler step.")
        elif kind == "gamma_star" and c["value"] == "oo":
            w = c["witness"]
            lines.append(f"P is not invariant: x = [{', '.join(w['x'])}] lies in P on facet {w['facet']} (g.x = b) and "
                         f"g_{w['facet']}.A x = {w['value']} > 0, so the flow leaves P there; gamma* = infinity.")
        elif kind == "gamma_star":
            lines.append("gamma* = -infinity: every row LP is unbounded; each row comes with a feasible h and a ray "
                         "that increases h_jj without bound.")
        elif kind == "polynomial_threshold":
            lines.append(
                f"Theorem 3.4: with H^ = H + gamma* I >= 0, r(dt H) = sum_i f_i(dt) H^i, so r(dt H) >= 0 while every f_i >= 0.  "
                f"For each i the certificate gives f_i at gamma* and tau_i = sup{{T : f_i >= 0 on [0, T]}} "
                f"(checked by Sturm sequences of the odd-multiplicity part of f_i); tau = min_i tau_i = {_real(c['value'])}.")
        elif kind == "absolute_monotonicity_radius":
            lines.append(f"The radius of absolute monotonicity (with j = 0, erratum E1) is {_real(c['value'])}; reason: {c['reason']}.")
        elif kind == "rational_threshold":
            lines.append(
                f"Theorem 3.12 with the convergence condition of erratum E2: tau = min(rho/gamma*, z_p/alpha(H)) = "
                f"{_real(c['value'])} (rho = {_real(c['rho'])}, smallest positive pole z_p = {_real(c['pole']) if c['pole'] else 'none'}, "
                f"spectral abscissa alpha(H) = {_real(c['alpha']) if c['alpha'] else 'not needed'}); "
                f"{'attained' if c['attained'] else 'valid on [0, tau) only'}.")
        elif kind == "largest_threshold":
            b = c.get("binding")
            how = (f"the condition of {b['kind']} {b['generator']} and facet {b['facet']} changes sign at tau"
                   if b else "r(dt A) becomes singular at tau")
            lines.append(
                f"The exact largest threshold is {_real(c['value'])} ({'attained' if c['attained'] else 'not attained'}).  "
                f"A_d(dt) P is inside P iff each of the {len(c['vertices'])} vertices (and rays/lines) is mapped into P (its "
                f"recession cone, lineality space); each vertex-facet pair is a polynomial inequality in dt, all of which hold "
                f"on [0, tau], and {how}.")
        elif kind in ("continuous_invariance", "discrete_invariance"):
            lines.append(f"{kind.replace('_', ' ')}: {'holds, certificate matrix given' if c['holds'] else 'fails, witness point given'}.")
        else:
            lines.append(f"(no explanation for claim type {kind})")
    lines.append("")
    lines.append("Run `exactinv check` on this file to re-verify every claim with the standard-library checker.")
    return "\n".join(lines)
