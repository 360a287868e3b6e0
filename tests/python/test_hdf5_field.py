# A field read from Python holds the bytes `bleedsim run` wrote to frames.h5 for that frame.
import numpy as np
import pytest

import bleedsim
from conftest import cli, short_default

h5py = pytest.importorskip("h5py", reason="the tests' Python has no h5py, the reader of frames.h5: NOT checked")

FRAMES = 4


def test_each_frames_fields_equal_the_hdf5_files(tmp_path):
    scenario = short_default(tmp_path, FRAMES)
    cli("run", scenario, "--backend", "cpu", "--out", tmp_path / "out", "--png-every", 0, "--contact-sheet", 0,
        "--quiet")
    simulation = bleedsim.Simulation(bleedsim.load_scenario(str(scenario)), backend="cpu")
    with h5py.File(tmp_path / "out" / "frames.h5", "r") as written:
        assert written["frame"].shape[0] == FRAMES
        for k in range(FRAMES):
            simulation.step()
            for name in ("frame", "spread/stain", "blur/thickness"):
                view = simulation.field(name)
                assert view.dtype == written[name].dtype and view.shape == written[name].shape[1:]
                assert view.tobytes() == written[name][k].tobytes(), f"{name} at frame {k}"
