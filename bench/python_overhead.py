"""Stepping the default scene from Python against the CLI's own measure of its simulation ("simulation
X ms/frame" of `bleedsim run`, which times Simulation::step and the frame's copy to the host): what the
module adds a frame (the GIL let go and taken back, the lock, the check for Ctrl-C). A benchmark, not a
test: the figure is in docs/python.md, with the machine it came from. The two alternate, round after
round, so that a machine busy for a while slows both.

  PYTHONPATH=build/cpu-only/python /usr/bin/python3 bench/python_overhead.py --cli build/cpu-only/cli/bleedsim
"""
import argparse
import re
import statistics
import subprocess
import tempfile
import time
from pathlib import Path

import bleedsim

SCENARIO = Path(__file__).resolve().parent.parent / "scenarios" / "default.toml"


def cli_ms_per_frame(cli, frames, backend):
    with tempfile.TemporaryDirectory() as out:
        done = subprocess.run([cli, "run", str(SCENARIO), "--backend", backend, "--set", f"scene.duration_s={frames / 30}",
                               "--no-hdf5", "--png-every", "0", "--contact-sheet", "0", "--out", out],
                              capture_output=True, text=True, check=True)
    return float(re.search(r"simulation ([0-9.]+) ms/frame", done.stdout).group(1))


def python_ms_per_frame(frames, backend):
    scenario = bleedsim.load_scenario(str(SCENARIO), overrides={"scene.duration_s": frames / 30})
    simulation = bleedsim.Simulation(scenario, backend=backend)
    start = time.perf_counter()
    simulation.step(frames)
    return 1000 * (time.perf_counter() - start) / frames


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--cli", required=True, help="the bleedsim CLI of the same build as the module")
    parser.add_argument("--frames", type=int, default=90, help="frames a run (default 90: 3 s of the scene)")
    parser.add_argument("--rounds", type=int, default=5)
    parser.add_argument("--backend", default="cpu")
    args = parser.parse_args()
    cli, python = [], []
    for round_ in range(args.rounds):
        cli.append(cli_ms_per_frame(args.cli, args.frames, args.backend))
        python.append(python_ms_per_frame(args.frames, args.backend))
        print(f"round {round_ + 1}: cli {cli[-1]:.2f} ms/frame, python {python[-1]:.2f} ms/frame")
    # The fastest round of each is the one least disturbed by the rest of the machine; the medians beside.
    for name, pick in (("fastest", min), ("median", statistics.median)):
        c, p = pick(cli), pick(python)
        print(f"{name} of {args.rounds} rounds of {args.frames} frames ({args.backend}): cli simulation {c:.2f} "
              f"ms/frame, python step {p:.2f} ms/frame: python {100 * (p - c) / c:+.1f} %")


if __name__ == "__main__":
    main()
