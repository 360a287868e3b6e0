# frames.xmf, read by ParaView's own XDMF reader (vtkXdmfReader), gives the values h5py reads of
# frames.h5: image fields on the panel's grid in mm, and the particles' positions, velocities and
# ages, at a frame without particles, one with, and one where the ring's run of particles wraps
# past its last slot.
import numpy as np
import pytest

from conftest import cli, short_default

h5py = pytest.importorskip("h5py", reason="the tests' Python has no h5py, the reader of frames.h5: NOT checked")
xdmf2 = pytest.importorskip(
    "vtkmodules.vtkIOXdmf2",
    reason="no VTK with ParaView's XDMF reader (Debian's python3-paraview, which scripts/setup installs; "
    "python3-vtk9 has none): frames.xmf NOT checked")
from vtkmodules.util.numpy_support import vtk_to_numpy  # noqa: E402
from vtkmodules.vtkCommonDataModel import vtkCompositeDataSet  # noqa: E402
from vtkmodules.vtkCommonExecutionModel import vtkStreamingDemandDrivenPipeline  # noqa: E402

FRAMES = 12
CAPACITY = 40  # the default scene emits about 5 particles a frame: the ring wraps by frame 8
PARTICLE_FIELDS = ["particles/accounting", "particles/position", "particles/velocity", "particles/age"]


def particle_run(tmp_path):
    """The default scene cut short, with a small ring and its per-particle arrays written."""
    path = short_default(tmp_path, FRAMES)
    text = path.read_text()
    fields = ", ".join(f'"{name}"' for name in ["spread/stain", "blur/thickness", *PARTICLE_FIELDS])
    # The first cut bleeds from 0.1 s, so that the first frames have no particles.
    changed = text.replace("[particles]", f"[particles]\ncapacity = {CAPACITY}", 1).replace(
        "[output]", f"[output]\nfields = [{fields}]", 1).replace("start_s = 0.0", "start_s = 0.1", 1)
    assert changed.count("capacity =") == 1 and changed.count("fields =") == 1 and "start_s = 0.0" not in changed
    path.write_text(changed)
    out = tmp_path / "out"
    cli("run", path, "--backend", "cpu", "--out", out, "--png-every", 0, "--contact-sheet", 0, "--quiet")
    return out


def blocks_at(reader, time_s):
    """The reader's output at `time_s`: {block name: dataset}."""
    reader.UpdateTimeStep(time_s)
    output = reader.GetOutputDataObject(0)
    return {output.GetMetaData(b).Get(vtkCompositeDataSet.NAME()): output.GetBlock(b)
            for b in range(output.GetNumberOfBlocks())}


def test_paraviews_reader_gives_the_hdf5_files_values(tmp_path):
    out = particle_run(tmp_path)
    reader = xdmf2.vtkXdmfReader()
    reader.SetFileName(str(out / "frames.xmf"))
    reader.UpdateInformation()
    times = reader.GetOutputInformation(0).Get(vtkStreamingDemandDrivenPipeline.TIME_STEPS())
    with h5py.File(out / "frames.h5", "r") as f:
        assert np.array_equal(np.array(times), f["time"][:])
        counts = f["particles/accounting"][:]
        emitted, alive = counts[:, 0].astype(np.int64), counts[:, 1].astype(np.int64)
        first = (emitted - alive) % CAPACITY
        wrapped = [k for k in range(FRAMES) if first[k] + alive[k] > CAPACITY]
        assert wrapped, f"the ring never wrapped in {FRAMES} frames: the test would not cover it"
        assert alive[0] == 0 and alive[4] > 0 and 4 not in wrapped
        mm_per_px = np.float32(32.0 / 640)
        for k in (0, 4, wrapped[-1]):
            blocks = blocks_at(reader, times[k])
            panel, particles = blocks["panel"], blocks["particles"]

            assert panel.GetDimensions() == (640, 480, 1)
            assert panel.GetSpacing()[:2] == (mm_per_px, mm_per_px)
            assert panel.GetOrigin()[:2] == (mm_per_px / 2, mm_per_px / 2)
            for name in ("blur/thickness", "frame"):
                read = vtk_to_numpy(panel.GetPointData().GetArray(name))
                stored = f[name][k]
                assert read.dtype == stored.dtype
                assert np.array_equal(read, stored.reshape(read.shape)), f"{name} at frame {k}"

            slots = (first[k] + np.arange(alive[k])) % CAPACITY
            points = vtk_to_numpy(particles.GetPoints().GetData())
            assert particles.GetNumberOfCells() == alive[k]
            assert np.array_equal(points[:, :2], f["particles/position"][k][slots]), f"positions at frame {k}"
            assert not points[:, 2].any()
            velocity = vtk_to_numpy(particles.GetPointData().GetArray("particles/velocity"))
            assert np.array_equal(velocity[:, :2], f["particles/velocity"][k][slots]), f"velocities at frame {k}"
            age = vtk_to_numpy(particles.GetPointData().GetArray("particles/age"))
            assert age.dtype == np.uint32
            assert np.array_equal(age, f["particles/age"][k][slots]), f"ages at frame {k}"

