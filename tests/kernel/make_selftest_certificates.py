"""Regenerate the genuine certificates of the kernel's selftest (exactinv_check/selftest_certificates/).

    python tests/kernel/make_selftest_certificates.py

Each is made by the engine and must be accepted by the kernel; they are small (a few KB) and cover
every family of claims: invariance and gamma*, the paper's thresholds (polynomial and rational),
forward Euler, discrete invariance, the radius (its tail, Bernstein, a tie), valid sets by the vertex, box and
LP routes and with a pruning record, ellipsoids (continuous and discrete invariance), the optimal gain (holding
and not) and a robust threshold.  The versions 1 and
2 examples come from docs/certificate-format.md."""

import json
import re
from pathlib import Path

import exactinv as ei
import exactinv.conditions.pruning as engine_pruning
import exactinv.validset.lp_route as engine_lp
from exactinv.certificates import certificate, dumps

ROOT = Path(__file__).resolve().parents[2]
OUT = ROOT / "exactinv_check" / "selftest_certificates"



def _with_dual_pieces(make):
    """The LP route with a dual piece tried at the end of every basis piece (DualPolicy(0, 0, 1, 10**9))."""
    old = engine_lp.DUAL_POLICY
    engine_lp.DUAL_POLICY = engine_lp.DualPolicy(0, 0, 1, 10**9)
    try:
        return make()
    finally:
        engine_lp.DUAL_POLICY = old


def main():
    OUT.mkdir(exist_ok=True)
    for old in OUT.glob("*.json"):
        old.unlink()
    certs = {}
    S = ei.LinearSystem([[-1, 1], [-1, -1]])
    box = ei.Polyhedron.box([-1, -1], [1, 1])
    octagon = ei.Polyhedron([[1, 0], [-1, 0], [0, 1], [0, -1], [1, 1], [1, -1], [-1, 1], [-1, -1]],
                            [1, 1, 1, 1, "3/2", "3/2", "3/2", "3/2"])
    t4 = ei.methods.taylor(4)
    certs["box-taylor4"] = certificate(S, box, t4, [
        ei.optimal_gamma(S, box), ei.forward_euler_threshold(S, box), ei.steplength_threshold(S, box, t4),
         ei.largest_threshold(S, box, t4, route="vertex"), ei.valid_steplengths(S, box, t4)])
    certs["box-route-rk4"] = ei.largest_threshold(S, box, ei.methods.PRESETS["rk4"](), route="box").certificate
    certs["lp-route-taylor2"] = ei.largest_threshold(S, octagon, ei.methods.taylor(2), route="lp").certificate
    certs["lp-dual-taylor2"] = _with_dual_pieces(lambda: certificate(S, octagon, ei.methods.taylor(2), [
        ei.largest_threshold(S, octagon, ei.methods.taylor(2), route="lp"),
        ei.valid_steplengths(S, octagon, ei.methods.taylor(2), route="lp")]))
    slab, feed = ei.Polyhedron([[1, 0], [-1, 0]], [1, 1]), ei.LinearSystem([[-1, 1], [0, -1]])  # P with a line
    certs["lp-lines-taylor2"] = certificate(feed, slab, ei.methods.taylor(2), [
        ei.largest_threshold(feed, slab, ei.methods.taylor(2), route="lp"),
        ei.valid_steplengths(feed, slab, ei.methods.taylor(2), route="lp")])
    orthant = ei.Polyhedron([[-1, 0], [0, -1]], [0, 0])
    be = ei.methods.PRESETS["backward_euler"]()
    E2 = ei.LinearSystem([[-1, 2], [0, 1]])
    certs["erratum-e2-backward-euler"] = certificate(E2, orthant, be, [ei.steplength_threshold(E2, orthant, be),
                                                          ei.valid_steplengths(E2, orthant, be)])
    certs["octagon-pade22"] = certificate(S, octagon, ei.methods.pade(2, 2), [
        ei.steplength_threshold(S, octagon, ei.methods.pade(2, 2)),
         ei.largest_threshold(S, octagon, ei.methods.pade(2, 2))])
    for name in ("sdirk4", "radau_iia3", "ssprk33"):
        certs[f"radius-{name}"] = ei.absolute_monotonicity_radius(ei.methods.PRESETS[name]()).certificate
    E = ei.Ellipsoid([[1, 0], [0, 1]])
    certs["ellipsoid-taylor2"] = certificate(S, E, ei.methods.taylor(2), [
        ei.continuous_invariance(S, E), ei.largest_threshold(S, E, ei.methods.taylor(2)),
         ei.valid_steplengths(S, E, ei.methods.taylor(2)), ei.forward_euler_threshold(S, E)])
    certs["gain-double-integrator"] = ei.optimal_gain([[0, 1], [0, 0]], [[0], [1]], box).certificate
    t2 = ei.methods.taylor(2)
    certs["discrete-invariance-taylor2"] = certificate(S, box, t2, [ei.discrete_invariance(S, box, t2, "1/2")])
    certs["ellipsoid-discrete-taylor2"] = certificate(S, E, t2, [ei.discrete_invariance(S, E, t2, "1/2")])
    certs["gain-holds"] = ei.optimal_gain([[-1, 0], [0, 1]], [[0], [1]], box).certificate
    # a pruning record: pruning forced (the engine applies it only where it pays) on a Taylor-2 valid set whose
    # pairs mostly cannot bind (tests/conditions/test_pruning.py: 23 of 64 survive)
    spin = ei.LinearSystem([[-1, "1/4"], ["-1/4", -1]])
    diamond = ei.Polyhedron.from_vertices([[10, 0], [0, 1], [-10, 0], [0, -1], [7, "7/10"], [-7, "7/10"],
                                           [7, "-7/10"], [-7, "-7/10"]])
    worthwhile, engine_pruning.WORTHWHILE = engine_pruning.WORTHWHILE, 1.0
    try:
        pruned = ei.valid_steplengths(spin, diamond, t2)
    finally:
        engine_pruning.WORTHWHILE = worthwhile
    assert pruned.pruning.applied and "pruning" in pruned.certificate["claims"][0]
    certs["pruning-diamond-taylor2"] = pruned.certificate
    hull = [ei.LinearSystem([[-1, 1], [-1, -1]]), ei.LinearSystem([[-2, 1], [0, -1]])]
    certs["robust-ssprk33"] = ei.robust_threshold(hull, box, ei.methods.PRESETS["ssprk33"]()).certificate
    doc = (ROOT / "docs" / "certificate-format.md").read_text()
    for block in re.findall(r"```json\n(.*?)```", doc, flags=re.S):
        example = json.loads(block)
        if "format" in example and example["version"] < 3:
            certs.setdefault(f"doc-version-{example['version']}", example)
    for name, cert in certs.items():
        report = ei.check(cert)
        assert report.ok, (name, str(report))
        (OUT / f"{name}.json").write_text(dumps(cert) + "\n")
        print(f"{name}: {len(dumps(cert))} bytes, {len(cert['claims'])} claims")


if __name__ == "__main__":
    main()
