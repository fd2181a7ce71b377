"""A seeded mutation fuzzer of genuine lp records with *chained* dual pieces (red team rt-chain,
tests/kernel/test_lp_duals_attacks.py): the engine's LP route with dual pieces forced on and chained
(``DualPolicy(after=0 or 1, chain=2 or 3)``), each record mutated at a chain -- two dual pieces in a row of
one facet -- one way at a time: their shared end moved (a gap or an overlap of the two y(h)'s), made an
algebraic number of the same value, or moved to the later piece's end; the chained piece's y_k replaced by
the first piece's y_k not re-expanded (valid only at the old anchor), or by the first piece's y(h) written at
the new start (Lemma D3: the identity holds, q decides); the two pieces merged (either y(h) stretched over
both), or one of them stretched over every later piece of the facet; the two pieces' vectors swapped; a dual
piece split at a rational inside it (with and without the re-expansion); a point piece inserted at the shared
end; the facet cut right after a dual piece (its last piece a dual piece ending before the horizon); and any
number of the record changed by :func:`lp_duals_fuzz.mutate`.  Every record the kernel accepts must give the
vertex route's exact valid set of its problem."""

import copy
from fractions import Fraction as F
from math import comb

from lp_duals_fuzz import METHODS, fuzz, genuine, mutate

from exactinv.validset import lp_route as engine_lp

__all__ = ["METHODS", "chains", "genuine_chain", "mutate_chain", "reexpand", "fuzz_chains"]


def _is_dual(p):
    return isinstance(p, dict) and "dual" in p


def chains(facets):
    """(facet, k): piece k is a dual piece right after a dual piece (a chained piece)."""
    return [(i, k) for i, f in enumerate(facets) for k in range(1, len(f["bases"]))
            if _is_dual(f["bases"][k]) and _is_dual(f["bases"][k - 1])]


def genuine_chain(rng, dims, shapes, tries=10**6):
    """One genuine certificate holding a chained dual piece: (problem, record, method), or None."""
    policy = engine_lp.DualPolicy(F(0), 0, rng.choice([0, 1]), 10**9, rng.choice([2, 3]))
    return genuine(rng, dims, shapes, policy=policy, wanted=chains, tries=tries)


def reexpand(ys, a1, a):
    """Lemma D3: the vectors z_k = sum_(j >= k) C(j, k) (a - a1)^(j - k) y_j of y(h) = sum_j (h - a1)^j y_j
    written in powers of h - a (lists of [row, value-string])."""
    out = []
    for k in range(len(ys)):
        z = {}
        for j in range(k, len(ys)):
            w = comb(j, k) * (a - a1) ** (j - k)
            for r, v in ys[j]:
                z[r] = z.get(r, F(0)) + w * F(v)
        out.append([[r, str(v)] for r, v in sorted(z.items()) if v != 0])
    return out


def _start(f, k):
    return F(0) if k == 0 else F(f["ends"][k - 1])


def mutate_chain(rng, problem, record, kinds=None):
    """(problem, record) with one chain changed, or None when the chosen kind does not apply (``kinds``: a
    dict counting the kinds tried)."""
    pr, rec = copy.deepcopy(problem), copy.deepcopy(record)
    facets = rec["facets"]
    where = chains(facets)
    if not where:
        return None
    i, k = rng.choice(where)
    f = facets[i]
    ends, bases = f["ends"], f["bases"]
    first, second = bases[k - 1]["dual"], bases[k]["dual"]
    if isinstance(ends[k - 1], dict) or (k >= 2 and isinstance(ends[k - 2], dict)):
        return None
    a1, a = _start(f, k - 1), F(ends[k - 1])
    kind = rng.randrange(13)
    if kinds is not None:
        kinds[kind] = kinds.get(kind, 0) + 1
    if kind == 0:  # the shared end moved: a gap or overlap between the two y(h)'s
        eps = F(rng.choice([1, -1]), 10 ** rng.randint(1, 12))
        ends[k - 1] = str(a * (1 + eps) if a else eps * eps)
    elif kind == 1:  # the shared end an algebraic number of the same value (not a rational)
        den = 10 ** rng.randint(1, 6)
        poly = [str(2 * a), "-2", str(-a), "1"]  # (h - a)(h^2 - 2)
        ends[k - 1] = {"poly": poly, "interval": [str(a - F(1, den)), str(a + F(1, den))]}
    elif kind == 2:  # the chained piece's y_k (k >= 1, or all) the first piece's, not re-expanded
        bases[k]["dual"] = ([second[0]] if rng.random() < 0.5 else []) + copy.deepcopy(first[1:]) \
            if len(first) > 1 else copy.deepcopy(first)
    elif kind == 3:  # the chained piece the first piece's y(h) written at its start (Lemma D3; q decides)
        z = reexpand(first, a1, a)
        if rng.random() < 0.5:
            z[0] = second[0]
        bases[k]["dual"] = z
    elif kind == 4:  # merged: the first piece's y(h) stretched over both
        del ends[k - 1]
        del bases[k]
    elif kind == 5:  # merged: the chained piece's y(h) stretched back to the first piece's start
        del ends[k - 1]
        del bases[k - 1]
    elif kind == 6:  # the two pieces' vectors swapped
        bases[k - 1]["dual"], bases[k]["dual"] = second, first
    elif kind == 7:  # the facet cut after the first or the chained piece (its last piece dual, before the horizon)
        cut = rng.choice([k - 1, k])
        del ends[cut + 1:]
        del bases[cut + 1:]
    elif kind == 8:  # the shared end moved to (or past) the chained piece's end
        if isinstance(ends[k], dict) or ends[k] == "oo":
            return None
        ends[k - 1] = str(F(ends[k]) * rng.choice([1, F(1) + F(1, 10 ** rng.randint(1, 9))]))
    elif kind == 9:  # a dual piece split at a rational m inside it, the second half re-expanded or not
        j = rng.choice([k - 1, k])
        if isinstance(ends[j], dict) or ends[j] == "oo":
            e = _start(f, j) + 1
        else:
            e = F(ends[j])
        s = _start(f, j)
        m = s + (e - s) * F(rng.randint(1, 15), 16)
        ys = bases[j]["dual"]
        half = reexpand(ys, s, m) if rng.random() < 0.7 else copy.deepcopy(ys)
        ends.insert(j, str(m))
        bases.insert(j + 1, {"dual": half})
    elif kind == 10:  # a point piece [a, a] inserted at the shared end: the first piece's y(h) there
        z = reexpand(first, a1, a)
        ends.insert(k - 1, str(a))
        bases.insert(k, {"dual": z if rng.random() < 0.5 else copy.deepcopy(first)})
    elif kind == 11:  # the chain runs on: the first or the chained piece absorbs every later piece of the facet
        j = rng.choice([k - 1, k])
        if j == len(bases) - 1:
            return None
        del ends[j:-1]
        del bases[j + 1:]
    else:  # any number of the record (lp_duals_fuzz.mutate: entries, rows, ends, b, A)
        return mutate(rng, problem, record)
    return pr, rec


def fuzz_chains(seed, problems, mutations, dims=(2, 3), shapes=("bounded", "rays", "lines")):
    """(tried, accepted, false accepts): mutants of genuine chained dual-piece records; a false accept is an
    accepted mutant whose valid set is not the vertex route's."""
    return fuzz(seed, problems, mutations, dims, shapes, genuine_record=genuine_chain, mutate_record=mutate_chain)
