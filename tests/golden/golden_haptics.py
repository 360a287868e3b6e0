"""The independent check of a golden scene that replays a Falcon trace (docs/haptics.md).

From the scenario and the trace file alone (no bleedsim code), in float64: every haptic tick's
sample (the trace at t_first + n / 1000 s, interpolated), its panel point, contact, penetration,
force (spring plus damper along the normal, clamped to [0, cap]) and cutting, against the whole
channel stored in keyframes.h5; the force must rise on each contact and stay within the cap; and
the cuts the strokes lay (at once, then every cut_spacing_mm), which check_goldens.py then
checks the stain and the particles against, as if the scenario had listed them.
"""
import math

import numpy as np

from golden_mesh import check_mesh_channel

HAPTIC_RATE_HZ = 1000
POSITION_TOLERANCE_M = 1e-12   # the same formulas in the same order; float64 both sides
FORCE_TOLERANCE_N = 1e-9


def read_trace(path):
    """t, positions (N, 3) in m, buttons: the samples after the header line."""
    rows = []
    seen_header = False
    for line in path.read_text().splitlines():
        line = line.strip()
        if not line or line.startswith("#"):
            continue
        if not seen_header:
            seen_header = line.startswith("t_s,")
            continue
        rows.append([float(v) for v in line.split(",")[:5]])
    a = np.array(rows)
    return a[:, 0], a[:, 1:4], a[:, 4].astype(np.int64)


def replay_samples(t, xyz, buttons, ticks):
    """Tick n's sample: linear between the samples either side of t_first + n/1000, buttons from the
    one at or before, the last sample held after the end (written as the loader's a + w·(b − a))."""
    when = t[0] + np.arange(ticks) / HAPTIC_RATE_HZ
    after = np.searchsorted(t, when, side="right")
    before = after - 1
    inside = after < len(t)
    nxt = np.where(inside, after, before)
    w = np.where(inside, (when - t[before]) / np.where(inside, t[nxt] - t[before], 1.0), 0.0)
    position = xyz[before] + w[:, None] * (xyz[nxt] - xyz[before])
    return when - t[0], position, buttons[before]


def expected_channel(scenario, trace_path, ticks):
    s, h = scenario["scene"], scenario["haptics"]   # its defaults filled in by scenario_defaults.py
    origin = h["panel_origin_mm"]
    t, xyz, buttons = read_trace(trace_path)
    time, tool, held = replay_samples(t, xyz, buttons, ticks)
    panel = np.stack([origin[0] + h["scale"] * (1000.0 * tool[:, 0]),
                      origin[1] + h["scale"] * (-1000.0 * tool[:, 1])], axis=1)
    depth = h["surface_z_mm"] / 1000.0 - tool[:, 2]
    over = (panel[:, 0] >= 0) & (panel[:, 0] <= s["width_mm"]) & (panel[:, 1] >= 0) & (panel[:, 1] <= s["height_mm"])
    contact = (depth > 0) & over
    penetration = np.where(contact, depth, 0.0)
    speed = np.concatenate([[0.0], np.diff(tool[:, 2]) / (1.0 / HAPTIC_RATE_HZ)])
    push = h["stiffness_N_per_m"] * penetration - h["damping_Ns_per_m"] * speed
    force = np.where(contact, np.clip(push, 0.0, h["max_force_N"]), 0.0)
    cutting = contact & ((held & h["cut_button"]) != 0)
    return {"time": time, "tool_position": tool, "panel_position": panel, "buttons": held,
            "contact": contact, "penetration": penetration, "force": force, "cutting": cutting,
            "spacing": h["cut_spacing_mm"], "cap": h["max_force_N"]}


def cuts_along_strokes(channel):
    """A cut at a stroke's first cutting tick, then at each tick the tip is cut_spacing_mm or more
    from the last cut (on the panel); a tick without cutting ends the stroke."""
    cuts, last = [], None
    for n in np.flatnonzero(channel["cutting"] | np.roll(channel["cutting"], 1)):
        if not channel["cutting"][n]:
            last = None
            continue
        x, y = channel["panel_position"][n]
        if last is None or math.sqrt((x - last[0]) ** 2 + (y - last[1]) ** 2) >= channel["spacing"]:
            # Each stands for cut_spacing_mm of the stroke's wound, in the direction the stroke came
            # from its last cut (along x for its first).
            angle = math.atan2(y - last[1], x - last[0]) * 180.0 / math.pi if last is not None else 0.0
            last = (x, y)
            cuts.append({"x_mm": float(x), "y_mm": float(y), "start_s": float(n) / HAPTIC_RATE_HZ,
                         "wound_mm": channel["spacing"], "wound_angle_deg": angle})
    return cuts


def check_haptics(root, scenario, f, frames, problems, notes, mesh=None):
    """Checks /haptics in keyframes.h5 against the replay; returns the cuts the stylus made and the
    replayed channel (its ticks' time, panel position, contact and buttons). With a tissue `mesh`
    (golden_mesh.read_mesh) the contact is the mesh's (golden_mesh.check_mesh_channel)."""
    fps = scenario["scene"]["frame_rate_hz"]
    ticks = math.floor(frames * HAPTIC_RATE_HZ / fps) + 1   # ticks 0 .. the last frame's end
    trace_path = (root / "scenarios/golden" / scenario["haptics"]["trace"]).resolve()
    want = expected_channel(scenario, trace_path, ticks)
    if "haptics" not in f:
        problems.append("keyframes.h5 has no /haptics: the haptic channel is not pinned")
        return [], want
    got = {name: f["haptics"][name][()] for name in f["haptics"]}
    if got["time"].shape != (ticks,):
        problems.append(f"/haptics holds {got['time'].shape[0]} ticks, expected {ticks}")
        return [], want
    if not np.array_equal(got["time"], np.arange(ticks) / HAPTIC_RATE_HZ):
        problems.append("/haptics/time is not n / 1000 s")
    if mesh is not None:   # the stylus touches the mesh: its own checks, after the replayed samples'
        error = np.abs(got["tool_position"] - want["tool_position"]).max()
        if error > POSITION_TOLERANCE_M:
            problems.append(f"/haptics/tool_position differs from the replayed trace by {error:.3g}")
        if not np.array_equal(got["buttons"].astype(np.int64), want["buttons"].astype(np.int64)):
            problems.append("/haptics/buttons differ from the replayed trace")
        return check_mesh_channel(scenario, mesh, got, ticks, want["tool_position"], problems, notes)
    for name, tolerance in (("tool_position", POSITION_TOLERANCE_M), ("panel_position", 1e-9),
                            ("penetration", POSITION_TOLERANCE_M)):
        error = np.abs(got[name] - want[name]).max()
        if error > tolerance:
            problems.append(f"/haptics/{name} differs from the replayed trace by {error:.3g}")
    # Contact and cutting may only differ where the tip lies on the surface to rounding.
    borderline = np.abs(want["penetration"] - 0) < 1e-12
    for name in ("contact", "cutting", "buttons"):
        wrong = (got[name].astype(np.int64) != want[name].astype(np.int64)) & ~borderline
        if wrong.any():
            problems.append(f"/haptics/{name} differs at {wrong.sum()} ticks (first {np.flatnonzero(wrong)[0]})")
    force = got["force"]
    if np.abs(force[:, :2]).max() > 0:
        problems.append("/haptics/force has a component across the surface normal")
    error = np.abs(force[:, 2] - want["force"]).max()
    if error > FORCE_TOLERANCE_N:
        problems.append(f"/haptics/force differs from clamp(k·p − b·v, 0, cap) by {error:.3g} N")
    if force[:, 2].max() > want["cap"] or force[:, 2].min() < 0:
        problems.append(f"/haptics/force leaves [0, {want['cap']}] N")
    # The force rises on contact: 20 ms into each contact it is above its first tick's.
    onsets = np.flatnonzero(np.diff(got["contact"].astype(np.int64)) == 1) + 1
    falling = [int(n) for n in onsets if n + 20 < ticks and got["contact"][n + 20] and force[n + 20, 2] <= force[n, 2]]
    if len(onsets) == 0:
        problems.append("the stylus never touches the tissue")
    elif falling:
        problems.append(f"the force does not rise after contact at ticks {falling}")
    cuts = cuts_along_strokes(want)
    notes.append(f"haptics: {ticks} ticks replayed from {trace_path.name}, {len(onsets)} contacts, "
                 f"force up to {force[:, 2].max():.3f} N (cap {want['cap']} N), {len(cuts)} cuts")
    return cuts, want
