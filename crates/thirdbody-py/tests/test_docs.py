"""docs/python.md's tutorial runs as written (issue 12, item 4): its ``python`` blocks,
in order, in one namespace, from the repository's root, writing into a scratch folder.
"""

import os
import pathlib
import re

ROOT = pathlib.Path(__file__).resolve().parents[3]


def python_blocks(markdown):
    return re.findall(r"^```python\n(.*?)^```", markdown, flags=re.S | re.M)


def test_the_tutorial_runs_as_written(tmp_path, monkeypatch):
    blocks = python_blocks((ROOT / "docs" / "python.md").read_text())
    assert len(blocks) >= 5, "the tutorial lost its code"
    # Run from a scratch folder that sees the repository's examples as ./examples,
    # so the files it writes do not land in the checkout.
    (tmp_path / "examples").symlink_to(ROOT / "examples")
    monkeypatch.chdir(tmp_path)
    namespace = {"__name__": "__tutorial__"}
    for block in blocks:
        exec(compile(block, "docs/python.md", "exec"), namespace)
    assert (tmp_path / "fig3_pressure.png").stat().st_size > 10_000
    assert (tmp_path / "fig3.nc").exists()
    assert len(namespace["table"]) == 16
    assert os.path.exists(tmp_path / "examples" / "paper_fig3.toml")
