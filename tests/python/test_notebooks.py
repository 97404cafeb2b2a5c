"""The example notebooks run from top to bottom (nbclient, a real kernel) and show images.
With OCTRACE_NOTEBOOK_IMAGES=DIR the last image of each is written there (docs/images holds
them: `OCTRACE_NOTEBOOK_IMAGES=docs/images ctest -R Python.test_notebooks`)."""

import base64
import os
import pathlib

import pytest

from conftest import shared

nbformat = pytest.importorskip("nbformat")
nbclient = pytest.importorskip("nbclient")

EXAMPLES = pathlib.Path(__file__).parents[2] / "examples"


@pytest.mark.parametrize("name, needs", [("ocean", "ocean/levitus_climatology.cdf"), ("ct", "medical/lidc2_chest_ct.nrrd")])
def test_the_notebook_runs(name, needs):
    shared(needs)
    notebook = nbformat.read(EXAMPLES / f"{name}.ipynb", as_version=4)
    nbclient.NotebookClient(notebook, timeout=900, kernel_name="python3",
                            resources={"metadata": {"path": str(EXAMPLES)}}).execute()
    images = [base64.b64decode(out["data"]["image/png"])
              for cell in notebook.cells if cell.cell_type == "code"
              for out in cell.get("outputs", []) if "image/png" in out.get("data", {})]
    assert len(images) >= 2, f"{name}.ipynb shows {len(images)} image(s)"
    assert all(img[:8] == b"\x89PNG\r\n\x1a\n" for img in images)
    errors = [out for cell in notebook.cells for out in cell.get("outputs", []) if out.get("output_type") == "error"]
    assert not errors
    folder = os.environ.get("OCTRACE_NOTEBOOK_IMAGES")
    if folder:
        (pathlib.Path(folder) / f"notebook-{name}.png").write_bytes(images[-1])
