"""The particles' part of the independent golden check (check_goldens.py): the accounting, the
live slots and the film of blood, recomputed from the scenario file and the key frames'
particle state in float64 with NumPy (no bleedsim code). See check_goldens.py for what each check
demands.
"""
import math

import numpy as np

from golden_bleeding import blood_given_mm3
from golden_rest import check_rest
from scenario_defaults import particle_substeps

EDGE_MM = 1e-5           # a pixel centre this close to a splat's edge may fall either side in float32
NEVER_USED = 0xFFFFFFFF  # the age of a ring slot that never held a particle
ASPIRATED = 0x80000000   # the age's top bit: the suction took the particle (core/physics/particles.h)
FLOAT32_UNIT = 2.0 ** -24       # float32's unit roundoff: one rounding is off by at most this, relatively

# The film (core/physics/splat.h, docs/particles.md#the-film-of-blood): a live particle's blood as
# film over one pixel, T = V · fade / (pixel area · 2⁻²⁴ mm), in whole units of 2⁻²⁴ mm (rounded
# half up from float32, at most 1e9), is shared among the pixels whose centres its splat reaches, in
# proportion to their weights w = (1 − d²/R²)² (each in whole units of 2⁻²³), each share rounded
# half up; a splat whose weights all round to 0 puts all of T into the pixel holding its centre.
SPLAT_UNIT_MM = 2.0 ** -24
SPLAT_MAX_UNITS = 1.0e9
WEIGHT_UNIT = 2.0 ** -23
# float32's roundings of T: V, the fade's two conversions and its division, the units per mm³ and
# two products; 7 of 2⁻²⁴, 8 allowed for the second-order terms.
BLOOD_RELATIVE = 8 * FLOAT32_UNIT
# float32's roundings of a weight q², q = 1 − t, t = d²/R²: the two differences, their squares and
# sum, R² and the division put t within 6u·t of itself; 1 − t adds u·q, so q is within 7u; the
# square is then within 2q·7u + (7u)² + u·q²: 16u·q + (8u)² allowed.
WEIGHT_ROUNDINGS = 16 * FLOAT32_UNIT
WEIGHT_FLOOR = (8 * FLOAT32_UNIT) ** 2
# Where the reference puts a pixel's centre: (i + 0.5) · float32(mm per pixel), in float32, off
# the exact centre by up to 2⁻²³ of the coordinate; so d by up to (width + height) · 2⁻²³ mm.
PIXEL_CENTRE_RELATIVE = 2.0 ** -23


def pixel_centres(scene):
    w, h = scene["width_px"], scene["height_px"]
    x = (np.arange(w) + 0.5) * (scene["width_mm"] / w)
    y = (np.arange(h) + 0.5) * (scene["height_mm"] / h)
    return x, y


def steps_in(seconds, steps_per_s):
    """Whole steps in a span (rounded half up, at least one): the model's lifetime and fade."""
    return max(1, math.floor(seconds * steps_per_s + 0.5))


def particle_settings(scenario):
    """The [particles] table's settings (its defaults filled in by scenario_defaults.py)."""
    p = scenario["particles"]
    substeps = particle_substeps(scenario)
    steps_per_s = scenario["scene"]["frame_rate_hz"] * substeps
    lifetime = steps_in(p["lifetime_s"], steps_per_s)
    diameter = p["diameter_mm"]
    rest_steps = steps_in(min(p["rest_s"], p["lifetime_s"]), steps_per_s) if p["rest_s"] > 0 else 0
    return {
        "capacity": p["capacity"],
        "radius": diameter / 2.0,
        "splat_radius": p["splat_radius_mm"] or diameter,   # 0: the diameter
        "volume": p["particle_volume_mm3"],
        "substeps": substeps,
        "steps_per_s": steps_per_s,
        "lifetime": lifetime,
        "fade": min(lifetime, steps_in(p["fade_s"], steps_per_s)),
        "rest_steps": rest_steps,
        "rest_distance": p["rest_speed_mm_s"] * p["rest_s"],
        "film_depth": p.get("film_depth", False),
        "join_steps": steps_in(0.25, steps_per_s),   # kFilmJoinS, core/effects/particles/particle_params.h
        "cuts": scenario["cut"],   # each with its vessel density (golden_bleeding.with_vessels)
        "pulse": scenario.get("pulse"),
    }


def emission_steps(settings, steps):
    """The step each particle id was emitted in, for the first `steps` steps.

    A cut has emitted floor(blood given so far / V) particles by time t, the blood being its
    wound's flow (mm³/s) over the time bled so far s, or clot·(1 − e^(−s/clot)) of it as it clots,
    or the beating waveform's integral (golden_bleeding.blood_given_mm3); step n runs from n/sps to
    (n+1)/sps and emits the difference. Ids count emissions in step order
    (and cut order within a step, which does not matter here: a step's particles share their step)."""
    t = np.arange(steps + 1) / settings["steps_per_s"]
    per_step = np.zeros(steps, dtype=np.int64)
    for cut in settings["cuts"]:
        by = np.floor(blood_given_mm3(cut, t, settings["pulse"]) / settings["volume"]).astype(np.int64)
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


def check_aspirated_counts(k, stored, by_id, quota, problems):
    """With [suction]: emitted as the schedule gives it, and each particle in one state, as the ids
    have them (alive, expired, overwritten) less what the suction took of each; the suction within
    its quota."""
    emitted, alive, expired, overwritten, aspirated = stored
    if emitted != by_id[0] or alive + expired + overwritten + aspirated != emitted:
        problems.append(f"key frame {k}: accounting (emitted, alive, expired, overwritten, aspirated) is {stored}: "
                        f"the schedule emits {by_id[0]}, and the five must add up")
    if alive > by_id[1] or expired > by_id[2] or overwritten > by_id[3]:
        problems.append(f"key frame {k}: accounting {stored[1:4]} exceeds the ids' own {by_id[1:]}: the suction "
                        f"only takes from them")
    if aspirated > quota:
        problems.append(f"key frame {k}: {aspirated} aspirated, past the suction's quota of {quota}")


# ---- the film of blood -----------------------------------------------------------------------

def centre_error_mm(scene):
    """How far the reference's float32 pixel centres may put d from the exact one."""
    return (scene["width_mm"] + scene["height_mm"]) * PIXEL_CENTRE_RELATIVE


def edge_band_mm(scene):
    """A pixel centre this close to a splat's edge may fall either side of it in float32."""
    return max(EDGE_MM, centre_error_mm(scene))


def splat_pairs(scene, r, x, y):
    """Every (particle, pixel) pair whose pixel centre lies closer than R + the edge band to the
    particle, on the panel: the particle (an index into x, y), the pixel (a flat index) and the
    distance d."""
    w, h = scene["width_px"], scene["height_px"]
    px, py = scene["width_mm"] / w, scene["height_mm"] / h
    cx, cy = pixel_centres(scene)
    reach = r + edge_band_mm(scene)
    k = int(math.ceil(reach / min(px, py))) + 1
    offsets = np.arange(-k, k + 1)
    ii = np.floor(x / px).astype(np.int64)[:, None, None] + offsets[None, None, :]
    jj = np.floor(y / py).astype(np.int64)[:, None, None] + offsets[None, :, None]
    ii, jj = np.broadcast_arrays(ii, jj)
    d = np.hypot(cx[np.clip(ii, 0, w - 1)] - x[:, None, None], cy[np.clip(jj, 0, h - 1)] - y[:, None, None])
    near = (ii >= 0) & (ii < w) & (jj >= 0) & (jj < h) & (d < reach)
    particle = np.broadcast_to(np.arange(x.size)[:, None, None], d.shape)[near]
    return particle, (jj * w + ii)[near], d[near]


def holding_pixels(scene, x, y):
    """The pixel holding each centre (clamped to the panel), and four candidates per particle for
    the reference's: its float32 x / (mm per pixel) is within 2 · 2⁻²⁴ of the exact quotient (the
    float32 pixel size, the division), under width · 2⁻²³ pixels, so a centre within twice that of
    a pixel edge may fall either side. Returns the pixel, the candidates (particles × 4, each
    listed once, the rest -1) and whether there is more than one."""
    w, h = scene["width_px"], scene["height_px"]
    fx, fy = x / (scene["width_mm"] / w), y / (scene["height_mm"] / h)
    mx, my = 4 * FLOAT32_UNIT * w, 4 * FLOAT32_UNIT * h

    def column(v, n):
        return np.clip(np.floor(v), 0, n - 1).astype(np.int64)
    i, j = [column(fx - mx, w), column(fx + mx, w)], [column(fy - my, h), column(fy + my, h)]
    candidates = np.stack([j[b] * w + i[a] for a in (0, 1) for b in (0, 1)], axis=1)
    for c in range(1, 4):
        repeated = (candidates[:, c, None] == candidates[:, :c]).any(axis=1)
        candidates[repeated, c] = -1
    return column(fy, h) * w + column(fx, w), candidates, (candidates[:, 1:] >= 0).any(axis=1)


def expected_thickness(settings, scene, position, age):
    """The film recomputed from the live particles, in film units (2⁻²⁴ mm), as H × W fields:

    exact    each particle's T = V · fade / (pixel area · 2⁻²⁴ mm) shared as T · w / S among the
             pixels whose centres it reaches (d < R), S = Σ w; where it reaches none, all of T in
             the pixel holding its centre; in float64;
    allowed  what the reference's may differ by, summed over the particles: its T (half a unit and
             float32's roundings), its weights (a weight unit, float32's roundings, the slope times
             how far its float32 pixel centres lie from the exact ones, near R the band's weight)
             and so its S, each share bounded between the extremes of T · w / S these allow, and
             half a unit for the share's rounding; then float32's 2⁻²⁴ of the pixel's sum when it
             is converted to mm. A particle whose weights may all round to 0 or not (S is within
             their error of 0) may land either way: its whole T is allowed at every pixel it may
             reach, and a centre within float32's reach of a pixel edge may fall either side;
    reach    where any particle may put blood: elsewhere the film is exactly 0.

    Also per particle: how many pixels it may share its blood among (each share's rounding, for the
    volume), its T's error, and how many particles shared, fell back, or may have done either."""
    w_px, h_px = scene["width_px"], scene["height_px"]
    pixel_area = scene["width_mm"] / w_px * scene["height_mm"] / h_px
    r, band, delta = settings["splat_radius"], edge_band_mm(scene), centre_error_mm(scene)
    x, y = position[:, 0].astype(np.float64), position[:, 1].astype(np.float64)
    finite = np.isfinite(x) & np.isfinite(y)   # a non-finite centre is check 3's to report
    x, y, age = x[finite], y[finite], age[finite]
    fade = np.minimum(1.0, (settings["lifetime"] - age.astype(np.float64)) / settings["fade"])
    blood = np.minimum(settings["volume"] * fade / (pixel_area * SPLAT_UNIT_MM), SPLAT_MAX_UNITS)
    blood_error = 0.5 + BLOOD_RELATIVE * blood

    # The weights, their sums and how far the reference's may lie from them.
    particle, pixel, d = splat_pairs(scene, r, x, y)
    q = np.maximum(1.0 - (d / r) ** 2, 0.0)
    weight = np.where(d < r, q * q, 0.0)
    band_q = max(0.0, 1.0 - ((r - band) / r) ** 2)
    float_error = (WEIGHT_ROUNDINGS * q + WEIGHT_FLOOR + 4.0 * q * d / (r * r) * delta +
                   np.where(np.abs(d - r) <= band, band_q * band_q, 0.0))
    weight_error = float_error + WEIGHT_UNIT   # its whole units: half of one, a hair more below one
    count = x.size
    pairs = np.bincount(particle, minlength=count)
    total = np.bincount(particle, weight, minlength=count)
    total_error = np.bincount(particle, weight_error, minlength=count)
    shares = total - total_error > 0.0   # the reference's S is surely at least a unit
    surely_zero = (weight + float_error) < 0.49 * WEIGHT_UNIT   # 2²³ · w + ½ stays below 1
    falls_back = np.bincount(particle, ~surely_zero, minlength=count) == 0
    either = ~shares & ~falls_back

    # Shares: T · w / (w + the rest of S), between the extremes its three parts' ranges allow (it
    # grows with T and w, shrinks with the rest), and the rounding.
    t, te, s, se = blood[particle], blood_error[particle], total[particle], total_error[particle]
    exact = np.where(s > 0.0, t * weight / np.where(s > 0.0, s, 1.0), 0.0)
    rest, rest_error = s - weight, se - weight_error
    most = (t + te) * (weight + weight_error) / (weight + weight_error + np.maximum(rest - rest_error, 0.0))
    low = np.maximum(weight - weight_error, 0.0)
    below = low + rest + rest_error   # 0 only where low is
    least = np.maximum(t - te, 0.0) * low / np.where(below > 0.0, below, 1.0)
    allowed = 0.5 + np.maximum(most - exact, exact - least)
    spread, unsure = shares[particle], either[particle]
    allowed = np.where(spread, allowed, np.where(unsure, t + te, 0.0))

    # Falling back: all of T into the pixel holding the centre; where float32 may put the centre
    # across a pixel edge, or the particle may have shared its blood instead, all of T is allowed
    # at each pixel that may hold it.
    holder, candidates, crossing = holding_pixels(scene, x, y)
    into_holder = falls_back | (either & (total == 0.0))
    anywhere = (falls_back & crossing) | either
    pick = anywhere[:, None] & (candidates >= 0)
    picked, picked_blood = candidates[pick], np.broadcast_to((blood + blood_error)[:, None], pick.shape)[pick]

    def field(at, values):
        return np.bincount(at, values, minlength=w_px * h_px).astype(np.float64).reshape(h_px, w_px)
    exact_field = (field(pixel, np.where(spread | (unsure & (s > 0.0)), exact, 0.0)) +
                   field(holder, np.where(into_holder, blood, 0.0)))
    allowed_field = (field(pixel, allowed) + field(holder, np.where(falls_back & ~crossing, blood_error, 0.0)) +
                     field(picked, picked_blood))
    allowed_field += FLOAT32_UNIT * (exact_field + allowed_field)
    reach = (field(pixel, (allowed > 0.0).astype(float)) + field(holder, falls_back.astype(float)) +
             field(picked, np.ones(picked.size))) > 0.0
    return {"exact": exact_field, "allowed": allowed_field, "reach": reach,
            "share_pixels": np.where(falls_back, 0, pairs), "blood_error": blood_error,
            "counts": (int(shares.sum()), int(falls_back.sum()), int(either.sum()))}


def check_on_surface(scene, frame, k, p, problems):
    """Live centres finite, inside the panel, and on texels the mesh covers."""
    w, h = scene["width_px"], scene["height_px"]
    finite = np.isfinite(p).all(axis=1)
    i = np.clip(np.floor(p[finite, 0] / (scene["width_mm"] / w)), 0, w - 1).astype(np.int64)
    j = np.clip(np.floor(p[finite, 1] / (scene["height_mm"] / h)), 0, h - 1).astype(np.int64)
    inside = ((p[finite] >= 0) & (p[finite] <= [scene["width_mm"], scene["height_mm"]])).all(axis=1)
    off = (~finite).sum() + (~inside).sum() + (frame[j, i, 3] == 0).sum()
    if off:
        problems.append(f"key frame {k}: {off} live particles lie off the surface or outside the panel")


def check_film_on_surface(settings, scene, frame, k, p, age, film, problems):
    """On a mesh: the film is finite and not negative, lies only within a splat's reach of a live
    centre or in the pixel holding it (R on the surface is at most R / σ on the panel, σ the frames'
    least stretch, the least singular value of [[a, b], [0, c]], at least a·c / √(a² + b² + c²)),
    and holds the live particles' blood: Σ film · pixel area · a·c (the texel's area on the surface)
    = Σ V · fade, but for rounding."""
    pixel_area = scene["width_mm"] / scene["width_px"] * scene["height_mm"] / scene["height_px"]
    if not np.isfinite(film).all() or (film < 0).any():
        problems.append(f"key frame {k}: the film is negative or not finite somewhere")
        return
    a, b, c = frame[..., 0], frame[..., 1], frame[..., 2]
    # The least singular value of [[a, b], [0, c]]: det / the largest, which is at most the Frobenius norm.
    least = float((a * c / np.sqrt(a * a + b * b + c * c)).min())
    reach = settings["splat_radius"] / least + 2 * edge_band_mm(scene)
    _, pixel, _ = splat_pairs(scene, reach, p[:, 0], p[:, 1])
    reached = np.zeros(film.size, dtype=bool)
    reached[pixel] = True
    holder, _, _ = holding_pixels(scene, p[:, 0], p[:, 1])
    reached[holder] = True
    stray = (film.reshape(-1) != 0) & ~reached
    if stray.any():
        problems.append(f"key frame {k}: {stray.sum()} pixels hold film further than a splat reaches on the surface")
    fade = np.minimum(1.0, (settings["lifetime"] - age.astype(np.float64)) / settings["fade"])
    volume = float((settings["volume"] * fade).sum())
    held = float((film * a * c).sum() * pixel_area)
    # As on the panel (check 5): each particle's T is off by half a unit and BLOOD_RELATIVE of itself,
    # each share by half a unit, at most one share a pixel of its reach's box; film · a·c is the
    # units again (a·c cancels the stretch), but for float32's roundings of the film in mm, the
    # division and a·c itself.
    box = (2.0 * reach / min(scene["width_mm"] / scene["width_px"], scene["height_mm"] / scene["height_px"]) + 3.0) ** 2
    slack = (0.5 * box + 0.5) * p.shape[0] * SPLAT_UNIT_MM * pixel_area + BLOOD_RELATIVE * volume + 4 * FLOAT32_UNIT * held
    if not abs(held - volume) <= slack:
        problems.append(f"key frame {k}: the film holds {held:.9g} mm³ on the surface, the live particles' blood is "
                        f"{volume:.9g} mm³ (± {slack:.3g})")


def check_particles(scenario, f, keys, problems, notes, quota=None, frame=None):
    """Checks 1–5 of the particle state and its film; returns each key frame's film (mm). In a scene
    with [suction], `quota` is the most it may have taken by the end of each step. On a tissue mesh,
    `frame` is the surface's (H, W, 4: a, b, c, on the surface; golden_mesh.surface_maps): centres
    must lie on the surface, and the film is checked by its reach and its volume on the surface,
    not recomputed splat by splat (its footprint is an ellipse in the frame of the texel holding each
    centre, which float32 may put either side of a texel edge)."""
    scene = scenario["scene"]
    settings = particle_settings(scenario)
    capacity, lifetime, r = settings["capacity"], settings["lifetime"], settings["radius"]
    counts, ages = f["particles/accounting"][:], f["particles/age"][:]
    positions, velocities, films = f["particles/position"][:], f["particles/velocity"][:], f["splat/thickness"][:]
    rests, anchors = f["particles/rest"][:], f["particles/anchor"][:]
    step_of_id = emission_steps(settings, (max(keys) + 1) * settings["substeps"])
    panel = (scene["width_mm"], scene["height_mm"])
    bound_slack = float(np.spacing(np.float32(max(panel))))   # the bound is stored as a float32
    pixel_area = scene["width_mm"] / scene["width_px"] * scene["height_mm"] / scene["height_px"]
    film_pixels = 0
    splats = np.zeros(3, dtype=np.int64)   # shared, fell back, either
    worst_share = worst_volume = widest_volume = 0.0
    for i, k in enumerate(keys):
        steps_done = (k + 1) * settings["substeps"]
        emitted, alive, expired, overwritten, age = replay(settings, step_of_id, steps_done)
        wanted = [emitted, int(alive.sum()), int(expired.sum()), int(overwritten.sum())]
        stored = [int(c) for c in counts[i]]
        if quota is None and stored != wanted:
            problems.append(f"key frame {k}: accounting (emitted, alive, expired, overwritten) is {stored}, "
                            f"the schedule gives {wanted}")
        if quota is not None:
            check_aspirated_counts(k, stored, wanted, int(quota[steps_done - 1]), problems)
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
        # The suction's particles keep their slots and age there, marked: the schedule's live ids are
        # the living and the aspirated, and nothing else lives.
        aspirated = (slot_age != NEVER_USED) & ((slot_age & ASPIRATED) != 0)
        if not np.array_equal(live, wanted_live & ~aspirated) or (quota is None and aspirated.any()):
            wrong = np.flatnonzero(live != (wanted_live & ~aspirated))
            problems.append(f"key frame {k}: {wrong.size} slots live or dead against the schedule's live ids "
                            f"(first: slot {wrong[0] if wrong.size else '-'}; {aspirated.sum()} aspirated)")
        slot_age = np.where(aspirated, slot_age & ~ASPIRATED, slot_age)
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
        check_rest(settings, k, live, slot_age, rests[i], positions[i], anchors[i], velocities[i], problems)
        # 3. Live centres inside the panel less a radius, but for what the walls give: a wall is a
        # contact (docs/particles.md#walls) and a centre stops at half a radius past its line at the
        # most (on a mesh: on the surface, inside the panel).
        p = positions[i][live].astype(np.float64)
        if frame is not None:
            check_on_surface(scene, frame, k, p, problems)
            film = films[i].astype(np.float64)
            film_pixels += int((film > 0.0).sum())
            check_film_on_surface(settings, scene, frame, k, p, slot_age[live], film, problems)
            continue
        # A wall's line: where a centre touches it; a film with depth's parcels reach the edge itself.
        margin = 0.0 if scenario["particles"]["film_depth"] else min(r, min(panel) / 2)
        low, high = np.full(2, margin / 2), np.array(panel) - margin / 2   # the backstop: half the margin past it
        outside = ~np.isfinite(p).all(axis=1) | ((p < low - bound_slack) | (p > high + bound_slack)).any(axis=1)
        if outside.any():
            s = np.flatnonzero(live)[np.flatnonzero(outside)[0]]
            problems.append(f"key frame {k}: {outside.sum()} live particles lie outside the panel less half a radius "
                            f"(slot {s} at {tuple(positions[i][s])})")
        # 4. The film, recomputed: within float32's rounding where particles reach, exactly 0 elsewhere.
        live_position, live_age = positions[i][live], slot_age[live]
        want = expected_thickness(settings, scene, live_position, live_age)
        film = films[i].astype(np.float64) / SPLAT_UNIT_MM   # in film units, exactly
        error = np.abs(film - want["exact"])
        beyond = ~(error <= want["allowed"])   # NaN is beyond too
        unreached = ~want["reach"] & (film != 0.0)   # the blend tests thickness > 0: no slack
        bad = beyond | unreached
        if bad.any():
            j, x = np.argwhere(bad)[0]
            problems.append(f"key frame {k}: the film differs from the recomputed splats on {bad.sum()} pixels "
                            f"({unreached.sum()} of them no particle reaches; first ({x}, {j}): "
                            f"{film[j, x] * SPLAT_UNIT_MM:.9g} mm, expected {want['exact'][j, x] * SPLAT_UNIT_MM:.9g} "
                            f"± {want['allowed'][j, x] * SPLAT_UNIT_MM:.3g})")
        film_pixels += int((film > 0.0).sum())
        splats += want["counts"]
        reached = want["allowed"] > 0.0
        if reached.any():
            worst_share = max(worst_share, float((error[reached] / want["allowed"][reached]).max()))
        # 5. The film's volume, sum × pixel area, is the live particles' blood, Σ V · fade, exactly
        # but for rounding: each particle's T (its blood_error), each share (half a unit), and each
        # pixel's sum converted to mm (2⁻²⁴ of it).
        fade = np.minimum(1.0, (lifetime - live_age.astype(np.float64)) / settings["fade"])
        volume = float((settings["volume"] * fade).sum())
        held = film.sum() * SPLAT_UNIT_MM * pixel_area
        rounding = (0.5 * want["share_pixels"].sum() + want["blood_error"].sum() + FLOAT32_UNIT * film.sum())
        slack = rounding * SPLAT_UNIT_MM * pixel_area
        if not abs(held - volume) <= slack:
            problems.append(f"key frame {k}: the film holds {held:.9g} mm³, the live particles' blood is "
                            f"{volume:.9g} mm³ (± {slack:.3g})")
        elif volume > 0.0:
            worst_volume = max(worst_volume, abs(held - volume) / slack)
            widest_volume = max(widest_volume, slack / volume)
    if quota is not None:
        notes.append(f"{int(counts[-1][4])} aspirated by the last key frame, its quota {int(quota[-1])}")
    if frame is not None:
        notes.append(f"{int(counts[-1][0])} emitted; film on the surface on {film_pixels} pixels: its reach and "
                     f"volume checked")
        return films
    notes.append(f"{int(counts[-1][0])} emitted; film recomputed on {film_pixels} pixels, worst "
                 f"{worst_share:.2f} of the float32 allowance; splats shared among the pixel centres they "
                 f"reach {splats[0]}, whole into the pixel holding their centre {splats[1]}, either {splats[2]}")
    notes.append(f"film volume worst {worst_volume:.2f} of its rounding allowance (at most "
                 f"{widest_volume:.2g} of the blood)")
    return films
