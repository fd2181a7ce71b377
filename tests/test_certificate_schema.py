"""docs/certificate.schema.json and docs/certificate-format.md agree with the kernel and the engine.

* every certificate of the shared corpus (made by the engine) and every ```json
  example of docs/certificate-format.md is valid against the schema;
* every complete certificate shown in the doc is VERIFIED by the kernel;
* docs/certificate.schema.json is exactly the text generated from
  ``exactinv_check.format`` (``python -m exactinv_check.format``), and the
  schema's required/optional keys per claim type are exactly
  ``exactinv_check.kernel.CLAIMS`` (and its format, versions, boolean keys and
  radius reasons are the kernel's), so neither document can drift from the kernel;
* the schema is not vacuous: typical malformed certificates are invalid.

Validation uses a small validator for the subset of JSON Schema the schema
uses (below), so the test needs no extra dependency; when ``jsonschema`` is
installed it is run as well, and both must agree.
"""

import copy
import json
import re
from pathlib import Path

import pytest
from certificate_corpus import corpus

from exactinv_check import format as fmt
from exactinv_check import kernel
from exactinv_check.claims_radius import REASONS
from exactinv_check.kernel import CLAIMS

DOCS = Path(__file__).resolve().parent.parent / "docs"
SCHEMA = json.loads((DOCS / "certificate.schema.json").read_text())
DOC = (DOCS / "certificate-format.md").read_text()

try:
    import jsonschema
except ImportError:  # the small validator below is enough
    jsonschema = None


# ---------------------------------------------------------------------------- a small validator
_ANNOTATIONS = {"$schema", "$id", "$defs", "title", "description", "$comment", "examples"}
_TYPES = {
    "object": lambda x: isinstance(x, dict),
    "array": lambda x: isinstance(x, list),
    "string": lambda x: isinstance(x, str),
    "integer": lambda x: isinstance(x, int) and not isinstance(x, bool),
    "number": lambda x: isinstance(x, (int, float)) and not isinstance(x, bool),
    "boolean": lambda x: isinstance(x, bool),
    "null": lambda x: x is None,
}


def _equal(a, b):
    """JSON equality: true is not 1."""
    if isinstance(a, bool) or isinstance(b, bool):
        return type(a) is type(b) and a == b
    if isinstance(a, list) and isinstance(b, list):
        return len(a) == len(b) and all(_equal(x, y) for x, y in zip(a, b))
    if isinstance(a, dict) and isinstance(b, dict):
        return a.keys() == b.keys() and all(_equal(a[k], b[k]) for k in a)
    return a == b


def _resolve(ref, root):
    assert ref.startswith("#/"), f"only local references are supported: {ref}"
    node = root
    for part in ref[2:].split("/"):
        node = node[part.replace("~1", "/").replace("~0", "~")]
    return node


def errors(instance, schema, root=SCHEMA, path="$"):
    """The list of violations of ``schema`` by ``instance`` (empty: valid).

    Supports: type, const, enum, pattern, maxLength, minimum, required,
    properties, additionalProperties, dependentRequired, items, prefixItems, minItems,
    maxItems, oneOf, anyOf, allOf, $ref (to #/...).  Any other keyword is an
    error of the test, so the schema cannot silently outgrow this validator."""
    unknown = set(schema) - _ANNOTATIONS - {
        "type", "const", "enum", "pattern", "maxLength", "minimum", "required", "properties",
        "additionalProperties", "dependentRequired", "items", "prefixItems", "minItems", "maxItems", "oneOf", "anyOf", "allOf",
        "$ref"}
    assert not unknown, f"the test's validator does not support {sorted(unknown)}"
    out = []
    if "$ref" in schema:
        out += errors(instance, _resolve(schema["$ref"], root), root, path)
    if "type" in schema:
        types = schema["type"] if isinstance(schema["type"], list) else [schema["type"]]
        if not any(_TYPES[t](instance) for t in types):
            return out + [f"{path}: {instance!r:.60} is not of type {types}"]
    if "const" in schema and not _equal(instance, schema["const"]):
        out.append(f"{path}: {instance!r:.60} is not {schema['const']!r}")
    if "enum" in schema and not any(_equal(instance, e) for e in schema["enum"]):
        out.append(f"{path}: {instance!r:.60} is not one of {schema['enum']}")
    if isinstance(instance, str):
        if "pattern" in schema and re.search(schema["pattern"], instance) is None:
            out.append(f"{path}: {instance!r:.60} does not match {schema['pattern']}")
        if "maxLength" in schema and len(instance) > schema["maxLength"]:
            out.append(f"{path}: longer than {schema['maxLength']}")
    if "minimum" in schema and _TYPES["number"](instance) and instance < schema["minimum"]:
        out.append(f"{path}: {instance} < {schema['minimum']}")
    if isinstance(instance, dict):
        for key in schema.get("required", []):
            if key not in instance:
                out.append(f"{path}: missing key {key!r}")
        props = schema.get("properties", {})
        for key, value in instance.items():
            if key in props:
                out += errors(value, props[key], root, f"{path}.{key}")
            elif schema.get("additionalProperties") is False:
                out.append(f"{path}: unknown key {key!r}")
            elif isinstance(schema.get("additionalProperties"), dict):
                out += errors(value, schema["additionalProperties"], root, f"{path}.{key}")
        for key, needed in schema.get("dependentRequired", {}).items():
            if key in instance:
                out += [f"{path}: {key!r} needs {k!r}" for k in needed if k not in instance]
    if isinstance(instance, list):
        prefix = schema.get("prefixItems", [])
        for i, (x, sub) in enumerate(zip(instance, prefix)):
            out += errors(x, sub, root, f"{path}[{i}]")
        if "items" in schema:
            for i, x in enumerate(instance[len(prefix):], len(prefix)):
                out += errors(x, schema["items"], root, f"{path}[{i}]")
        if len(instance) < schema.get("minItems", 0):
            out.append(f"{path}: fewer than {schema['minItems']} items")
        if "maxItems" in schema and len(instance) > schema["maxItems"]:
            out.append(f"{path}: more than {schema['maxItems']} items")
    for sub in schema.get("allOf", []):
        out += errors(instance, sub, root, path)
    if "anyOf" in schema and all(errors(instance, s, root, path) for s in schema["anyOf"]):
        out.append(f"{path}: matches none of anyOf")
    if "oneOf" in schema:
        results = [errors(instance, s, root, path) for s in schema["oneOf"]]
        good = sum(1 for r in results if not r)
        if good != 1:
            detail = min(results, key=len) if good == 0 else []
            out.append(f"{path}: matches {good} of the oneOf branches (exactly one needed) {detail[:3]}")
    return out


_VALIDATORS: dict = {}


def _validator(schema):
    """jsonschema's validator for ``schema`` (resolved against the full schema), built once per schema
    object: ``jsonschema.validate`` re-checks the schema itself on every call, 0.2 s each, which made the
    kernel fuzz test spend most of its time here (the schema itself is checked once, in
    test_the_schema_is_a_valid_draft_2020_12_schema below)."""
    kept = _VALIDATORS.get(id(schema))
    if kept is None or kept[0] is not schema:
        kept = (schema, jsonschema.Draft202012Validator(SCHEMA if schema is SCHEMA else {**SCHEMA, **schema}))
        _VALIDATORS[id(schema)] = kept
    return kept[1]


def assert_valid(instance, schema=SCHEMA, what="instance"):
    found = errors(instance, schema)
    assert not found, f"{what} is not valid against the schema:\n" + "\n".join(found[:20])
    if jsonschema is not None:
        _validator(schema).validate(instance)


def is_valid(instance, schema=SCHEMA):
    ours = not errors(instance, schema)
    if jsonschema is not None:
        theirs = _validator(schema).is_valid(instance)
        assert ours == theirs, f"the test's validator ({ours}) and jsonschema ({theirs}) disagree on {instance!r:.200}"
    return ours


def _sub(name):
    """The schema of one $defs entry, resolvable against the full schema."""
    return {"$ref": f"#/$defs/{name}"}


# ---------------------------------------------------------------------------- the doc's examples
def doc_examples():
    """Every ```json block of docs/certificate-format.md, parsed."""
    blocks = re.findall(r"```json\n(.*?)```", DOC, flags=re.S)
    return [json.loads(b) for b in blocks]


def _kind(example):
    if "format" in example:
        return "certificate"
    if "type" in example:
        return "claim"
    assert set(example) <= {"A", "G", "b", "Q", "method", "B", "inputs", "hull"}, f"unrecognised example {example!r:.200}"
    return "problem"


# ---------------------------------------------------------------------------- tests
def test_the_schema_in_docs_is_the_one_generated_from_the_format():
    """The file can never drift: regenerate it with ``python -m exactinv_check.format > docs/certificate.schema.json``."""
    assert (DOCS / "certificate.schema.json").read_text() == fmt.schema_text()
    assert SCHEMA == fmt.json_schema()


def test_the_generator_runs_with_the_standard_library_only(tmp_path):
    import shutil
    import subprocess
    import sys

    import exactinv_check

    shutil.copytree(Path(exactinv_check.__file__).parent, tmp_path / "exactinv_check")
    done = subprocess.run([sys.executable, "-S", "-m", "exactinv_check.format"], cwd=tmp_path,
                          capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    assert done.stdout == (DOCS / "certificate.schema.json").read_text()


def test_the_format_tables_are_consistent():
    """Every key table of the kernel is the format's: claim types, keys, version-2 keys, boolean keys."""
    assert set(fmt.CLAIMS) == set(fmt.ClaimType) == set(CLAIMS)
    for kind, spec in fmt.CLAIMS.items():
        assert spec.required.isdisjoint(spec.optional) and "type" not in spec.keys, kind
        assert CLAIMS[kind][1:] == (set(spec.required), set(spec.optional)), kind
        for name, key in spec.keys.items():
            assert key.since in fmt.VERSIONS, (kind, name)
            assert (key.schema.get("type") == "boolean") == (name in fmt.BOOLEAN_KEYS), (kind, name)
    assert kernel.V2_KEYS == {"discrete_invariance": {"dt"}, "absolute_monotonicity_radius": {"poles"}}
    assert REASONS == set(fmt.RadiusReason)
    assert fmt.VERSION == max(fmt.VERSIONS) and kernel.FORMAT == fmt.FORMAT


def test_the_schema_is_a_valid_draft_2020_12_schema():
    assert SCHEMA["$schema"] == "https://json-schema.org/draft/2020-12/schema"
    if jsonschema is not None:
        jsonschema.Draft202012Validator.check_schema(SCHEMA)


@pytest.mark.parametrize("name", sorted(corpus()))
def test_every_corpus_certificate_is_valid(name):
    assert_valid(corpus()[name], what=f"corpus certificate {name}")


def test_the_doc_has_examples_of_every_kind_and_every_claim_type():
    examples = doc_examples()
    kinds = {_kind(e) for e in examples}
    assert kinds == {"certificate", "claim", "problem"}
    types = {e["type"] for e in examples if _kind(e) == "claim"}
    types |= {c["type"] for e in examples if _kind(e) == "certificate" for c in e["claims"]}
    assert types == set(CLAIMS), f"claim types without an example: {sorted(set(CLAIMS) - types)}"
    versions = {e["version"] for e in examples if _kind(e) == "certificate"}
    assert versions == set(kernel.VERSIONS)


@pytest.mark.parametrize("index", range(len(doc_examples())))
def test_every_doc_example_is_valid(index):
    example = doc_examples()[index]
    kind = _kind(example)
    schema = {"certificate": SCHEMA, "claim": _sub("claim"), "problem": _sub("problem")}[kind]
    assert_valid(example, schema, what=f"doc example {index} ({kind})")


def test_every_complete_certificate_in_the_doc_is_verified_by_the_kernel():
    from exactinv_check import check

    certificates = [e for e in doc_examples() if _kind(e) == "certificate"]
    assert certificates
    for cert in certificates:
        report = check(copy.deepcopy(cert))
        assert report.ok, str(report)


def _claim_schemas():
    out = {}
    for branch in SCHEMA["$defs"]["claim"]["oneOf"]:
        s = _resolve(branch["$ref"], SCHEMA)
        out[s["properties"]["type"]["const"]] = s
    return out


def test_the_schema_key_sets_are_the_kernels():
    schemas = _claim_schemas()
    assert set(schemas) == set(CLAIMS)
    for kind, (_, required, optional) in CLAIMS.items():
        s = schemas[kind]
        assert s["additionalProperties"] is False, kind
        assert set(s["required"]) == {"type"} | required, f"{kind}: required keys differ from the kernel's"
        assert set(s["properties"]) - set(s["required"]) == optional, f"{kind}: optional keys differ from the kernel's"
        for key in fmt.BOOLEAN_KEYS & (required | optional):
            assert s["properties"][key]["type"] == "boolean", f"{kind}.{key} must be a JSON boolean"


def test_the_schema_constants_are_the_kernels():
    envelope = SCHEMA["$defs"]["certificate"]
    assert envelope["properties"]["format"]["const"] == kernel.FORMAT
    assert set(envelope["properties"]["version"]["enum"]) == set(kernel.VERSIONS)
    assert set(envelope["required"]) == set(envelope["properties"]) == {"format", "version", "problem", "claims"}
    assert set(SCHEMA["$defs"]["problem"]["properties"]) == {"A", "G", "b", "Q", "method", "B", "inputs", "hull"}
    assert set(SCHEMA["$defs"]["method"]["properties"]) == {"name", "numerator", "denominator"}
    radius = _claim_schemas()["absolute_monotonicity_radius"]
    assert set(radius["properties"]["reason"]["enum"]) == REASONS


def test_the_doc_names_every_claim_type_and_key():
    for kind, (_, required, optional) in CLAIMS.items():
        assert f"## {kind}" in DOC or f"`{kind}`" in DOC, kind
        for key in required | optional:
            assert f"`{key}`" in DOC, f"{kind}: the doc never names the key {key!r}"


def test_the_proof_table_claims_nothing_on_trust():
    table = DOC.split("## What the kernel proves", 1)[1].split("\n## ", 1)[0]
    rows = [line for line in table.splitlines() if line.startswith("| ") and not line.startswith("| ---")]
    named = {m for row in rows for m in re.findall(r"`([a-z_]+)`", row.split("|")[1])}
    assert set(CLAIMS) <= named, f"claim types without a row: {sorted(set(CLAIMS) - named)}"
    for row in rows:
        assert not re.search(r"trusted|not re-?checked|unchecked", row, flags=re.I), row


def _mutants():
    """(what, certificate) pairs that the schema must reject."""
    base = corpus()["box-taylor4"]

    def mutate(f):
        c = copy.deepcopy(base)
        f(c)
        return c

    gamma = 0  # claims[0] is gamma_star
    return [
        ("a JSON float", mutate(lambda c: c["claims"][gamma].update(value=1.0))),
        ("a JSON integer for a number", mutate(lambda c: c["problem"]["b"].__setitem__(0, 1))),
        ("an exponent", mutate(lambda c: c["claims"][gamma].update(value="1e0"))),
        ("a zero denominator", mutate(lambda c: c["claims"][gamma].update(value="1/0"))),
        ("a space in a number", mutate(lambda c: c["problem"]["b"].__setitem__(0, " 1"))),
        ("an over-long number", mutate(lambda c: c["problem"]["b"].__setitem__(0, "1" * 4001))),
        ("an unknown claim key", mutate(lambda c: c["claims"][gamma].update(trust_me=True))),
        ("an unknown envelope key", mutate(lambda c: c.update(comment="x"))),
        ("an unknown problem key", mutate(lambda c: c["problem"].update(P="x"))),
        ("a missing required key", mutate(lambda c: c["claims"][1].pop("vertices"))),
        ("an unknown claim type", mutate(lambda c: c["claims"][gamma].update(type="gamma"))),
        ("version 4", mutate(lambda c: c.update(version=4))),
        ("a wrong format", mutate(lambda c: c.update(format="exactinv"))),
        ("no claims", mutate(lambda c: c.update(claims=[]))),
        ("a string boolean", mutate(lambda c: c["claims"][3].update(attained="true"))),
        ("an algebraic number with an extra key",
         mutate(lambda c: c["claims"][3].update(value={"poly": ["-2", "0", "1"], "interval": ["1", "2"], "approx": "1.41"}))),
        ("an algebraic number of degree 0",
         mutate(lambda c: c["claims"][3].update(value={"poly": ["2"], "interval": ["1", "2"]}))),
        ("an algebraic number of degree 1001",  # MAX_ALGEBRAIC_DEGREE: above 200 priced by size, not refused
         mutate(lambda c: c["claims"][3].update(value={"poly": ["-2"] + ["0"] * 1000 + ["1"], "interval": ["1", "2"]}))),
        ("oo where a rational is needed", mutate(lambda c: c["problem"]["b"].__setitem__(0, "oo"))),
        ("an algebraic gamma*",
         mutate(lambda c: c["claims"][gamma].update(value={"poly": ["-2", "0", "1"], "interval": ["1", "2"]}))),
        ("a finite gamma* without its dual", mutate(lambda c: c["claims"][gamma].pop("dual"))),
        ("A without G and b", mutate(lambda c: [c["problem"].pop("G"), c["problem"].pop("b")])),
        ("a method without a denominator", mutate(lambda c: c["problem"]["method"].pop("denominator"))),
        ("a negative index", mutate(lambda c: c["claims"][gamma].update(binding_row=-1))),
        ("a boolean index", mutate(lambda c: c["claims"][gamma].update(binding_row=False))),
        ("forward Euler not attained", mutate(lambda c: c["claims"][1].update(attained=False))),
    ]


@pytest.mark.parametrize("what,cert", _mutants(), ids=[w for w, _ in _mutants()])
def test_the_schema_rejects_malformed_certificates(what, cert):
    assert not is_valid(cert), f"the schema accepts {what}"


def test_discrete_invariance_needs_Ad_or_dt_and_the_right_evidence():
    claim = {"type": "discrete_invariance", "holds": True, "H": [["1"]]}
    assert not is_valid(claim, _sub("claim"))
    assert is_valid({**claim, "dt": "1/2"}, _sub("claim"))
    assert is_valid({**claim, "Ad": [["1"]]}, _sub("claim"))
    assert not is_valid({"type": "discrete_invariance", "holds": False, "Ad": [["1"]], "H": [["1"]]}, _sub("claim"))
