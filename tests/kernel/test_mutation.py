"""Mutation test: every field of genuine certificates is mutated; each mutant
the kernel accepts must still be TRUE, as an independent recomputation by the
engine (FLINT, PPL, HiGHS -- no kernel code) confirms.

The counts (tried, rejected, accepted-and-true) are printed; the test fails on
an accepted false mutant, and also if it would pass vacuously (too few mutants
tried, or none rejected).
"""


import copy
import json
import random
from fractions import Fraction

import pytest
from certificate_corpus import corpus

import exactinv as ei
from exactinv_check import check

pytestmark = pytest.mark.workload  # the kernel's own workload: left out at the lowest versions (.ci/run stage 3)


PER_CERTIFICATE = 160  # mutants sampled per certificate (deterministic)


def _number_mutations(s):
    if s in ("oo", "-oo"):
        return ["-oo" if s == "oo" else "oo", "0"]
    q = Fraction(s)
    return [str(q + 1), str(q - 1), str(2 * q), str(-q), "0"]


def _mutants(node, path=()):
    """(path, description, new value or DELETE) for every field of the JSON tree."""
    if isinstance(node, dict):
        for key, value in node.items():
            if key not in ("type", "format"):
                yield path, f"drop {key}", ("drop", key)
            yield from _mutants(value, path + (key,))
    elif isinstance(node, list):
        for i in range(len(node)):
            yield path, f"drop [{i}]", ("drop", i)
        if len(node) >= 2:
            yield path, "swap [0],[1]", ("swap", None)
        if node:
            yield path, "duplicate [0]", ("dup", None)
        for i, value in enumerate(node):
            yield from _mutants(value, path + (i,))
    elif isinstance(node, bool):
        yield path, "flip", ("set", not node)
    elif isinstance(node, int):
        for v in (node + 1, node - 1):
            yield path, f"{node} -> {v}", ("set", v)
    elif isinstance(node, str) and (node in ("oo", "-oo") or node.lstrip("-").replace("/", "").isdigit()):
        for v in _number_mutations(node):
            if v != node:
                yield path, f"{node} -> {v}", ("set", v)


def _apply(cert, path, op):
    cert = copy.deepcopy(cert)
    parent = cert
    for key in path[:-1] if op[0] == "set" else path:
        parent = parent[key]
    kind, arg = op
    if kind == "set":
        parent[path[-1]] = arg
    elif kind == "drop":
        del parent[arg]
    elif kind == "swap":
        parent[0], parent[1] = parent[1], parent[0]
    elif kind == "dup":
        parent.insert(0, copy.deepcopy(parent[0]))
    return cert


def _engine_value(v):
    return ei.INF if v == "oo" else (-ei.INF if v == "-oo" else (Fraction(v) if isinstance(v, str) else v))


def _same(engine_value, claimed):
    """Exact equality of an engine value with a certificate number."""
    if isinstance(claimed, dict):
        return (not isinstance(engine_value, (Fraction, type(ei.INF))) and
                ei.RealAlgebraic.from_isolating_interval(*_algebraic(claimed)) == engine_value) \
            if _irreducible(claimed) else _root_equals(engine_value, claimed)
    return engine_value == _engine_value(claimed)


def _algebraic(d):
    return [int(Fraction(c)) for c in d["poly"]], Fraction(d["interval"][0]), Fraction(d["interval"][1])


def _irreducible(d):
    import flint

    poly, _, _ = _algebraic(d)
    _, factors = flint.fmpz_poly(poly).factor()
    return len(factors) == 1 and factors[0][1] == 1 and flint.fmpz_poly(poly).degree() >= 2


def _root_equals(engine_value, d):
    """engine_value is the unique root of d's poly in its interval (reducible poly)."""
    import flint

    from exactinv.core.roots import real_roots

    poly, lo, hi = _algebraic(d)
    inside = [r for r, _ in real_roots(flint.fmpq_poly(poly)) if lo < r < hi]
    return len(inside) == 1 and inside[0] == engine_value


def _problem(cert):
    p = cert["problem"]
    m = p.get("method")
    method = ei.methods.rational(m["numerator"], m["denominator"]) if m else None
    if "A" not in p:
        return None, None, method
    return ei.LinearSystem(p["A"]), ei.Polyhedron(p["G"], p["b"]), method


def _claim_is_true(cert, claim):
    S, P, m = _problem(cert)
    kind = claim["type"]
    if kind == "gamma_star":
        return _same(ei.optimal_gamma(S, P).value, claim["value"])
    if kind == "continuous_invariance":
        return ei.continuous_invariance(S, P).holds == claim["holds"]
    if kind == "discrete_invariance":
        Ad = m.matrix(S, Fraction(claim["dt"])) if "dt" in claim else [[Fraction(x) for x in r] for r in claim["Ad"]]
        return ei.discrete_invariance(Ad, P).holds == claim["holds"]
    if kind in ("polynomial_threshold", "rational_threshold"):
        t = ei.steplength_threshold(S, P, m)
        return _same(t.value, claim["value"]) and claim.get("attained", t.attained) == t.attained
    if kind == "absolute_monotonicity_radius":
        R = ei.absolute_monotonicity_radius(m)
        return _same(R.value, claim["value"]) and claim["attained"] == R.attained
    if kind == "largest_threshold":
        L = ei.largest_threshold(S, P, m)
        return _same(L.value, claim["value"]) and claim["attained"] == L.attained
    if kind == "valid_steplengths":
        V = list(ei.valid_steplengths(S, P, m))
        ivs = claim["intervals"]
        return len(V) == len(ivs) and all(
            _same(v.lo, iv["lo"]) and _same(v.hi, iv["hi"]) and v.lo_closed == iv["lo_closed"]
            and v.hi_closed == iv["hi_closed"] for v, iv in zip(V, ivs))
    if kind == "forward_euler_threshold":
        return _same(ei.forward_euler_threshold(S, P).value, claim["value"])
    raise AssertionError(f"no truth for {kind}")


# ------------------------------------------------------------------ soundness

@pytest.mark.heavy
def test_accepted_mutants_are_true(capsys):
    rng = random.Random(20261122)
    tried = rejected = accepted_true = 0
    false_accepted = []
    for name, cert in sorted(corpus().items()):
        candidates = list(_mutants(cert))
        rng.shuffle(candidates)
        for path, what, op in candidates[:PER_CERTIFICATE]:
            mutant = _apply(cert, path, op)
            tried += 1
            if not check(json.loads(json.dumps(mutant))).ok:
                rejected += 1
                continue
            try:
                true = all(_claim_is_true(mutant, c) for c in mutant["claims"])
            except ei.ExactinvError as exc:  # the engine refuses the mutated problem: it was not a valid claim
                true = False
                what += f" (engine: {exc})"
            if true:
                accepted_true += 1
            else:
                false_accepted.append(f"{name}: {'/'.join(map(str, path))}: {what}")
    with capsys.disabled():
        print(f"\nkernel mutation test: {tried} mutants tried, {rejected} rejected, "
              f"{accepted_true} accepted and proved true, {len(false_accepted)} accepted but false")
    assert not false_accepted, "\n".join(false_accepted)
    assert tried >= 1000 and rejected >= tried // 2  # never vacuous


# ------------------------------------------------------------------ resource
# No test here is about this module's work limits: the certificate's account is tested in test_budget.py.
