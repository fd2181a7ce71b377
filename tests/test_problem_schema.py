"""docs/problem.schema.json and docs/problem-format.md agree with the problem-file reader.

* every example under examples/ (and every ```json example of the doc) is valid
  against the schema and is read by ``load_problem``;
* the schema's method kinds and preset names are exactly the reader's;
* the schema is not vacuous: misspelled keys, floats, mixed forms are invalid,
  and the reader refuses them too.
"""

import json
import re
from pathlib import Path

import jsonschema
import pytest

from exactinv.errors import InvalidInput
from exactinv.interfaces.method_format import METHOD_KINDS
from exactinv.interfaces.problem import TOP_KEYS, load_problem
from exactinv.model.methods import PRESETS

ROOT = Path(__file__).resolve().parent.parent
SCHEMA = json.loads((ROOT / "docs" / "problem.schema.json").read_text())
DOC = (ROOT / "docs" / "problem-format.md").read_text()
VALIDATOR = jsonschema.Draft202012Validator(SCHEMA)
EXAMPLES = sorted((ROOT / "examples").rglob("*.json"))
DOC_EXAMPLES = [json.loads(block) for block in re.findall(r"```json\n(.*?)```", DOC, re.S)]


def test_the_schema_is_a_valid_schema():
    jsonschema.Draft202012Validator.check_schema(SCHEMA)


@pytest.mark.parametrize("path", EXAMPLES, ids=[p.name for p in EXAMPLES])
def test_every_example_validates_and_loads(path):
    data = json.loads(path.read_text())
    VALIDATOR.validate(data)
    load_problem(path)


def test_the_doc_has_examples_of_every_form():
    assert len(DOC_EXAMPLES) >= 8
    kinds = {next(iter(d["method"])) if isinstance(d.get("method"), dict) else d.get("method") for d in DOC_EXAMPLES}
    assert set(METHOD_KINDS) <= kinds | {None} | set(PRESETS), set(METHOD_KINDS) - kinds
    assert any("A0" in d["system"] for d in DOC_EXAMPLES)
    assert any("vertices" in d.get("polyhedron", {}) for d in DOC_EXAMPLES)
    assert any("ellipsoid" in d for d in DOC_EXAMPLES)
    assert any("cdd" in d.get("polyhedron", {}) for d in DOC_EXAMPLES)


@pytest.mark.parametrize("k", range(len(DOC_EXAMPLES)))
def test_every_doc_example_validates_and_loads(k):
    VALIDATOR.validate(DOC_EXAMPLES[k])
    load_problem(DOC_EXAMPLES[k], base=str(ROOT / "examples" / "cdd"))  # the cdd example's file lives there


def test_schema_and_reader_know_the_same_names():
    assert set(SCHEMA["$defs"]["problem"]["properties"]) == set(TOP_KEYS)
    kinds = set()
    for alternative in SCHEMA["$defs"]["method"]["oneOf"]:
        kinds |= set(alternative.get("properties", {}))
    assert kinds == set(METHOD_KINDS)
    assert set(SCHEMA["$defs"]["preset"]["enum"]) == set(PRESETS)
    for name in PRESETS:
        assert f"`{name}`" in DOC, name
    for kind in METHOD_KINDS:
        assert f'"{kind}"' in DOC, kind


BOX = {"system": {"A": [["-1", "1"], ["-1", "-1"]]},
       "polyhedron": {"G": [[1, 0], [-1, 0], [0, 1], [0, -1]], "b": [1, 1, 1, 1]}}
BAD = {
    "misspelled top key": {**BOX, "methd": {"taylor": 4}},
    "misspelled nested key": {**BOX, "polyhedron": {"G": [[1, 0]], "bb": [1]}},
    "float": {**BOX, "system": {"A": [[-1.5, 1], [-1, -1]]}},
    "mixed polyhedron forms": {**BOX, "polyhedron": {"G": [[1, 0]], "b": [1], "vertices": [[1, 0]]}},
    "mixed system forms": {**BOX, "system": {"A": [["1"]], "A0": [["1"]]}},
    "unknown method": {**BOX, "method": {"euler": 1}},
    "unknown preset": {**BOX, "method": "rk5"},
    "two method keys": {**BOX, "method": {"taylor": 2, "theta": "1/2"}},
    "butcher key": {**BOX, "method": {"butcher": {"A": [[0]], "b": [1], "cc": [0]}}},
    "not a number": {**BOX, "polyhedron": {"G": [[1, 0]], "b": ["one"]}},
    "no system": {"polyhedron": BOX["polyhedron"]},
    "polyhedron and ellipsoid": {**BOX, "ellipsoid": {"Q": [[1, 0], [0, 1]]}},
    "ellipsoid without Q": {"system": BOX["system"], "ellipsoid": {"q": [[1, 0], [0, 1]]}},
    "cdd with G": {**BOX, "polyhedron": {"cdd": "octagon.ine", "G": [[1, 0]]}},
    "cdd not a string": {**BOX, "polyhedron": {"cdd": ["octagon.ine"]}},
    "cdd empty": {**BOX, "polyhedron": {"cdd": ""}},
}


@pytest.mark.parametrize("name", sorted(BAD))
def test_bad_problems_are_invalid_for_both(name):
    assert not VALIDATOR.is_valid(BAD[name])
    with pytest.raises(InvalidInput):
        load_problem(BAD[name])
