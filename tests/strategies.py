"""Hypothesis strategies shared by several test modules."""

from fractions import Fraction

from hypothesis import assume
from hypothesis import strategies as st

import exactinv as ei
from exactinv.core.flintq import fmpq_matrix


@st.composite
def metzler_cones(draw):
    """Random cones {x : Gx <= 0} = T^-1(orthant) with A = T^-1 M T, M Metzler
    (off-diagonal >= 0, so the cone is invariant; stable or unstable)."""
    n = draw(st.integers(1, 3))
    M = [[Fraction(draw(st.integers(-3, 3)), draw(st.integers(1, 2))) if i == j
          else Fraction(draw(st.integers(0, 3)), draw(st.integers(1, 2))) for j in range(n)] for i in range(n)]
    T = [[Fraction(draw(st.integers(-2, 2))) for _ in range(n)] for _ in range(n)]
    Tq = fmpq_matrix(T)
    assume(Tq.det() != 0)
    A = Tq.inv() * fmpq_matrix(M) * Tq
    G = -Tq
    return (ei.LinearSystem([[A[i, j] for j in range(n)] for i in range(n)]),
            ei.Polyhedron([[G[i, j] for j in range(n)] for i in range(n)], [0] * n))
