"""exactinv_check.claims_invariance, attacked: ``claims_invariance.check_H`` over the nonzero entries of
H's rows, ``claims_thresholds._ratio_tests`` (forward Euler) in integers cross-multiplied, and
``rationals.rational``'s fast path for the string "0"; plus the engine's ``gamma=`` keyword
(``exactinv.invariance.gamma_star.gamma_for``).

What held (kept as fast regressions below):

* check_H is the dense definition (HG = GA, Hb <= 0, off-diagonal >= 0) on random problems and on
  H moved along the left null space of G (y^T G = 0, so HG = GA is kept and only Hb and the signs
  decide), with zero entries spelt "0", "00", "-0", "+0", "0/5", "0.0", "-0/7" or the JSON
  integer 0: every zero spelling parses to Fraction(0), is skipped, and changes no verdict.
  Malformed spellings are still rejected.
* _ratio_tests equals the Fraction ratio tests over huge (200-bit) and tiny entries, int
  vertices, zero rows of G, n = 1, empty generator lists, rays and lines only.
* Forged forward-Euler values on genuine certificates are rejected unless equal to the truth.

No soundness hole found.  Findings, all fixed (their tests below pass):

1. RESOURCE (kernel): _ratio_tests scales A by its common denominator L and cross-multiplies
   num * best_den < best_num * den, numbers of L's size, for every vertex-facet pair, unpriced.
   A whose off-diagonal entries have distinct 3990-digit denominators (L ~ (n - 1)^2 * 13,000
   bits) on the cube [-1, 1]^n: a TRUE certificate (_fe_certificate) of 601 KB (n = 8) checks in
   148 s, 147 s of it in _ratio_tests (profiled); the Fraction version before the sparse rows: 16 s on
   the same certificate (n = 6: 9.9 s against 1.4 s).  Load ~1.5-2 on 2 cores.
2. ENGINE: optimal_gamma raises OverflowError (not an ExactinvError) when A's common denominator
   times an entry exceeds a float (gamma_batch._integers converts the scaled integers to float).
3. ENGINE (the kernel catches it): a caller-TAMPERED OptimalGamma (dataclasses.replace on a
   genuine one) passed gamma_for, and steplength_threshold returned a wrong tau (2, true 1)
   without any error; its certificate is rejected by the kernel.  Now the public functions take
   no gamma: only exactinv.certify passes the gamma* it solved itself.
"""


import dataclasses
import json
import random
from fractions import Fraction as F
from types import SimpleNamespace

import pytest
from test_kernel_attacks import _check_in_subprocess
from test_speed_paths import _ratio_reference
from versions import as_version

import exactinv as ei
from exactinv import forward_euler_threshold
from exactinv.invariance.gamma_star import optimal_gamma
from exactinv.thresholds.steplength import steplength_threshold, steplength_threshold_from_gamma
from exactinv.validset.engine import forward_euler_with_gamma
from exactinv_check import check, claims_thresholds
from exactinv_check.claims_invariance import check_H
from exactinv_check.failure import CheckFailure
from exactinv_check.rationals import rational

pytestmark = pytest.mark.workload  # the kernel's own workload: left out at the lowest versions (.ci/run stage 3)


ZERO_SPELLINGS = ["0", "-0", "+0", "0/5", "0.0", "-0/7", 0]


NOT_NUMBERS = ["0/0", "0e0", " 0", "0 ", "0.", ".0", "", "-", "0x0", "\u0660", "0_0", False, 0.0, None, ["0"],
               "00", "-00", "0/05"]  # leading zeros: rejected since issue 22 (the format is strict where it says it is)


def _dense_check_H(A, G, b, H):
    """The definition, dense: True iff HG = GA, Hb <= 0 and H's off-diagonal entries are >= 0."""
    m, n = len(G), len(A)
    HG = [[sum(H[i][k] * G[k][c] for k in range(m)) for c in range(n)] for i in range(m)]
    GA = [[sum(G[i][k] * A[k][c] for k in range(n)) for c in range(n)] for i in range(m)]
    return (HG == GA and all(sum(H[i][k] * b[k] for k in range(m)) <= 0 for i in range(m))
            and all(H[i][k] >= 0 for i in range(m) for k in range(m) if i != k))


def _left_null(G):
    """A nonzero y with y^T G = 0 (exact Gaussian elimination on G^T), or None."""
    m, n = len(G), len(G[0])
    M = [[G[k][c] for k in range(m)] for c in range(n)]
    pivots, r = [], 0
    for col in range(m):
        p = next((i for i in range(r, n) if M[i][col]), None)
        if p is None:
            continue
        M[r], M[p] = M[p], M[r]
        M[r] = [v / M[r][col] for v in M[r]]
        for i in range(n):
            if i != r and M[i][col]:
                M[i] = [a - M[i][col] * c for a, c in zip(M[i], M[r])]
        pivots.append(col)
        r += 1
    free = next((c for c in range(m) if c not in pivots), None)
    if free is None:
        return None
    y = [F(0)] * m
    y[free] = F(1)
    for i, col in enumerate(pivots):
        y[col] = -M[i][free]
    return y


def _random_problem(rng, n, m):
    q = lambda: F(rng.randint(-4, 4), rng.randint(1, 3))  # noqa: E731
    A = [[q() for _ in range(n)] for _ in range(n)]
    G = [[q() for _ in range(n)] for _ in range(m)]
    return A, G, [q() for _ in G]


def _square_certificate():
    S, P = ei.LinearSystem([[-1, 1], [-1, -1]]), ei.Polyhedron.box([-1, -1], [1, 1])
    return forward_euler_threshold(S, P).certificate


def _huge(rng):
    r = rng.random()
    if r < 0.3:
        return F(0)
    if r < 0.45:
        return F(rng.randint(-2**200, 2**200), rng.randint(1, 2**150))
    if r < 0.6:
        return F(rng.randint(-3, 3), 10 ** rng.randint(0, 40))
    return F(rng.randint(-5, 5), rng.randint(1, 7))


def _fe_certificate(n, digits, seed=1):
    """A TRUE forward-Euler certificate on the cube [-1, 1]^n for A = -n I plus off-diagonal entries:
    row 0 has n/(n - 1) (so gamma* = (n + s_0)/2 = n, binding row 0), the other rows 1/p_ik with
    distinct `digits`-digit odd p_ik (tiny, so their rows' H need no diagonal shift): H rows
    h_r = -n e_r + A_ik on the facet of e_k's sign; the dual y = e_0/2 - sum_(k>0) e_k/2, lambda = 1/2.
    A's common denominator L has about (n - 1)^2 digits-digit factors."""
    rng = random.Random(seed)
    A = [[F(-n) if i == c else F(n, n - 1) if i == 0 else F(1, rng.randint(10 ** (digits - 1), 10 ** digits) | 1)
          for c in range(n)] for i in range(n)]
    m = 2 * n
    H = [[F(0)] * m for _ in range(m)]
    for i in range(n):
        for r, offset in ((i, 0), (n + i, n)):
            H[r][r] = F(-n)
            for k in range(n):
                if k != i:
                    H[r][offset + k] = A[i][k]
    text = lambda M: [[str(v) for v in row] for row in M]  # noqa: E731
    vertices = [[str(1 - 2 * ((v >> k) & 1)) for k in range(n)] for v in range(2**n)]
    return {"format": "exactinv-certificate", "version": 2,
            "problem": {"A": text(A), "G": text([[F(int(i == c)) for c in range(n)] for i in range(n)]
                                                + [[F(-int(i == c)) for c in range(n)] for i in range(n)]),
                        "b": ["1"] * m},
            "claims": [{"type": "gamma_star", "value": str(n), "H": text(H), "binding_row": 0,
                        "dual": {"y": ["1/2"] + ["-1/2"] * (n - 1), "lambda": "1/2"}},
                       {"type": "forward_euler_threshold", "value": f"1/{n}", "vertices": vertices,
                        "rays": [], "lines": []}]}


def _interval_certificate(k, alpha=True, cyclic=False):
    """P = [-1, 1] as k copies of x <= 1 and k of -x <= 1 (m = 2k), A = -1, backward Euler.

    H pairs row i with row k + i: h_ii = -1/2, h_i,k+i = 1/2 (and symmetrically), so HG = GA = -G,
    Hb = 0, off-diagonal >= 0, gamma* = 1/2 (dual: row 0, y = 1/2, lambda = 1/2).  H is block diagonal
    with blocks [[-1/2, 1/2], [1/2, -1/2]] of eigenvalues 0 and -1: alpha(H) = 0, so no E2 bound, and
    backward Euler has rho = oo and no singular point for A = -1: tau = oo, attained.
    ``cyclic``: row k + i points to row i + 1 (mod k) instead, so H = -I/2 + C/2 with C the permutation
    matrix of one 2k-cycle: the same HG, Hb and gamma*, one strongly connected block of size m, and
    eigenvalues (w - 1)/2 for the 2k-th roots of unity w: alpha(H) = 0 again."""
    m = 2 * k
    rows = ([[[i, "-1/2"], [k + i, "1/2"]] for i in range(k)]
            + [sorted([[(i + 1) % k if cyclic else i, "1/2"], [k + i, "-1/2"]]) for i in range(k)])
    threshold = {"type": "rational_threshold", "value": "oo", "attained": True, "rho": "oo", "pole": "1"}
    if alpha:
        threshold["alpha"] = "0"
    return {"format": "exactinv-certificate", "version": 3,
            "problem": {"A": [["-1"]], "G": [["1"]] * k + [["-1"]] * k, "b": ["1"] * m,
                        "method": {"name": "backward_euler", "numerator": ["1"], "denominator": ["1", "-1"]}},
            "claims": [{"type": "gamma_star", "value": "1/2", "H": {"sparse": rows}, "binding_row": 0,
                        "dual": {"y": ["1/2"], "lambda": "1/2"}},
                       {"type": "absolute_monotonicity_radius", "value": "oo", "reason": "product",
                        "attained": True, "pole": "1"},
                       threshold]}


def _report_in_subprocess(cert, seconds, megabytes):
    """str(check(cert)) in a child limited to ``seconds`` of CPU and ``megabytes`` of address space."""
    import resource
    import subprocess
    import sys

    def limits():
        resource.setrlimit(resource.RLIMIT_CPU, (seconds, seconds + 1))
        resource.setrlimit(resource.RLIMIT_AS, (megabytes << 20, megabytes << 20))

    code = "import json, sys; from exactinv_check import check; print(check(json.load(sys.stdin)))"
    proc = subprocess.run([sys.executable, "-c", code], input=json.dumps(cert), capture_output=True, text=True,
                          timeout=30 * seconds + 60, preexec_fn=limits)
    assert proc.returncode == 0, proc.stderr[-2000:]
    return proc.stdout


# ------------------------------------------------------------------ soundness

def test_check_H_is_the_dense_definition():
    """Random H, and H = H0 + sum_i t_i e_i y^T (y in G's left null space): check_H accepts exactly
    when the dense definition holds."""
    rng = random.Random(7)
    seen = {True: 0, False: 0}
    for _ in range(400):
        n, m = rng.randint(1, 3), rng.randint(1, 5)
        A, G, b = _random_problem(rng, n, m)
        sparse = lambda: F(rng.randint(-3, 3), rng.randint(1, 3)) if rng.random() < 0.4 else F(0)  # noqa: E731
        H = [[sparse() for _ in range(m)] for _ in range(m)]
        y = _left_null(G)
        if y is not None and rng.random() < 0.7:  # make HG = GA hold, then move along y
            # A = -I makes H0 = -I satisfy HG = GA; moving H0's rows along y keeps it
            A = [[F(-1) if i == c else F(0) for c in range(n)] for i in range(n)]
            b = [abs(v) for v in b]  # H0 b = -b <= 0
            H = [[F(-1) if i == k else F(0) for k in range(m)] for i in range(m)]
            for i in range(m):
                t = F(rng.randint(-2, 2), rng.randint(1, 2)) if rng.random() < 0.3 else F(0)
                H[i] = [h + t * v for h, v in zip(H[i], y)]
        problem = SimpleNamespace(A=A, G=G, b=b, n=n, m=m)
        truth = _dense_check_H(A, G, b, H)
        seen[truth] += 1
        try:
            check_H(problem, [[(k, x) for k, x in enumerate(row) if x] for row in H])  # sparse rows
            verdict = True
        except CheckFailure:
            verdict = False
        assert verdict == truth
    assert min(seen.values()) > 20  # both verdicts exercised


def test_zero_spellings_parse_to_zero_and_bad_ones_are_rejected():
    for s in ZERO_SPELLINGS:
        assert rational(s) == 0 and isinstance(rational(s), F)
    for s in NOT_NUMBERS:
        with pytest.raises(CheckFailure):
            rational(s)
    assert rational("0") + 1 == 1 and rational("0") == 0


def test_integer_ratio_tests_on_adversarial_entries():
    """_ratio_tests against the Fraction definition: huge/tiny/zero entries, int vertices, zero rows,
    n = 1, empty generator lists."""
    rng = random.Random(11)
    for _ in range(1500):
        n = rng.randint(1, 3)
        A = [[_huge(rng) for _ in range(n)] for _ in range(n)]
        G = [[_huge(rng) for _ in range(n)] for _ in range(rng.randint(0, 5))]
        b = [_huge(rng) for _ in G]
        gens = SimpleNamespace(**{k: [[_huge(rng) for _ in range(n)] for _ in range(rng.randint(0, 3))]
                                  for k in ("vertices", "rays", "lines")})
        if rng.random() < 0.2:
            gens.vertices = [[int(v) for v in x] for x in gens.vertices]
        problem = SimpleNamespace(A=A, G=G, b=b, n=n, m=len(G))
        assert claims_thresholds._ratio_tests(problem, gens) == _ratio_reference(A, G, b, gens)


def test_forged_forward_euler_values_are_rejected():
    """Genuine forward-Euler certificates on random polygons; the value replaced by nearby ones:
    accepted only when equal to the true 1/gamma* (from the Fraction ratio tests on P's vertices)."""
    rng = random.Random(3)
    done = 0
    while done < 6:
        k = rng.randint(3, 6)
        pts = [(rng.randint(-5, 5), rng.randint(-5, 5)) for _ in range(k)] + [(0, 0)]
        try:
            P = ei.Polyhedron.from_vertices(pts)
            S = ei.LinearSystem([[rng.randint(-3, 1), rng.randint(-2, 2)], [rng.randint(-2, 2), rng.randint(-3, 1)]])
            cert = forward_euler_threshold(S, P).certificate
        except ei.ExactinvError:
            continue
        done += 1
        gens = SimpleNamespace(vertices=[list(v) for v in P.vertices], rays=[], lines=[])
        truth = _ratio_reference([list(r) for r in S.A], [list(r) for r in P.G], list(P.b), gens)
        truth = "oo" if truth is None else truth
        assert check(cert)
        for value in ["0", "1", "1/3", "oo", "2"] + ([] if truth == "oo" else [str(truth + F(1, 10**30)), str(truth * 2)]):
            forged = json.loads(json.dumps(cert))
            forged["claims"][-1]["value"] = value
            assert bool(check(forged)) == (value == str(truth)), (value, truth)


def test_the_public_thresholds_take_no_gamma():
    """Fixed (3.): gamma* is passed along only inside exactinv.certify (the private
    _forward_euler_threshold / _steplength_threshold, with the gamma* certify solved itself):
    the public functions solve it themselves and accept no caller's gamma."""
    S, P = ei.LinearSystem([[-1, 1], [-1, -1]]), ei.Polyhedron.box([-1, -1], [1, 1])
    g = optimal_gamma(S, P)
    with pytest.raises(TypeError):
        forward_euler_threshold(S, P, gamma=g)
    with pytest.raises(TypeError):
        steplength_threshold(S, P, ei.methods.taylor(2), gamma=g)
    assert steplength_threshold(S, P, ei.methods.taylor(2)).value == 1


def test_a_tampered_gamma_is_caught_by_the_kernel():
    """An OptimalGamma with a replaced value handed to the private helpers: the engine's forward
    Euler cross-check refuses it, and the kernel rejects the paper's threshold built from it."""
    S, P = ei.LinearSystem([[-1, 1], [-1, -1]]), ei.Polyhedron.box([-1, -1], [1, 1])
    fake = dataclasses.replace(optimal_gamma(S, P), value=F(1, 2))
    with pytest.raises(ei.VerificationFailed):
        forward_euler_with_gamma(S, P, fake)  # cross-checked by the valid set
    assert not check(steplength_threshold_from_gamma(ei.methods.taylor(2), fake).certificate)


def test_the_cube_certificate_is_genuine():
    assert check(_fe_certificate(3, 30))


def test_the_interval_certificate_is_true():
    """The truth of the small instance, independently: HG = GA, Hb <= 0, signs (dense definition),
    and alpha(H) = 0 from the characteristic polynomial x^k (x + 1)^k of the 2 x 2 blocks."""
    k = 3
    cert = _interval_certificate(k)
    H = [[F(0)] * (2 * k) for _ in range(2 * k)]
    for i, row in enumerate(cert["claims"][0]["H"]["sparse"]):
        for c, x in row:
            H[i][c] = F(x)
    G = [[F(g[0])] for g in cert["problem"]["G"]]
    assert _dense_check_H([[F(-1)]], G, [F(1)] * (2 * k), H)
    for i in range(k):  # the block of rows/columns {i, k + i}: trace -1, determinant 0
        block = [[H[i][i], H[i][k + i]], [H[k + i][i], H[k + i][k + i]]]
        assert block[0][0] + block[1][1] == -1 and block[0][0] * block[1][1] - block[0][1] * block[1][0] == 0
    assert check(cert).ok
    assert check(_interval_certificate(k, alpha=False)).ok
    bad = _interval_certificate(k)
    bad["claims"][2]["alpha"] = "1"  # alpha(H) is 0, not 1
    assert not check(bad).ok


def test_alpha_is_computed_block_by_block():
    """The block-diagonal H of any size: 2 x 2 blocks, alpha(H) = 0, VERIFIED (it was rejected as a degree-m
    polynomial); a false alpha is still rejected; the cyclic H of a size the kernel affords agrees (alpha = 0)."""
    assert _check_in_subprocess(_interval_certificate(1000), 20) == "OK"
    for k in (3, 40):
        for cyclic in (False, True):
            assert check(_interval_certificate(k, cyclic=cyclic)).ok
            bad = _interval_certificate(k, cyclic=cyclic)
            bad["claims"][2]["alpha"] = "-1"
            assert not check(bad).ok


def test_strongly_connected_blocks_are_the_components():
    """Tarjan's components against the definition (mutual reachability by a closure) on random sparse patterns."""
    from exactinv_check.linalg import strongly_connected_blocks

    rng = random.Random(11)
    for _ in range(200):
        n = rng.randint(1, 12)
        rows = [[(k, F(rng.choice([1, -2]))) for k in range(n) if rng.random() < 0.2] for _ in range(n)]
        reach = [[i == k or any(c == k and c != i for c, _ in rows[i]) for k in range(n)] for i in range(n)]
        for via in range(n):
            for i in range(n):
                if reach[i][via]:
                    reach[i] = [a or b for a, b in zip(reach[i], reach[via])]
        expected = sorted({tuple(k for k in range(n) if reach[i][k] and reach[k][i]) for i in range(n)})
        assert sorted(tuple(b) for b in strongly_connected_blocks(rows)) == expected


def test_mutation_fuzzer_of_version_3_certificates():
    """A small seeded run of tests/sparse_fuzz.py: genuine v3 certificates (random polygons, Taylor 1/2/4,
    trapezoid, backward Euler; continuous and discrete invariance, gamma*, thresholds, robust vertices),
    one sparse field mutated at a time; every accepted mutant is checked true by a dense Fraction check.
    (Longer runs: no false accept.)"""
    import sparse_fuzz

    count, accepted, false = sparse_fuzz.run(mutants=100, seed=3)
    assert count == 100 and not false, [what for what, _ in false]


def test_the_fuzzer_truth_check_can_fail():
    """The fuzzer's truth check is not vacuous: a genuine H with one entry changed is false, the genuine one true."""
    import sparse_fuzz

    rng = random.Random(5)
    cert = None
    while cert is None:
        cert = sparse_fuzz.genuine(rng)
    i, path = sparse_fuzz._sparse_fields(cert)[0]
    assert sparse_fuzz._truth(cert, i, path)
    rows = sparse_fuzz._get(cert["claims"][i], path)["sparse"]
    row = next(r for r in rows if r)
    row[0][1] = str(F(row[0][1]) + 1)
    assert not sparse_fuzz._truth(cert, i, path)


# ------------------------------------------------------------------ resource

def test_zero_spellings_in_H_change_no_verdict():
    """The genuine square certificate (as version 2, H dense) with its H's zeros spelt otherwise:
    verified; a zero replaced by a tiny nonzero, or by a malformed zero: rejected.  In version 3
    every spelling of zero, listed as an entry, is rejected (absent entries are the zeros)."""
    cert = _square_certificate()
    assert check(cert)
    for s in ZERO_SPELLINGS:
        forged = json.loads(json.dumps(cert))
        forged["claims"][0]["H"]["sparse"][0].append([3, s])  # row 0 lists columns 0 and 1
        assert not check(forged), s
    cert = as_version(cert, 2)
    H = cert["claims"][0]["H"]
    zeros = [(i, k) for i, row in enumerate(H) for k, v in enumerate(row) if v == "0"]
    assert zeros
    for s in ZERO_SPELLINGS[:-1]:  # the JSON integer 0 verifies too, but is outside the schema
        forged = json.loads(json.dumps(cert))
        for i, k in zeros:
            forged["claims"][0]["H"][i][k] = s
        assert check(forged), s
    for s in ["1/10000000000000000000000000", "-1/10000000000000000000000000"] + NOT_NUMBERS:
        forged = json.loads(json.dumps(cert))
        i, k = zeros[0]
        forged["claims"][0]["H"][i][k] = s
        assert not check(forged), s


def test_integer_ratio_tests_are_priced():
    """Fixed (1.): the least ratio is kept reduced (a long number times a short one per comparison)
    and the tests are priced first."""
    _check_in_subprocess(_fe_certificate(8, 3990), 6)  # an answer (verified, or rejected as over budget) in time


def test_engine_gamma_with_long_denominators():
    """Fixed (2.): gamma_batch._integers checks the sizes as integers, before any float."""
    A = [[F(-2), F(1, 10**400 + 1)], [F(0), F(-2)]]
    # on [-1, 1]^2 forward Euler keeps row i iff |1 + h a_ii| + h sum_(k != i) |a_ik| <= 1, i.e.
    # h <= 2/(-a_ii + sum |a_ik|): gamma* = max_i (-a_ii + sum_(k != i) |a_ik|)/2 = 1 + 1/(2 (10^400 + 1))
    assert optimal_gamma(ei.LinearSystem(A), ei.Polyhedron.box([-1, -1], [1, 1])).value == 1 + F(1, 2 * (10**400 + 1))


def test_a_large_sparse_H_does_not_reach_the_characteristic_polynomial():
    cert = _interval_certificate(1000, cyclic=True)  # m = 2000 in one strongly connected block
    assert len(json.dumps(cert)) < 100_000
    assert _check_in_subprocess(cert, 20) == "REJECTED"
    report = check(_interval_certificate(200, cyclic=True))  # m = 400: the degree bound, before any dense copy
    assert not report.ok and "size 400" in str(report)
    assert check(_interval_certificate(1000, alpha=False, cyclic=True)).ok  # without alpha no E2 bound (Hb = 0)


def test_a_huge_m_with_a_tiny_sparse_H_is_rejected_without_a_dense_copy():
    """m = 20000 in 0.9 MB: a dense copy would be 4 x 10^8 entries (3 GB); under 1 GB of address space
    the kernel rejects the claim for its degree, not for a MemoryError."""
    cert = _interval_certificate(10000, cyclic=True)
    assert len(json.dumps(cert)) < 1_000_000
    report = _report_in_subprocess(cert, 20, 1024)
    assert "REJECTED" in report and "size 20000" in report and "MemoryError" not in report, report
