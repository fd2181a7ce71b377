"""The polyhedron P = {x : Gx <= b}, immutable and exact (entries are Fractions).

It knows its
H-representation (G, b) and, computed exactly with the Parma Polyhedra Library
(pplpy) on first use, its V-representation: vertices, rays and lines.
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from functools import cached_property
from math import lcm
from typing import Any, ClassVar, Sequence

import flint
import ppl

from ..core.flintq import fmpq_matrix
from ..core.latex import LatexMixin, latex_column, latex_matrix
from ..core.scalars import Matrix, Vector, matrix_text, to_matrix, to_vector, vector_text
from ..errors import InvalidInput
from ..lp import INFEASIBLE, ExactLPSolver
from .cdd import ext_text, ine_text, read_cdd

__all__ = ["Polyhedron"]


@dataclass(frozen=True, init=False)
class Polyhedron(LatexMixin):
    """The polyhedron P = {x in Q^n : G x <= b}.

    Construct it from inequalities, ``Polyhedron(G, b)``, from generators,
    ``Polyhedron.from_vertices(vertices, rays=(), lines=())``, as a box,
    ``Polyhedron.box(lo, hi)``, or from a cdd file, ``Polyhedron.from_cdd(path_or_text)``
    (written back by ``P.to_cdd("ine" | "ext")``).  Conversions between the two representations
    are exact (double description, pplpy).

    >>> P = Polyhedron.box([-1, -1], [1, 1])
    >>> P.vertices
    ((Fraction(-1, 1), Fraction(-1, 1)), (Fraction(-1, 1), Fraction(1, 1)), (Fraction(1, 1), Fraction(-1, 1)), (Fraction(1, 1), Fraction(1, 1)))
    """  # noqa: E501 (doctest output)

    G: Matrix
    b: Vector
    family: ClassVar[str] = "polyhedron"  # the set type, for exactinv.model.sets.set_family

    def __init__(self, G: Any, b: Any, *, allow_float: bool = False):
        Gm = to_matrix(G, "G", allow_float=allow_float)
        bv = to_vector(b, "b", allow_float=allow_float)
        if len(bv) != len(Gm):
            raise InvalidInput(f"b: G has {len(Gm)} rows but b has {len(bv)} entries")
        for j, row in enumerate(Gm):
            if not any(row):
                raise InvalidInput(
                    f"G: row {j} is zero; the constraint 0 <= {bv[j]} is either void or makes P empty -- remove it"
                )
        object.__setattr__(self, "G", Gm)
        object.__setattr__(self, "b", bv)

    # ----------------------------------------------------------- constructors
    @classmethod
    def from_vertices(
        cls,
        vertices: Any,
        rays: Any = (),
        lines: Any = (),
        *,
        allow_float: bool = False,
    ) -> "Polyhedron":
        """P = conv(vertices) + cone(rays) + span(lines), converted exactly to
        inequalities (an affine hull becomes pairs of opposite inequalities).

        >>> T = Polyhedron.from_vertices([[0, 0], [1, 0], [0, 1]])   # the unit triangle
        >>> T.contains(['1/2', '1/2']), T.contains(['1/2', '2/3']), T.m
        (True, False, 3)
        """
        V = to_matrix(vertices, "vertices", allow_float=allow_float)
        n = len(V[0])
        R = to_matrix(rays, "rays", shape=(None, n), allow_float=allow_float) if _nonempty(rays) else ()
        L = to_matrix(lines, "lines", shape=(None, n), allow_float=allow_float) if _nonempty(lines) else ()
        for name, gens in (("rays", R), ("lines", L)):
            for i, g in enumerate(gens):
                if not any(g):
                    raise InvalidInput(f"{name}: entry {i} is the zero vector")
        gs = ppl.Generator_System()
        for v in V:
            d = lcm(*(x.denominator for x in v))
            gs.insert(ppl.point(ppl.Linear_Expression([int(x * d) for x in v], 0), d))
        for r in R:
            gs.insert(ppl.ray(ppl.Linear_Expression(_integer_row(r), 0)))
        for l in L:
            gs.insert(ppl.line(ppl.Linear_Expression(_integer_row(l), 0)))
        poly = ppl.C_Polyhedron(gs)
        G, b = _inequalities_of(poly, n)
        if not G:
            raise InvalidInput("from_vertices: the generators span the whole space; P has no inequality")
        P = cls(G, b)
        P.__dict__["_ppl"] = poly
        return P

    @classmethod
    def from_cdd(cls, source: Any, *, allow_float: bool = False) -> "Polyhedron":
        """P from a cdd file (a path, or the file's text): an H-representation
        (``.ine``: rows ``b -a`` meaning a.x <= b, ``linearity`` rows equalities)
        or a V-representation (``.ext``: rows ``1 v`` points, ``0 r`` rays, lines
        when listed in ``linearity``; no point means the origin).  Exact:
        ``integer`` and ``rational`` files only, unless ``allow_float=True``
        reads a ``real`` file's entries as the exact values of their doubles.
        An equality becomes two opposite inequalities; a void row ``b 0 ... 0``
        with b >= 0 is dropped.  Errors name the file and line
        (:mod:`exactinv.model.cdd`).

        >>> P = Polyhedron.from_cdd('''H-representation
        ... linearity 1 3
        ... begin
        ...  3 3 rational
        ...  1 -1 0
        ...  1 0 -1
        ...  0 1/2 -1/2
        ... end''')                 # x <= 1, y <= 1, x = y
        >>> P.vertices, P.rays                # the half-line from (1, 1) towards (-1, -1)
        (((Fraction(1, 1), Fraction(1, 1)),), ((Fraction(-1, 1), Fraction(-1, 1)),))
        """
        data = read_cdd(source, allow_float=allow_float)
        where = "cdd text" if isinstance(source, str) and "\n" in source.strip() else str(source)
        try:
            if data.kind == "H":
                G = list(data.G) + list(data.E) + [tuple(-x for x in g) for g in data.E]
                b = list(data.b) + list(data.e) + [-x for x in data.e]
                if not G:
                    raise InvalidInput("the H-representation has no inequality; P would be the whole space")
                return cls(G, b)
            points = data.points or ((0,) * data.dimension,)
            return cls.from_vertices(points, data.rays, data.lines)
        except InvalidInput as exc:
            raise InvalidInput(f"{where}: {exc}") from None

    def to_cdd(self, kind: str = "ine", path: Any = None) -> str:
        """The cdd file of P, exact (``integer`` when every entry is an integer,
        else ``rational``): ``"ine"``, the H-representation G x <= b row by row
        (rows ``b -g``), or ``"ext"``, the V-representation (vertices, rays, and
        lines listed in ``linearity``).  With ``path``, the text is also written
        there.  ``Polyhedron.from_cdd`` reads either back to the same set.

        >>> print(Polyhedron.box([0], ['1/2']).to_cdd("ext"), end="")
        V-representation
        begin
        2 2 rational
        1 0
        1 1/2
        end
        """
        key = str(kind).lower()
        if key in ("ine", "h"):
            text = ine_text(self.G, self.b)
        elif key in ("ext", "v"):
            if not self.vertices:
                raise InvalidInput("to_cdd: P is empty; an empty polyhedron has no V-representation")
            text = ext_text(self.vertices, self.rays, self.lines)
        else:
            raise InvalidInput(f'kind: expected "ine" (H-representation) or "ext" (V-representation), got {kind!r}')
        if path is not None:
            try:
                with open(path, "w", encoding="utf-8") as fh:
                    fh.write(text)
            except OSError as exc:
                raise InvalidInput(f"path: cannot write {path} ({exc.strerror or exc})") from None
        return text

    @classmethod
    def box(cls, lo: Any, hi: Any, *, allow_float: bool = False) -> "Polyhedron":
        """The box {x : lo <= x <= hi} with rows e_1..e_n, then -e_1..-e_n.

        >>> Polyhedron.box([-1, 0], [1, '1/2'])
        Polyhedron(G=[[1, 0], [0, 1], [-1, 0], [0, -1]], b=[1, 1/2, 1, 0])
        """
        lov = to_vector(lo, "lo", allow_float=allow_float)
        hiv = to_vector(hi, "hi", length=len(lov), allow_float=allow_float)
        for i, (l, h) in enumerate(zip(lov, hiv)):
            if l > h:
                raise InvalidInput(f"box: lo[{i}] = {l} exceeds hi[{i}] = {h}; the box is empty")
        n = len(lov)
        G = [[int(i == k) for k in range(n)] for i in range(n)] + [[-int(i == k) for k in range(n)] for i in range(n)]
        return cls(G, list(hiv) + [-x for x in lov])

    # ------------------------------------------------------------- properties
    @property
    def n(self) -> int:
        """The ambient dimension."""
        return len(self.G[0])

    @property
    def m(self) -> int:
        """The number of inequalities."""
        return len(self.G)

    @cached_property
    def G_flint(self) -> flint.fmpq_mat:
        return fmpq_matrix(self.G)

    @cached_property
    def b_flint(self) -> flint.fmpq_mat:
        return fmpq_matrix([[x] for x in self.b])

    @cached_property
    def _ppl(self) -> ppl.C_Polyhedron:
        cs = ppl.Constraint_System()
        for g, beta in zip(self.G, self.b):
            d = lcm(*(x.denominator for x in g), beta.denominator)
            # ppl constraints read  e(x) >= 0 :  d*beta - d*g.x >= 0
            cs.insert(ppl.Linear_Expression([int(-x * d) for x in g], int(beta * d)) >= 0)
        return ppl.C_Polyhedron(cs)

    @cached_property
    def _generators(self) -> tuple[Matrix, Matrix, Matrix]:
        points, rays, lines = [], [], []
        for g in self._ppl.minimized_generators():
            coeffs = [Fraction(int(c)) for c in g.coefficients()]
            if g.is_point():
                d = int(g.divisor())
                points.append(tuple(c / d for c in coeffs))
            elif g.is_ray():
                rays.append(tuple(coeffs))
            elif g.is_line():
                lines.append(tuple(coeffs))
        return tuple(sorted(points)), tuple(sorted(rays)), tuple(sorted(lines))

    @property
    def vertices(self) -> Matrix:
        """The vertices (for a polyhedron with lines: the points of a minimal
        generator system), exact and sorted."""
        return self._generators[0]

    @property
    def rays(self) -> Matrix:
        """Extreme rays of the recession cone (modulo lines), as integer vectors."""
        return self._generators[1]

    @property
    def lines(self) -> Matrix:
        """A basis of the lineality space, as integer vectors."""
        return self._generators[2]

    @cached_property
    def is_empty(self) -> bool:
        """Exact emptiness test: b >= 0 puts the origin in P (G 0 = 0 <= b), so P is
        nonempty without an LP; otherwise a verified LP (a Farkas certificate when
        empty).  Unlike PPL's own test it never enumerates generators.

        >>> Polyhedron.box([-1], [1]).is_empty, Polyhedron([[1], [-1]], [-1, -1]).is_empty
        (False, True)
        """
        if all(beta >= 0 for beta in self.b):
            return False
        res = ExactLPSolver(self.G_flint, [False] * self.m).solve([0] * self.n, self.b, [False] * self.n)
        return res.status == INFEASIBLE

    @cached_property
    def dimension(self) -> int:
        """The affine dimension of P (-1 when P is empty)."""
        return -1 if self.is_empty else int(self._ppl.affine_dimension())

    @cached_property
    def is_bounded(self) -> bool:
        return self._ppl.is_bounded()

    def contains(self, x: Sequence[Any]) -> bool:
        """Exact membership test G x <= b for a rational point x.

        >>> P = Polyhedron.box([-1, -1], [1, 1])
        >>> P.contains(['1', '-1']), P.contains(['1', '1001/1000'])
        (True, False)
        """
        xv = to_vector(x, "x", length=self.n)
        return all(sum(g * xi for g, xi in zip(row, xv)) <= beta for row, beta in zip(self.G, self.b))

    def __contains__(self, x: Sequence[Any]) -> bool:
        return self.contains(x)

    def to_latex(self) -> str:
        """LaTeX: P = {x : G x <= b}.

        >>> print(Polyhedron.box([-1], [1]).to_latex())
        P = \\{x : \\begin{pmatrix} 1 \\\\ -1 \\end{pmatrix} x \\le \\begin{pmatrix} 1 \\\\ 1 \\end{pmatrix}\\}
        """
        return rf"P = \{{x : {latex_matrix(self.G)} x \le {latex_column(self.b)}\}}"

    def __repr__(self) -> str:
        return f"Polyhedron(G={matrix_text(self.G)}, b={vector_text(self.b)})"


def _nonempty(x: Any) -> bool:
    try:
        return len(x) > 0
    except TypeError:
        return True


def _integer_row(row: Sequence[Fraction]) -> list[int]:
    d = lcm(*(x.denominator for x in row))
    return [int(x * d) for x in row]


def _inequalities_of(poly: ppl.C_Polyhedron, n: int) -> tuple[list, list]:
    G, b = [], []
    for c in poly.minimized_constraints():
        coeffs = [int(x) for x in c.coefficients()]
        coeffs += [0] * (n - len(coeffs))
        beta = int(c.inhomogeneous_term())
        G.append([-x for x in coeffs])
        b.append(beta)
        if c.is_equality():
            G.append(coeffs)
            b.append(-beta)
    return G, b
