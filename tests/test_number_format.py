"""One number format (issue 21, item 4): reports on polyhedra and ellipsoids,
``exactinv explain`` and the trusted kernel print exact numbers alike.  The
engine's formatter is exactinv.core.digits (with core.polys.poly_text); the
kernel, standalone, keeps its own copy (exactinv_check.text): both are run on
the same inputs here and must agree character for character."""

from fractions import Fraction
from math import isqrt
from pathlib import Path

from hypothesis import given
from hypothesis import strategies as st

import exactinv as ei
import exactinv_check
from exactinv.core import digits as engine
from exactinv.core.polys import poly_text
from exactinv.core.real_algebraic import RealAlgebraic
from exactinv.core.text import exact_text
from exactinv.interfaces.explain import explain
from exactinv.interfaces.pipeline import certify
from exactinv.interfaces.problem import load_problem
from exactinv_check import text as kernel
from exactinv_check.reals import Real

ROOT = Path(__file__).parent.parent

rationals = st.builds(lambda n, d, e: Fraction(n, d) * Fraction(10) ** e,
                      st.integers(-10**25, 10**25), st.integers(1, 10**25), st.integers(-80, 80))
small = st.builds(Fraction, st.integers(-10**6, 10**6), st.integers(1, 10**6))


@given(rationals, rationals, st.integers(1, 25))
def test_significant_digits_agree(a, b, digits):
    lo, hi = min(a, b), max(a, b)
    assert engine.significant_digits(lo, hi, digits) == kernel.significant_digits(lo, hi, digits)


@given(rationals)
def test_rationals_print_alike(q):
    assert engine.rational_text(q) == kernel.rational_text(q) == Real.rational(q).__str__()
    assert engine.decimal_text(q) == kernel.decimal_text(q)


@given(st.lists(small, min_size=1, max_size=6))
def test_polynomials_print_alike(coeffs):
    assert poly_text(coeffs) == kernel.poly_text(coeffs)


def test_huge_rationals_are_described_by_size_alike():
    q = Fraction(10**5000 + 1, 3)  # beyond Python's int -> str limit
    assert engine.rational_text(q) == kernel.rational_text(q) == "a 5001-digit rational  (= 3.3333333333333333e4999...)"


def test_huge_polynomials_are_described_by_size_alike():
    """Found by red team rt-gate in the kernel (a 6,000-digit coefficient made str() raise); the engine's printer
    had the same limit."""
    coeffs = [Fraction(1, 3), 0, Fraction(10**5000 + 1, 7)]
    assert poly_text(coeffs) == kernel.poly_text(coeffs) == "a polynomial of degree 2 with coefficients of up to 16610 bits"
    short = [Fraction(2**12999 - 1, 3), 1]  # at the limit: still printed digit by digit
    assert poly_text(short) == kernel.poly_text(short) and "bits" not in poly_text(short)


@given(st.integers(2, 10**9).filter(lambda k: isqrt(k) ** 2 != k), st.integers(-12, 12))
def test_algebraic_numbers_print_alike(k, e):
    """sqrt(k) 10^e from one isolating interval: the same digits and polynomial, and each
    side's printed interval (12 decimals, or exact) isolates it."""
    r = isqrt(k)
    a = RealAlgebraic.from_isolating_interval([-k, 0, 1], r, r + 1) * Fraction(10) ** e
    lo, hi = a.lower, a.upper
    ints = [int(c) for c in a.poly.coeffs()]
    ours, theirs = exact_text(a), kernel.algebraic_text(ints, lo, hi)
    assert ours.split(" in [")[0] == theirs.split(" in [")[0]
    assert ours.split(" in [")[0].split("  ")[0] == a.certified_digits(17)
    for text in (ours, theirs):
        left, right = text.split(" in [")[1].rstrip("])").split(", ")
        assert Fraction(left) < a < Fraction(right)


def test_the_report_the_kernel_and_explain_print_the_box_threshold_alike():
    """Taylor(4) on the paper's box: the report line, the kernel's verdict and explain show the
    largest threshold as one string."""
    problem = load_problem(ROOT / "examples" / "paper_box_taylor4.json")
    report = certify(problem)
    shown = "1.7496858314598103  (the root of x^4 - 6x^2 + 12x - 12 in [1.749685831459, 1.74968583146])"
    assert f"exact largest threshold: {shown}" in report.text
    assert f"largest threshold {shown}" in str(report.check)
    assert f"The exact largest threshold is {shown}" in explain(report.certificate, verified=True)


def test_ellipsoid_and_polyhedron_reports_share_the_format():
    """The ellipsoid report prints an algebraic threshold as the polyhedron report does (it printed
    FLINT's polynomial and raw fractions before), and rationals alike."""
    problem = load_problem(ROOT / "examples" / "ellipsoid_disc_taylor2.json")
    report = certify(problem)
    L = [r for r in report.results if isinstance(r, ei.LargestThreshold)][0]
    assert f"exact largest threshold: {exact_text(L.value)}" in report.text
    assert "(the root of 25x^3 - 20x^2 + 8x - 8 in [" in report.text  # docs/ellipsoids.md: 25h^3 - 20h^2 + 8h - 8
    assert "largest forward-Euler step on E: 2/5; use dt <= 0.39999999999999996" in report.text
    assert "x^3 - 20x^2" in str(report.check) or "25x^3 - 20x^2 + 8x - 8" in str(report.check)


def test_kernel_reals_print_through_the_copy():
    assert str(Real(inf=1)) == "oo"
    sqrt2 = Real.parse({"poly": ["-2", "0", "1"], "interval": ["1", "2"]})
    assert str(sqrt2) == "1.4142135623730950  (the root of x^2 - 2 in [1.414213562373, 1.414213562374])"
    assert str(sqrt2) == exact_text(RealAlgebraic.from_isolating_interval([-2, 0, 1], 1, 2))
    assert exactinv_check.check  # the kernel package imports nothing from exactinv (tests/kernel/test_standalone.py)
