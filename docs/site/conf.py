"""Sphinx configuration of the exactinv documentation site.

Build (warnings are errors, as in CI's tests/test_docs_build.py)::

    python -m pip install -e ".[docs]"
    sphinx-build -W --keep-going -b html docs/site docs/site/_build/html

The markdown docs (docs/*.md, with the JSON Schemas and figures they link to)
and the notebooks (notebooks/*.ipynb) live outside this directory; Sphinx reads
only files under its source directory, so they are copied into ``generated/``
(ignored by git, left out of the sdist) each time the build starts.  The
notebooks are executed during the build (myst-nb, ``force``), so the site shows
their outputs while the repository keeps them output-free.
"""

from __future__ import annotations

import re
import shutil
import sys
from pathlib import Path

SITE = Path(__file__).resolve().parent
ROOT = SITE.parent.parent
sys.path.insert(0, str(ROOT))  # document this checkout, not an installed copy

GENERATED = SITE / "generated"
REPO_LINKS = {"../exactinv_check": "api-kernel"}  # a link target -> the label of the page section on it


def _copy_sources() -> None:
    if GENERATED.exists():
        shutil.rmtree(GENERATED)
    (GENERATED / "notebooks").mkdir(parents=True)
    for name in ("problem.schema.json", "certificate.schema.json"):
        shutil.copy2(ROOT / "docs" / name, GENERATED / name)
    for name in ("problem-format.md", "certificate-format.md", "ellipsoids.md", "errata.md", "scale.md", "design.md"):
        text = (ROOT / "docs" / name).read_text(encoding="utf-8")
        # A link into the repository outside docs/ (read on a code host) points
        # here to the page that documents it.
        for target, label in REPO_LINKS.items():
            # [text](target) -> {ref}`text <label>`: a plain Sphinx reference,
            # resolved the same by every myst-parser (a #label link is not, in 5.0)
            text = re.sub(rf"\[([^\]]*)\]\({re.escape(target)}\)",
                          lambda m: "{ref}`" + m.group(1).replace("`", "") + f" <{label}>`", text)
        (GENERATED / name).write_text(text, encoding="utf-8")
    shutil.copytree(ROOT / "docs" / "img", GENERATED / "img")
    for nb in sorted((ROOT / "notebooks").glob("*.ipynb")):
        shutil.copy2(nb, GENERATED / "notebooks" / nb.name)


_copy_sources()

import exactinv  # noqa: E402  (after sys.path is set)

project = "exactinv"
author = "the exactinv authors"
copyright = "the exactinv authors (MIT License)"
version = release = exactinv.__version__

extensions = [
    "myst_nb",  # markdown (MyST) pages and executed notebooks
    "sphinx.ext.autodoc",
    "sphinx.ext.napoleon",
    "sphinx.ext.mathjax",
]

exclude_patterns = ["_build", "Thumbs.db", ".DS_Store", "**.ipynb_checkpoints"]
source_suffix = {".md": "myst-nb", ".ipynb": "myst-nb"}

# MyST: $...$ maths as in the markdown docs; anchors for the headings so that
# links like certificate-format.md#claims resolve.
myst_enable_extensions = ["dollarmath", "colon_fence"]
myst_heading_anchors = 3

# myst-nb: run every notebook at every build, fail the build on an error cell.
nb_execution_mode = "force"
nb_execution_timeout = 300
nb_execution_raise_on_error = True
nb_execution_show_tb = True
nb_execution_in_temp = True

# autodoc: members in source order, the signatures' annotations shown in the
# description (exact types such as Fraction are more readable there).
autodoc_default_options = {"members": True, "member-order": "bysource"}
autodoc_typehints = "description"
autodoc_preserve_defaults = True
napoleon_numpy_docstring = True
napoleon_google_docstring = True

html_theme = "alabaster"
html_title = f"exactinv {release}"
html_theme_options = {"description": "Exact, certified steplength thresholds", "fixed_sidebar": True}
