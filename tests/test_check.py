"""The independent checker: round trips, tampering, and its import list."""

import copy
import json
from fractions import Fraction
from pathlib import Path

import pytest

import exactinv as ei
from exactinv.certificates import certificate
from exactinv_check import check

EXAMPLES = sorted(Path(__file__).parent.parent.joinpath("examples").glob("*.json"))


def _box_taylor3():
    S = ei.LinearSystem([[-1, 1], [-1, -1]])
    P = ei.Polyhedron.box([-1, -1], [1, 1])
    return ei.steplength_threshold(S, P, ei.methods.taylor(3)).certificate


def _non_invariant():
    return ei.optimal_gamma(ei.LinearSystem([[1, 0], [1, 1]]), ei.Polyhedron.box([-1, -1], [1, 1])).certificate


def _minus_infinity():
    return ei.optimal_gamma(ei.LinearSystem([[-1, 0], [0, -2]]), ei.Polyhedron([[1, 0], [-1, 0]], [0, 0])).certificate


def _discrete():
    P = ei.Polyhedron.box([-1, -1], [1, 1])
    S = ei.LinearSystem([[0, 0], [0, 0]])
    return certificate(S, P, None, [ei.discrete_invariance([[0, 1], [-1, 0]], P), ei.discrete_invariance([[1, 1], [0, 1]], P)])


def _gap_set():
    S, P = ei.LinearSystem([[-1]]), ei.Polyhedron.box([-1], [1])
    return ei.valid_steplengths(S, P, ei.methods.polynomial([1, "1/2", "3/4", "1/4"]), box=False).certificate


def _e2_largest():
    S, O = ei.LinearSystem([[-1, 2], [0, 1]]), ei.Polyhedron([[-1, 0], [0, -1]], [0, 0])
    return certificate(S, O, ei.methods.backward_euler(),
                       [ei.steplength_threshold(S, O, ei.methods.backward_euler()),
                        ei.largest_threshold(S, O, ei.methods.backward_euler())])


def _largest_taylor2():
    S = ei.LinearSystem([[-1, 1], [-1, -1]])
    return ei.largest_threshold(S, ei.Polyhedron.box([-1, -1], [1, 1]), ei.methods.taylor(2)).certificate


def test_standalone_certificates():
    S = ei.LinearSystem([[-1, 1], [-1, -1]])
    P = ei.Polyhedron.box([-1, -1], [1, 1])
    assert check(ei.forward_euler_threshold(S, P).certificate).ok
    for m in (ei.methods.rk4(), ei.methods.lobatto_iiic2(), ei.methods.backward_euler(), ei.methods.trapezoid()):
        assert check(json.loads(json.dumps(ei.absolute_monotonicity_radius(m).certificate))).ok
    bad = ei.absolute_monotonicity_radius(ei.methods.rk4()).certificate
    bad["claims"][0]["value"] = "2"
    assert not check(bad).ok


def test_round_trip_through_json(tmp_path):
    for cert in (_box_taylor3(), _non_invariant(), _minus_infinity(), _discrete(), _gap_set(), _e2_largest(), _largest_taylor2()):
        path = tmp_path / "c.json"
        path.write_text(json.dumps(cert))
        report = check(str(path))
        assert report.ok, str(report)
        assert check(json.dumps(cert)).ok


@pytest.mark.parametrize("example", EXAMPLES, ids=lambda p: p.stem)
def test_every_example_round_trips(example):
    from exactinv.interfaces.problem import load_problem

    prob = load_problem(example)
    if prob.is_ellipsoid:  # no gamma* and no paper threshold on an ellipsoid
        results = [ei.continuous_invariance(prob.system, prob.polyhedron),
                   ei.forward_euler_threshold(prob.system, prob.polyhedron)]
        if prob.method is not None:
            results += [ei.largest_threshold(prob.system, prob.polyhedron, prob.method),
                        ei.valid_steplengths(prob.system, prob.polyhedron, prob.method)]
        assert check(json.loads(json.dumps(certificate(prob.system, prob.polyhedron, prob.method, results)))).ok
        return
    if prob.design == "optimal_gain":  # the gain's certificate, then the closed loop's own problem
        gain = ei.optimal_gain(prob.system, prob.B, prob.polyhedron, prob.inputs)
        assert check(json.loads(json.dumps(gain.certificate))).ok
        prob = type(prob)(gain.system, prob.polyhedron, prob.method)
    results = [ei.optimal_gamma(prob.system, prob.polyhedron)]
    if prob.method is not None:
        results.append(ei.steplength_threshold(prob.system, prob.polyhedron, prob.method))
        results.append(ei.largest_threshold(prob.system, prob.polyhedron, prob.method))
        results.append(ei.valid_steplengths(prob.system, prob.polyhedron, prob.method))
    assert check(json.loads(json.dumps(certificate(prob.system, prob.polyhedron, prob.method, results)))).ok


def _claim(cert, kind):
    return next(c for c in cert["claims"] if c["type"] == kind)


def _bump(s):
    return str(Fraction(s) + Fraction(1, 7))


TAMPERS = {
    "H entry": (_box_taylor3, lambda c: _claim(c, "gamma_star")["H"]["sparse"][0][1].__setitem__(
        1, _bump(_claim(c, "gamma_star")["H"]["sparse"][0][1][1]))),  # version 3: [column, value] pairs
    "gamma value": (_box_taylor3, lambda c: _claim(c, "gamma_star").__setitem__("value", "1/2")),
    "dual entry": (_box_taylor3,
                   lambda c: _claim(c, "gamma_star")["dual"]["y"].__setitem__(0, _bump(_claim(c, "gamma_star")["dual"]["y"][0]))),
    "dual lambda sign": (_box_taylor3, lambda c: _claim(c, "gamma_star")["dual"].__setitem__("lambda", "-1")),
    "binding row": (_box_taylor3,
                    lambda c: _claim(c, "gamma_star").__setitem__("binding_row", 1 - _claim(c, "gamma_star")["binding_row"] + 2)),
    "threshold value": (_box_taylor3, lambda c: _claim(c, "polynomial_threshold").__setitem__("value", "3/2")),
    "tau interval end": (_box_taylor3,
                         lambda c: _claim(c, "polynomial_threshold")["f"][0]["tau"]["interval"].__setitem__(0, "17/10")),
    "tau polynomial": (_box_taylor3, lambda c: _claim(c, "polynomial_threshold")["f"][0]["tau"]["poly"].__setitem__(0, "7")),
    "f coefficient": (_box_taylor3, lambda c: _claim(c, "polynomial_threshold")["f"][2]["coefficients"].__setitem__(3, "1")),
    "tau_i too large": (_box_taylor3, lambda c: _claim(c, "polynomial_threshold")["f"][2].__setitem__("tau", "2")),
    "dropped f_i": (_box_taylor3, lambda c: _claim(c, "polynomial_threshold")["f"].pop()),
    "method changed": (_box_taylor3, lambda c: c["problem"]["method"]["numerator"].__setitem__(3, "1/3")),
    "A changed": (_box_taylor3, lambda c: c["problem"]["A"][0].__setitem__(0, "-2")),
    "b changed": (_box_taylor3, lambda c: c["problem"]["b"].__setitem__(0, "2")),
    "witness point": (_non_invariant, lambda c: _claim(c, "gamma_star")["witness"]["x"].__setitem__(0, "1/2")),
    "witness facet": (_non_invariant, lambda c: _claim(c, "gamma_star")["witness"].__setitem__("facet", 3)),
    "ray sign": (_minus_infinity,
                 lambda c: _claim(c, "gamma_star")["rows"][0]["ray"].__setitem__(
                     0, str(-Fraction(_claim(c, "gamma_star")["rows"][0]["ray"][0]) - 1))),
    "H~ entry": (_discrete, lambda c: c["claims"][0]["H"]["sparse"][0].insert(0, [0, "1"])),
    "discrete verdict flipped": (_discrete, lambda c: c["claims"][1].__setitem__("holds", True)),
    "version": (_box_taylor3, lambda c: c.__setitem__("version", 99)),
    "valid set end moved": (_gap_set, lambda c: c["claims"][0]["intervals"][1].__setitem__("hi", "3")),
    "valid set gap closed": (_gap_set, lambda c: c["claims"][0]["intervals"][0].__setitem__("hi", "3/2")),
    "valid set vertex moved out of P": (_gap_set, lambda c: c["claims"][0]["vertices"][0].__setitem__(0, "2")),
    "largest value": (_largest_taylor2, lambda c: c["claims"][0].__setitem__("value", "3/2")),
    "largest attained flipped": (_e2_largest, lambda c: _claim(c, "largest_threshold").__setitem__("attained", True)),
    "rational threshold value": (_e2_largest, lambda c: _claim(c, "rational_threshold").__setitem__("value", "oo")),
    "rational pole": (_e2_largest, lambda c: _claim(c, "rational_threshold").__setitem__("pole", "2")),
    "radius reason": (_e2_largest, lambda c: _claim(c, "absolute_monotonicity_radius").__setitem__("reason", "coefficient")),
    "no claims": (_box_taylor3, lambda c: c.__setitem__("claims", [])),
    "unknown claim": (_box_taylor3, lambda c: c["claims"].append({"type": "trust_me"})),
    "float smuggled": (_box_taylor3, lambda c: c["problem"]["b"].__setitem__(0, 1.0)),
}


@pytest.mark.parametrize("name", sorted(TAMPERS))
def test_tampering_is_rejected(name):
    make, mutate = TAMPERS[name]
    cert = make()
    assert check(cert).ok
    bad = copy.deepcopy(cert)
    mutate(bad)
    report = check(bad)
    assert not report.ok, f"{name} was accepted:\n{report}"
    assert "REJECTED" in str(report)


def test_checker_main_exit_codes(tmp_path, capsys):
    from exactinv_check import main

    good = tmp_path / "good.json"
    good.write_text(json.dumps(_box_taylor3()))
    assert main([str(good)]) == 0
    bad = _box_taylor3()
    _claim(bad, "gamma_star")["value"] = "2"
    path = tmp_path / "bad.json"
    path.write_text(json.dumps(bad))
    assert main([str(path)]) == 1
    assert "REJECTED" in capsys.readouterr().out


def test_regressions_found_by_fuzzing():
    """A binding ray (generators are numbered within their kind) and a double pole."""
    L = ei.largest_threshold(ei.LinearSystem([[-1]]), ei.Polyhedron([[-2]], [0]), ei.methods.polynomial([1, 1, "1/2", "1/4"]))
    assert L.binding.kind == "ray" and check(L.certificate).ok
    V = ei.valid_steplengths(ei.LinearSystem([[2]]), ei.Polyhedron([[1]], [0]), ei.methods.rational([1, "1/2"], [1, -1, "1/4"]))
    assert len(V) == 2 and check(V.certificate).ok
