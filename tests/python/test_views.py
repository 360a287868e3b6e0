# Fields are read-only NumPy views of the simulation's host memory, as docs/python.md says: the last
# frame's values until the next step overwrites them in place; a view keeps its Simulation alive.
import gc

import numpy as np
import pytest

import bleedsim
from conftest import DEFAULT


@pytest.fixture(scope="module")
def scenario():
    return bleedsim.load_scenario(str(DEFAULT))


def test_a_view_is_read_only(scenario):
    simulation = bleedsim.Simulation(scenario, backend="cpu")
    simulation.step()
    view = simulation.field("frame")
    assert view.shape == (480, 640, 4) and view.dtype == np.uint8
    with pytest.raises(ValueError):
        view[0, 0, 0] = 1
    with pytest.raises(ValueError):
        view.setflags(write=True)


def test_a_step_overwrites_the_views_memory_in_place(scenario):
    simulation = bleedsim.Simulation(scenario, backend="cpu")
    simulation.step()
    view = simulation.field("spread/stain")
    kept = np.array(view)
    simulation.step()
    assert np.shares_memory(view, simulation.field("spread/stain"))
    assert np.array_equal(view, simulation.copy_field("spread/stain"))
    assert not np.array_equal(view, kept)
    assert kept.flags.writeable


def test_a_view_keeps_its_simulation_alive(scenario):
    simulation = bleedsim.Simulation(scenario, backend="cpu")
    simulation.step()
    view = simulation.field("frame")
    kept = np.array(view)
    del simulation
    gc.collect()
    assert isinstance(view.base, bleedsim.Simulation)
    assert np.array_equal(view, kept)


def test_shapes_follow_the_fields_description(scenario):
    simulation = bleedsim.Simulation(scenario, backend="cpu")
    simulation.step()
    assert simulation.field("particles/position").shape[1:] == (2,)
    assert simulation.field("particles/age").ndim == 1
    with pytest.raises(KeyError):
        simulation.field("no/such")
    with pytest.raises(RuntimeError):
        bleedsim.Simulation(scenario, backend="cpu").frame_hash()
