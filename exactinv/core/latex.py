"""LaTeX for exact values: fractions, infinities, algebraic numbers (certified
digits and their defining polynomial), matrices and polynomials in dt.

>>> latex_real(Fraction(-3, 4))
'-\\\\frac{3}{4}'
>>> latex_matrix([[1, 0], [0, 1]])
'\\\\begin{pmatrix} 1 & 0 \\\\\\\\ 0 & 1 \\\\end{pmatrix}'
"""

from __future__ import annotations

from fractions import Fraction
from typing import Any, Sequence

from .polys import poly_latex
from .real_algebraic import RealAlgebraic
from .scalars import Infinity

__all__ = ["latex_decimal", "latex_text", "latex_real", "latex_matrix", "latex_column", "dt_poly_latex", "LatexMixin"]


def latex_decimal(v: RealAlgebraic, digits: int = 10) -> str:
    """The certified decimal of an algebraic number in LaTeX, ``digits`` after the
    point of the mantissa, marked as truncated: ``1.4142135623\\ldots`` or
    ``2.5127452049\\ldots \\times 10^{-7}``.

    >>> print(latex_decimal(RealAlgebraic.from_isolating_interval([-2, 0, 1], 1, 2), 6))
    1.414213\\ldots
    """
    text = v.certified_digits(digits + 1)
    if "e" in text:
        mantissa, exponent = text.split("e")
        return rf"{mantissa}\ldots \times 10^{{{exponent}}}"
    return text + r"\ldots"

# LaTeX's special characters, as math-mode symbols that LaTeX and MathJax both know
_MATH_SYMBOLS = {
    "\\": r"\backslash ", "{": r"\{", "}": r"\}", "_": r"\_", "^": r"\hat{}", "#": r"\#",
    "$": r"\$", "%": r"\%", "&": r"\&", "~": r"\sim ", "<": "<", ">": ">",
}


def latex_text(s: str) -> str:
    """Plain text (a method name, a theorem, a reason) as math-mode LaTeX: runs of
    ordinary characters in ``\\text{...}``, LaTeX's special characters as
    symbols between them, so that pdflatex and MathJax both typeset it.

    >>> latex_text("backward_euler")
    '\\\\text{backward}\\\\_\\\\text{euler}'
    """
    out, run = [], []
    for ch in str(s):
        if ch in _MATH_SYMBOLS:
            if run:
                out.append(r"\text{" + "".join(run) + "}")
                run = []
            out.append(_MATH_SYMBOLS[ch])
        else:
            run.append(ch)
    if run:
        out.append(r"\text{" + "".join(run) + "}")
    return "".join(out)


def latex_real(v: Any, digits: int = 10) -> str:
    """A Fraction as \\frac, INF as \\infty, an algebraic number as its certified
    decimal with the defining polynomial ("1.4142135623\\ldots, root of x^2-2").

    >>> print(latex_real(Fraction(-3, 4)), latex_real(Infinity(1)))
    -\\frac{3}{4} \\infty
    """
    if isinstance(v, Infinity):
        return r"\infty" if v.sign > 0 else r"-\infty"
    if isinstance(v, RealAlgebraic):
        decimal = latex_decimal(v, digits)
        return rf"{decimal}\ (\text{{root of }} {poly_latex(v.poly)})"
    v = Fraction(v)
    if v.denominator == 1:
        return str(v.numerator)
    sign = "-" if v < 0 else ""
    return rf"{sign}\frac{{{abs(v.numerator)}}}{{{v.denominator}}}"


def latex_matrix(M: Sequence[Sequence[Any]]) -> str:
    """A matrix of exact values as a LaTeX ``pmatrix``.

    >>> print(latex_matrix([[1, Fraction(1, 2)], [0, -1]]))
    \\begin{pmatrix} 1 & \\frac{1}{2} \\\\ 0 & -1 \\end{pmatrix}
    """
    rows = r" \\ ".join(" & ".join(latex_real(x) for x in row) for row in M)
    return rf"\begin{{pmatrix}} {rows} \end{{pmatrix}}"


def latex_column(v: Sequence[Any]) -> str:
    """A vector as a LaTeX column.

    >>> print(latex_column([Fraction(1, 3), 2]))
    \\begin{pmatrix} \\frac{1}{3} \\\\ 2 \\end{pmatrix}
    """
    return latex_matrix([[x] for x in v])


def dt_poly_latex(coeffs: Sequence[Fraction]) -> str:
    """A polynomial in dt (coefficients from dt^0 up) in LaTeX.

    >>> print(dt_poly_latex([Fraction(1), Fraction(-1), Fraction(1, 2)]))   # 1 - dt + dt^2/2
    1-\\Delta t+\\frac{1}{2}\\Delta t^{2}
    """
    terms = []
    for k, c in enumerate(coeffs):
        if c == 0:
            continue
        mono = "" if k == 0 else (r"\Delta t" if k == 1 else rf"\Delta t^{{{k}}}")
        body = latex_real(abs(c)) if (abs(c) != 1 or k == 0) else ""
        terms.append(("-" if c < 0 else "+") + body + mono)
    text = "".join(terms) or "0"
    return text[1:] if text.startswith("+") else text


class LatexMixin:
    """``_repr_latex_`` (for Jupyter) from the class's own ``to_latex()`` (for papers)."""

    def to_latex(self) -> str:  # pragma: no cover - every result defines it
        """The result in LaTeX (every result class defines it).

        >>> LatexMixin().to_latex()
        Traceback (most recent call last):
        ...
        NotImplementedError: no LaTeX for LatexMixin
        """
        raise NotImplementedError(f"no LaTeX for {type(self).__name__}")

    def _repr_latex_(self) -> str:
        return "$" + self.to_latex() + "$"
