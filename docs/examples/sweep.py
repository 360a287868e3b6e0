"""How much of the panel the blood wets, against the bleeding rate: the default scene at three flows,
three seeds each (the seed moves the particles' jitter), plotted with matplotlib."""
import os
import sys

import matplotlib

matplotlib.use("Agg")  # files only, no display
import matplotlib.pyplot as plt
import numpy as np

import bleedsim

FLOWS = [0.3, 0.6, 1.2]  # particles.flow_mm3_per_s_per_mm: blood per second from each mm of wound
SEEDS = [1, 2, 3]
FRAMES = int(os.environ.get("SWEEP_FRAMES", "90"))  # 3 s at 30 Hz
PIXEL_MM2 = 0.05 * 0.05  # the default panel: 32 x 24 mm over 640 x 480 px


def wetted_mm2(flow, seed):
    """The film's area after FRAMES frames: the pixels where splat/thickness is above 0."""
    scenario = bleedsim.load_scenario("scenarios/default.toml",
                                      overrides={"particles.flow_mm3_per_s_per_mm": flow, "scene.seed": seed})
    simulation = bleedsim.Simulation(scenario, backend="auto")
    simulation.step(FRAMES)
    return np.count_nonzero(simulation.field("splat/thickness")) * PIXEL_MM2


areas = np.array([[wetted_mm2(flow, seed) for seed in SEEDS] for flow in FLOWS])
for flow, row in zip(FLOWS, areas):
    print(f"flow {flow:.1f} mm3/s/mm: wetted {row.mean():.2f} mm2 (seeds: {', '.join(f'{a:.2f}' for a in row)})")

figure, axes = plt.subplots(figsize=(5, 3.5))
for column, seed in enumerate(SEEDS):
    axes.plot(FLOWS, areas[:, column], "o", alpha=0.5, label=f"seed {seed}")
axes.plot(FLOWS, areas.mean(axis=1), "k-", label="mean")
axes.set_xlabel("flow (mm³/s per mm of wound)")
axes.set_ylabel(f"wetted area after {FRAMES} frames (mm²)")
axes.legend()
figure.tight_layout()
figure.savefig(sys.argv[1] if len(sys.argv) > 1 else "sweep.png", dpi=100)
