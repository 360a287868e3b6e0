#!/usr/bin/env python3
"""An independent check that the golden key frames show the report's radial spread and particles.

The goldens pin the CPU reference's bytes; this recomputes what it can of every key frame from the
scenario file alone, in float64 with NumPy (no bleedsim code), and demands agreement to float32
rounding:

- the spread's stain (scenes with a [spread] table; the stain is 0 in a scene without one);
- for scenes with a [particles] table (docs/particles.md), the accounting (emitted, alive,
  expired, overwritten) replayed id by id from the emission schedule, the ring buffer and the
  lifetime; which ring slots hold the live particles and their ages; every live centre inside the
  panel less a radius; the cover field redrawn from the stored positions and ages;
- what the blend must do to the frame: alpha untouched; where no particle covers a pixel, red
  untouched and green and blue only ever taken away, and by the stain; where particles cover it
  fully, the flat blood colour; where they cover it partly, a mix between the blood colour and
  the uncovered byte.

Run: /usr/bin/python3 tests/golden/check_goldens.py [repo root] [--golden-dir DIR]
(DIR defaults to <repo root>/golden; the scenarios are always <repo root>/scenarios/golden.)
"""
import argparse
import math
import pathlib
import sys
import tomllib

import h5py
import numpy as np

STAIN_TOLERANCE = 2e-6   # float32 arithmetic in the reference, float64 here
BYTE_TOLERANCE = 1       # the frame's bytes: one rounding step
COVER_TOLERANCE = 1e-6   # a particle's opacity: float32 there, float64 here
EDGE_MM = 1e-5           # a pixel centre this close to a disc's edge may fall either side in float32
NEVER_USED = 0xFFFFFFFF  # the age of a ring slot that never held a particle
BLOOD = (0.45, 0.02, 0.03)  # the flat particle colour of the blend (core/blend.h)


def byte_half_up(v):
    """[0, 1] to a byte, rounding half up, as the blend does."""
    return np.floor(np.clip(v, 0.0, 1.0) * 255.0 + 0.5)


BLOOD_BYTES = tuple(int(byte_half_up(c)) for c in BLOOD)   # (115, 5, 8)


def pixel_centres(scene):
    w, h = scene["width_px"], scene["height_px"]
    x = (np.arange(w) + 0.5) * (scene["width_mm"] / w)
    y = (np.arange(h) + 0.5) * (scene["height_mm"] / h)
    return x, y


def expected_stain(scenario, t):
    scene = scenario["scene"]
    x, y = pixel_centres(scene)
    xx, yy = np.meshgrid(x, y)
    spread = scenario.get("spread", {})
    light_left = np.ones((scene["height_px"], scene["width_px"]))
    for cut in scenario.get("cut", []):
        r = cut.get("radius_mm", spread.get("radius_mm", 4.0))
        growth = cut.get("growth_per_s", spread.get("growth_per_s", 0.5))
        amplitude = np.clip((t - cut.get("start_s", 0.0)) * growth, 0.0, 1.0)
        d = np.hypot(xx - cut["x_mm"], yy - cut["y_mm"])
        final = np.where(d < r, ((r - d) / r) ** 6, 0.0)   # the report's profile
        light_left *= 1.0 - amplitude * final
    return 1.0 - light_left


# ---- particles -------------------------------------------------------------------------------

def steps_in(seconds, steps_per_s):
    """Whole steps in a span (rounded half up, at least one): the model's lifetime and fade."""
    return max(1, math.floor(seconds * steps_per_s + 0.5))


def particle_settings(scenario):
    """The [particles] table with its documented defaults (core/scene.h, docs/scenario-format.md)."""
    p = scenario["particles"]
    fps = scenario["scene"].get("frame_rate_hz", 30.0)
    substeps = p.get("substeps", 40)
    steps_per_s = fps * substeps
    if "volume_mm3_per_s" in p:
        rate = p["volume_mm3_per_s"] / p["particle_volume_mm3"]
    else:
        rate = p.get("rate_per_s", 500.0)
    bleed = p.get("bleed_s", 2.0)
    lifetime_s = p.get("lifetime_s", 30.0)
    fade_s = p.get("fade_s", min(1.0, lifetime_s))
    lifetime = steps_in(lifetime_s, steps_per_s)
    cuts = [(c.get("start_s", 0.0), c.get("rate_per_s", rate), c.get("bleed_s", bleed))
            for c in scenario.get("cut", [])]
    return {
        "capacity": p.get("capacity", 65536),
        "radius": p.get("diameter_mm", 0.2) / 2.0,
        "substeps": substeps,
        "steps_per_s": steps_per_s,
        "lifetime": lifetime,
        "fade": min(lifetime, steps_in(fade_s, steps_per_s)),
        "cuts": cuts,
    }


def emission_steps(settings, steps):
    """The step each particle id was emitted in, for the first `steps` steps.

    A cut has emitted floor(rate · time bled so far) particles by time t; step n runs from n/sps
    to (n+1)/sps and emits the difference. Ids count emissions in step order (and cut order within
    a step, which does not matter here: a step's particles share their step)."""
    t = np.arange(steps + 1) / settings["steps_per_s"]
    per_step = np.zeros(steps, dtype=np.int64)
    for start, rate, bleed in settings["cuts"]:
        by = np.floor(rate * np.clip(t - start, 0.0, bleed)).astype(np.int64)
        per_step += np.diff(by)
    return np.repeat(np.arange(steps, dtype=np.int64), per_step)


def replay(settings, step_of_id, steps_done):
    """The fate of every id emitted in the first `steps_done` steps.

    Id n lives in slot n mod capacity and ages one per step from its emission step s (its age at
    the end of step m is m − s + 1); it expires once that reaches the lifetime, and is overwritten
    if id n + capacity is emitted while it still lives (at the start of step s', its age is
    s' − s)."""
    capacity, lifetime = settings["capacity"], settings["lifetime"]
    emitted = int(np.searchsorted(step_of_id, steps_done))   # ids with step < steps_done
    s = step_of_id[:emitted]
    successor = np.full(emitted, np.iinfo(np.int64).max)
    if emitted > capacity:
        successor[:emitted - capacity] = s[capacity:]
    overwritten = successor - s < lifetime
    expired = ~overwritten & (steps_done - s >= lifetime)
    alive = ~overwritten & ~expired
    age = steps_done - s
    return emitted, alive, expired, overwritten, age


def expected_cover(settings, scene, position, age):
    """The cover field redrawn from the live particles: the largest opacity over the discs holding
    each pixel centre. Returns (exact, lowest, highest): `lowest` and `highest` take a centre
    within EDGE_MM of a disc's edge as outside and inside."""
    w, h = scene["width_px"], scene["height_px"]
    px, py = scene["width_mm"] / w, scene["height_mm"] / h
    cx, cy = pixel_centres(scene)
    r = settings["radius"]
    alpha = np.minimum(1.0, (settings["lifetime"] - age.astype(np.float64)) / settings["fade"])
    x, y = position[:, 0].astype(np.float64), position[:, 1].astype(np.float64)
    k = int(math.ceil(r / min(px, py))) + 1
    offsets = np.arange(-k, k + 1)
    ii = np.floor(x / px).astype(np.int64)[:, None, None] + offsets[None, None, :]
    jj = np.floor(y / py).astype(np.int64)[:, None, None] + offsets[None, :, None]
    ii, jj = np.broadcast_arrays(ii, jj)
    inside_grid = (ii >= 0) & (ii < w) & (jj >= 0) & (jj < h)
    d = np.hypot(cx[np.clip(ii, 0, w - 1)] - x[:, None, None], cy[np.clip(jj, 0, h - 1)] - y[:, None, None])
    flat = (np.clip(jj, 0, h - 1) * w + np.clip(ii, 0, w - 1)).ravel()
    a = np.broadcast_to(alpha[:, None, None], d.shape)
    fields = []
    for inside in (d <= r, d < r - EDGE_MM, d <= r + EDGE_MM):
        field = np.zeros(h * w)
        np.maximum.at(field, flat, np.where(inside & inside_grid, a, 0.0).ravel())
        fields.append(field.reshape(h, w))
    return fields


def check_particles(scenario, f, keys, problems, notes):
    """Checks 1–4 of the particle state; returns each key frame's cover field."""
    scene = scenario["scene"]
    settings = particle_settings(scenario)
    capacity, lifetime, r = settings["capacity"], settings["lifetime"], settings["radius"]
    counts, ages = f["particles/accounting"][:], f["particles/age"][:]
    positions, velocities, covers = f["particles/position"][:], f["particles/velocity"][:], f["particles/cover"][:]
    step_of_id = emission_steps(settings, (max(keys) + 1) * settings["substeps"])
    panel = (scene["width_mm"], scene["height_mm"])
    bound_slack = float(np.spacing(np.float32(max(panel))))   # the bound is stored as a float32
    edge_pixels = 0
    for i, k in enumerate(keys):
        steps_done = (k + 1) * settings["substeps"]
        emitted, alive, expired, overwritten, age = replay(settings, step_of_id, steps_done)
        wanted = [emitted, int(alive.sum()), int(expired.sum()), int(overwritten.sum())]
        stored = [int(c) for c in counts[i]]
        if stored != wanted:
            problems.append(f"key frame {k}: accounting (emitted, alive, expired, overwritten) is {stored}, "
                            f"the schedule gives {wanted}")
        # 2. The slots: the newest id written into each slot decides what it holds.
        ids = np.arange(emitted)
        live_ids = ids[alive]
        if live_ids.size and not np.array_equal(live_ids, np.arange(emitted - live_ids.size, emitted)):
            problems.append(f"key frame {k}: the schedule's live ids are not the newest ones")
        slot_age = ages[i].astype(np.int64)
        live = slot_age < lifetime
        if live.sum() != stored[1]:
            problems.append(f"key frame {k}: {live.sum()} slots have an age below the lifetime of {lifetime} steps, "
                            f"the accounting says {stored[1]} alive")
        wanted_live = np.zeros(capacity, dtype=bool)
        wanted_live[live_ids % capacity] = True
        if not np.array_equal(live, wanted_live):
            wrong = np.flatnonzero(live != wanted_live)
            problems.append(f"key frame {k}: {wrong.size} slots live or dead against the schedule's live ids "
                            f"(first: slot {wrong[0]})")
        wanted_age = np.full(capacity, -1, dtype=np.int64)
        wanted_age[live_ids % capacity] = age[live_ids]
        off = wanted_live & (slot_age != wanted_age)
        if off.any():
            s = np.flatnonzero(off)[0]
            problems.append(f"key frame {k}: {off.sum()} live slots have the wrong age (slot {s}: "
                            f"{slot_age[s]}, emitted {wanted_age[s]} steps ago)")
        never = np.arange(capacity) >= emitted
        if (slot_age[never] != NEVER_USED).any() or positions[i][never].any() or velocities[i][never].any():
            problems.append(f"key frame {k}: a slot that never held a particle is not age 2^32-1 at rest at (0, 0)")
        # 3. Live centres inside the panel less a radius.
        p = positions[i][live].astype(np.float64)
        low, high = np.array([r, r]), np.array(panel) - r
        outside = ~np.isfinite(p).all(axis=1) | ((p < low - bound_slack) | (p > high + bound_slack)).any(axis=1)
        if outside.any():
            s = np.flatnonzero(live)[np.flatnonzero(outside)[0]]
            problems.append(f"key frame {k}: {outside.sum()} live particles lie outside the panel less a radius "
                            f"(slot {s} at {tuple(positions[i][s])})")
        # 4. The cover field, redrawn.
        exact, lowest, highest = expected_cover(settings, scene, positions[i][live], slot_age[live])
        cover = covers[i].astype(np.float64)
        differs = np.abs(cover - exact) > COVER_TOLERANCE
        on_edge = (lowest != highest)
        explained = differs & on_edge & (cover >= lowest - COVER_TOLERANCE) & (cover <= highest + COVER_TOLERANCE)
        unexplained = differs & ~explained
        uncovered_not_zero = (highest == 0.0) & (cover != 0.0)   # the blend tests cover > 0: no slack
        bad = unexplained | uncovered_not_zero
        if bad.any():
            j, x = np.argwhere(bad)[0]
            problems.append(f"key frame {k}: cover differs from the redrawn discs on {bad.sum()} pixels "
                            f"(first ({x}, {j}): {cover[j, x]:.9g}, expected {exact[j, x]:.9g})")
        edge_pixels += int(explained.sum())
    notes.append(f"{int(counts[-1][0])} emitted; cover redrawn, {edge_pixels} pixels differ on a disc edge")
    return covers


# ---- the scene -------------------------------------------------------------------------------

def check_frames(keys, frames, stains, covers, problems):
    """What the blend must have done. The tissue is not stored: where some key frame shows it
    uncovered its red is the tissue's, and where that frame is unstained too, its green and blue."""
    frames = frames.astype(int)
    uncovered = covers == 0.0
    if not (frames[..., 3] == frames[0, ..., 3]).all():
        problems.append("alpha changed between key frames; the blend passes it through")
    tissue = np.zeros(frames.shape[1:3] + (3,), dtype=int)
    known = np.zeros(frames.shape[1:3] + (3,), dtype=bool)
    for i in reversed(range(len(keys))):   # frame 0 last: the least stained wins
        clean = uncovered[i] & (stains[i] == 0.0)
        for c, where in ((0, uncovered[i]), (1, clean), (2, clean)):
            tissue[..., c][where] = frames[i, ..., c][where]
            known[..., c] |= where
    for i, k in enumerate(keys):
        now, cover, stain = frames[i], covers[i].astype(np.float64), stains[i].astype(np.float64)
        # No particle: red untouched, green and blue the tissue's less the stain.
        if (now[..., 0] != tissue[..., 0])[uncovered[i]].any():
            problems.append(f"key frame {k}: red changed where no particle covers; only the stain takes green and blue")
        for c in (1, 2):
            wanted = np.clip(tissue[..., c] - stain * 255.0, 0, 255)
            where = uncovered[i] & known[..., c]
            off = np.abs(now[..., c] - wanted)[where].max(initial=0)
            if off > BYTE_TOLERANCE:
                problems.append(f"key frame {k}: channel {c} is off the tissue minus the stain by {off}")
        # Fully covered: the blood colour, exactly.
        full = cover == 1.0
        if (now[..., :3][full] != BLOOD_BYTES).any():
            wrong = (now[..., :3] != BLOOD_BYTES).any(axis=-1) & full
            j, x = np.argwhere(wrong)[0]
            problems.append(f"key frame {k}: {wrong.sum()} fully covered pixels are not the blood colour "
                            f"{BLOOD_BYTES} (first ({x}, {j}): {tuple(now[j, x, :3])})")
        # Partly covered: between the blood byte and the uncovered byte, where that is known.
        part = (cover > 0.0) & (cover < 1.0)
        for c in range(3):
            where = part & known[..., c]
            if not where.any():
                continue
            below = tissue[..., c] / 255.0 - (stain if c else 0.0)
            bare = byte_half_up(below)
            blood = BLOOD_BYTES[c]
            lo = np.minimum(bare, blood) - BYTE_TOLERANCE
            hi = np.maximum(bare, blood) + BYTE_TOLERANCE
            mixed = byte_half_up(np.maximum(below, 0.0) * (1.0 - cover) + BLOOD[c] * cover)
            bad = where & ((now[..., c] < lo) | (now[..., c] > hi) | (np.abs(now[..., c] - mixed) > BYTE_TOLERANCE))
            if bad.any():
                j, x = np.argwhere(bad)[0]
                problems.append(f"key frame {k}: channel {c} of {bad.sum()} partly covered pixels is not the blood "
                                f"mixed in by the cover (first ({x}, {j}): {now[j, x, c]}, cover {cover[j, x]:.4g}, "
                                f"uncovered {int(bare[j, x])}, mixed {int(mixed[j, x])})")


def check_scene(root, golden, name):
    problems, notes = [], []
    scenario = tomllib.loads((root / "scenarios/golden" / f"{name}.toml").read_text())
    fps = scenario["scene"].get("frame_rate_hz", 30.0)
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
        has_spread, has_particles = "spread" in scenario, "particles" in scenario
        if has_spread != ("spread/stain" in f) or has_particles != ("particles/cover" in f):
            problems.append("the fields stored are not the effects the scenario calls for")
            return problems, notes
        stains = f["spread/stain"][:] if has_spread else np.zeros(frames.shape[:3], dtype=np.float32)
        covers = (check_particles(scenario, f, keys, problems, notes) if has_particles
                  else np.zeros(frames.shape[:3], dtype=np.float32))
    for i, k in enumerate(keys):
        t = (k + 1) / fps
        if abs(times[i] - t) > 1e-12:
            problems.append(f"key frame {k}: time {times[i]} s, expected {t} s")
        error = np.abs(stains[i] - expected_stain(scenario, t)).max() if has_spread else np.abs(stains[i]).max()
        if error > STAIN_TOLERANCE:
            problems.append(f"key frame {k}: stain differs from the report's formula by {error:.3g}")
    check_frames(keys, frames, stains, covers, problems)
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
    args = parser.parse_args()
    golden = args.golden_dir or args.root / "golden"
    scenes = sorted(p.name for p in golden.iterdir() if p.is_dir())
    failed = False
    for name in scenes:
        problems, notes = check_scene(args.root, golden, name)
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
