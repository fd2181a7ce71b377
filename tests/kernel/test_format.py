"""exactinv_check.format: the one definition of the certificate vocabulary.

Soundness of the vocabulary: the kernel's tables are the format's; the engine spells no certificate
string of its own (it imports the names); the tables are immutable; the schema follows the bounds.
(The generated schema against docs/certificate.schema.json: tests/test_certificate_schema.py.)
"""


import ast
import json
from pathlib import Path

import pytest

from exactinv_check import format as fmt
from exactinv_check import kernel, rationals, tail
from exactinv_check.routes import pruning, pruning_rational

ROOT = Path(__file__).resolve().parents[2]


def _engine_strings():
    """(file, line, string) of every string constant in exactinv/ outside docstrings."""
    for path in sorted((ROOT / "exactinv").rglob("*.py")):
        tree = ast.parse(path.read_text())
        docs = {id(node.body[0].value) for node in ast.walk(tree)
                if isinstance(node, (ast.Module, ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef))
                and node.body and isinstance(node.body[0], ast.Expr) and isinstance(node.body[0].value, ast.Constant)}
        for node in ast.walk(tree):
            if isinstance(node, ast.Dict):
                for k, v in zip(node.keys, node.values):
                    if isinstance(k, ast.Constant) and k.value == "type" and isinstance(v, ast.Constant):
                        yield path, v.lineno, ("type", v.value)
            if isinstance(node, ast.Constant) and isinstance(node.value, str) and id(node) not in docs:
                yield path, node.lineno, node.value


# ------------------------------------------------------------------ soundness

def test_tags_are_their_strings_so_certificates_are_byte_identical():
    assert json.dumps({"type": fmt.ClaimType.GAMMA_STAR, "reason": fmt.RadiusReason.BALANCED_TIE}) == \
        '{"type": "gamma_star", "reason": "balanced-tie"}'
    assert repr(fmt.ClaimType.OPTIMAL_GAIN) == "'optimal_gain'"
    assert [str(v) for v in fmt.Verdict] == ["accepted", "rejected", "over-budget", "kernel-fault", "bad-input"]


def test_the_kernel_reads_its_tables_and_bounds_from_the_format():
    assert kernel.FORMAT == fmt.FORMAT and kernel.VERSIONS == fmt.VERSIONS
    assert {kind: (req, opt) for kind, (_, req, opt) in kernel.CLAIMS.items()} == \
        {kind: (set(s.required), set(s.optional)) for kind, s in fmt.CLAIMS.items()}
    assert set(kernel.HANDLERS) == set(fmt.ClaimType)
    assert kernel.V2_KEYS == fmt.keys_since(1) and fmt.keys_since(2) == {} == fmt.keys_since(3)
    assert (rationals.MAX_DIGITS, tail.MAX_INDEX, pruning.HORIZON_BITS, pruning_rational.MAX_PIECES,
            pruning_rational.VARIABLE) == (fmt.MAX_DIGITS, fmt.MAX_TAIL_INDEX, fmt.HORIZON_BITS,
                                           fmt.MAX_RATIONAL_PIECES, fmt.PRUNING_VARIABLE)


def test_the_engine_shares_the_kernels_constants():
    from exactinv.conditions import pruning as engine_pruning
    from exactinv.conditions import pruning_rational as engine_rational
    from exactinv.core import encode
    from exactinv.monotonicity import line_poles, poles
    from exactinv.monotonicity import tail as monotonicity_tail

    assert (encode.FORMAT, encode.VERSION) == (fmt.FORMAT, fmt.VERSION)
    assert engine_pruning.HORIZON_BITS is fmt.HORIZON_BITS and engine_rational.VARIABLE is fmt.PRUNING_VARIABLE
    assert line_poles.MAX_LINE_EXPONENT is fmt.MAX_LINE_EXPONENT
    assert monotonicity_tail._MAX_INDEX is fmt.MAX_COEFFICIENTS and poles._MAX_INDEX is fmt.MAX_TAIL_INDEX


def test_the_engine_spells_no_certificate_vocabulary_of_its_own():
    """FORMAT, the pruning variable, the radius reasons and the claim types as a claim's "type" are
    imported from exactinv_check.format, never written as literals (function names that equal a claim
    type, e.g. ``__all__ = ["largest_threshold"]``, are not the vocabulary)."""
    words = {fmt.FORMAT, fmt.PRUNING_VARIABLE} | {str(r) for r in fmt.RadiusReason if "-" in r}
    claim_types = {str(k) for k in fmt.ClaimType}
    found = [f"{path.relative_to(ROOT)}:{line}: {value!r}" for path, line, value in _engine_strings()
             if value in words or (isinstance(value, tuple) and value[1] in claim_types)]
    assert not found, "spell these with exactinv_check.format's names:\n" + "\n".join(found)


def test_the_tables_are_immutable():
    spec = fmt.CLAIMS[fmt.ClaimType.GAMMA_STAR]
    with pytest.raises(TypeError):
        fmt.CLAIMS["new_claim"] = spec
    with pytest.raises(TypeError):
        spec.keys["new_key"] = spec.keys["value"]
    with pytest.raises(AttributeError):
        spec.keys["value"].required = False
    with pytest.raises(AttributeError):
        spec.description = "changed"


def test_the_schema_follows_the_bounds_and_vocabulary(monkeypatch):
    schema = fmt.json_schema()
    defs = schema["$defs"]
    assert defs["algebraic"]["properties"]["poly"]["maxItems"] == fmt.MAX_ALGEBRAIC_DEGREE + 1
    assert defs["rational"]["maxLength"] == fmt.MAX_DIGITS
    assert defs["claim_absolute_monotonicity_radius"]["properties"]["reason"]["enum"] == [str(r) for r in fmt.RadiusReason]
    assert defs["claim_absolute_monotonicity_radius"]["properties"]["poles"]["oneOf"][0]["maxItems"] == fmt.MAX_POLES
    assert len(str(2 ** fmt.HORIZON_BITS - 1)) * 2 + 1 == defs["pruning"]["oneOf"][0]["properties"]["horizon"]["maxLength"]
    monkeypatch.setattr(fmt, "MAX_ALGEBRAIC_DEGREE", 10)
    assert fmt.json_schema()["$defs"]["algebraic"]["properties"]["poly"]["maxItems"] == 11
    for kind, spec in fmt.CLAIMS.items():
        claim = defs[f"claim_{kind}"]
        assert claim["properties"]["type"] == {"const": kind}
        assert set(claim["required"]) == {"type"} | spec.required


# ------------------------------------------------------------------ resource
# No test here is about this module's work limits: the certificate's account is tested in test_budget.py.
