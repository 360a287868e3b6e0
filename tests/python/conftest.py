# What the module's tests share: the tree, the CLI (ctest names both, as for the C++ tests:
# tests/test_paths.h) and a run of the CLI.
import os
import subprocess
from pathlib import Path

import pytest

SOURCE = Path(os.environ["BLEEDSIM_SOURCE_DIR"])
CLI = os.environ["BLEEDSIM_CLI"]
DEFAULT = SOURCE / "scenarios" / "default.toml"


def cli(*args, check=True):
    """The CLI's exit code, stdout and stderr."""
    done = subprocess.run([CLI, *map(str, args)], capture_output=True, text=True, timeout=120)
    if check and done.returncode != 0:
        pytest.fail(f"bleedsim {' '.join(map(str, args))}: exit {done.returncode}: {done.stderr}")
    return done


def cli_hash_lines(scenario, frames, *options):
    """The first `frames` frame lines `bleedsim hash` prints, the run then stopped."""
    with subprocess.Popen([CLI, "hash", str(scenario), "--backend", "cpu", *options], stdout=subprocess.PIPE,
                          stderr=subprocess.DEVNULL, text=True) as process:
        lines = [process.stdout.readline().rstrip("\n") for _ in range(frames)]
        process.kill()
    return lines


def hash_line(simulation):
    """The frame's line as `bleedsim hash` prints it."""
    fields = " ".join(f"{name}={value}" for name, value in simulation.frame_hash().items())
    return f"{simulation.frames_done - 1} {fields}"


def short_default(folder, frames):
    """The default scene cut to `frames` frames, as a file of its own (for the CLI and Python alike)."""
    text = DEFAULT.read_text().replace("duration_s = 8.0", f"duration_s = {frames / 30}", 1)
    assert text != DEFAULT.read_text()
    path = folder / "short.toml"
    path.write_text(text)
    return path
