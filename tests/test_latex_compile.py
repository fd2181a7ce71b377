"""Paper-ready LaTeX: every ``_repr_latex_`` and ``to_latex`` compiles with a real engine.

The objects below cover each result class (methods, systems, polyhedra,
gamma*, invariance, thresholds with their f_i tables, radii, valid sets,
largest thresholds, algebraic numbers), including names and reasons that
carry LaTeX's special characters.  They go into one document, compiled by the
first engine found (pdflatex, lualatex, xelatex, tectonic); the test is
skipped where none is installed (``.ci/run`` installs pdflatex).
"""

from __future__ import annotations

import os
import re
import shutil
import subprocess

import pytest

import exactinv as ei
from exactinv import methods as M
from exactinv.core.latex import latex_text

BOX = ei.Polyhedron.box([-1, -1], [1, 1])
SPIRAL = ei.LinearSystem([[-1, 1], [-1, -1]])
ORTHANT = ei.Polyhedron([[-1, 0], [0, -1]], [0, 0])
E2 = ei.LinearSystem([[-1, 2], [0, 1]])
ROTATED = ei.Polyhedron.from_vertices([[1, 0], [0, 1], [-1, 0], [0, -1]])
LINE = ei.LinearSystem([[1]])
SEGMENT = ei.Polyhedron.box([-1], [1])

ENGINES = ("pdflatex", "lualatex", "xelatex", "tectonic")


def _engine() -> str | None:
    return next((e for e in ENGINES if shutil.which(e)), None)


def _objects() -> dict[str, object]:
    objs: dict[str, object] = {
        "system": SPIRAL,
        "polyhedron": BOX,
        "gamma*": ei.optimal_gamma(SPIRAL, BOX),
        "gamma* (not invariant)": ei.optimal_gamma(LINE, SEGMENT),
        "continuous invariance": ei.continuous_invariance(SPIRAL, BOX),
        "continuous invariance (refuted)": ei.continuous_invariance(LINE, SEGMENT),
        "discrete invariance": ei.discrete_invariance([[0, 1], [-1, 0]], BOX),
        "discrete invariance (refuted)": ei.discrete_invariance([[1, 1], [0, 1]], BOX),
        "forward Euler threshold": ei.forward_euler_threshold(SPIRAL, BOX),
        "Taylor-3 threshold": ei.steplength_threshold(SPIRAL, BOX, M.taylor(3)),
        "Taylor-4 threshold": ei.steplength_threshold(SPIRAL, BOX, M.taylor(4)),
        "backward Euler threshold (E2)": ei.steplength_threshold(E2, ORTHANT, M.backward_euler()),
        "trapezoid threshold": ei.steplength_threshold(SPIRAL, BOX, M.trapezoid()),
        "rk4 threshold": ei.steplength_threshold(SPIRAL, BOX, M.rk4()),
        "largest (algebraic)": ei.largest_threshold(SPIRAL, ROTATED, M.taylor(2)),
        "largest (Taylor-4)": ei.largest_threshold(SPIRAL, BOX, M.taylor(4)),
        "largest (open)": ei.largest_threshold(E2, ORTHANT, M.backward_euler()),
        "valid set": ei.valid_steplengths(SPIRAL, BOX, M.taylor(4)),
        "valid set (split)": ei.valid_steplengths(LINE, SEGMENT, M.backward_euler()),
        "valid set (open end)": ei.valid_steplengths(E2, ORTHANT, M.backward_euler()),
        "algebraic number": ei.real_roots([-2, 0, 1])[1][0],
        "infinity": ei.INF,
        "odd method name": M.rational([1, "1/2"], [1, "-1/2"], name="my_method #1 & 50% {x}^2 ~ \\o/ <a>"),
    }
    for name in ("forward_euler", "backward_euler", "trapezoid", "implicit_midpoint", "heun", "ssprk33",
                 "rk4", "radau_iia2", "lobatto_iiic2", "gauss2"):
        method = M.preset(name)
        objs[f"method {name}"] = method
        try:
            objs[f"radius {name}"] = ei.absolute_monotonicity_radius(method)
        except ei.Undecided:
            pass
    objs["method theta(1/3)"] = M.theta("1/3")
    objs["method pade(1,2)"] = M.pade(1, 2)
    objs["method ssprk(3,1)"] = M.ssprk_s1(3)
    objs["radius pade(1,2)"] = ei.absolute_monotonicity_radius(M.pade(1, 2))
    for iv in objs["valid set (split)"]:
        objs[f"interval {iv!r}"] = iv
    return objs


def _document(objs: dict[str, object]) -> tuple[str, dict[int, str]]:
    """One article: each object's ``_repr_latex_`` inline and its ``to_latex`` displayed."""
    lines = [r"\documentclass{article}", r"\usepackage{amsmath}", r"\usepackage[margin=1cm]{geometry}",
             r"\begin{document}", r"\sloppy"]
    where: dict[int, str] = {}
    for name, obj in objs.items():
        lines.append(rf"\paragraph{{${latex_text(name)}$}}")
        where[len(lines) + 1] = f"{name}: _repr_latex_"
        lines.append(obj._repr_latex_())
        if hasattr(obj, "to_latex"):
            where[len(lines) + 1] = f"{name}: to_latex"
            lines.append(r"\[" + obj.to_latex() + r"\]")
    lines.append(r"\end{document}")
    return "\n".join(lines) + "\n", where


def test_latex_text_keeps_special_characters_out_of_text():
    assert latex_text("backward_euler") == r"\text{backward}\_\text{euler}"
    assert latex_text("a #$%&~_^\\{}<>") == r"\text{a }\#\$\%\&\sim \_\hat{}\backslash \{\}<>"


def test_every_object_has_latex():
    for name, obj in _objects().items():
        assert obj._repr_latex_().startswith("$"), name


def test_latex_output_compiles(tmp_path):
    engine = _engine()
    if engine is None:  # .ci/run installs pdflatex: in CI a missing engine is a failure
        (pytest.fail if os.environ.get("CI") else pytest.skip)("no LaTeX engine installed (.ci/run installs pdflatex)")
    tex, where = _document(_objects())
    (tmp_path / "objects.tex").write_text(tex, encoding="utf-8")
    if engine == "tectonic":
        cmd = [engine, "--chatter", "minimal", "objects.tex"]
    else:
        cmd = [engine, "-interaction=nonstopmode", "-halt-on-error", "-file-line-error", "objects.tex"]
    run = subprocess.run(cmd, cwd=tmp_path, capture_output=True, text=True, timeout=120)
    log = tmp_path / "objects.log"
    text = log.read_text(errors="replace") if log.exists() else run.stdout + run.stderr
    if run.returncode != 0 or not (tmp_path / "objects.pdf").exists():
        lines = [int(n) for n in re.findall(r"objects\.tex:(\d+):", text)]
        culprits = sorted({where.get(n, f"line {n}") for n in lines}) or ["(unknown)"]
        errors = [line for line in text.splitlines() if line.startswith(("!", "./objects.tex:"))][:10]
        pytest.fail(f"{engine} failed on {', '.join(culprits)}:\n" + "\n".join(errors))
    assert "Missing character" not in text, "a character the font does not have"
