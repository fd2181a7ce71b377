"""cdd files (exactinv/model/cdd.py, Polyhedron.from_cdd / to_cdd): hand-written
cddlib-style samples read to the set they describe (checked against pplpy built
here, independently of Polyhedron), exact round trips H -> cdd -> H and
V -> cdd -> V (hypothesis, random rational polytopes), 'real' files refused
unless opted in, and every malformed file refused naming its line."""

from __future__ import annotations

import json
from fractions import Fraction
from math import lcm
from pathlib import Path

import ppl
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import exactinv as ei
from exactinv.interfaces.problem import load_problem
from exactinv.model.cdd import parse_cdd, read_cdd

ROOT = Path(__file__).resolve().parents[2]


def ppl_h(G, b):
    """{x : Gx <= b} as a pplpy polyhedron, built here from the rows."""
    cs = ppl.Constraint_System()
    for g, beta in zip(G, b):
        g = [Fraction(x) for x in g]
        d = lcm(*(x.denominator for x in g), Fraction(beta).denominator)
        cs.insert(ppl.Linear_Expression([int(-x * d) for x in g], int(Fraction(beta) * d)) >= 0)
    return ppl.C_Polyhedron(cs)


def ppl_v(points, rays=(), lines=()):
    gs = ppl.Generator_System()
    for p in points:
        p = [Fraction(x) for x in p]
        d = lcm(*(x.denominator for x in p))
        gs.insert(ppl.point(ppl.Linear_Expression([int(x * d) for x in p], 0), d))
    for kind, gens in ((ppl.ray, rays), (ppl.line, lines)):
        for r in gens:
            gs.insert(kind(ppl.Linear_Expression([int(x) for x in r], 0)))
    return ppl.C_Polyhedron(gs)


def same_set(P: ei.Polyhedron, Q: ei.Polyhedron) -> bool:
    return ppl_h(P.G, P.b) == ppl_h(Q.G, Q.b)


# ---------------------------------------------------------------- samples
CUBE_INE = """* the cube [-1, 1]^3, as cddlib's examples write it
cube
H-representation
begin
  6  4  integer
  1  1  0  0
  1  0  1  0
  1  0  0  1
  1 -1  0  0
  1  0 -1  0
  1  0  0 -1
end
incidence
"""

CUBE_EXT = """V-representation
begin
8 4 integer
1  1  1  1
1 -1  1  1
1  1 -1  1
1 -1 -1  1
1  1  1 -1
1 -1  1 -1
1  1 -1 -1
1 -1 -1 -1
end
"""

# the triangle {x, y, z >= 0, x + y + z = 1/2}: one linearity row, rational entries
SIMPLEX_INE = """H-representation
linearity 1 4
begin
4 4 rational
0 1 0 0
0 0 1 0
0 0 0 1
1/2 -1 -1 -1
end
"""

# the quadrant cone x >= 0, y >= 0 by rays only: cdd implies the origin
CONE_EXT = """V-representation
begin
 2 3 rational
 0 1 0
 0 0 1
end
"""

# the strip |y| <= 2/3 along the x axis: points plus a line (linearity names a ray row)
STRIP_EXT = """* a strip
V-representation
linearity 1 3
begin
3 3 rational
1 0 2/3
1 0 -2/3
0 1 0
end
"""


def test_cube_ine_is_the_cube():
    P = ei.Polyhedron.from_cdd(CUBE_INE)
    assert P.G == tuple(tuple(Fraction(-x) for x in r) for r in
                        ((1, 0, 0), (0, 1, 0), (0, 0, 1), (-1, 0, 0), (0, -1, 0), (0, 0, -1)))
    assert P.b == (1,) * 6
    assert same_set(P, ei.Polyhedron.box([-1] * 3, [1] * 3))


def test_cube_ext_is_the_cube():
    P = ei.Polyhedron.from_cdd(CUBE_EXT)
    assert same_set(P, ei.Polyhedron.box([-1] * 3, [1] * 3))
    assert len(P.vertices) == 8 and P.is_bounded


def test_linearity_is_an_equality():
    P = ei.Polyhedron.from_cdd(SIMPLEX_INE)
    assert P.dimension == 2
    half = Fraction(1, 2)
    assert set(P.vertices) == {(half, 0, 0), (0, half, 0), (0, 0, half)}
    assert P.contains(["1/6", "1/6", "1/6"]) and not P.contains(["1/6", "1/6", "1/7"])
    assert ppl_h(P.G, P.b) == ppl_v([(half, 0, 0), (0, half, 0), (0, 0, half)])


def test_rays_without_a_point_contain_the_origin():
    P = ei.Polyhedron.from_cdd(CONE_EXT)
    assert ppl_h(P.G, P.b) == ppl_v([(0, 0)], rays=[(1, 0), (0, 1)])
    assert P.rays == ((0, 1), (1, 0)) and P.vertices == ((0, 0),)


def test_linearity_in_a_v_representation_is_a_line():
    P = ei.Polyhedron.from_cdd(STRIP_EXT)
    assert P.lines in (((1, 0),), ((-1, 0),))
    assert P.contains([10**9, "2/3"]) and not P.contains([0, "3/4"])
    assert ppl_h(P.G, P.b) == ppl_v([(0, Fraction(2, 3)), (0, Fraction(-2, 3))], lines=[(1, 0)])


def test_files_and_paths(tmp_path):
    path = tmp_path / "cube.ine"
    path.write_text(CUBE_INE)
    assert ei.Polyhedron.from_cdd(path) == ei.Polyhedron.from_cdd(str(path)) == ei.Polyhedron.from_cdd(CUBE_INE)
    out = tmp_path / "cube.ext"
    text = ei.Polyhedron.from_cdd(path).to_cdd("ext", out)
    assert out.read_text() == text
    assert same_set(ei.Polyhedron.from_cdd(out), ei.Polyhedron.from_cdd(path))


def test_written_files_follow_the_format():
    P = ei.Polyhedron([[1, "1/2"], [-1, 0], [0, -1]], [1, 0, "1/3"])
    assert P.to_cdd("ine") == "H-representation\nbegin\n3 3 rational\n1 -1 -1/2\n0 1 0\n1/3 0 1\nend\n"
    assert P.to_cdd() == P.to_cdd("H") == P.to_cdd("ine")
    box = ei.Polyhedron.box([0, 0], [1, 2])
    assert box.to_cdd("ext") == "V-representation\nbegin\n4 3 integer\n1 0 0\n1 0 2\n1 1 0\n1 1 2\nend\n"
    strip = ei.Polyhedron.from_cdd(STRIP_EXT).to_cdd("ext")
    assert "linearity 1 3" in strip.splitlines()[1]


# ---------------------------------------------------------------- real files
REAL_INE = """H-representation
begin
2 2 real
0.1 -1
1e-1 1
end
"""


def test_real_files_are_refused_naming_file_and_line(tmp_path):
    path = tmp_path / "p.ine"
    path.write_text(REAL_INE)
    with pytest.raises(ei.ExactinvError, match=rf"{path}, line 3: the number type is 'real'.*allow_float=True"):
        ei.Polyhedron.from_cdd(path)


def test_real_files_with_the_opt_in_read_exact_doubles():
    P = ei.Polyhedron.from_cdd(REAL_INE, allow_float=True)
    assert P.b == (ei.exact_from_float(0.1), ei.exact_from_float(0.1))
    assert P.b[0] != Fraction(1, 10)  # the double, not the decimal
    third = read_cdd("begin\n1 2 real\n1/3 1\nend\n", allow_float=True)
    assert third.b == (ei.exact_from_float(1 / 3),)


def test_decimals_in_a_rational_file_are_refused():
    with pytest.raises(ei.ExactinvError, match=r"line 3: '0.5' is not an integer or p/q.*a decimal"):
        parse_cdd("begin\n1 2 rational\n0.5 1\nend")


# ---------------------------------------------------------------- malformed
MALFORMED = {
    "no begin": ("H-representation\n1 2 integer\n1 1\nend\n", r"no 'begin' line"),
    "no end": ("begin\n1 2 integer\n1 1\n", r"no 'end' line"),
    "nothing after begin": ("H-representation\nbegin\n\n", r"nothing after 'begin'"),
    "bad size line": ("begin\n1 integer\n1 1\nend\n", r"line 2: expected the size line"),
    "size not integers": ("begin\nm 2 integer\n1 1\nend\n", r"line 2: .*needs two integers"),
    "unknown number type": ("begin\n1 2 float\n1 1\nend\n", r"line 2: unknown number type 'float'"),
    "too few rows": ("begin\n3 2 integer\n1 1\n1 -1\nend\n", r"line 2: the size line announces 3 rows but 2"),
    "short row": ("begin\n2 3 integer\n1 1 0\n1 -1\nend\n", r"line 4: the row has 2 entries, expected 3"),
    "not a number": ("begin\n1 2 integer\n1 x\nend\n", r"line 3: 'x' is not an integer"),
    "fraction in integer file": ("begin\n1 2 integer\n1/2 1\nend\n", r"line 3: '1/2' is not an integer"),
    "zero denominator": ("begin\n1 2 rational\n1/0 1\nend\n", r"line 3: '1/0' divides by zero"),
    "linearity count": ("linearity 2 1\nbegin\n1 2 integer\n1 1\nend\n", r"line 1: 'linearity k i_1 \.\.\. i_k' must list"),
    "linearity out of range": ("linearity 1 5\nbegin\n1 2 integer\n1 1\nend\n", r"line 1: linearity names row 5"),
    "linearity zero": ("linearity 1 0\nbegin\n1 2 integer\n1 1\nend\n", r"line 1: linearity row indices start at 1"),
    "empty row": ("begin\n2 2 integer\n-1 0\n1 1\nend\n", r"line 3: the row reads 0 <= -1, so the polyhedron is empty"),
    "whole space": ("begin\n1 2 integer\n1 0\nend\n", r"no inequality; P would be the whole space"),
    "V row neither 0 nor 1": ("V-representation\nbegin\n1 2 integer\n2 1\nend\n",
                              r"line 4: a V-representation row starts with 1"),
    "V zero ray": ("V-representation\nbegin\n2 2 integer\n1 1\n0 0\nend\n", r"line 5: the ray is the zero vector"),
    "V point as line": ("V-representation\nlinearity 1 1\nbegin\n1 2 integer\n1 1\nend\n",
                        r"line 5: linearity names row 1, a point"),
    "V whole space": ("V-representation\nlinearity 1 2\nbegin\n2 2 integer\n1 0\n0 1\nend\n", r"span the whole space"),
}


@pytest.mark.parametrize("name", sorted(MALFORMED))
def test_malformed_files_are_refused_clearly(name, tmp_path):
    text, message = MALFORMED[name]
    with pytest.raises(ei.ExactinvError, match=message) as info:
        ei.Polyhedron.from_cdd(text)
    assert str(info.value).startswith("cdd text")
    path = tmp_path / "bad.ine"
    path.write_text(text)
    with pytest.raises(ei.ExactinvError, match=rf"^{path}[:,]"):
        ei.Polyhedron.from_cdd(path)


def test_missing_file_and_bad_arguments(tmp_path):
    with pytest.raises(ei.ExactinvError, match=r"nope.ine: cannot read the cdd file"):
        ei.Polyhedron.from_cdd(tmp_path / "nope.ine")
    with pytest.raises(ei.ExactinvError, match=r"is a directory"):
        ei.Polyhedron.from_cdd(tmp_path)
    with pytest.raises(ei.ExactinvError, match=r"expected a path or the text"):
        ei.Polyhedron.from_cdd(42)
    with pytest.raises(ei.ExactinvError, match=r'kind: expected "ine"'):
        ei.Polyhedron.box([0], [1]).to_cdd("lrs")
    empty = ei.Polyhedron([[1], [-1]], [0, -1])
    with pytest.raises(ei.ExactinvError, match=r"P is empty"):
        empty.to_cdd("ext")
    assert empty.to_cdd("ine")  # an empty P still has its inequalities


# ---------------------------------------------------------------- round trips
rationals = st.fractions(min_value=-5, max_value=5, max_denominator=7)


@st.composite
def polytopes(draw):
    n = draw(st.integers(1, 3))
    points = draw(st.lists(st.tuples(*[rationals] * n), min_size=n + 1, max_size=7))
    return [list(p) for p in points]


@settings(max_examples=40, deadline=None)
@given(polytopes())
def test_round_trips_of_random_rational_polytopes(points):
    P = ei.Polyhedron.from_vertices(points)
    H = ei.Polyhedron.from_cdd(P.to_cdd("ine"))
    assert (H.G, H.b) == (P.G, P.b)          # H -> cdd -> H: the same rows, exactly
    V = ei.Polyhedron.from_cdd(P.to_cdd("ext"))
    assert same_set(V, P)                      # V -> cdd -> V: the same set
    assert V.vertices == P.vertices
    assert ppl_h(P.G, P.b) == ppl_v(points)    # and the set is the hull of the points


@settings(max_examples=25, deadline=None)
@given(st.integers(1, 3).flatmap(lambda n: st.tuples(
    st.lists(st.tuples(*[rationals] * n), min_size=1, max_size=4),
    st.lists(st.tuples(*[st.integers(-3, 3)] * n).filter(any), max_size=2),
    st.lists(st.tuples(*[st.integers(-3, 3)] * n).filter(any), max_size=1))))
def test_round_trips_with_rays_and_lines(gens):
    points, rays, lines = gens
    try:
        P = ei.Polyhedron.from_vertices(points, rays, lines)
    except ei.ExactinvError:  # the generators span the whole space
        return
    for kind in ("ine", "ext"):
        Q = ei.Polyhedron.from_cdd(P.to_cdd(kind))
        assert same_set(P, Q), kind
    assert ppl_h(P.G, P.b) == ppl_v(points, rays, lines)


# ---------------------------------------------------------------- problem files
def test_a_problem_file_reads_its_cdd_file(tmp_path):
    example = load_problem(ROOT / "examples" / "cdd" / "octagon_heun_cdd.json")
    twin = load_problem(ROOT / "examples" / "octagon_heun.json")
    assert same_set(example.polyhedron, twin.polyhedron)
    assert example.system == twin.system
    m = example.method
    assert ei.steplength_threshold(example.system, example.polyhedron, m).value == \
        ei.steplength_threshold(twin.system, twin.polyhedron, m).value


def test_problem_cdd_paths_are_relative_to_the_problem_file(tmp_path, monkeypatch):
    (tmp_path / "sets").mkdir()
    (tmp_path / "sets" / "box.ext").write_text("V-representation\nbegin\n2 2 integer\n1 -1\n1 1\nend\n")
    problem = tmp_path / "sets" / "p.json"
    problem.write_text(json.dumps({"system": {"A": [[-1]]}, "polyhedron": {"cdd": "box.ext"}}))
    monkeypatch.chdir(tmp_path)
    assert load_problem(problem).polyhedron.b == (1, 1)
    as_dict = {"system": {"A": [[-1]]}, "polyhedron": {"cdd": "sets/box.ext"}}
    assert load_problem(as_dict).polyhedron.b == (1, 1)          # a dict: the working directory
    assert load_problem({**as_dict, "polyhedron": {"cdd": "box.ext"}}, base=str(tmp_path / "sets")).polyhedron.m == 2
    inline = {"system": {"A": [[-1]]}, "polyhedron": {"cdd": CONE_EXT.replace("0 1 0\n 0 0 1", "0 1").replace("2 3", "1 2")}}
    assert load_problem(inline).polyhedron.rays == ((1,),)


def test_problem_cdd_errors_name_everything(tmp_path):
    (tmp_path / "real.ine").write_text(REAL_INE)
    problem = tmp_path / "p.json"
    problem.write_text(json.dumps({"system": {"A": [[-1]]}, "polyhedron": {"cdd": "real.ine"}}))
    with pytest.raises(ei.ExactinvError, match=rf"^{problem}: polyhedron.cdd: {tmp_path / 'real.ine'}, line 3: .*'real'"):
        load_problem(problem)
    problem.write_text(json.dumps({"system": {"A": [[-1]]}, "polyhedron": {"cdd": "missing.ine"}}))
    with pytest.raises(ei.ExactinvError, match=r"polyhedron.cdd: .*missing.ine: cannot read the cdd file"):
        load_problem(problem)


def test_a_batch_finds_the_cdd_file_next_to_its_problem(tmp_path, monkeypatch):
    from exactinv.interfaces.batch.corpus import read_corpus
    from exactinv.interfaces.batch.task import Limits, run_task

    monkeypatch.chdir(tmp_path)  # not the examples' folder
    tasks = [t for t in read_corpus([str(ROOT / "examples" / "cdd")]) if t.kind == "certify"]
    assert tasks
    for task in tasks:
        record = run_task(task, Limits(timeout=300, check=True))
        assert record["status"] == "ok", record
    lines = tmp_path / "corpus.jsonl"   # a .jsonl corpus: relative to the corpus file's folder
    (tmp_path / "sets").mkdir()
    (tmp_path / "sets" / "seg.ine").write_text("begin\n2 2 integer\n1 -1\n1 1\nend\n")
    lines.write_text(json.dumps({"name": "seg", "system": {"A": [[-1]]}, "polyhedron": {"cdd": "sets/seg.ine"},
                                 "method": {"taylor": 2}}) + "\n")
    monkeypatch.chdir(ROOT)
    (task,) = read_corpus([str(lines)])
    record = run_task(task, Limits(timeout=300, check=True))
    assert record["status"] == "ok" and record["values"]["largest_threshold"] == "2", record
