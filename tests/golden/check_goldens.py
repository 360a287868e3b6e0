#!/usr/bin/env python3
"""An independent check that the golden key frames show the report's radial spread.

The goldens pin the CPU reference's bytes; this recomputes the stain of every key frame from the
scenario file alone, in float64 with NumPy (no bleedsim code), and demands agreement to float32
rounding. It also checks what the blend must do to the frame: red untouched, green and blue only
ever taken away, and by the stain. Run: /usr/bin/python3 tests/golden/check_goldens.py [repo root]
"""
import pathlib
import sys
import tomllib

import h5py
import numpy as np

STAIN_TOLERANCE = 2e-6   # float32 arithmetic in the reference, float64 here
BYTE_TOLERANCE = 1       # the frame's bytes: one rounding step


def expected_stain(scenario, t):
    scene = scenario["scene"]
    w, h = scene["width_px"], scene["height_px"]
    x = (np.arange(w) + 0.5) * (scene["width_mm"] / w)
    y = (np.arange(h) + 0.5) * (scene["height_mm"] / h)
    xx, yy = np.meshgrid(x, y)
    spread = scenario.get("spread", {})
    light_left = np.ones((h, w))
    for cut in scenario.get("cut", []):
        r = cut.get("radius_mm", spread.get("radius_mm", 4.0))
        growth = cut.get("growth_per_s", spread.get("growth_per_s", 0.5))
        amplitude = np.clip((t - cut.get("start_s", 0.0)) * growth, 0.0, 1.0)
        d = np.hypot(xx - cut["x_mm"], yy - cut["y_mm"])
        final = np.where(d < r, ((r - d) / r) ** 6, 0.0)   # the report's profile
        light_left *= 1.0 - amplitude * final
    return 1.0 - light_left


def check_scene(root, name):
    problems = []
    scenario = tomllib.loads((root / "scenarios/golden" / f"{name}.toml").read_text())
    fps = scenario["scene"].get("frame_rate_hz", 30.0)
    frames_pinned = sum(1 for line in (root / "golden" / name / "hashes.txt").read_text().splitlines()
                        if line and not line.startswith("#"))
    expected_frames = round(scenario["scene"]["duration_s"] * fps)
    if frames_pinned != expected_frames:
        problems.append(f"hashes.txt pins {frames_pinned} frames, the scenario has {expected_frames}")
    with h5py.File(root / "golden" / name / "keyframes.h5", "r") as f:
        keys = [int(k) for k in f.attrs["key_frames"].split()]
        stains, frames, times = f["spread/stain"][:], f["frame"][:], f["time"][:]
    for i, k in enumerate(keys):
        t = (k + 1) / fps
        if abs(times[i] - t) > 1e-12:
            problems.append(f"key frame {k}: time {times[i]} s, expected {t} s")
        error = np.abs(stains[i] - expected_stain(scenario, t)).max()
        if error > STAIN_TOLERANCE:
            problems.append(f"key frame {k}: stain differs from the report's formula by {error:.3g}")
    first = frames[0].astype(int)
    for i, k in enumerate(keys):
        now = frames[i].astype(int)
        if not np.array_equal(now[..., 0], first[..., 0]) or not np.array_equal(now[..., 3], first[..., 3]):
            problems.append(f"key frame {k}: red or alpha changed; the stain takes only green and blue")
        # Where frame 0 is still unstained it is the tissue: the stain must take exactly s·255.
        clean = stains[0] == 0.0
        for c in (1, 2):
            wanted = np.clip(first[..., c] - stains[i] * 255.0, 0, 255)
            off = np.abs(now[..., c] - wanted)[clean].max()
            if off > BYTE_TOLERANCE:
                problems.append(f"key frame {k}: channel {c} is off the tissue minus the stain by {off}")
    stained = (stains[-1] > 0.05).mean()
    if not 0.001 < stained < 0.9:
        problems.append(f"last key frame: {stained:.1%} of pixels visibly stained; expected a bounded stain")
    return problems


def main():
    root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).resolve().parents[2])
    scenes = sorted(p.name for p in (root / "golden").iterdir() if p.is_dir())
    failed = False
    for name in scenes:
        problems = check_scene(root, name)
        for problem in problems:
            print(f"FAIL {name}: {problem}")
        failed |= bool(problems)
        if not problems:
            print(f"ok   {name}")
    if len(scenes) < 3:
        print(f"FAIL only {len(scenes)} golden scenes")
        failed = True
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
