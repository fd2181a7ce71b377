"""Forged certificates: one per defect class the kernel once accepted.

Each forgery starts from a genuine certificate (which the kernel verifies),
changes what a cheat would change, and must be rejected with a reason.
"""


import copy
import json
import time

import pytest
from certificate_corpus import BOX, ROT, corpus

import exactinv as ei
from exactinv.certificates import certificate
from exactinv_check import check


def _genuine(name):
    cert = copy.deepcopy(corpus()[name])
    assert check(cert).ok, check(cert)
    return cert


def _claim(cert, kind):
    return next(c for c in cert["claims"] if c["type"] == kind)


def _rejected(cert, reason=""):
    report = check(json.loads(json.dumps(cert)))
    assert not report.ok, f"accepted:\n{report}"
    text = str(report)
    assert reason.lower() in text.lower(), text
    return text


def _e2_counterexample():
    S, O = ei.LinearSystem([[-1, 2], [0, 1]]), ei.Polyhedron([[-1, 0], [0, -1]], [0, 0])
    return certificate(S, O, ei.methods.backward_euler(), [ei.steplength_threshold(S, O, ei.methods.backward_euler())])


def _gap_set():
    cert = _genuine("gap-set")
    return cert, _claim(cert, "valid_steplengths")["intervals"]


# ------------------------------------------------------------------ soundness

@pytest.mark.parametrize("kind", ["largest_threshold", "valid_steplengths", "forward_euler_threshold"])
def test_an_empty_vertex_list_is_rejected(kind):
    cert = _genuine("box-taylor4-listed")
    c = _claim(cert, kind)
    c["vertices"] = []
    if kind == "largest_threshold":
        c.update(value="oo", attained=True, binding=None)
    elif kind == "valid_steplengths":
        c["intervals"] = [{"lo": "0", "hi": "oo", "lo_closed": True, "hi_closed": False}]
    _rejected(cert, "vertex")


def test_an_incomplete_vertex_list_is_rejected():
    cert = _genuine("box-taylor4-listed")
    c = _claim(cert, "largest_threshold")
    c["vertices"] = [v for v in c["vertices"] if v != ["1", "1"] and v != ["-1", "-1"]]
    _rejected(cert)


def test_the_vertices_of_a_smaller_polytope_are_rejected():
    cert = _genuine("box-taylor4-listed")
    c = _claim(cert, "valid_steplengths")
    c["vertices"] = [[str(x / 2) if False else ("1/2" if x == "1" else "-1/2") for x in v] for v in c["vertices"]]
    _rejected(cert)


def test_a_short_vector_is_rejected():
    cert = _genuine("box-taylor4-listed")
    c = _claim(cert, "largest_threshold")
    c["vertices"] = [["1"]] + c["vertices"]
    _rejected(cert, "length")


def test_a_missing_ray_and_a_missing_line_are_rejected():
    cert = _genuine("orthant-e2")
    c = _claim(cert, "valid_steplengths")
    c["rays"] = c["rays"][:1]
    _rejected(cert)
    cert = _genuine("halfplane-e2prime")
    c = _claim(cert, "valid_steplengths")
    c["lines"] = []
    _rejected(cert, "line")


def test_f_rows_must_run_over_exactly_0_to_p():
    S, P = ROT, BOX
    cert = ei.steplength_threshold(S, P, ei.methods.forward_euler()).certificate
    assert check(cert).ok
    c = _claim(cert, "polynomial_threshold")
    rows = c["f"]
    duplicate = copy.deepcopy(cert)
    _claim(duplicate, "polynomial_threshold")["f"] = [rows[1], rows[1]]
    _claim(duplicate, "polynomial_threshold")["value"] = "oo"
    _rejected(duplicate)
    out_of_range = copy.deepcopy(cert)
    _claim(out_of_range, "polynomial_threshold")["f"] = [dict(rows[1], i=5), rows[1]]
    _claim(out_of_range, "polynomial_threshold")["value"] = "oo"
    _rejected(out_of_range)


def test_a_wrong_tau_i_is_rejected():
    cert = _genuine("box-taylor4")
    row = _claim(cert, "polynomial_threshold")["f"][1]
    row["tau"] = "oo" if row["tau"] != "oo" else "7"
    _rejected(cert, "tau_1")


@pytest.mark.parametrize("row", [-1, 4, True, "0", 0.0])
def test_binding_row_must_be_an_integer_in_range(row):
    cert = _genuine("box-taylor4")
    _claim(cert, "gamma_star")["binding_row"] = row
    _rejected(cert, "binding_row")


def test_dropping_pole_and_alpha_does_not_disable_erratum_e2():
    cert = _e2_counterexample()
    assert check(cert).ok
    c = _claim(cert, "rational_threshold")
    c.pop("pole"), c.pop("alpha")
    c.update(value="oo", attained=True)
    _rejected(cert, "tau is not")


def test_a_wrong_pole_is_rejected():
    cert = _e2_counterexample()
    _claim(cert, "rational_threshold")["pole"] = {"poly": ["-2", "0", "1"], "interval": ["1", "2"]}
    _rejected(cert, "pole")


def test_gamma_infinity_gives_no_rational_threshold():
    S, P = ei.LinearSystem([[1, 0], [1, 1]]), BOX
    m = ei.methods.backward_euler()
    cert = certificate(S, P, m, [ei.optimal_gamma(S, P), ei.absolute_monotonicity_radius(m)])
    cert["claims"].append({"type": "rational_threshold", "value": "oo", "attained": True, "rho": "oo"})
    _rejected(cert, "not invariant")


def test_erratum_e2_prime_singular_point_is_enforced():
    cert = _genuine("halfplane-e2prime")
    c = _claim(cert, "rational_threshold")
    assert c["value"] == "1" and c["attained"] is False
    c.update(value="oo", attained=True)
    _rejected(cert)


def test_the_tail_is_proved_not_trusted():
    cert = _genuine("radius-sdirk")
    c = cert["claims"][0]
    assert c["value"] == "2"  # (1 + z/2)/(1 - z/4)^2
    c.update(value="oo", reason="coefficient", d=c["d"][:1], tail_index=1, binding=None)
    _rejected(cert)
    c.update(reason="termwise")
    _rejected(cert)


def test_a_radius_from_too_few_coefficients_is_rejected():
    cert = _genuine("radius-sdirk")
    c = cert["claims"][0]
    c.update(value="3", d=c["d"][:1], tail_index=1, binding=0)
    _rejected(cert)


def test_a_negated_denominator_represents_the_same_r():
    cert = _genuine("radius-sdirk")
    method = cert["problem"]["method"]
    for key in ("numerator", "denominator"):
        method[key] = [str(-ei.numbers.Fraction(x)) for x in method[key]]
    claim = cert["claims"][0]
    claim.pop("d")
    assert check(cert).ok  # r = (-g)/(-h) is the same function: the true radius 2 stands
    claim["value"] = "3"
    _rejected(cert)


def test_negative_polynomial_coefficient_gives_rho_zero_not_attained():
    R = ei.absolute_monotonicity_radius(ei.methods.polynomial([1, 1, "-1"]))
    assert R.value == 0 and R.attained is False
    cert = R.certificate
    assert check(cert).ok
    cert["claims"][0]["attained"] = True
    _rejected(cert, "attained")


def test_binding_null_cannot_skip_a_pole():
    cert = _genuine("halfplane-e2prime")
    c = _claim(cert, "largest_threshold")
    assert c["value"] == "1" and not c["attained"]
    c.update(value="2", attained=True, binding=None)
    _rejected(cert)


def test_closedness_flags_are_checked():
    for key in ("lo_closed", "hi_closed"):
        cert, ivs = _gap_set()
        ivs[-1 if key == "lo_closed" else 0][key] = not ivs[-1 if key == "lo_closed" else 0][key]
        _rejected(cert, key)


def test_a_spurious_degenerate_interval_is_rejected():
    cert = _genuine("box-taylor4")
    ivs = _claim(cert, "valid_steplengths")["intervals"]
    ivs.append({"lo": "2", "hi": "2", "lo_closed": True, "hi_closed": True})
    _rejected(cert, "intervals")


def test_everything_after_the_last_interval_is_checked():
    cert, ivs = _gap_set()
    assert len(ivs) == 2
    del ivs[-1]
    _rejected(cert)
    cert, ivs = _gap_set()
    ivs[-1]["hi"], ivs[-1]["hi_closed"] = "oo", False
    if ivs[-1]["hi"] == _claim(_genuine("gap-set"), "valid_steplengths")["intervals"][-1]["hi"]:
        ivs[-1]["hi"], ivs[-1]["hi_closed"] = "100", True
    _rejected(cert)


def test_a_gap_cannot_hide_a_valid_interval():
    cert, ivs = _gap_set()
    merged = {"lo": ivs[0]["lo"], "hi": ivs[-1]["hi"], "lo_closed": True, "hi_closed": ivs[-1]["hi_closed"]}
    _claim(cert, "valid_steplengths")["intervals"] = [merged]
    _rejected(cert)


def test_a_pole_cannot_hide_inside_an_interval():
    V = ei.valid_steplengths(ei.LinearSystem([[2]]), ei.Polyhedron([[1]], [0]),
                             ei.methods.rational([1, "1/2"], [1, -1, "1/4"]))
    cert = V.certificate
    assert check(cert).ok and len(V) == 2
    ivs = _claim(cert, "valid_steplengths")["intervals"]
    _claim(cert, "valid_steplengths")["intervals"] = [{"lo": "0", "hi": ivs[-1]["hi"], "lo_closed": True,
                                                       "hi_closed": ivs[-1]["hi_closed"]}]
    _rejected(cert)


def test_touching_intervals_need_a_singular_point():
    cert = _genuine("box-taylor4")
    ivs = _claim(cert, "valid_steplengths")["intervals"]
    first = ivs[0]
    ivs[:] = [{"lo": "0", "hi": "1", "lo_closed": True, "hi_closed": False},
              {"lo": "1", "hi": first["hi"], "lo_closed": False, "hi_closed": first["hi_closed"]}]
    _rejected(cert)


def test_a_string_boolean_is_rejected():
    cert = _genuine("halfplane-e2prime")
    _claim(cert, "largest_threshold")["attained"] = "false"
    _rejected(cert, "boolean")


@pytest.mark.parametrize("key", ["lo_closed", "hi_closed"])
def test_missing_closedness_keys_are_rejected(key):
    cert, ivs = _gap_set()
    del ivs[0][key]
    _rejected(cert, key)


def test_a_missing_attained_key_is_rejected():
    cert = _genuine("halfplane-e2prime")
    del _claim(cert, "largest_threshold")["attained"]
    _rejected(cert, "missing")


def test_unknown_keys_are_rejected():
    cert = _genuine("box-taylor4")
    _claim(cert, "gamma_star")["trust_me"] = True
    _rejected(cert, "unknown")
    cert = _genuine("box-taylor4")
    cert["note"] = "hello"
    _rejected(cert, "exactly the keys")


def test_json_floats_are_rejected():
    text = json.dumps(_genuine("box-taylor4")).replace('"b": ["1", "1", "1", "1"]', '"b": [1.0, 1, 1, 1]')
    assert '1.0' in text
    assert not check(text).ok


def test_discrete_invariance_with_dt_is_tied_to_the_method():
    S, P, m = ROT, BOX, ei.methods.taylor(2)
    for dt in ("1/2", "2"):  # invariant at 1/2, not at 2
        D = ei.discrete_invariance(S, P, m, dt)
        cert = D.certificate_json
        claim = _claim(cert, "discrete_invariance")
        assert claim["dt"] == dt and cert["version"] == 3
        assert check(cert).ok, check(cert)
        claim["dt"] = "1/3"
        _rejected(cert, "r(dt A)")


# ------------------------------------------------------------------ resource

def test_a_larger_gamma_with_a_dropped_dual_row_is_rejected():
    cert = _genuine("box-taylor4")
    g = _claim(cert, "gamma_star")
    g["value"], g["binding_row"] = "2", -1
    _rejected(cert)


@pytest.mark.parametrize("number", ["1/0", "1e999999999", "9" * 5000, "0x10", "nan", "1.5e3"])
def test_hostile_number_strings_are_rejected_fast(number):
    cert = _genuine("box-taylor4")
    cert["problem"]["method"]["denominator"] = [number]
    start = time.process_time()
    _rejected(cert)
    assert time.process_time() - start < 5  # a hang would never get here (CPU time, not a timing claim)
