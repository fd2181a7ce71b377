"""Certificate version 3 (exactinv_check/sparse.py): H and H~ by rows, nonzero entries only.

* the engine writes version 3 and the kernel verifies it, claim type by claim type;
* the same certificates rewritten as version 2 and version 1 (H dense) still verify;
* forged sparse matrices are rejected: an index out of range, a negative, bool, string or
  float index, a repeated or unsorted column, an explicit zero in any spelling, a wrong entry,
  a missing, extra or removed entry, a missing or extra row, a malformed pair, an unknown key,
  a dense H in version 3 and a sparse H in version 2;
* the reader is the dense definition: random matrices, encoded sparse, read back equal.
"""


from __future__ import annotations

import copy
import json
import random
from fractions import Fraction as F

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from versions import as_version, dense_of

import exactinv as ei
from exactinv import forward_euler_threshold
from exactinv import methods as M
from exactinv.certificates import certificate
from exactinv.core.encode import sparse_of_dense
from exactinv_check import check
from exactinv_check.failure import CheckFailure
from exactinv_check.sparse import read_square, sparse_matrix

ROT = ei.LinearSystem([[-1, 1], [-1, -1]])


BOX = ei.Polyhedron.box([-1, -1], [1, 1])


HEX = ei.Polyhedron.from_vertices([(2, 0), (1, 2), (-1, 2), (-2, 0), (-1, -2), (1, -2)])


def _certificates():
    """Engine certificates with an H or H~ in every claim type that has one."""
    S, P = ROT, BOX
    out = {
        "gamma_star+forward_euler": forward_euler_threshold(S, HEX).certificate,
        "polynomial threshold": ei.steplength_threshold(S, P, M.taylor(3)).certificate,
        "rational threshold": ei.steplength_threshold(S, P, M.trapezoid()).certificate,
        "continuous invariance": certificate(S, P, None, [ei.continuous_invariance(S, P)]),
        "discrete invariance (Ad)": certificate(S, P, None, [ei.discrete_invariance([[0, 1], [-1, 0]], P)]),
        "discrete invariance (dt)": certificate(S, P, M.taylor(3), [ei.discrete_invariance(S, P, M.taylor(3), F(1, 2))]),
        "robust threshold": ei.robust_threshold([ei.LinearSystem([[-1]]), ei.LinearSystem([[-2]])],
                                                ei.Polyhedron.box([-1], [1]), M.taylor(2)).certificate,
    }
    # gamma* = -oo with an H (the line x1 = 0): the rational threshold's own H (E2 on the unpushed rows)
    line = ei.Polyhedron([[1, 0], [-1, 0]], [0, 0])
    out["rational threshold, own H"] = ei.steplength_threshold(ei.LinearSystem([[-1, 0], [0, -1]]), line,
                                                                M.backward_euler()).certificate
    return out


CERTS = _certificates()


def _has_sparse(cert):
    text = json.dumps(cert)
    return '"sparse"' in text


def _H(cert):
    return next(c for c in cert["claims"] if c["type"] == "gamma_star")["H"]


def _forged(mutate, name="gamma_star+forward_euler"):
    cert = copy.deepcopy(CERTS[name])
    mutate(_H(cert)["sparse"], cert)
    return check(cert)


def _add_entry(row, m, value):
    """A new nonzero entry in a column the row does not list (kept sorted)."""
    present = {k for k, _ in row}
    row.append([next(k for k in range(m) if k not in present), value])
    row.sort(key=lambda pair: pair[0])


FORGERIES = {
    "index out of range": (lambda rows, c: rows[0].append([len(rows), "1"]), "out of range"),
    "negative index": (lambda rows, c: rows[0].insert(0, [-1, "1"]), "out of range"),
    "bool index": (lambda rows, c: rows[0].__setitem__(0, [True, rows[0][0][1]]), "not a JSON integer"),
    "string index": (lambda rows, c: rows[0].__setitem__(0, [str(rows[0][0][0]), rows[0][0][1]]), "not a JSON integer"),
    "float index": (lambda rows, c: rows[0].__setitem__(0, [float(rows[0][0][0]), rows[0][0][1]]), "not a JSON integer"),
    "duplicate entry": (lambda rows, c: rows[0].append(list(rows[0][-1])), "repeats or is out of order"),
    "duplicate column, other value": (lambda rows, c: rows[0].append([rows[0][-1][0], "1"]), "repeats or is out of order"),
    "unsorted row": (lambda rows, c: rows[0].reverse() if len(rows[0]) > 1 else None, "repeats or is out of order"),
    "wrong entry": (lambda rows, c: rows[0][0].__setitem__(1, str(F(rows[0][0][1]) + F(1, 7))), ""),
    "entry removed": (lambda rows, c: rows[0].pop(), ""),
    "entry added": (lambda rows, c: _add_entry(rows[0], len(rows), "1/1000"), ""),
    "missing row": (lambda rows, c: rows.pop(), "expected"),
    "extra row": (lambda rows, c: rows.append([]), "expected"),
    "empty row": (lambda rows, c: rows.__setitem__(0, []), ""),
    "pair of three": (lambda rows, c: rows[0][0].append("0"), "pair"),
    "pair as object": (lambda rows, c: rows[0].__setitem__(0, {"k": rows[0][0][0], "v": rows[0][0][1]}), "pair"),
    "row not a list": (lambda rows, c: rows.__setitem__(0, {"0": "1"}), "not a list"),
    "value a float": (lambda rows, c: rows[0][0].__setitem__(1, 0.5), "exact number"),
    "value not a number": (lambda rows, c: rows[0][0].__setitem__(1, "1e3"), "not an exact rational"),
    "unknown key": (lambda rows, c: _H(c).__setitem__("shape", [len(rows), len(rows)]), "nothing else"),
    "rows not a list": (lambda rows, c: _H(c).__setitem__("sparse", {"0": rows[0]}), "list of rows"),
}


@st.composite
def matrices(draw):
    m = draw(st.integers(0, 6))
    entry = st.one_of(st.just(F(0)), st.fractions(max_denominator=10**12).filter(lambda q: abs(q) < 10**15))
    return [[draw(entry) for _ in range(m)] for _ in range(m)]


# ------------------------------------------------------------------ soundness

@pytest.mark.parametrize("name", sorted(CERTS))
def test_the_engine_writes_version_3_and_the_kernel_verifies_it(name):
    cert = CERTS[name]
    assert cert["version"] == 3 and _has_sparse(cert)
    assert check(copy.deepcopy(cert)).ok, check(copy.deepcopy(cert))


@pytest.mark.parametrize("name", sorted(CERTS))
def test_versions_1_and_2_still_verify(name):
    v2 = as_version(CERTS[name], 2)
    assert not _has_sparse(v2)
    assert check(v2).ok, check(v2)
    v1 = as_version(CERTS[name], 1)
    for claim in v1["claims"]:
        claim.pop("dt", None)  # a version 2 key; the stated Ad is the version 1 claim
    if all("Ad" in c or c["type"] != "discrete_invariance" for c in v1["claims"]):
        assert check(v1).ok, check(v1)


def test_the_encodings_do_not_mix():
    cert = CERTS["polynomial threshold"]
    dense_in_v3 = as_version(cert, 2)
    dense_in_v3["version"] = 3
    report = check(dense_in_v3)
    assert not report.ok and "version 3 matrix" in str(report)
    sparse_in_v2 = copy.deepcopy(cert)
    sparse_in_v2["version"] = 2
    report = check(sparse_in_v2)
    assert not report.ok and "expected a list of rows" in str(report)


@pytest.mark.parametrize("name", sorted(FORGERIES))
def test_forged_sparse_matrices_are_rejected(name):
    mutate, message = FORGERIES[name]
    report = _forged(mutate)
    assert not report.ok, name
    assert message in str(report), str(report)


@pytest.mark.parametrize("spelling", ["0", "-0", "+0", "0/5", "0.0", "-0.000", 0])
def test_an_explicit_zero_is_rejected_in_every_spelling(spelling):
    """Absent entries are the zeros: a listed zero (which would change no product) is still rejected."""
    report = _forged(lambda rows, cert: _add_entry(rows[0], len(rows), spelling))
    assert not report.ok and "explicit zero" in str(report), str(report)


def test_forged_h_tilde_and_robust_vertices_are_rejected():
    cert = copy.deepcopy(CERTS["discrete invariance (dt)"])
    rows = cert["claims"][0]["H"]["sparse"]
    rows[1][0][1] = str(F(rows[1][0][1]) * 2)
    assert not check(cert).ok
    cert = copy.deepcopy(CERTS["discrete invariance (Ad)"])
    cert["claims"][0]["H"]["sparse"][0].append([0, "0"])
    cert["claims"][0]["H"]["sparse"][0].sort()
    assert "explicit zero" in str(check(cert))
    cert = copy.deepcopy(CERTS["robust threshold"])
    vertex = cert["claims"][-1]["vertices"][0]
    vertex["H"]["sparse"][0][0][0] = 5
    assert "out of range" in str(check(cert))
    cert = copy.deepcopy(CERTS["rational threshold, own H"])
    own = next(c for c in cert["claims"] if c["type"] == "rational_threshold")["H"]["sparse"]
    own.pop()
    assert not check(cert).ok


@settings(max_examples=200, deadline=None)
@given(matrices())
def test_the_reader_is_the_dense_definition(M):
    """encode sparse (engine) -> JSON -> read (kernel) gives the nonzero entries of M, by row,
    and the version 2 reader of the dense M gives the same."""
    m = len(M)
    encoded = json.loads(json.dumps(sparse_of_dense(M)))
    rows = read_square(encoded, "H", m, 3)
    assert rows == [[(k, x) for k, x in enumerate(row) if x] for row in M]
    assert read_square([[str(x) for x in row] for row in M], "H", m, 2) == rows
    assert [[F(v) for v in row] for row in dense_of(encoded)] == M


def test_random_forgeries_of_indices_are_rejected():
    rng = random.Random(24)
    base = CERTS["gamma_star+forward_euler"]
    for _ in range(60):
        cert = copy.deepcopy(base)
        rows = _H(cert)["sparse"]
        i = rng.randrange(len(rows))
        if not rows[i]:
            continue
        t = rng.randrange(len(rows[i]))
        rows[i][t][0] = rng.choice([rows[i][t][0] + len(rows), -1 - rng.randrange(5), len(rows)])
        assert not check(cert).ok


# ------------------------------------------------------------------ resource

def test_a_huge_sparse_matrix_is_priced_before_its_numbers_are_parsed():
    """1000 rows of 200 entries of 4000-digit strings: rejected by the price of reading them
    (entries x words^2, over the certificate's budget), before one number is parsed."""
    m, big = 1000, "7" * 4000
    value = {"sparse": [[[k, big] for k in range(200)] for _ in range(m)]}
    from exactinv_check import budget, rationals
    parsed = []
    real = rationals.rational
    with budget.account() as acc:
        import exactinv_check.sparse as sparse
        sparse.rational = lambda *a: parsed.append(1) or real(*a)
        try:
            with pytest.raises(CheckFailure, match="numbers of up to 4000 digits"):
                sparse_matrix(value, "H", m, m)
        finally:
            sparse.rational = real
        assert not parsed and acc.spent <= budget.sparse_read_cost(200 * m, 1)  # only the count was charged
