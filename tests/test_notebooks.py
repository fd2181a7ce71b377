"""Every notebook runs top to bottom (outputs are not committed).

Where the ``docs`` extra is installed, tests/test_docs_build.py executes every
notebook during the site's build (myst-nb, ``nb_execution_mode = "force"`` and
``nb_execution_raise_on_error = True``, docs/site/conf.py), so a cell that
raises fails that test; executing them here again would double the suite's
longest work.  Here they are executed only where that build cannot run.
"""

import importlib.util
from pathlib import Path

import pytest

nbformat = pytest.importorskip("nbformat")

NOTEBOOKS = sorted(Path(__file__).parent.parent.joinpath("notebooks").glob("*.ipynb"))
BUILT_WITH_THE_SITE = all(importlib.util.find_spec(m) is not None for m in ("sphinx", "myst_nb"))


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.stem)
def test_no_outputs_are_committed(path):
    nb = nbformat.read(path, as_version=4)
    assert not any(c.get("outputs") for c in nb.cells if c.cell_type == "code"), "outputs must not be committed"


@pytest.mark.skipif(BUILT_WITH_THE_SITE, reason="executed by the site's build (tests/test_docs_build.py)")
@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.stem)
def test_notebook_runs(path, tmp_path):
    nbclient = pytest.importorskip("nbclient")
    nb = nbformat.read(path, as_version=4)
    client = nbclient.NotebookClient(nb, timeout=300, kernel_name="python3", resources={"metadata": {"path": str(tmp_path)}})
    client.execute()
    errors = [o for c in nb.cells if c.cell_type == "code" for o in c.outputs if o.output_type == "error"]
    assert not errors
