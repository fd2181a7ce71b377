"""Matrices and vectors as users already hold them (exactinv/core/scalars.py, the one
conversion point): sympy matrices of Rationals/Integers, numpy integer arrays and
numpy object arrays of Fractions/ints, accepted wherever a matrix or vector is taken
(LinearSystem, Polyhedron, Ellipsoid, from_vertices, box, Butcher tableaux,
discrete_invariance); numpy float arrays and sympy Floats refused without
``allow_float=True`` (then read at their exact binary value); nothing the user
passed is changed or kept."""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st

import exactinv as ei
from exactinv.core.scalars import to_matrix, to_rational, to_vector

F = Fraction
A_LIST = [[F(-1), F(1, 2)], [F(-1), F(-3, 7)]]


def forms(M):
    """The same exact matrix as a sympy Matrix, an ImmutableMatrix, a numpy object array
    of Fractions, and (when integral) a numpy int64 array."""
    out = {"sympy": sp.Matrix([[sp.Rational(x.numerator, x.denominator) for x in r] for r in M]),
           "sympy-immutable": sp.ImmutableMatrix([[sp.Rational(x.numerator, x.denominator) for x in r] for r in M]),
           "numpy-object": np.array(M, dtype=object)}
    if all(x.denominator == 1 for r in M for x in r):
        out["numpy-int64"] = np.array([[int(x) for x in r] for r in M], dtype=np.int64)
        out["numpy-int8"] = np.array([[int(x) for x in r] for r in M], dtype=np.int8)
    return out


@pytest.mark.parametrize("kind", ["sympy", "sympy-immutable", "numpy-object"])
def test_linear_system_from_every_form(kind):
    S = ei.LinearSystem(forms(A_LIST)[kind])
    assert S.A == tuple(tuple(r) for r in A_LIST)
    assert all(type(x) is Fraction for r in S.A for x in r)


def test_polyhedron_ellipsoid_box_vertices_from_every_form():
    G = [[F(1), F(0)], [F(0), F(1)], [F(-1), F(0)], [F(0), F(-1)]]
    box = ei.Polyhedron.box([-1, -1], [1, 1])
    for kind, Gk in forms(G).items():
        for b in (np.array([1, 1, 1, 1]), sp.Matrix([1, 1, 1, 1]), sp.Matrix([[1, 1, 1, 1]]),
                  np.array([[1], [1], [1], [1]]), np.array([F(1)] * 4, dtype=object)):
            assert ei.Polyhedron(Gk, b) == box, (kind, type(b))
    assert ei.Polyhedron.box(np.array([-1, -1]), sp.Matrix([1, 1])) == box
    tri = ei.Polyhedron.from_vertices(np.array([[0, 0], [1, 0], [0, 1]]), rays=np.zeros((0, 2), dtype=int))
    assert tri == ei.Polyhedron.from_vertices([[0, 0], [1, 0], [0, 1]])
    Q = [[F(2), F(1, 2)], [F(1, 2), F(1)]]
    for kind, Qk in forms(Q).items():
        assert ei.Ellipsoid(Qk).Q == tuple(tuple(r) for r in Q), kind
    assert ei.Ellipsoid(np.eye(2, dtype=np.int32), center=np.zeros(2, dtype=int)).Q == ((1, 0), (0, 1))


def test_methods_and_discrete_maps_take_them_too():
    m = ei.methods.from_butcher(sp.Matrix([[sp.Rational(1, 2)]]), np.array([1]))
    assert m == ei.methods.from_butcher([["1/2"]], [1])
    P = ei.Polyhedron.box([-1, -1], [1, 1])
    rot = np.array([[0, 1], [-1, 0]])
    assert ei.discrete_invariance(rot, P).holds
    assert not ei.discrete_invariance(sp.Matrix([[1, 1], [0, 1]]), P).holds


def test_results_are_the_same_as_from_lists():
    S_list = ei.LinearSystem([[-1, 1], [-1, -1]])
    P_list = ei.Polyhedron.box([-1, -1], [1, 1])
    S = ei.LinearSystem(sp.Matrix([[-1, 1], [-1, -1]]))
    P = ei.Polyhedron(np.array([[1, 0], [0, 1], [-1, 0], [0, -1]]), np.array([1, 1, 1, 1], dtype=object))
    assert ei.optimal_gamma(S, P).value == ei.optimal_gamma(S_list, P_list).value == 1


# ---------------------------------------------------------------- floats refused
FLOATS = {
    "numpy float64 array": np.array([[0.5, 0], [0, 1]]),
    "numpy float32 array": np.array([[1, 0], [0, 1]], dtype=np.float32),
    "numpy complex array": np.array([[1, 0], [0, 1]], dtype=complex),
    "numpy object array holding a float": np.array([[F(1), 0.5], [0, 1]], dtype=object),
    "sympy Float": sp.Matrix([[sp.Float("0.5"), 0], [0, 1]]),
    "sympy Float of 30 digits": sp.Matrix([[sp.Float("0.1", 30), 0], [0, 1]]),
}


@pytest.mark.parametrize("name", sorted(FLOATS))
def test_floats_are_refused_with_a_clear_message(name):
    with pytest.raises(ei.ExactinvError, match=r"^A(\[\d\]\[\d\])?: got (a numpy array of dtype|the float).*"
                                                r"floats are not exact.*allow_float=True"):
        ei.LinearSystem(FLOATS[name])


def test_non_rational_and_non_numbers_are_refused():
    with pytest.raises(ei.ExactinvError, match=r"A\[0\]\[0\]: sqrt\(2\) is not a rational number"):
        ei.LinearSystem(sp.Matrix([[sp.sqrt(2)]]))
    with pytest.raises(ei.ExactinvError, match=r"A\[0\]\[0\]: cannot read x"):
        ei.LinearSystem(sp.Matrix([[sp.Symbol("x")]]))
    with pytest.raises(ei.ExactinvError, match=r"A\[0\]\[0\]: got the bool True"):
        ei.LinearSystem(np.array([[True]]))
    with pytest.raises(ei.ExactinvError, match=r"b: expected length 2"):
        to_vector(sp.Matrix([1, 2, 3]), "b", length=2)
    with pytest.raises(ei.ExactinvError, match=r"A: must be square"):
        ei.LinearSystem(np.ones((2, 3), dtype=int))


def test_the_opt_in_reads_the_exact_binary_value():
    assert ei.LinearSystem(np.array([[0.1]]), allow_float=True).A[0][0] == Fraction(0.1)
    third = np.longdouble(1) / 3
    exact = to_rational(third, allow_float=True)
    assert exact == Fraction(*third.as_integer_ratio())          # the long double's own value
    assert abs(exact - F(1, 3)) < F(1, 10**18) and exact != F(1, 3)
    x = to_rational(sp.Float("0.1", 30), allow_float=True)        # the sympy Float at its precision
    assert x.denominator & (x.denominator - 1) == 0 and abs(x - F(1, 10)) < F(1, 10**29)
    assert x != Fraction(0.1)


def test_zero_dimensional_arrays_are_scalars():
    assert to_rational(np.array(3)) == 3
    assert to_rational(np.array(F(2, 3), dtype=object)) == F(2, 3)
    with pytest.raises(ei.ExactinvError, match="got the float"):
        to_rational(np.array(0.5))


# ---------------------------------------------------------------- nothing mutated, nothing kept
def test_inputs_are_neither_changed_nor_kept():
    G = np.array([[1, 0], [0, 1], [-1, 0], [0, -1]])
    b = np.array([F(1), F(1, 2), F(1), F(1, 3)], dtype=object)
    A = sp.Matrix([[-1, sp.Rational(1, 2)], [0, -1]])
    G0, b0, A0 = G.copy(), b.copy(), A.copy()
    P, S = ei.Polyhedron(G, b), ei.LinearSystem(A)
    assert (G == G0).all() and (b == b0).all() and A == A0 and G.flags.writeable
    G[0, 0], b[1], A[0, 0] = 7, F(9), 5     # the user's objects change afterwards ...
    assert P.G[0][0] == 1 and P.b[1] == F(1, 2) and S.A[0][0] == -1   # ... the model does not


@settings(max_examples=30, deadline=None)
@given(st.integers(1, 4).flatmap(lambda n: st.lists(
    st.lists(st.fractions(min_value=-9, max_value=9, max_denominator=9), min_size=n, max_size=n),
    min_size=1, max_size=4)))
def test_every_form_parses_to_the_same_exact_matrix(rows):
    expected = to_matrix(rows, "M")
    for kind, M in forms(rows).items():
        assert to_matrix(M, "M") == expected, kind
    assert to_vector(np.array(rows[0], dtype=object), "v") == expected[0]
    assert to_vector(sp.Matrix(rows[0]), "v") == expected[0]            # a sympy column
