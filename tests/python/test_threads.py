# Simulation.step releases the GIL while frames compute, so other Python threads run meanwhile; between
# frames it reports progress and answers Ctrl-C.
#
# No timing: the switch interval is made so long that a thread holding the GIL keeps it until it
# blocks or releases it. The other thread then runs Python only where step() lets go of the GIL, and
# what it reads there (frames_done, below the frames asked for) shows it ran inside the call.
import _thread
import sys
import threading

import pytest

import bleedsim
from conftest import DEFAULT

FRAMES = 8


@pytest.fixture
def gil_kept_until_released():
    interval = sys.getswitchinterval()
    sys.setswitchinterval(1000.0)
    yield
    sys.setswitchinterval(interval)


def inside_step(simulation, work):
    """Runs work() in another thread that can start only once the GIL is free, while
    simulation.step(FRAMES) runs here; returns what work() returned and what step() raised."""
    go = threading.Event()
    seen = []
    thread = threading.Thread(target=lambda: (go.wait(), seen.append(work())))
    thread.start()
    go.set()  # the thread now waits for the GIL, which this one keeps until step() lets go of it
    try:
        simulation.step(FRAMES)
        raised = None
    except BaseException as e:  # noqa: B036 - KeyboardInterrupt is what one test expects
        raised = e
    thread.join()
    return seen[0], raised


def test_another_thread_runs_python_while_frames_compute(gil_kept_until_released):
    simulation = bleedsim.Simulation(bleedsim.load_scenario(str(DEFAULT)), backend="cpu")
    frames_seen, raised = inside_step(simulation, lambda: simulation.frames_done)
    assert raised is None and simulation.frames_done == FRAMES
    assert frames_seen < FRAMES  # read before step() returned: the GIL was free while it ran


def test_ctrl_c_stops_a_long_step_between_frames(gil_kept_until_released):
    simulation = bleedsim.Simulation(bleedsim.load_scenario(str(DEFAULT)), backend="cpu")
    _, raised = inside_step(simulation, _thread.interrupt_main)
    assert isinstance(raised, KeyboardInterrupt)
    assert 1 <= simulation.frames_done < FRAMES  # stopped after a frame, not at the end


def test_progress_is_called_after_each_frame():
    simulation = bleedsim.Simulation(bleedsim.load_scenario(str(DEFAULT)), backend="cpu")
    calls = []
    simulation.step(3, progress=lambda done, frames: calls.append((done, frames, simulation.frames_done)))
    assert calls == [(1, 3, 1), (2, 3, 2), (3, 3, 3)]

    def stop_after_two(done, frames):
        if done == 2:
            raise RuntimeError("enough")

    with pytest.raises(RuntimeError, match="enough"):
        simulation.step(5, progress=stop_after_two)
    assert simulation.frames_done == 5
    with pytest.raises(TypeError, match="progress"):
        simulation.step(1, progress=3)
