"""docs/methods.md: the committed table matches docs/gen_method_table.py (every column but the time), every
row was verified by the kernel, and every value agrees with the slow exact reference (tests/radius_reference):
the coefficients c_j at rationals just below and above rho, and the tie of the poles (mpmath) for `tie` rows."""

import importlib.util
from fractions import Fraction
from pathlib import Path

import mpmath
import pytest
from radius_reference import admissible, coefficients_at, tie_kappa

import exactinv as ei
from exactinv.core.real_algebraic import RealAlgebraic

DOCS = Path(__file__).resolve().parents[1] / "docs"
spec = importlib.util.spec_from_file_location("gen_method_table", DOCS / "gen_method_table.py")
gen = importlib.util.module_from_spec(spec)
spec.loader.exec_module(gen)
ENTRIES = gen.entries()


def committed_rows():
    rows = {}
    for line in (DOCS / "methods.md").read_text().splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) == 8 and cells[0] in ENTRIES:
            rows[cells[0]] = cells
    return rows


ROWS = committed_rows()


def test_every_entry_has_a_row():
    assert set(ROWS) == set(ENTRIES)
    assert len(ROWS) == len(ei.methods.PRESETS) + 49


@pytest.mark.parametrize("name", sorted(ENTRIES))
def test_row_matches_the_engine_and_the_reference(name):
    method = ENTRIES[name]
    cells = ROWS[name]
    assert cells[6] == "verified"
    r = ei.absolute_monotonicity_radius(method)
    assert cells[2:6] == [gen._exact(r.value), gen._decimals(r.value), r.reason,
                          "" if r.tail_index is None else str(r.tail_index)]
    num, den, J = method.numerator, method.denominator, max(60, (r.binding or 0) + 2, (r.witness_j or 0) + 2)
    if r.value == ei.INF:
        assert all(admissible(num, den, Fraction(k), J) for k in (1, 10))
        return
    lo, hi = (r.value.lower, r.value.upper) if isinstance(r.value, RealAlgebraic) else (r.value, r.value)
    below, above = Fraction(int(lo * 10 ** 7) - 50, 10 ** 7), Fraction(int(hi * 10 ** 7) + 51, 10 ** 7)
    if below > 0:
        assert admissible(num, den, below, J)
    if r.reason == "tie":
        assert abs(mpmath.mpf(float(r.value)) - tie_kappa(num, den)) < 1e-9
    elif r.witness_j is not None:
        assert coefficients_at(num, den, Fraction(0), r.witness_j + 1)[-1] < 0
    else:
        assert not admissible(num, den, above, J)
    decimals = cells[3].rstrip(".")
    assert Fraction(decimals) <= hi and (r.value == 0 or lo < Fraction(decimals) + Fraction(1, 10 ** 11))
