# Cuts and stylus samples given from Python run as the same cuts and path written in a scenario file:
# the same frame hashes as `bleedsim hash` prints for the file; bad ones are refused with the C++ API's
# messages.
import re

import pytest

import bleedsim
from conftest import DEFAULT, SOURCE, cli, hash_line

# Three cuts, the last two made while the run goes on; every key a default [[cut]] may give.
CUTS = [dict(x_mm=12.0, y_mm=9.0, start_s=0.0, radius_mm=12.0),
        dict(x_mm=19.0, y_mm=11.0, start_s=0.1, growth_per_s=0.8, flow_mm3_per_s_per_mm=1.2),
        dict(x_mm=15.0, y_mm=15.0, start_s=0.2, bleed_s=1.0, clot_s=0.5, wound_mm=2.0)]


def cut_tables(cuts):
    return "".join("[[cut]]\n" + "".join(f"{key} = {value}\n" for key, value in cut.items()) + "\n" for cut in cuts)


def default_without_cuts(frames):
    """The default scene, `frames` frames long, its [[cut]] tables taken out."""
    text = DEFAULT.read_text().replace("duration_s = 8.0", f"duration_s = {frames / 30}", 1)
    without = re.sub(r"\[\[cut\]\][^\[]*", "", text)
    assert "[[cut]]" in text and "[[cut]]" not in without and "[output]" in without
    return without


def cli_hashes(path):
    """The frame lines `bleedsim hash` prints (less the run's line after them)."""
    lines = cli("hash", path, "--backend", "cpu").stdout.splitlines()
    assert lines[-1].startswith("run ")
    return lines[:-1]


def run(simulation, before_frame=lambda simulation, end_s: None):
    """Every frame's hash line; before_frame(simulation, end_s) is called before each frame."""
    lines = []
    while simulation.frames_done < simulation.frame_count:
        before_frame(simulation, (simulation.frames_done + 1) / 30)
        simulation.step()
        lines.append(hash_line(simulation))
    return lines


def test_cuts_added_from_python_run_as_the_same_cuts_in_a_file(tmp_path):
    without = default_without_cuts(12)
    in_file = tmp_path / "cuts.toml"
    in_file.write_text(without.replace("[output]", cut_tables(CUTS) + "[output]"))
    pending = [dict(cut) for cut in CUTS]

    def cut_when_due(simulation, end_s):
        while pending and pending[0]["start_s"] <= end_s:
            keys = pending.pop(0)
            simulation.add_cut(keys.pop("x_mm"), keys.pop("y_mm"), keys.pop("start_s"), **keys)

    scenario = bleedsim.load_scenario_text(without, path=str(tmp_path / "no-cuts.toml"))
    from_python = run(bleedsim.Simulation(scenario, backend="cpu"), cut_when_due)
    assert not pending
    assert from_python == cli_hashes(in_file)
    assert from_python != run(bleedsim.Simulation(scenario, backend="cpu"))  # the cuts are what made them


@pytest.mark.parametrize("keys, key", [
    (dict(radius_mm=0.0), "radius_mm"),
    (dict(flow_mm3_per_s_per_mm=-1.0), "flow_mm3_per_s_per_mm"),
    (dict(x_mm=40.0), "x_mm"),  # off the 32 mm panel: a rule of the table, not a range
])
def test_a_bad_cut_is_refused_as_the_c_api_and_the_file_refuse_it(tmp_path, keys, key):
    cut = {**dict(x_mm=12.0, y_mm=9.0, start_s=0.0), **keys}
    bad = tmp_path / "bad.toml"
    bad.write_text(default_without_cuts(3).replace("[output]", cut_tables([cut]) + "[output]"))
    file_message = cli("hash", bad, check=False).stderr.strip()
    assert f"cut[0].{key}: " in file_message
    simulation = bleedsim.Simulation(bleedsim.load_scenario(str(DEFAULT)), backend="cpu")
    with pytest.raises(ValueError) as raised:
        simulation.add_cut(cut.pop("x_mm"), cut.pop("y_mm"), cut.pop("start_s"), **cut)
    assert str(raised.value) == f"cut.{key}: " + file_message.split(f"cut[0].{key}: ", 1)[1]


def test_a_key_no_cut_has_or_a_value_of_the_wrong_type_is_a_type_error():
    simulation = bleedsim.Simulation(bleedsim.load_scenario(str(DEFAULT)), backend="cpu")
    with pytest.raises(TypeError, match=r"no key 'radius'.*radius_mm"):
        simulation.add_cut(12.0, 9.0, 0.0, radius=3.0)
    with pytest.raises(TypeError, match="radius_mm is a number, not str"):
        simulation.add_cut(12.0, 9.0, 0.0, radius_mm="3")
    with pytest.raises(TypeError, match="arterial is True or False, not int"):
        simulation.add_cut(12.0, 9.0, 0.0, arterial=1)
    assert hash_line(step_once(simulation)) == hash_line(step_once(
        bleedsim.Simulation(bleedsim.load_scenario(str(DEFAULT)), backend="cpu")))  # nothing was added


def step_once(simulation):
    simulation.step()
    return simulation


def stylus_scene(instrument):
    """suction-pass.toml's scene, 0.6 s long, a cut under the instrument's path, and `instrument`."""
    text = (SOURCE / "scenarios" / "suction-pass.toml").read_text()
    scene = text[:text.index("[[tip]]")].replace("duration_s = 4.5", "duration_s = 0.6", 1)
    assert "duration_s = 0.6" in scene
    return scene + instrument + "[[cut]]\nx_mm = 8.0\ny_mm = 11.0\nwound_mm = 2.0\n"


# The path: touching down at 0.1 s, drawn through the cut to the run's end (after its last point a
# scripted tip is gone and a stylus stays, so the path lasts as long as the run).
PATH = [(0.1, 5.0, 11.0), (0.6, 11.0, 11.0)]


def test_stylus_samples_from_python_move_the_instrument_as_a_scripted_path_does(tmp_path):
    scripted = tmp_path / "scripted.toml"
    scripted.write_text(stylus_scene("".join(f"[[tip]]\nt_s = {t}\nx_mm = {x}\ny_mm = {y}\n\n" for t, x, y in PATH)))
    trace = SOURCE / "scenarios" / "traces" / "cut-then-suction.csv"
    scenario = bleedsim.load_scenario_text(stylus_scene(f'[haptics]\ntrace = "{trace}"\n\n'),
                                           path=str(tmp_path / "stylus.toml"))

    def path_at_once(simulation, end_s):
        # A host that knows its path gives it ahead; given frame by frame, the tip would wait at the
        # last sample given, as a live stylus does.
        if simulation.frames_done == 0:
            for t, x, y in PATH:
                simulation.add_stylus_sample(t, x, y, contact=True, buttons=0xF)  # a path holds every button

    from_python = run(bleedsim.Simulation(scenario, backend="cpu", host_stylus=True), path_at_once)
    assert from_python == cli_hashes(scripted)
    assert from_python != run(bleedsim.Simulation(scenario, backend="cpu", host_stylus=True))  # the samples acted


def test_bad_stylus_samples_are_refused_with_the_c_apis_messages(tmp_path):
    plain = bleedsim.Simulation(bleedsim.load_scenario(str(DEFAULT)), backend="cpu")
    with pytest.raises(ValueError, match=r"^stylus samples: this scene's stylus is absent \(it declares no \[haptics\]\)$"):
        plain.add_stylus_sample(0.1, 1.0, 1.0)
    with pytest.raises(ValueError, match=r"^host_stylus=True: this scene declares no \[haptics\]"):
        bleedsim.Simulation(bleedsim.load_scenario(str(DEFAULT)), backend="cpu", host_stylus=True)
    falcon = bleedsim.load_scenario(str(SOURCE / "scenarios" / "falcon-suction.toml"))
    with pytest.raises(ValueError, match=r"^stylus samples: this scene's stylus is its trace's$"):
        bleedsim.Simulation(falcon, backend="cpu").add_stylus_sample(0.1, 1.0, 1.0)
    host = bleedsim.Simulation(falcon, backend="cpu", host_stylus=True)
    host.add_stylus_sample(0.1, 1.0, 1.0)
    with pytest.raises(ValueError, match=r"^stylus samples: each must be later than the one before$"):
        host.add_stylus_sample(0.1, 2.0, 1.0)
    with pytest.raises(ValueError, match=r"^stylus samples: t_s, x_mm and y_mm must be finite$"):
        host.add_stylus_sample(0.2, float("nan"), 1.0)
