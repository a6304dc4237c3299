"""The lecture notebook runs top to bottom, as `jupyter nbconvert --execute` runs it."""

import importlib
import os

import pytest

from conftest import EXAMPLES

NOTEBOOK = EXAMPLES / "notebooks" / "lecture.ipynb"


def test_the_lecture_notebook_runs():
    if os.environ.get("LUCENT_REQUIRE_TOOLS") == "1":
        nbformat, nbclient = (importlib.import_module(m) for m in ("nbformat", "nbclient"))
    else:
        nbformat = pytest.importorskip("nbformat")
        nbclient = pytest.importorskip("nbclient")
    nb = nbformat.read(NOTEBOOK, as_version=4)
    client = nbclient.NotebookClient(
        nb, timeout=300, kernel_name="python3", resources={"metadata": {"path": str(NOTEBOOK.parent)}}
    )
    client.execute()
    pictures = [
        out
        for cell in nb.cells
        if cell.cell_type == "code"
        for out in cell.outputs
        if "image/png" in out.get("data", {})
    ]
    # Every step shows its picture.
    assert len(pictures) >= 6, f"{len(pictures)} pictures"
