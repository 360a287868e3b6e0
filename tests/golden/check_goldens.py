#!/usr/bin/env python3
"""An independent check that the golden key frames show the report's radial spread and particles.

The goldens pin the CPU reference's bytes; this recomputes what it can of every key frame from the
scenario file alone, in float64 with NumPy (no bleedsim code), and demands agreement to float32
rounding:

- the spread's stain (scenes with a [spread] table; the stain is 0 in a scene without one);
- for scenes with a [particles] table (docs/particles.md), the accounting (emitted, alive,
  expired, overwritten) replayed id by id from the emission schedule, the ring buffer and the
  lifetime; which ring slots hold the live particles and their ages; every live centre inside the
  panel less a radius;
- the film of blood (splat/thickness, mm) recomputed from the stored positions and ages: each live
  particle shares its blood, V · fade, among the pixels whose centres lie at d < R from it in
  proportion to (1 − d²/R²)², or puts it all into the pixel holding its centre where it reaches
  none; and the film's volume, sum × pixel area, against the particles' V · fade, exactly but for
  the fixed point's rounding (a splat cut by the panel's edge keeps all of its blood on the panel);
- for scenes with a [blur] table too (docs/particles.md#the-blur), the blurred film
  (blur/thickness, mm) recomputed from the stored splat/thickness (block means, the normalised
  Gaussian across and down with clamped taps, the bilinear upsample), to a bound on float32's
  rounding carried through the passes, and exactly 0 where no film reaches; and its volume: the
  film's, plus exactly what the edges' clamped taps and partial blocks move (the blur keeps the
  volume of the film further than its reach from the edges);
- what the blend must do to the frame, with the film it lays over the tissue (blur/thickness in a
  scene with [blur], splat/thickness otherwise): alpha untouched; where there is no film, red
  untouched and green and blue only ever taken away, and by the stain; under the film, each
  channel of the stained tissue times the Beer–Lambert transmission exp(−a_c · h),
  a = (4, 40, 45) per mm.

- for scenes with a [haptics] table (docs/haptics.md), the whole haptic channel replayed from the
  trace file (samples, contact, penetration, force, cutting), the force rising on contact and
  within the cap, and the cuts the strokes lay, which the checks above then use.

The particles' checks (accounting, live slots, film, blur) live in golden_film.py beside this file,
the haptics' in golden_haptics.py.

Run: /usr/bin/python3 tests/golden/check_goldens.py [repo root] [--golden-dir DIR]
(DIR defaults to <repo root>/golden; the scenarios are always <repo root>/scenarios/golden.)
"""
import argparse
import pathlib
import sys
import tomllib

import h5py
import numpy as np

from golden_film import check_blur, check_particles, pixel_centres
from golden_haptics import check_haptics
from scenario_defaults import fill_cut, load_params, read_scenario

STAIN_TOLERANCE = 2e-6   # float32 arithmetic in the reference, float64 here ...
STAIN_TOLERANCE_PER_CUT = 3e-7   # ... and each overlapping cut's factor adds a few float32 roundings
BYTE_TOLERANCE = 1       # the frame's bytes: one rounding step
ABSORPTION_PER_MM = (4.0, 40.0, 45.0)  # the blend's Beer–Lambert coefficients (core/physics/blend.h)
OPTICAL_DEPTH_MAX = 32.0               # the transmission table's end: deeper reads exp(−32)


def byte_half_up(v):
    """[0, 1] to a byte, rounding half up, as the blend does."""
    return np.floor(np.clip(v, 0.0, 1.0) * 255.0 + 0.5)


def expected_stain(scenario, t):
    scene = scenario["scene"]
    x, y = pixel_centres(scene)
    xx, yy = np.meshgrid(x, y)
    light_left = np.ones((scene["height_px"], scene["width_px"]))
    for cut in scenario["cut"]:
        r, growth = cut["radius_mm"], cut["growth_per_s"]
        amplitude = np.clip((t - cut["start_s"]) * growth, 0.0, 1.0)
        d = np.hypot(xx - cut["x_mm"], yy - cut["y_mm"])
        final = np.where(d < r, ((r - d) / r) ** 6, 0.0)   # the report's profile
        light_left *= 1.0 - amplitude * final
    return 1.0 - light_left


# ---- particles -------------------------------------------------------------------------------

def check_frames(keys, frames, stains, films, problems, notes, film_name="splat/thickness"):
    """What the blend must have done. The tissue is not stored: where some key frame shows it with
    no film over it its red is the tissue's, and where that frame is unstained too, its green and
    blue. films is the film the blend lays over the tissue, film_name's field."""
    frames = frames.astype(int)
    bare = films == 0.0
    if not (frames[..., 3] == frames[0, ..., 3]).all():
        problems.append("alpha changed between key frames; the blend passes it through")
    tissue = np.zeros(frames.shape[1:3] + (3,), dtype=int)
    known = np.zeros(frames.shape[1:3] + (3,), dtype=bool)
    for i in reversed(range(len(keys))):   # frame 0 last: the least stained wins
        clean = bare[i] & (stains[i] == 0.0)
        for c, where in ((0, bare[i]), (1, clean), (2, clean)):
            tissue[..., c][where] = frames[i, ..., c][where]
            known[..., c] |= where
    checked = unknown = 0
    for i, k in enumerate(keys):
        now, film, stain = frames[i], films[i].astype(np.float64), stains[i].astype(np.float64)
        # No film: red untouched, green and blue the tissue's less the stain.
        if (now[..., 0] != tissue[..., 0])[bare[i]].any():
            problems.append(f"key frame {k}: red changed where there is no film; only the stain takes green and blue")
        for c in (1, 2):
            wanted = np.clip(tissue[..., c] - stain * 255.0, 0, 255)
            where = bare[i] & known[..., c]
            off = np.abs(now[..., c] - wanted)[where].max(initial=0)
            if off > BYTE_TOLERANCE:
                problems.append(f"key frame {k}: channel {c} is off the tissue minus the stain by {off}")
        # Under the film: the stained tissue times the light that crosses it, exp(−a_c · h)
        # (the reference reads it from a table of exp(−n/64), linearly: 3e-5 off at most).
        under = ~bare[i]
        for c in range(3):
            where = under & known[..., c]
            checked += int(where.sum())
            unknown += int((under & ~known[..., c]).sum())
            if not where.any():
                continue
            below = np.maximum(tissue[..., c] / 255.0 - (stain if c else 0.0), 0.0)
            depth = np.minimum(ABSORPTION_PER_MM[c] * film, OPTICAL_DEPTH_MAX)
            wanted = byte_half_up(below * np.exp(-depth))
            bad = where & (np.abs(now[..., c] - wanted) > BYTE_TOLERANCE)
            if bad.any():
                j, x = np.argwhere(bad)[0]
                problems.append(f"key frame {k}: channel {c} of {bad.sum()} pixels under the film is not the "
                                f"stained tissue's light through it (first ({x}, {j}): {now[j, x, c]}, film "
                                f"{film[j, x]:.4g} mm, tissue {int(byte_half_up(below[j, x]))}, "
                                f"expected {int(wanted[j, x])})")
        # A film only takes light away: under it, red is never above the tissue's (exactly: the
        # transmission is at most 1, and v/255 back to a byte is v).
        brighter = under & known[..., 0] & (now[..., 0] > tissue[..., 0])
        if brighter.any():
            j, x = np.argwhere(brighter)[0]
            problems.append(f"key frame {k}: {brighter.sum()} pixels under the film are redder than the tissue "
                            f"(first ({x}, {j}): {now[j, x, 0]} over {tissue[j, x, 0]})")
    if checked or unknown:
        notes.append(f"frame under the film ({film_name}): {checked} pixel channels checked, {unknown} with the tissue unknown")


def check_scene(root, golden, name, params):
    problems, notes = [], []
    scenario = read_scenario(tomllib.loads((root / "scenarios/golden" / f"{name}.toml").read_text()), params)
    fps = scenario["scene"]["frame_rate_hz"]
    frames_pinned = sum(1 for line in (golden / name / "hashes.txt").read_text().splitlines()
                        if line and not line.startswith("#"))
    expected_frames = round(scenario["scene"]["duration_s"] * fps)
    if frames_pinned != expected_frames:
        problems.append(f"hashes.txt pins {frames_pinned} frames, the scenario has {expected_frames}")
    with h5py.File(golden / name / "keyframes.h5", "r") as f:
        keys = [int(k) for k in f.attrs["key_frames"].split()]
        wanted_keys = sorted({0, expected_frames // 3, 2 * expected_frames // 3, expected_frames - 1})
        if keys != wanted_keys:
            problems.append(f"key frames {keys}, expected {wanted_keys}")
        frames, times = f["frame"][:], f["time"][:]
        if "haptics" in scenario:   # the stylus' cuts follow the scripted ones, as in the run
            scenario["cut"] += [fill_cut(cut, scenario, params)
                                for cut in check_haptics(root, scenario, f, expected_frames, problems, notes)]
        has_spread, has_particles = "spread" in scenario, "particles" in scenario
        has_blur = has_particles and "blur" in scenario   # the parser refuses [blur] without [particles]
        wanted_fields = ((["spread/stain"] if has_spread else []) +
                         (["particles/position", "particles/velocity", "particles/age", "particles/accounting",
                           "splat/thickness"] if has_particles else []) +
                         (["blur/thickness"] if has_blur else []) + ["frame"])
        stored_fields = f.attrs["fields"].split()
        if sorted(stored_fields) != sorted(wanted_fields) or not all(name in f for name in wanted_fields):
            problems.append(f"the fields stored ({' '.join(stored_fields)}) are not the ones the scenario's "
                            f"effects make ({' '.join(wanted_fields)})")
            return problems, notes
        stains = f["spread/stain"][:] if has_spread else np.zeros(frames.shape[:3], dtype=np.float32)
        films = (check_particles(scenario, f, keys, problems, notes) if has_particles
                 else np.zeros(frames.shape[:3], dtype=np.float32))
        if has_blur:   # the film the blend lays over the tissue: the blurred one
            films = check_blur(scenario, f, keys, films, problems, notes)
    for i, k in enumerate(keys):
        t = (k + 1) / fps
        if abs(times[i] - t) > 1e-12:
            problems.append(f"key frame {k}: time {times[i]} s, expected {t} s")
        error = np.abs(stains[i] - expected_stain(scenario, t)).max() if has_spread else np.abs(stains[i]).max()
        if error > STAIN_TOLERANCE + STAIN_TOLERANCE_PER_CUT * len(scenario["cut"]):
            problems.append(f"key frame {k}: stain differs from the report's formula by {error:.3g}")
    check_frames(keys, frames, stains, films, problems, notes,
                 "blur/thickness" if has_blur else "splat/thickness")
    if has_spread:
        stained = (stains[-1] > 0.05).mean()
        if not 0.001 < stained < 0.9:
            problems.append(f"last key frame: {stained:.1%} of pixels visibly stained; expected a bounded stain")
    return problems, notes


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("root", nargs="?", type=pathlib.Path, default=pathlib.Path(__file__).resolve().parents[2],
                        help="the repository root (its scenarios/golden)")
    parser.add_argument("--golden-dir", type=pathlib.Path, help="the golden scenes' folders (default: ROOT/golden)")
    parser.add_argument("--bleedsim", required=True,
                        help="the bleedsim CLI, whose `params --json` gives every default")
    args = parser.parse_args()
    params = load_params(args.bleedsim)
    golden = args.golden_dir or args.root / "golden"
    scenes = sorted(p.name for p in golden.iterdir() if p.is_dir())
    failed = False
    for name in scenes:
        problems, notes = check_scene(args.root, golden, name, params)
        for problem in problems:
            print(f"FAIL {name}: {problem}")
        failed |= bool(problems)
        if not problems:
            print(f"ok   {name}" + (f" ({'; '.join(notes)})" if notes else ""))
    if len(scenes) < 3:
        print(f"FAIL only {len(scenes)} golden scenes")
        failed = True
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
