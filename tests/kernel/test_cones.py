"""exactinv_check.cones: the extreme rays of a cone {y : A y <= 0} in integers, against brute force."""


import itertools
import math
import random
from fractions import Fraction as F

from exactinv_check import cones
from exactinv_check.rationals import rank_and_nullspace

# ------------------------------------------------------------------ soundness

def test_degenerate_cone_enumeration_matches_brute_force():
    """The double description at a degenerate vertex finds exactly the extreme
    rays that the subset enumeration (rank r - 1 tight sets) finds."""
    rng = random.Random(5)
    tested = 0
    while tested < 300:
        r = rng.randint(1, 4)
        A = [[rng.randint(-2, 2) for _ in range(r)] for _ in range(rng.randint(r, r + 5))]
        rank, _, basis, _, _ = cones.reduce_rows(A, r)
        if rank != r:
            continue
        got = [tuple(y) for y in cones.cone_rays(A, basis, r)]
        want = set()
        for S in itertools.combinations(range(len(A)), r - 1):
            k, null = rank_and_nullspace([[F(x) for x in A[i]] for i in S], r)
            if k != r - 1:
                continue
            for sign in (1, -1):
                y = [sign * x for x in null[0]]
                Ay = [sum(a * c for a, c in zip(row, y)) for row in A]
                if max(Ay) <= 0 and any(Ay):
                    den = math.lcm(*(x.denominator for x in y))
                    want.add(tuple(cones.primitive([int(x * den) for x in y])))
        assert len(got) == len(set(got)) and set(got) == want, (A, got, want)
        tested += 1


# ------------------------------------------------------------------ resource
# No test here is about this module's work limits: the certificate's account is tested in test_budget.py.
