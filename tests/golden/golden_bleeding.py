"""Where and how hard wounds bleed, and what the instrument does, for the independent golden check
(check_goldens.py; docs/bleeding.md), from the scenario and its files alone, in float64:

- [vessels]: each wound's mean of the PNG map along it (bilinear between pixel centres, the
  midpoint rule over steps of at most a quarter pixel), which scales its flow and, with [pulse],
  makes it arterial at arterial_density;
- [pulse]: the blood an arterial wound has given by t, the waveform's integral in closed form;
- [suction]: when the stylus sucks (the replayed haptic channel: in contact, a suction button held),
  the quota that bounds what it may have taken, and the path along which it dried the trail;
- [contact]: where the tip was at a key frame's end, which no live particle's centre may lie within.

The same formulas as the program's, in the same order and in the same precision (double), so the
emission schedule that golden_film.py replays from them agrees particle by particle.
"""
import math

import numpy as np

from golden_haptics import HAPTIC_RATE_HZ

REACH_BAND_MM = 1e-4   # a pixel centre this close to the suction's reach may fall either side in float32


# ---- vessels -----------------------------------------------------------------------------------

def vessel_map(root, scenario):
    """The [vessels] map as the program holds it (float32(byte) / 255 per pixel), or None. Only a PNG
    as large as the panel can be checked here (the procedural map is the program's own drawing)."""
    if "vessels" not in scenario:
        return None
    name = scenario["vessels"]["map"]
    if name == "procedural":
        raise ValueError("[vessels] map = \"procedural\": the check needs a PNG map as large as the panel")
    from PIL import Image
    image = np.asarray(Image.open(root / "scenarios/golden" / name).convert("RGBA"))[..., 0]
    scene = scenario["scene"]
    if image.shape != (scene["height_px"], scene["width_px"]):
        raise ValueError(f"[vessels] map {name} is {image.shape[1]} x {image.shape[0]}, not the panel's size")
    return (image.astype(np.float32) / np.float32(255.0)).astype(np.float64)


def density_at(scene, density, x, y):
    """The map at (x, y) mm (arrays), bilinearly between pixel centres, held flat beyond them."""
    w, h = scene["width_px"], scene["height_px"]
    u = np.clip(x * w / scene["width_mm"] - 0.5, 0.0, w - 1.0)
    v = np.clip(y * h / scene["height_mm"] - 0.5, 0.0, h - 1.0)
    i = np.maximum(0, np.minimum(u.astype(np.int64), w - 2))
    j = np.maximum(0, np.minimum(v.astype(np.int64), h - 2))
    i1, j1 = np.minimum(i + 1, w - 1), np.minimum(j + 1, h - 1)
    fx, fy = u - i, v - j
    return ((1 - fy) * ((1 - fx) * density[j, i] + fx * density[j, i1]) +
            fy * ((1 - fx) * density[j1, i] + fx * density[j1, i1]))


def mean_density(scene, density, x0, y0, x1, y1):
    """The midpoint rule along the segment, steps of at most a quarter pixel, summed in order."""
    pixel_mm = min(scene["width_mm"] / scene["width_px"], scene["height_mm"] / scene["height_px"])
    steps = max(1, math.ceil(4.0 * math.hypot(x1 - x0, y1 - y0) / pixel_mm))
    s = (np.arange(steps) + 0.5) / steps
    values = density_at(scene, density, x0 + s * (x1 - x0), y0 + s * (y1 - y0))
    return float(np.cumsum(values)[-1]) / steps


def with_vessels(scenario, density, cut):
    """The cut with its wound's mean density, arterial where the map makes it so."""
    if density is None:
        return {**cut, "vessel_density": 1.0}
    half, a = cut["wound_mm"] / 2.0, cut["wound_angle_deg"] * (math.pi / 180.0)
    dx, dy = half * math.cos(a), half * math.sin(a)
    rho = mean_density(scenario["scene"], density, cut["x_mm"] - dx, cut["y_mm"] - dy,
                       cut["x_mm"] + dx, cut["y_mm"] + dy)
    arterial = cut["arterial"] or ("pulse" in scenario and rho >= scenario["pulse"]["arterial_density"])
    return {**cut, "vessel_density": rho, "arterial": arterial}


def describe_wounds(cuts):
    """Each cut's mean vessel density, arterial ones marked."""
    return "wounds' mean vessel density " + ", ".join(f"{c['vessel_density']:.3f}{' (arterial)' if c['arterial'] else ''}"
                                                     for c in cuts)


# ---- pulse -------------------------------------------------------------------------------------

def damped_sine_integral(k, omega, phase, s):
    """∫₀ˢ e^(−ku) sin(ωu + φ) du in closed form (docs/bleeding.md, "Pulse")."""
    end = omega * s + phase
    return ((k * math.sin(phase) + omega * math.cos(phase) - math.exp(-k * s) * (k * math.sin(end) + omega * math.cos(end)))
            / (k * k + omega * omega))


def pulsed_flowing_s(pulse, opened_s, bleeding_s, clot_s):
    """The waveform w(t) = 1 + a₁ sin(ωt) + a₂ sin(2ωt), damped by clotting, integrated over the
    bleeding so far: seconds of the wound's mean flow."""
    k, omega = (1.0 / clot_s if clot_s > 0 else 0.0), 2 * math.pi * pulse["heart_rate_per_min"] / 60.0
    steady = clot_s * -math.expm1(-bleeding_s / clot_s) if clot_s > 0 else bleeding_s
    return (steady + pulse["systolic"] * damped_sine_integral(k, omega, omega * opened_s, bleeding_s) +
            pulse["dicrotic"] * damped_sine_integral(k, 2.0 * omega, 2.0 * omega * opened_s, bleeding_s))


def blood_given_mm3(cut, t, pulse):
    """The blood a cut has given by each time in t (mm³): wound · density · flow · the seconds it
    has flowed (steady, clotting, or beating)."""
    bleeding = np.clip(t - cut["start_s"], 0.0, cut["bleed_s"])
    clot = cut["clot_s"]
    if cut["arterial"] and pulse is not None:
        flowing = np.array([pulsed_flowing_s(pulse, cut["start_s"], float(s), clot) for s in bleeding])
    else:
        flowing = clot * -np.expm1(-bleeding / clot) if clot > 0 else bleeding
    return cut["wound_mm"] * cut["vessel_density"] * cut["flow_mm3_per_s_per_mm"] * flowing


# ---- the instrument ----------------------------------------------------------------------------

def stylus_at(channel, t, frame, fps):
    """The stylus' sample at each time t in frame `frame`, as the program's tool_at reads the tick
    samples it has then (a frame replays the ticks through its end first, n ≤ (k + 1) · 1000 / fps):
    on the line between the ticks around t, with the flags of the tick at or before; the last held."""
    ticks = np.arange(channel["time"].size) / HAPTIC_RATE_HZ
    known = np.floor((np.asarray(frame) + 1) * HAPTIC_RATE_HZ / fps).astype(np.int64)   # the last tick known
    before = np.minimum(np.searchsorted(ticks, t, side="right") - 1, known)
    after = np.minimum(before + 1, known)
    share = (t - ticks[before]) / np.where(after > before, ticks[after] - ticks[before], 1.0) * (after > before)
    p = channel["panel_position"]
    position = p[before] + share[:, None] * (p[after] - p[before])
    return position, channel["contact"][before], channel["sucking"][before]


def sucking(scenario, channel):
    """Per tick: the stylus in contact with a suction button held."""
    buttons = scenario["suction"]["buttons"]
    return channel["contact"] & ((channel["buttons"] & buttons) != 0)


def suction_quota(scenario, channel, steps_per_s, steps):
    """The most the suction may have taken by the end of each step: ⌊k · flow · dt / V⌋, k the steps
    so far that ended with it on."""
    fps = scenario["scene"]["frame_rate_hz"]
    frame = np.arange(steps) // round(steps_per_s / fps)
    on = stylus_at(channel, (np.arange(steps) + 1) / steps_per_s, frame, fps)[2]
    per_step = scenario["suction"]["max_flow_mm3_per_s"] / steps_per_s / scenario["particles"]["particle_volume_mm3"]
    return np.floor(np.cumsum(on) * per_step).astype(np.int64)


def suction_reach(scenario, channel, frame, pixel_x, pixel_y):
    """Pixels surely within the suction's reach of its path over a frame, and pixels that may be:
    the path is the polyline through the tip at the frame's start, at each tick inside it and at its
    end; a segment counts where the suction was on at both its ends."""
    fps = scenario["scene"]["frame_rate_hz"]
    t0, t1 = frame / fps, (frame + 1) / fps
    inside = np.arange(channel["time"].size) / HAPTIC_RATE_HZ
    times = np.concatenate([[t0], inside[(inside > t0) & (inside < t1)], [t1]])
    position, _, on = stylus_at(channel, times, frame, fps)
    radius = scenario["suction"]["radius_mm"]
    distance = np.full(pixel_x.shape, np.inf)
    for a, b in zip(np.flatnonzero(on[:-1] & on[1:]), np.flatnonzero(on[:-1] & on[1:]) + 1):
        u = position[b] - position[a]
        u2 = float(u @ u)
        along = np.clip(((pixel_x - position[a, 0]) * u[0] + (pixel_y - position[a, 1]) * u[1]) / u2, 0, 1) \
            if u2 > 0 else 0.0
        distance = np.minimum(distance, np.hypot(pixel_x - position[a, 0] - along * u[0],
                                                 pixel_y - position[a, 1] - along * u[1]))
    return distance < radius - REACH_BAND_MM, distance <= radius + REACH_BAND_MM


def check_contact(scenario, channel, keys, positions, ages, lifetime, problems, notes):
    """At each key frame whose end finds the tip on the tissue (where the frame's last sub-step
    ended), no live particle's centre lies within the tip's body: its radius and a particle's."""
    body = scenario["contact"]["tip_radius_mm"] + scenario["particles"]["diameter_mm"] / 2.0
    ends = (np.array(keys) + 1) / scenario["scene"]["frame_rate_hz"]
    tips, touching, _ = stylus_at(channel, ends, np.array(keys), scenario["scene"]["frame_rate_hz"])
    nearest = []
    for i, k in enumerate(keys):
        if not touching[i]:
            continue
        live = positions[i][ages[i].astype(np.int64) < lifetime].astype(np.float64)
        d = np.hypot(live[:, 0] - tips[i, 0], live[:, 1] - tips[i, 1])
        inside = d < body - REACH_BAND_MM
        if inside.any():
            problems.append(f"key frame {k}: {inside.sum()} live particles' centres lie inside the tip's body "
                            f"({body} mm about ({tips[i, 0]:.4f}, {tips[i, 1]:.4f}); nearest at {d.min():.6f} mm)")
        nearest.append(f"{d.min() if d.size else math.inf:.4f}")
    notes.append(f"contact: the tip on the tissue at {len(nearest)} key frames, the nearest live centre at "
                 f"{', '.join(nearest) or '-'} mm (its body {body} mm)")
