# Overrides take effect; bad input raises bleedsim.InputError (a ValueError) with the CLI's message.
import pytest

import bleedsim
from conftest import DEFAULT, cli, cli_hash_lines, hash_line


def cli_error(*args):
    done = cli(*args, check=False)
    assert done.returncode == 2, done.stderr
    return done.stderr.strip()


def test_an_override_changes_the_run_as_the_clis_set_does():
    scenario = bleedsim.load_scenario(str(DEFAULT), overrides={"particles.diameter_mm": 0.5, "scene.duration_s": 1.0})
    assert scenario.frame_count == 30
    simulation = bleedsim.Simulation(scenario, backend="cpu")
    simulation.step()
    plain = bleedsim.Simulation(bleedsim.load_scenario(str(DEFAULT)), backend="cpu")
    plain.step()
    assert hash_line(simulation) != hash_line(plain)
    assert [hash_line(simulation)] == cli_hash_lines(DEFAULT, 1, "--set", "particles.diameter_mm=0.5")


@pytest.mark.parametrize("key, value, cli_text", [
    ("particles.diameter_mm", -1.0, "-1.0"),      # out of range
    ("particles.diamter_mm", 0.1, "0.1"),         # unknown key
    ("particles.diameter_mm", "thin", '"thin"'),  # wrong type
    ("cut.x_mm", 1.0, "1.0"),                     # [[cut]] is an array of tables
])
def test_a_bad_override_raises_the_clis_message(key, value, cli_text):
    with pytest.raises(ValueError) as raised:
        bleedsim.load_scenario(str(DEFAULT), overrides={key: value})
    assert isinstance(raised.value, bleedsim.InputError)
    assert str(raised.value).startswith("overrides:1:")
    assert cli_error("hash", DEFAULT, "--set", f"{key}={cli_text}") == f"bleedsim: error: {raised.value}"


def test_a_bad_scenario_raises_the_clis_message(tmp_path):
    bad = tmp_path / "bad.toml"
    text = DEFAULT.read_text().replace("width_px = 640", "width_px = -640", 1)
    bad.write_text(text)
    with pytest.raises(bleedsim.InputError) as from_file:
        bleedsim.load_scenario(str(bad))
    with pytest.raises(bleedsim.InputError) as from_text:
        bleedsim.load_scenario_text(text, path=str(bad))
    message = cli_error("hash", bad)
    assert message == f"bleedsim: error: {from_file.value}" == f"bleedsim: error: {from_text.value}"
    assert str(from_file.value).startswith(f"{bad}:15:")
    assert "scene.width_px" in message


def test_a_value_that_is_no_toml_value_is_a_type_error():
    with pytest.raises(TypeError, match="particles.diameter_mm"):
        bleedsim.load_scenario(str(DEFAULT), overrides={"particles.diameter_mm": None})


def test_a_string_override_is_one_value_whatever_it_holds():
    # Read as one string (refused as a name), not as a [scene] table and a width after it.
    with pytest.raises(bleedsim.InputError, match=r"^overrides:1:12: scene\.name: 'a\"\n\[scene\]\nwidth_px = 1' must"):
        bleedsim.load_scenario(str(DEFAULT), overrides={"scene.name": 'a"\n[scene]\nwidth_px = 1'})
