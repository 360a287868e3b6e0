# The default scene's first 10 frames from Python hash as `bleedsim hash` prints them.
import bleedsim
from conftest import DEFAULT, cli_hash_lines, hash_line


def test_first_ten_frames_hash_as_the_cli_prints_them():
    simulation = bleedsim.Simulation(bleedsim.load_scenario(str(DEFAULT)), backend="cpu")
    from_python = []
    for _ in range(10):
        simulation.step()
        from_python.append(hash_line(simulation))
    assert from_python == cli_hash_lines(DEFAULT, 10)
    assert simulation.frames_done == 10 and abs(simulation.time_s - 10 / 30) < 1e-12
