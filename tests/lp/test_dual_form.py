"""exactinv.lp.dual_form: HiGHS on the dual form names optimal bases of max c^T x over P, checked in Q.

Every basis the hint names is checked against the exact LP chain: its n rows are independent, their vertex
x_B = B^-1 b_B lies in P, and c^T x_B is the exact optimum (so B^-T c >= 0 is not even needed to conclude).
A hint may say nothing (None), never something false that the caller would not catch, and never raises.
"""

from fractions import Fraction as F

import flint
import numpy as np
from hypothesis import given
from hypothesis import strategies as st

from exactinv.lp.dual_form import DualFormHint
from exactinv.lp.solver import OPTIMAL, ExactLPSolver


def _exact_vertex(G: list[list[int]], b: list[int], rows: tuple[int, ...]) -> list[F] | None:
    n = len(G[0])
    B = flint.fmpq_mat([[G[r][l] for l in range(n)] for r in rows])
    try:
        x = B.solve(flint.fmpq_mat([[b[r]] for r in rows]))
    except ZeroDivisionError:
        return None
    return [F(int(v.p), int(v.q)) for v in x.entries()]


@st.composite
def polytopes(draw):
    """P = {G x <= b}: the box [-2, 2]^n (bounded, nonempty) cut by random integer rows with b >= 1
    (0 stays inside), and an integer cost."""
    n = draw(st.integers(2, 4))
    G = [[int(i == j) for j in range(n)] for i in range(n)] + [[-int(i == j) for j in range(n)] for i in range(n)]
    b = [2] * (2 * n)
    for _ in range(draw(st.integers(0, 8))):
        row = draw(st.lists(st.integers(-3, 3), min_size=n, max_size=n))
        if any(row):
            G.append(row)
            b.append(draw(st.integers(1, 4)))
    c = draw(st.lists(st.integers(-5, 5), min_size=n, max_size=n))
    return G, b, c


@given(polytopes())
def test_a_named_basis_is_an_optimal_vertex_in_q(problem):
    G, b, c = problem
    m, n = len(G), len(G[0])
    rows = DualFormHint(np.array(G, dtype=float), np.array(b, dtype=float)).basis_rows(np.array(c, dtype=float))
    exact = ExactLPSolver(flint.fmpq_mat(G), (False,) * m).solve(
        flint.fmpq_mat([[v] for v in c]), flint.fmpq_mat([[v] for v in b]), (False,) * n)
    assert exact.status == OPTIMAL  # P is bounded and nonempty
    if not any(c):
        return  # every vertex is optimal: nothing to compare
    if rows is None:
        return  # a hint may say nothing (a degenerate optimum named no vertex)
    assert len(rows) == n and list(rows) == sorted(set(rows))
    x = _exact_vertex(G, b, rows)
    assert x is not None, "the named rows are dependent"
    assert all(sum(g * v for g, v in zip(row, x)) <= br for row, br in zip(G, b)), "x_B is not in P"
    assert sum(ci * v for ci, v in zip(c, x)) == exact.value


def test_the_square_names_each_vertex_and_says_nothing_inside_a_face():
    """The square [-1, 1]^2: the cost (1, 2) has the vertex (1, 1) (rows 0 and 1).  The cost (1, 0) has the
    face x1 = 1: from a fresh model the dual form's optimal x is the face's midpoint (1, 0), no vertex
    (``degenerate``: the caller asks the primal form); warm-started from the vertex (-1, 1), the answer is an
    end of the face or nothing."""
    G = np.array([[1.0, 0.0], [0.0, 1.0], [-1.0, 0.0], [0.0, -1.0]])
    fresh = DualFormHint(G, np.ones(4))
    assert fresh.basis_rows(np.array([1.0, 0.0])) is None and fresh.degenerate
    assert fresh.basis_rows(np.array([1.0, 2.0])) == (0, 1) and not fresh.degenerate
    warm = DualFormHint(G, np.ones(4))
    assert warm.basis_rows(np.array([-3.0, 1.0])) == (1, 2) and not warm.degenerate
    assert warm.basis_rows(np.array([1.0, 0.0])) in {(0, 1), (0, 3), None}


def test_a_hint_never_raises():
    """Costs of the wrong length, NaN or infinite entries, an unbounded LP (the dual form infeasible), an
    empty P: no basis, no exception."""
    hint = DualFormHint(np.array([[1.0, 0.0], [0.0, 1.0]]), np.ones(2))  # the quadrant x <= 1: unbounded below
    assert hint.basis_rows(np.array([1.0])) is None
    assert hint.basis_rows(np.array([np.nan, 1.0])) is None
    assert hint.basis_rows(np.array([np.inf, 1.0])) is None
    assert hint.basis_rows(np.array([-1.0, 1.0])) is None  # unbounded along -e_1
    assert hint.basis_rows(np.array([1.0, 1.0])) == (0, 1)  # and the model still serves afterwards
    empty = DualFormHint(np.array([[1.0], [-1.0]]), np.array([-1.0, -1.0]))  # x <= -1 and x >= 1
    assert empty.basis_rows(np.array([1.0])) is None
