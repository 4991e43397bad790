"""docs/python.md's walk-through, its blocks run one after another in one namespace as a notebook
runs its cells, from the checkout's root."""
import os
import pathlib
import re

import pytest

SOURCE = pathlib.Path(os.environ["ROVING_SOURCE_DIR"])


def test_the_walk_through_runs_as_written(monkeypatch):
    pytest.importorskip("matplotlib")  # the histogram's (the package test's clean tree has none)
    monkeypatch.chdir(SOURCE)
    blocks = re.findall(r"```python\n(.*?)```", (SOURCE / "docs" / "python.md").read_text(), re.S)
    assert len(blocks) >= 5
    namespace = {}
    for block in blocks:
        exec(compile(block, "docs/python.md", "exec"), namespace)
    assert (namespace["hit"].sum() > 0) and namespace["status"] == 0
