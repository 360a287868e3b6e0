# docs/python.md's sweep script is docs/examples/sweep.py, word for word, and it runs: a few frames
# a simulation (SWEEP_FRAMES), a line a flow and the figure.
import os
import subprocess
import sys

import pytest

from conftest import SOURCE

pytest.importorskip("matplotlib", reason="the tests' Python has no matplotlib (python3-matplotlib): the sweep NOT run")

SCRIPT = SOURCE / "docs" / "examples" / "sweep.py"


def test_the_docs_show_the_script_as_it_is():
    assert f"```python\n{SCRIPT.read_text()}```\n" in (SOURCE / "docs" / "python.md").read_text()


def test_the_sweep_runs_and_draws_its_figure(tmp_path):
    figure = tmp_path / "sweep.png"
    done = subprocess.run([sys.executable, str(SCRIPT), str(figure)], cwd=SOURCE, capture_output=True, text=True,
                          env={**os.environ, "SWEEP_FRAMES": "2"}, timeout=300)
    assert done.returncode == 0, done.stderr
    lines = done.stdout.splitlines()
    assert [line.split(":")[0] for line in lines] == ["flow 0.3 mm3/s/mm", "flow 0.6 mm3/s/mm", "flow 1.2 mm3/s/mm"]
    assert figure.read_bytes().startswith(b"\x89PNG\r\n\x1a\n")
