#!/usr/bin/env python3
"""An independent check that the golden key frames show the report's radial spread and particles.

The goldens pin the CPU reference's bytes; this recomputes what it can of every key frame from the
scenario file alone, in float64 with NumPy (no bleedsim code), and demands agreement to float32
rounding:

- the spread's stain (scenes with a [spread] table; the stain is 0 in a scene without one);
- for scenes with a [particles] table (docs/particles.md), the accounting (emitted, alive,
  expired, overwritten) replayed id by id from the emission schedule, the ring buffer and the
  lifetime; which ring slots hold the live particles and their ages; every live centre inside the
  panel less half a radius (a wall is a contact, its backstop half a radius past its line); rest
  (docs/particles.md#rest): every live particle within the rest distance
  of its anchor, at it when its count is 0, the count at most its age and the rest steps, and a
  sleeper (count at the rest steps) at exactly no speed;
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
- what the blend must do to the frame (docs/optics.md), from the tissue, the stain, the film it lays
  over the tissue (blur/thickness in a scene with [blur], splat/thickness otherwise) and the residue
  (trail/residue in a scene with [trail]): in linear light (IEC 61966-2-1), the tissue times
  exp(−2 · μ_c · depth), depth = film + stain · stain_depth_mm + residue, with μ_c whole blood's
  absorption at 650, 550 and 450 nm from haemoglobin's molar extinction (Prahl, after Gratzer and
  Kollias) at the scene's saturation; in a scene with [optics], lit by the headlight at the lens: its
  falloff (h² / (h² + ρ²))^(3/2) and the highlights, the tissue's sheen (n·v)^q and the blood's
  (n·v)^p less the flat plane's, n from the film's slope by central differences; back to bytes by
  rounding to the nearest code. The tissue is the scene's texture where it is as large as the panel
  (read with PIL), else where a key frame shows it bare (no blood, unlit); alpha passes through. The
  residue is at least its share of the film under it.

- for scenes with a [haptics] table (docs/haptics.md), the whole haptic channel replayed from the
  trace file (samples, contact, penetration, force, cutting), the force rising on contact and
  within the cap, and the cuts the strokes lay, which the checks above then use;
- for scenes with [vessels] and [pulse] (docs/bleeding.md), the emission schedule above from each
  wound's mean of the PNG map along it and the waveform's integral in closed form, particle by
  particle; with [suction] (the stylus its instrument), the five counts (emitted as scheduled; the
  ids' alive, expired and overwritten less what the suction took of each; all five adding up), the
  aspirated slots among the schedule's live ids, the suction within its quota ⌊k · flow · dt / V⌋
  over the sub-steps k it was on, and no residue within its reach of its path; with [contact], no
  live centre within the tip's body at a key frame that ends with the tip on the tissue.

- for scenes on a tissue mesh (docs/mesh.md), the surface maps recomputed from the OBJ file and the
  scenario's placement; the haptic channel against the mesh (the proxy on it with the tip behind it
  along the shading normal, force shading under the energy bound, the cuts spaced on the surface);
  the stain with distances on the surface; the particles on the surface, and the film by its reach
  and its volume on the surface (golden_mesh.py says what it leaves to the C++ tests).

The particles' checks (accounting, live slots, film) live in golden_film.py beside this file, the
blur's in golden_blur.py, the haptics' in golden_haptics.py, the mesh's in golden_mesh.py, the
vessels', pulse's and instrument's in golden_bleeding.py.

Run: /usr/bin/python3 tests/golden/check_goldens.py [repo root] [--golden-dir DIR]
(DIR defaults to <repo root>/golden; the scenarios are always <repo root>/scenarios/golden.)
"""
import argparse
import pathlib
import sys
import tomllib

import h5py
import numpy as np

from golden_bleeding import (check_contact, describe_wounds, suction_quota, suction_reach, sucking, vessel_map,
                             with_vessels)
from golden_blur import check_blur
from golden_film import check_particles, particle_settings, pixel_centres
from golden_haptics import check_haptics
from golden_mesh import check_maps, device_gravity, read_mesh, surface_maps
from scenario_defaults import defaults, fill_cut, load_params, read_scenario

STAIN_TOLERANCE = 2e-6   # float32 arithmetic in the reference, float64 here ...
STAIN_TOLERANCE_PER_CUT = 3e-7   # ... and each overlapping cut's factor adds a few float32 roundings
BYTE_TOLERANCE = 1       # the frame's bytes: one rounding step
OPTICAL_DEPTH_MAX = 32.0 # the transmission table's end: deeper reads exp(−32)
EXTINCTION = ((368.0, 3750.12), (43016.0, 53412.0), (62816.0, 103292.0))  # cm⁻¹/M, (HbO2, Hb) at 650, 550, 450 nm
HAEMOGLOBIN_G_PER_MOLE = 64500.0


def srgb_to_linear(byte):
    c = np.asarray(byte, dtype=np.float64) / 255.0
    return np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)


def linear_to_byte(v):
    """Linear light to the nearest sRGB code, as the blend rounds."""
    v = np.clip(np.asarray(v, dtype=np.float64), 0.0, 1.0)
    return np.floor(np.where(v <= 0.0031308, 12.92 * v, 1.055 * v ** (1 / 2.4) - 0.055) * 255.0 + 0.5)


def absorption_per_mm(optics):
    s, c = optics["oxygen_saturation"], optics["haemoglobin_g_per_l"] / HAEMOGLOBIN_G_PER_MOLE
    return [2.303 * (s * o + (1 - s) * d) * c / 10.0 for o, d in EXTINCTION]


def lit_terms(scene, optics, film):
    """(highlight, irradiance) per pixel for the headlight at the lens."""
    x, y = pixel_centres(scene)
    xx, yy = np.meshgrid(x, y)
    pitch_x, pitch_y = scene["width_mm"] / scene["width_px"], scene["height_mm"] / scene["height_px"]
    padded = np.pad(film.astype(np.float64), 1, mode="edge")
    slope_x = (padded[1:-1, 2:] - padded[1:-1, :-2]) / (2 * pitch_x)
    slope_y = (padded[2:, 1:-1] - padded[:-2, 1:-1]) / (2 * pitch_y)
    cx = scene["width_mm"] / 2 + optics["camera_mm"][0]
    cy = scene["height_mm"] / 2 + optics["camera_mm"][1]
    h = optics["camera_height_mm"]
    vx, vy, vz = cx - xx, cy - yy, h - film
    v = np.sqrt(vx * vx + vy * vy + vz * vz)
    upright = vz / v
    facing = (vz - slope_x * vx - slope_y * vy) / v / np.sqrt(slope_x ** 2 + slope_y ** 2 + 1)
    relief = np.where(facing > 0, np.maximum(facing, 0) ** optics["shininess"] - upright ** optics["shininess"], 0)
    highlight = optics["sheen"] * upright ** optics["sheen_shininess"] + optics["specular"] * np.maximum(relief, 0)
    rho2 = (xx - cx) ** 2 + (yy - cy) ** 2
    irradiance = (h * h / (h * h + rho2)) ** 1.5 if optics["falloff"] else np.ones_like(rho2)
    return highlight, irradiance


def scene_tissue(root, scenario):
    """The tissue's RGBA bytes where the scene's texture is as large as the panel, else None."""
    texture = scenario.get("tissue", {}).get("texture")
    if not texture:
        return None
    from PIL import Image
    image = np.asarray(Image.open(root / "scenarios/golden" / texture).convert("RGBA")).astype(int)
    scene = scenario["scene"]
    return image if image.shape[:2] == (scene["height_px"], scene["width_px"]) else None


def expected_stain(scenario, t, frame=None):
    """The report's stains combined; on a mesh, distances on the surface through each pixel's frame
    (a, b, c): (a·dx + b·dy, c·dy)."""
    scene = scenario["scene"]
    x, y = pixel_centres(scene)
    xx, yy = np.meshgrid(x, y)
    light_left = np.ones((scene["height_px"], scene["width_px"]))
    for cut in scenario["cut"]:
        r, growth = cut["radius_mm"], cut["growth_per_s"]
        amplitude = np.clip((t - cut["start_s"]) * growth, 0.0, 1.0)
        dx, dy = xx - cut["x_mm"], yy - cut["y_mm"]
        if frame is not None:
            dx, dy = frame[..., 0] * dx + frame[..., 1] * dy, frame[..., 2] * dy
        d = np.hypot(dx, dy)
        final = np.where(d < r, ((r - d) / r) ** 6, 0.0)   # the report's profile
        light_left *= 1.0 - amplitude * final
    return 1.0 - light_left


# ---- particles -------------------------------------------------------------------------------

def check_frames(keys, frames, depths, films, tissue, optics, lit, scene, problems, notes):
    """What the blend must have drawn: each key frame recomputed from the tissue and the blood over it
    (depths: film + stain · stain_depth_mm + residue; films: the film the blend lays over the tissue)."""
    frames = frames.astype(int)
    if not (frames[..., 3] == frames[0, ..., 3]).all():
        problems.append("alpha changed between key frames; the blend passes it through")
    known = np.ones(frames.shape[1:3], dtype=bool)
    if tissue is None:
        if lit:
            problems.append("a scene with [optics] needs a texture as large as the panel for its frames to be checked")
            return
        # Unlit, a pixel with no blood over it shows the tissue's bytes exactly (sRGB's round trip).
        tissue = np.zeros(frames.shape[1:3] + (4,), dtype=int)
        known[:] = False
        for i in range(len(keys)):
            bare = depths[i] == 0.0
            tissue[bare] = frames[i][bare]
            known |= bare
    mu = absorption_per_mm(optics)
    checked = 0
    for i, k in enumerate(keys):
        light = srgb_to_linear(tissue[..., :3])
        depth = depths[i].astype(np.float64)
        for c in range(3):
            light[..., c] *= np.exp(-np.minimum(2 * mu[c] * depth, OPTICAL_DEPTH_MAX))
        if lit:
            highlight, irradiance = lit_terms(scene, optics, films[i])
            light = (light + highlight[..., None]) * irradiance[..., None]
        wanted = linear_to_byte(light)
        bad = known[..., None] & (np.abs(frames[i, ..., :3] - wanted) > BYTE_TOLERANCE)
        checked += 3 * int(known.sum())
        if bad.any():
            j, x, c = np.argwhere(bad)[0]
            problems.append(f"key frame {k}: {bad.sum()} pixel channels are not the blood's light over the tissue "
                            f"(first ({x}, {j}) channel {c}: {frames[i, j, x, c]}, depth {depth[j, x]:.4g} mm, "
                            f"tissue {tissue[j, x, c]}, expected {int(wanted[j, x, c])})")
        if (frames[i, ..., 3] != tissue[..., 3])[known].any():
            problems.append(f"key frame {k}: alpha is not the tissue's")
    notes.append(f"frame: {checked} pixel channels recomputed{' (lit)' if lit else ''}, "
                 f"{int((~known).sum())} pixels with the tissue unknown")


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
        channel = mesh = frame = None
        if scenario["tissue"]["mesh"]:   # the texture on a mesh: its maps from the OBJ
            mesh = read_mesh(root, scenario)
            frames_of, tangential, surely, maybe = surface_maps(mesh, scenario["scene"],
                                                                device_gravity(scenario, defaults(params, "particles")))
            if "surface/frame" not in f or "surface/gravity" not in f:
                problems.append("a mesh scene's keyframes.h5 has no surface/frame and surface/gravity")
                return problems, notes
            check_maps(f, frames_of, tangential, surely, maybe, problems, notes)
            frame = f["surface/frame"][0].astype(np.float64)   # as checked: the pixels' frames the stages read
        if "haptics" in scenario:   # the stylus' cuts follow the scripted ones, as in the run
            cuts, channel = check_haptics(root, scenario, f, expected_frames, problems, notes, mesh)
            scenario["cut"] += [fill_cut(cut, scenario, params) for cut in cuts]
        try:
            density = vessel_map(root, scenario)
        except ValueError as e:
            problems.append(str(e))
            return problems, notes
        scenario["cut"] = [with_vessels(scenario, density, cut) for cut in scenario["cut"]]
        if density is not None:
            notes.append(describe_wounds(scenario["cut"]))
        quota = None
        if "suction" in scenario:
            if channel is None:
                problems.append("a golden scene with [suction] must replay a trace: its stylus is the instrument")
                return problems, notes
            channel["sucking"] = sucking(scenario, channel)
            settings = particle_settings(scenario)
            quota = suction_quota(scenario, channel, settings["steps_per_s"], (max(keys) + 1) * settings["substeps"])
        has_spread, has_particles = "spread" in scenario, "particles" in scenario
        has_blur = has_particles and "blur" in scenario   # the parser refuses [blur] without [particles]
        has_trail = has_particles and "trail" in scenario
        wanted_fields = ((["surface/frame", "surface/gravity"] if mesh is not None else []) +
                         (["spread/stain"] if has_spread else []) +
                         (["particles/position", "particles/velocity", "particles/age", "particles/rest",
                           "particles/anchor", "particles/accounting", "splat/thickness"] if has_particles else []) +
                         (["blur/thickness"] if has_blur else []) + (["trail/residue"] if has_trail else []) +
                         ["frame"])
        stored_fields = f.attrs["fields"].split()
        if sorted(stored_fields) != sorted(wanted_fields) or not all(name in f for name in wanted_fields):
            problems.append(f"the fields stored ({' '.join(stored_fields)}) are not the ones the scenario's "
                            f"effects make ({' '.join(wanted_fields)})")
            return problems, notes
        stains = f["spread/stain"][:] if has_spread else np.zeros(frames.shape[:3], dtype=np.float32)
        splats = (check_particles(scenario, f, keys, problems, notes, quota, frame) if has_particles
                  else np.zeros(frames.shape[:3], dtype=np.float32))
        if "contact" in scenario and channel is not None:
            check_contact(scenario, channel, keys, f["particles/position"][:], f["particles/age"][:],
                          particle_settings(scenario)["lifetime"], problems, notes)
        films = check_blur(scenario, f, keys, splats, problems, notes) if has_blur else splats
        residues = f["trail/residue"][:] if has_trail else np.zeros(frames.shape[:3], dtype=np.float32)
    if has_trail:   # what a pixel keeps is at least its share of the film over it now, but where the suction dried it
        dried = np.zeros(residues.shape, dtype=bool)
        if quota is not None:
            x, y = pixel_centres(scenario["scene"])
            xx, yy = np.meshgrid(x, y)
            for i, k in enumerate(keys):
                surely, maybe = suction_reach(scenario, channel, k, xx, yy)
                dried[i] = maybe
                if (residues[i][surely] != 0).any():
                    problems.append(f"key frame {k}: {(residues[i][surely] != 0).sum()} of the {surely.sum()} pixels "
                                    f"within the suction's reach of its path keep a residue")
            notes.append(f"trail: {dried.sum()} key-frame pixels near the suction's path")
        short = (residues < np.float32(scenario["trail"]["residue"]) * splats * (1 - 1e-6)) & ~dried
        if short.any():
            problems.append(f"{short.sum()} pixels' residue is below trail.residue times the film over them")
    for i, k in enumerate(keys):
        t = (k + 1) / fps
        if abs(times[i] - t) > 1e-12:
            problems.append(f"key frame {k}: time {times[i]} s, expected {t} s")
        error = np.abs(stains[i] - expected_stain(scenario, t, frame)).max() if has_spread else np.abs(stains[i]).max()
        if error > STAIN_TOLERANCE + STAIN_TOLERANCE_PER_CUT * len(scenario["cut"]):
            problems.append(f"key frame {k}: stain differs from the report's formula by {error:.3g}")
    optics = scenario.get("optics") or defaults(params, "optics")
    depths = films.astype(np.float64) + stains * optics["stain_depth_mm"] + residues
    check_frames(keys, frames, depths, films, scene_tissue(root, scenario), optics, "optics" in scenario,
                 scenario["scene"], problems, notes)
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
