"""docs/python.md's tutorial runs as written: its ``python`` blocks, in order, saved as
one script and run by a fresh Python, from a scratch folder that sees the repository's
examples, as a user runs it from the repository's root.
"""

import os
import pathlib
import re
import socket
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parents[3]


def python_blocks(markdown):
    return re.findall(r"^```python\n(.*?)^```", markdown, flags=re.S | re.M)


def test_the_tutorial_runs_as_a_script(tmp_path):
    blocks = python_blocks((ROOT / "docs" / "python.md").read_text())
    assert len(blocks) >= 5, "the tutorial lost its code"
    script = tmp_path / "tutorial.py"
    script.write_text("\n".join(blocks))
    # Run from a scratch folder that sees the repository's examples as ./examples,
    # so the files it writes do not land in the checkout.
    (tmp_path / "examples").symlink_to(ROOT / "examples")
    # Port 8787 held here: a scheduler that still wanted it would say so on stderr.
    holder = socket.socket()
    try:
        holder.bind(("127.0.0.1", 8787))
        holder.listen()
    except OSError:
        pass  # in use already: the stderr check below holds all the same
    try:
        run = subprocess.run([sys.executable, str(script)], cwd=tmp_path, capture_output=True,
                             text=True, timeout=600)
    finally:
        holder.close()
    assert run.returncode == 0, run.stderr
    assert "8787" not in run.stderr, run.stderr
    out = tmp_path / "out" / "tutorial"
    assert (out / "fig3_pressure.png").stat().st_size > 10_000
    assert (out / "fig3.nc").exists()
    assert len((out / "fig8_sweep.csv").read_text().splitlines()) == 1 + 16
    assert sorted(p.name for p in tmp_path.iterdir()) == ["examples", "out", "tutorial.py"]
    assert os.path.exists(tmp_path / "examples" / "paper_fig3.toml")
