"""ei.methods.from_nodepy (exactinv/model/nodepy_methods.py) on NodePy's own library:
every method with exact coefficients converts and its stability function equals
NodePy's own exact ``stability_function()`` (cross-multiplied in sympy); float
tableaux are refused unless opted in; closed forms (SSPRK(s,2), SSPRK3(n^2))
and the exact radii that NodePy's float bisection misses (docs/methods.md)."""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest
import sympy as sp

import exactinv as ei

rk = pytest.importorskip("nodepy.runge_kutta_method")  # the test extra installs it

LIBRARY = rk.loadRKM("All")
z = sp.Symbol("z")


def _has_float(x) -> bool:
    return isinstance(x, (float, np.floating)) or bool(getattr(x, "atoms", lambda *_: ())(sp.Float))


def float_tableau(m) -> bool:
    return any(_has_float(x) for x in list(np.ravel(m.A)) + list(np.ravel(m.b)))


EXACT = sorted(k for k, m in LIBRARY.items() if not float_tableau(m))
FLOAT = sorted(k for k, m in LIBRARY.items() if float_tableau(m))
IRRATIONAL_R = {"SDIRK23", "SDIRK34"}  # gamma = (3 + sqrt(3))/6 ...: R itself has irrational coefficients


def nodepy_ratio(m):
    p, q = m.stability_function()  # numpy poly1d, highest power first, sympy coefficients
    return (sum(sp.sympify(c) * z ** k for k, c in enumerate(reversed(list(p.coeffs)))),
            sum(sp.sympify(c) * z ** k for k, c in enumerate(reversed(list(q.coeffs)))))


def test_the_library_is_there():
    assert len(LIBRARY) >= 40 and len(EXACT) >= 30 and FLOAT


@pytest.mark.parametrize("key", EXACT)
def test_exact_methods_convert_to_nodepys_own_stability_function(key):
    m = LIBRARY[key]
    if key in IRRATIONAL_R:
        with pytest.raises(ei.ExactinvError, match=r"irrational.*R\(z\)"):
            ei.methods.from_nodepy(m)
        p, q = nodepy_ratio(m)  # and NodePy agrees that R is not rational
        assert not all(sp.nsimplify(c).is_Rational for c in sp.Poly(sp.expand(p), z).all_coeffs())
        return
    method = ei.methods.from_nodepy(m)
    p, q = nodepy_ratio(m)
    g = sum(sp.Rational(c.numerator, c.denominator) * z ** k for k, c in enumerate(method.numerator))
    h = sum(sp.Rational(c.numerator, c.denominator) * z ** k for k, c in enumerate(method.denominator))
    assert sp.simplify(sp.expand(g * q - h * p)) == 0, key
    assert method(0) == 1 and method.name == m.name
    assert method.is_polynomial == isinstance(m, rk.ExplicitRungeKuttaMethod)


@pytest.mark.parametrize("key", FLOAT)
def test_float_tableaux_need_the_opt_in(key):
    m = LIBRARY[key]
    with pytest.raises(ei.ExactinvError, match=r"rkm \(.*\): (A|b)\[\d+\](\[\d+\])?: got the float.*allow_float=True"):
        ei.methods.from_nodepy(m)
    method = ei.methods.from_nodepy(m, allow_float=True)
    A = [[ei.exact_from_float(float(x)) for x in row] for row in np.asarray(m.A)]
    b = [ei.exact_from_float(float(x)) for x in np.asarray(m.b)]
    # R of the tableau read exactly; against the tableau rounded to doubles entry by entry
    for t in (Fraction(-1, 2), Fraction(-3, 2)):
        assert abs(float(method(t)) - float(ei.methods.from_butcher(A, b)(t))) < 1e-12


def test_the_opt_in_takes_each_float_exactly():
    m = LIBRARY["Tsit5"]
    method = ei.methods.from_nodepy(m, allow_float=True)
    A = [[ei.exact_from_float(float(x)) for x in row] for row in m.A]
    b = [ei.exact_from_float(float(x)) for x in m.b]
    assert method == ei.methods.from_butcher(A, b, m.name)


def test_a_sympy_float_tableau_is_read_at_its_precision():
    m = LIBRARY["SSP22star"]
    assert any(getattr(x, "is_Float", False) for x in np.ravel(m.A))
    method = ei.methods.from_nodepy(m, allow_float=True)
    assert abs(float(method(Fraction(-1))) - float(m.stability_function()[0](-1) / m.stability_function()[1](-1))) < 1e-12


def test_bad_arguments():
    with pytest.raises(ei.ExactinvError, match=r"rkm: expected a NodePy Runge-Kutta method"):
        ei.methods.from_nodepy(ei.methods.rk4())
    with pytest.raises(ei.ExactinvError, match=r"rkm: expected a NodePy Runge-Kutta method"):
        ei.methods.from_nodepy({"A": [[0]], "b": [1]})


def test_nothing_of_the_method_is_changed():
    m = rk.SSPRK2(4)
    A, b = m.A.copy(), m.b.copy()
    ei.methods.from_nodepy(m, "renamed")
    assert (m.A == A).all() and (m.b == b).all()
    assert ei.methods.from_nodepy(m, "renamed").name == "renamed"


@pytest.mark.parametrize("s", range(2, 9))
def test_ssprk2_is_its_closed_form(s):
    """SSPRK(s,2): s - 1 forward-Euler stages of step 1/(s-1), then the average
    1/s u0 + (s-1)/s u_s; so R(z) = 1/s + (s-1)/s (1 + z/(s-1))^s, with radius s - 1."""
    method = ei.methods.from_nodepy(rk.SSPRK2(s))
    closed = sp.Poly(sp.Rational(1, s) + sp.Rational(s - 1, s) * (1 + z / (s - 1)) ** s, z).all_coeffs()[::-1]
    assert method.numerator == tuple(Fraction(int(c.p), int(c.q)) for c in closed)
    assert ei.absolute_monotonicity_radius(method).value == s - 1


@pytest.mark.parametrize("n", [2, 3, 4])
def test_ssprk3_square_has_threshold_factor_n2_minus_n(n):
    method = ei.methods.from_nodepy(rk.SSPRK3(n * n))
    assert method.is_polynomial and len(method.numerator) == n * n + 1
    assert ei.absolute_monotonicity_radius(method).value == n * n - n


@pytest.mark.parametrize("s, nodepy_value, exact", [(6, 4.999362285980169, 5), (8, 6.937463025406032, 7)])
def test_nodepy_float_threshold_factor_misses_the_exact_radius_ssprk2(s, nodepy_value, exact):
    """NodePy's linear_absolute_monotonicity_radius (bisection at acc = 1e-10 on float
    derivatives) stops short of the exact radius by far more than its accuracy."""
    m = rk.SSPRK2(s)
    found = m.linear_absolute_monotonicity_radius()
    assert abs(found - nodepy_value) < 1e-6
    assert ei.absolute_monotonicity_radius(ei.methods.from_nodepy(m)).value == exact
    assert exact - found > 1e-4


# ---------------------------------------------------------------- docs/methods.md
def _generator():
    import importlib.util
    from pathlib import Path

    path = Path(__file__).resolve().parents[2] / "docs" / "gen_method_table.py"
    spec = importlib.util.spec_from_file_location("gen_method_table", path)
    gen = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(gen)
    return gen, (path.parent / "methods.md").read_text()


def test_the_nodepy_table_in_the_docs_is_what_the_generator_gives():
    gen, doc = _generator()
    assert gen.NODEPY_HEADER.strip() in doc
    committed = {}
    for line in doc.splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) == 8 and cells[0].startswith("`"):
            committed[cells[0].strip("`")] = cells
    entries = gen.nodepy_entries()
    assert set(committed) == set(entries)
    for name, rkm in entries.items():
        assert committed[name] == gen.nodepy_row(name, rkm), name
    wrong = {name for name, cells in committed.items() if cells[5].startswith("**wrong**")}
    # the three examples are among them (NodePy 1.1.1: 4.99936, 6.93746, 11.5723)
    assert {"SSPRK2(6)", "SSPRK2(8)", "SSPRK3(16)"} <= wrong
    assert committed["SSPRK3(16)"][2] == "12" and committed["SSPRK3(16)"][4].startswith("11.572")
