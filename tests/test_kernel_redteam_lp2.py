"""Red team (round 2) of the LP route's lp record (exactinv_check/lp_pieces.py): the row exchange, the
packed slacks, the batched Descartes test, the end-polynomial shortcut and the horizon proof.

Resource attacks that ran for a minute before the fix, and a seeded mutation fuzzer of genuine lp
certificates whose every accepted mutation is checked against the vertex route's exact valid set."""

import copy
import json
import random
from fractions import Fraction as F
from math import factorial

import exactinv as ei
import exactinv_check
from exactinv_check import lp_pieces
from exactinv_check.budget import account
from exactinv_check.kernel import Problem
from exactinv_check.rationals import CheckFailure
from exactinv_check.reals import Real
from exactinv_check.validset import valid_set

M = ei.methods


def _digits(rng, k):
    return "9" + "".join(rng.choice("0123456789") for _ in range(k - 1))


def _box_certificate(n, ends):
    """A box [-1, 1]^n, A = -I, Taylor of degree n - 2 (even when n is: no real root, so every z_B > 0),
    facet 0 with the given ends, all on the basis of the vertex (1, ..., 1)."""
    G = [[int(i == j) for j in range(n)] for i in range(n)] + [[-int(i == j) for j in range(n)] for i in range(n)]
    facets = [{"ends": ends, "bases": [list(range(n))] * len(ends)}] + \
        [{"ends": ["1"], "bases": [list(range(n))]} for _ in range(2 * n - 1)]
    return {"format": "exactinv-certificate", "version": 2,
            "problem": {"A": [[-int(i == j) for j in range(n)] for i in range(n)], "G": G, "b": [1] * (2 * n),
                        "method": {"name": "taylor", "numerator": [str(F(1, factorial(k))) for k in range(n - 1)],
                                   "denominator": ["1"]}},
            "claims": [{"type": "valid_steplengths", "lp": {"facets": facets},
                        "intervals": [{"lo": "0", "hi": "1", "lo_closed": True, "hi_closed": True}]}]}


def test_ends_of_thousands_of_digits_are_priced_before_the_batched_transform():
    """Found: a 36 KB certificate (n = 28, Taylor(26), six pieces whose ends are 2000-digit fractions)
    ran the batched Descartes transform (:func:`lp_pieces._batch_positive`: L Moebius transforms of
    numbers growing to W times the ends' bits) before charging it, and charged it without the ends' bits
    (the Horner products by end-sized numbers): 61 s of CPU, stopped only by the clock ("over the kernel's
    time limit").  Now priced like polys.descartes_variations before the transform runs: rejected by the
    work budget, not the clock."""
    rng = random.Random(1)
    ends = [f"{k + 1}{_digits(rng, 1990)}/{_digits(rng, 1990)}" for k in range(6)]
    text = json.dumps(_box_certificate(28, ends), separators=(",", ":"))
    assert len(text) < 1_000_000
    report = exactinv_check.check(text)
    assert not report.ok
    assert "over the certificate's work budget" in str(report), report


def test_a_taylor_shift_at_a_long_end_is_priced_with_the_grown_numbers():
    """:func:`lp_pieces._positive_around` on (a, oo) shifts a degree-D polynomial by a: its numbers grow by
    D times a's bits, and the charge says so (it counted the coefficients' bits only: a D-fold underprice)."""
    a = F(int(_digits(random.Random(2), 1990)), int(_digits(random.Random(3), 1990)))
    ints = [1] * 40
    with account(limit=10**30) as acc:
        lp_pieces._positive_around(ints, a, None)
        spent = acc.spent
    assert spent > 10**8  # was about 2e5: the coefficients of one bit, never the grown ones
