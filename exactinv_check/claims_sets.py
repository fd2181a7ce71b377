"""Claims beyond the paper: the exact valid set and the largest threshold.

A_d(h)P is a subset of P iff A_d(h) maps every vertex into P, every ray into
rec(P) and every line into lin(P) -- over a generator system that the kernel
first proves complete (:mod:`exactinv_check.polyhedra`).  The kernel then
rebuilds every condition polynomial (:mod:`exactinv_check.conditions`) and
recomputes the valid set or its first interval (:mod:`exactinv_check.validset`);
the claim must equal the recomputation, end by end and flag by flag.  A claim
with a ``box`` record instead of generator lists is about a box; its conditions
come from :mod:`exactinv_check.routes.boxes` (P proved to be that box from G and b, no
vertex list: the sign patterns of the rows of N(h) on the cells between their
entries' roots, each one vertex-facet condition, together exact).  A claim with
an ``lp`` record is decided on the LP route's pieces (:mod:`exactinv_check.routes.lp_pieces`:
per facet, the pieces of [0, oo) with a basis each, proved optimal by weak
duality; the pieces' vertices give the conditions, no vertex enumeration).
"""

from __future__ import annotations

from fractions import Fraction
from types import SimpleNamespace
from typing import TYPE_CHECKING, Any, Sequence

from . import format as fmt
from . import poly_arithmetic
from .conditions import condition_polynomials, method_matrices
from .failure import require
from .format import GeneratorKind
from .polyhedra import prove_generators
from .rationals import boolean, integer, matrix, vector
from .reals import Real
from .routes import boxes, lp_pieces, pruning, pruning_rational
from .validset import first_end, require_intervals, valid_set

if TYPE_CHECKING:
    from .kernel import Problem


class _BoxVertices:
    """The vertices of the box [lo, hi], by index (never listed)."""

    def __init__(self, lo: Sequence[Fraction], hi: Sequence[Fraction]) -> None:
        self.lo, self.hi = lo, hi

    def __getitem__(self, i: int) -> Any:
        return boxes.vertex_of(i, self.lo, self.hi)


def _generators(problem: Problem, claim: Any) -> Any:
    """(count, vectors) per kind of a box claim or of generator lists (shape-checked), and whether a box."""
    has_box, has_lists = "box" in claim, {"vertices", "rays", "lines"} & set(claim)
    if "lp" in claim:
        require(not has_box and not has_lists and "pruning" not in claim,
                "an lp claim names neither a box nor generators nor a pruning record")
        return None, None
    require(has_box != bool(has_lists), "a claim names either the box or the vertices, rays and lines")
    if not has_box:
        require(set(claim) >= {"vertices", "rays", "lines"}, "missing keys: vertices, rays and lines go together")
        return None, tuple(matrix(claim[k], k, cols=problem.n) for k in ("vertices", "rays", "lines"))
    require("pruning" not in claim, "a box claim needs no pruning record")
    require(isinstance(claim["box"], dict), "box has the keys lo, hi")
    return claim["box"], None


def _pruning_variable(method: Any, record: dict[str, list[int] | int | str] | None) -> None:
    """The cheap test of a pruning record's variable against the method, before any generator is proved:
    a record in h (no variable) belongs to a polynomial method, one in u = h/(s+h) to a rational method."""
    if record is None:
        return
    rational = pruning_rational.is_rational_record(record)
    require(rational or method.is_polynomial, "pruning in h is defined for polynomial methods only "
            f"(a rational method's record names the variable {fmt.PRUNING_VARIABLE!r})")
    require(not (rational and method.is_polynomial), f"pruning in u = {fmt.PRUNING_VARIABLE} is written "
            "for rational methods only: a polynomial method's record is in h (no variable)")


def _conditions(problem: Any, claim: Any, context: Any, first_end_claim: Any = False) -> Any:
    """The proved generators and their conditions; computed once per certificate for
    the same generator lists (a fact this kernel derived itself, kept in the context).
    With a pruning record only the pairs that :mod:`exactinv_check.routes.pruning` cannot
    rule out are built, after proving that the record's vertex bounds the set by T;
    ``start`` is then that vertex's own set (first end) with its conditions, for
    :func:`valid_set` (:func:`first_end`) to start from (None otherwise).
    A box claim: P proved to be the box, the conditions of :mod:`exactinv_check.routes.boxes`."""
    require(problem.method is not None, "a method is needed")
    _pruning_variable(problem.method, claim.get("pruning"))
    box, lists = _generators(problem, claim)
    if "lp" in claim:
        key = ("lp", repr(claim["lp"]))
        if key not in context:
            gens, D, inequalities, equalities, horizon = lp_pieces.lp_conditions(problem, claim["lp"])
            lp_pieces.require_horizon(D, inequalities, equalities, horizon, context, key + ("set",))
            context[key] = (gens, D, inequalities, equalities)
        gens, D, inequalities, equalities = context[key]
        start = None
    elif box is not None:
        key = ("box", repr(box))
        if key not in context:
            D, inequalities, (lo, hi) = boxes.box_conditions(problem.A, problem.G, problem.b, problem.method.numerator,
                                                             problem.method.denominator, box)
            gens = SimpleNamespace(vertices=_BoxVertices(lo, hi), rays=[], lines=[], counts=(2 ** len(lo), 0, 0))
            context[key] = (gens, D, inequalities, {})
        gens, D, inequalities, equalities = context[key]
        start = None
    else:
        gens, D, inequalities, equalities, start = _listed(problem, claim, context, lists, first_end_claim)
    if claim.get("determinant") is not None:
        claimed = poly_arithmetic.trim(vector(claim["determinant"], "determinant"))
        require(poly_arithmetic.primitive(claimed) == poly_arithmetic.primitive(D), "det h(dt A) does not match")
    return gens, D, inequalities, equalities, start


def _listed(problem: Any, claim: Any, context: Any, lists: Any, first_end_claim: Any) -> Any:
    gkey = ("generators", repr(lists))
    if gkey not in context:
        g = prove_generators(problem.G, problem.b, *lists)
        context[gkey] = SimpleNamespace(vertices=g.vertices, rays=g.rays, lines=g.lines,
                                        counts=(len(g.vertices), len(g.rays), len(g.lines)))
    gens = context[gkey]
    record = claim.get("pruning")
    key = ("conditions", repr(lists), None if record is None else repr(record), first_end_claim and record is not None)
    if key not in context:
        if record is None:
            context[key] = (*condition_polynomials(problem.A, problem.G, problem.b, problem.method.numerator,
                                                   problem.method.denominator, gens), None)
        else:
            context[key] = _pruned(problem, gens, record, first_end_claim)
    return (gens, *context[key])


def _pruned(problem: Any, gens: Any, record: Any, first_end_claim: Any) -> Any:
    """The conditions of vertex k, the surviving pairs, every ray and line pair, and
    vertex k's own set (first end) with its conditions (:func:`_require_bound`)."""
    method = problem.method
    rational = pruning_rational.is_rational_record(record)
    _pruning_variable(method, record)
    if rational:
        s, U, count, k, _ = pruning_rational.parse(record, len(gens.vertices), problem.n)  # the kernel orders the vertices itself
        T = pruning_rational.horizon(s, U)
    else:
        T, k, _ = pruning.parse(record, len(gens.vertices))  # the kernel orders the vertices itself
    args = (problem.A, problem.G, problem.b, method.numerator, method.denominator)
    start = None if T is None else _require_bound(problem, gens, args, k, T, first_end_claim)
    D, N = method_matrices(problem.A, method.numerator, method.denominator)
    everything = range(problem.m)
    if not rational:
        near = pruning.survivors(problem.G, problem.b, gens.vertices, N, T)
        return (*condition_polynomials(*args, gens, lambda kind, i: (everything if kind != "vertex" or i == k else near[i])),
                start)
    pruning_rational.require_positive_determinant(D, T)
    near = pruning_rational.survivors(problem.G, problem.b, gens.vertices, D, N, s, U, count)
    return (*condition_polynomials(*args, gens, lambda kind, i: (everything if kind != "vertex" or i == k else near[i]),
                                   lambda kind, i: kind == "vertex" and (T is None or i != k)), start)


def _require_bound(problem: Any, gens: Any, args: Any, k: Any, T: Any, first_end_claim: Any) -> Any:
    """Vertex k's own valid set (first interval) ends by the horizon T; returns that set
    (its end) and vertex k's conditions, the ``start`` of :func:`valid_set` (:func:`first_end`)."""
    alone = SimpleNamespace(vertices=[gens.vertices[k]], rays=[], lines=[])
    D, own, _ = condition_polynomials(*args, alone)  # type: ignore[call-arg]
    if first_end_claim:
        end, _ = first_end(D, own, {})
        start = (end, list(own))
    else:
        own_set = valid_set(D, [], [], list(own))  # in facet order: near facets first, a bound early on
        end = own_set[-1].hi if own_set else Real.rational(0)
        start = (own_set, list(own))
    require(not end.inf and end.compare(Real.rational(T)) <= 0,
            f"vertex {k} does not bound the {'first interval' if first_end_claim else 'valid set'} by the "
            f"horizon {T}: its own ends at {end}")
    return start


def _first_vertex(inequalities: Any, claim: Any, n: int) -> list[Sequence[int]]:
    """The conditions of vertex 0: A_d(h)v in P alone already bounds the valid set
    for a bounded P, which lets the others be pruned (validset.valid_set).  A box claim
    rarely has vertex 0's conditions: there the n tightest ones (smallest p(0) relative
    to p's size) serve -- any subset is sound, a bounding one is faster."""
    if "box" in claim or "lp" in claim:
        return sorted(inequalities, key=lambda p: Fraction(abs(p[0]), max(map(abs, p))))[:n]
    return [p for p, origin in inequalities.items() if origin[:2] == ("vertex", 0)]


def largest_threshold(problem: Any, claim: Any, context: Any) -> str | None:
    gens, D, inequalities, equalities, start = _conditions(problem, claim, context, first_end_claim=True)
    tau, attained = first_end(D, inequalities, equalities, _first_vertex(inequalities, claim, problem.n), start)
    value = Real.parse(claim["value"], "tau")
    require(value.compare(tau) == 0, lambda: f"the largest threshold is {tau}, not {value}")
    require(boolean(claim["attained"], "attained") == attained, "the attained flag is wrong")
    binding = claim.get("binding")
    if binding is not None:
        require(isinstance(binding, dict) and set(binding) == {"kind", "generator", "facet", "poly"},
                "binding has the keys kind, generator, facet, poly")
        kind = binding["kind"]
        require(isinstance(kind, str) and kind in tuple(GeneratorKind), "binding kind is vertex, ray or line")
        field = {"vertex": "vertices", "ray": "rays", "line": "lines"}[kind]
        vectors = getattr(gens, field)
        i = integer(binding["generator"], "binding generator", 0, gens.counts[("vertex", "ray", "line").index(kind)])
        j = integer(binding["facet"], "binding facet", 0, problem.m)
        require(kind == "line" or i not in getattr(gens, "dual", ()),
                f"binding generator {i} is a dual piece of the lp record: its slot holds no point of P")
        one = SimpleNamespace(vertices=[], rays=[], lines=[])
        getattr(one, field).append(vectors[i])
        _, single, single_eq = condition_polynomials(problem.A, [problem.G[j]], [problem.b[j]],
                                                     problem.method.numerator, problem.method.denominator, one)
        own = list(single) + list(single_eq)
        require(len(own) == 1 and poly_arithmetic.primitive(vector(binding["poly"], "binding poly")) == list(own[0]),
                "the binding polynomial is not the recomputed condition of that generator and facet")
        end, _ = first_end(D, single, single_eq)
        require(end.compare(tau) == 0, "the binding condition does not end the first interval")
    return (f"largest threshold {value} ({'attained' if attained else 'not attained'}): recomputed from "
            f"{len(inequalities) + len(equalities)} distinct conditions over {_over(claim, gens)}")


def _over(claim: Any, gens: Any) -> str:
    if "lp" in claim:
        return (f"the LP route's {gens.counts[0]} pieces (each basis proved optimal on its piece by weak "
                f"duality, no vertex list)")
    if "box" in claim:
        return f"the box P proved from G and b (its {gens.counts[0]} vertices covered by the row sign patterns)"
    return f"{gens.counts[0]} vertices, {gens.counts[1]} rays and {gens.counts[2]} lines proved complete"


def valid_steplengths(problem: Any, claim: Any, context: Any) -> str | None:
    gens, D, inequalities, equalities, start = _conditions(problem, claim, context)
    truth = valid_set(D, list(inequalities), list(equalities), _first_vertex(inequalities, claim, problem.n), start)
    require_intervals(claim["intervals"], truth)
    return (f"the valid set {truth} recomputed from {len(inequalities) + len(equalities)} distinct conditions and "
            f"det h(hA): each condition proved >= 0 around the set by Descartes' rule or intersected exactly, "
            f"over {_over(claim, gens)}")
