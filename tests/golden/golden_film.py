"""The particles' part of the independent golden check (check_goldens.py): the accounting, the
live slots, the film of blood and its blur, recomputed from the scenario file and the key frames'
particle state in float64 with NumPy (no bleedsim code). See check_goldens.py for what each check
demands.
"""
import math

import numpy as np

EDGE_MM = 1e-5           # a pixel centre this close to a splat's edge may fall either side in float32
NEVER_USED = 0xFFFFFFFF  # the age of a ring slot that never held a particle

# The film (core/physics/splat.h, docs/particles.md): deposits are summed in whole units of 2⁻²⁴ mm, each
# rounded half up from its float32 value (so each is off by up to half a unit, and a little more
# for float32's products) and clamped at 1e9 units.
SPLAT_UNIT_MM = 2.0 ** -24
SPLAT_MAX_DEPOSIT_MM = 1.0e9 * SPLAT_UNIT_MM
# float32's arithmetic on a deposit (its scale V · fade / A and the weight's 1 − d²/R², squared):
# a few roundings, each of at most 2⁻²⁴ of the particle's centre deposit.
SPLAT_RELATIVE = 2e-6
# Where the reference puts a pixel's centre: (i + 0.5) · float32(mm per pixel), in float32, off
# the exact centre by up to 2⁻²³ of the coordinate; so d by up to (width + height) · 2⁻²³ mm.
PIXEL_CENTRE_RELATIVE = 2.0 ** -23
FINE = 16                              # sub-cells per pixel side of the film's volume integrals


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
    substeps = p["substeps"]
    steps_per_s = scenario["scene"]["frame_rate_hz"] * substeps
    lifetime = steps_in(p["lifetime_s"], steps_per_s)
    cuts = [(c["start_s"], c["rate_per_s"], c["bleed_s"]) for c in scenario["cut"]]
    diameter = p["diameter_mm"]
    return {
        "capacity": p["capacity"],
        "radius": diameter / 2.0,
        "splat_radius": p["splat_radius_mm"] or diameter,   # 0: the diameter
        "volume": p["particle_volume_mm3"],
        "substeps": substeps,
        "steps_per_s": steps_per_s,
        "lifetime": lifetime,
        "fade": min(lifetime, steps_in(p["fade_s"], steps_per_s)),
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


# ---- the film of blood -----------------------------------------------------------------------

def footprint_mm2(r):
    """∫ (1 − d²/R²)² dA over the disc of radius R: a film of V / this at the centre holds V."""
    return math.pi * r * r / 3.0


def centre_error_mm(scene):
    """How far the reference's float32 pixel centres may put d from the exact one."""
    return (scene["width_mm"] + scene["height_mm"]) * PIXEL_CENTRE_RELATIVE


def edge_band_mm(scene):
    """A pixel centre this close to a splat's edge may fall either side of it in float32."""
    return max(EDGE_MM, centre_error_mm(scene))


def splat_pairs(settings, scene, position, age):
    """Every (live particle, pixel) pair whose pixel centre lies closer than R + the edge band to the
    particle: the pixel (a flat index), the distance d, and the particle's film at its centre,
    V · fade / A, in mm."""
    w, h = scene["width_px"], scene["height_px"]
    px, py = scene["width_mm"] / w, scene["height_mm"] / h
    cx, cy = pixel_centres(scene)
    r, band = settings["splat_radius"], edge_band_mm(scene)
    fade = np.minimum(1.0, (settings["lifetime"] - age.astype(np.float64)) / settings["fade"])
    centre = settings["volume"] * fade / footprint_mm2(r)
    x, y = position[:, 0].astype(np.float64), position[:, 1].astype(np.float64)
    finite = np.isfinite(x) & np.isfinite(y)   # a non-finite centre is check 3's to report
    x, y, centre = x[finite], y[finite], centre[finite]
    k = int(math.ceil((r + band) / min(px, py))) + 1
    offsets = np.arange(-k, k + 1)
    ii = np.floor(x / px).astype(np.int64)[:, None, None] + offsets[None, None, :]
    jj = np.floor(y / py).astype(np.int64)[:, None, None] + offsets[None, :, None]
    ii, jj = np.broadcast_arrays(ii, jj)
    d = np.hypot(cx[np.clip(ii, 0, w - 1)] - x[:, None, None], cy[np.clip(jj, 0, h - 1)] - y[:, None, None])
    near = (ii >= 0) & (ii < w) & (jj >= 0) & (jj < h) & (d < r + band)
    which = np.broadcast_to(np.arange(x.size)[:, None, None], d.shape)[near]
    return (jj * w + ii)[near], d[near], centre[which]


def expected_thickness(settings, scene, position, age):
    """The film recomputed from the live particles, as H × W fields:

    exact    Σ V · fade · (1 − d²/R²)² / A over the pairs with d < R, in float64;
    allowed  what the reference's float32 may differ by, summed over the pairs: half a unit of
             rounding and float32's products (a unit, with SPLAT_RELATIVE of the centre deposit),
             and the deposit's slope times how far its float32 pixel centre may lie from the
             exact one;
    edge     for the pairs whose centre lies within the edge band of R, the deposit at R less the
             band, which float32 may include or not (≈ 0: the weight falls to 0 with zero slope);
    pairs    the pairs that reach each pixel (d < R + the band): where none do, the film is 0."""
    w, h = scene["width_px"], scene["height_px"]
    r, band, delta = settings["splat_radius"], edge_band_mm(scene), centre_error_mm(scene)
    pixel, d, centre = splat_pairs(settings, scene, position, age)
    q = np.maximum(1.0 - (d / r) ** 2, 0.0)
    deposit = np.where(d < r, np.minimum(centre * q * q, SPLAT_MAX_DEPOSIT_MM), 0.0)
    slope = centre * 4.0 * q * d / (r * r)
    allowed = SPLAT_UNIT_MM + SPLAT_RELATIVE * centre + slope * delta
    band_q = max(0.0, 1.0 - ((r - band) / r) ** 2)
    edge = np.where(np.abs(d - r) <= band, centre * band_q * band_q, 0.0)

    def field(values):
        return np.bincount(pixel, values, minlength=w * h).reshape(h, w)
    return {"exact": field(deposit), "allowed": field(allowed), "edge": field(edge),
            "pairs": np.bincount(pixel, minlength=w * h).reshape(h, w)}


def disc_integral(x, y, r, cell_x, cell_y, cells=None):
    """Σ (1 − d²/R²)² · cell area over a grid of cells [i, i + 1) · cell, sampled at their centres,
    for a particle at (x, y), in mm²: the footprint's integral as a pixel sum takes it. With
    cells = (nx, ny) only the cells of the panel [0, nx) × [0, ny) count. (Not from
    footprint_mm2: the film's volume is checked against the footprint summed out here.)"""
    i0, i1 = math.floor((x - r) / cell_x) - 1, math.ceil((x + r) / cell_x) + 1
    j0, j1 = math.floor((y - r) / cell_y) - 1, math.ceil((y + r) / cell_y) + 1
    if cells is not None:
        i0, i1, j0, j1 = max(i0, 0), min(i1, cells[0]), max(j0, 0), min(j1, cells[1])
    i, j = np.arange(i0, i1), np.arange(j0, j1)
    d2 = ((i + 0.5) * cell_x - x)[None, :] ** 2 + ((j + 0.5) * cell_y - y)[:, None] ** 2
    q = np.maximum(1.0 - d2 / (r * r), 0.0)
    return float((q * q).sum()) * cell_x * cell_y


def grid_sampling_error(r, px, py):
    """How far one particle's film summed over the pixels (× pixel area) may be from what the
    panel holds of its volume, as a share of the volume: (clear, cut). The footprint's whole
    integral is a FINE× finer sum; a splat clear of the panel's edges is swept over where its
    centre sits in its pixel, one cut by an edge or a corner over its centre's distance to them,
    against the finer sum over the panel (whose cells share the panel's edges). The sweeps'
    largest, with half as much again and 2e-4 to spare (between the sweep's points; the finer
    sums' own error). Returns (clear, cut, the footprint's integral in mm²)."""
    whole = disc_integral(0.0, 0.0, r, px / FINE, py / FINE)
    clear = max(abs(disc_integral(a * px / 16, b * py / 16, r, px, py) / whole - 1.0)
                for a in range(16) for b in range(16))
    far = 1 << 40
    at = [(r * m / 32, 4 * r + b * py / 8) for m in range(33) for b in range(8)]   # one edge
    at += [(r * m / 16, r * n / 16) for m in range(17) for n in range(17)]         # a corner
    cut = max(abs(disc_integral(x, y, r, px, py, (far, far)) -
                  disc_integral(x, y, r, px / FINE, py / FINE, (far, far))) / whole for x, y in at)
    return 1.5 * clear + 2e-4, 1.5 * cut + 2e-4, whole


def expected_volume(settings, scene, position, age, whole):
    """What the panel holds of the live particles' blood: Σ V · fade, each particle's taken whole
    where its splat lies clear of the panel's edges, and where an edge cuts it, the share inside
    (a FINE× finer sum over the panel, over `whole`, the same over the plane). Returns (volume,
    Σ V · fade of the clear ones, of the cut ones)."""
    w, h, width, height = scene["width_px"], scene["height_px"], scene["width_mm"], scene["height_mm"]
    r = settings["splat_radius"]
    fade = np.minimum(1.0, (settings["lifetime"] - age.astype(np.float64)) / settings["fade"])
    blood = settings["volume"] * fade
    x, y = position[:, 0].astype(np.float64), position[:, 1].astype(np.float64)
    clear = (x - r >= 0.0) & (x + r <= width) & (y - r >= 0.0) & (y + r <= height)
    cells = (w * FINE, h * FINE)
    share = [disc_integral(x[n], y[n], r, width / cells[0], height / cells[1], cells) / whole
             for n in np.flatnonzero(~clear)]
    volume = blood[clear].sum() + float(np.dot(blood[~clear], share))
    return volume, blood[clear].sum(), blood[~clear].sum()


def check_particles(scenario, f, keys, problems, notes):
    """Checks 1–5 of the particle state and its film; returns each key frame's film (mm)."""
    scene = scenario["scene"]
    settings = particle_settings(scenario)
    capacity, lifetime, r = settings["capacity"], settings["lifetime"], settings["radius"]
    counts, ages = f["particles/accounting"][:], f["particles/age"][:]
    positions, velocities, films = f["particles/position"][:], f["particles/velocity"][:], f["splat/thickness"][:]
    step_of_id = emission_steps(settings, (max(keys) + 1) * settings["substeps"])
    panel = (scene["width_mm"], scene["height_mm"])
    bound_slack = float(np.spacing(np.float32(max(panel))))   # the bound is stored as a float32
    pixel_area = scene["width_mm"] / scene["width_px"] * scene["height_mm"] / scene["height_px"]
    splat_r = settings["splat_radius"]
    narrow = 2.0 * splat_r > min(panel)   # a splat cut by two opposite edges: outside the sweep
    clear_error, cut_error, whole = grid_sampling_error(splat_r, scene["width_mm"] / scene["width_px"],
                                                 scene["height_mm"] / scene["height_px"])
    film_pixels = edge_pixels = edge_needed = 0
    worst_share = worst_volume = 0.0
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
        # 4. The film, recomputed: within float32's rounding where particles reach, exactly 0 elsewhere.
        want = expected_thickness(settings, scene, positions[i][live], slot_age[live])
        film = films[i].astype(np.float64)
        error = np.abs(film - want["exact"])
        beyond = error > want["allowed"]
        by_edge = beyond & (error <= want["allowed"] + want["edge"])
        unreached = (want["pairs"] == 0) & (film != 0.0)   # the blend tests thickness > 0: no slack
        bad = (beyond & ~by_edge) | unreached
        if bad.any():
            j, x = np.argwhere(bad)[0]
            problems.append(f"key frame {k}: the film differs from the recomputed splats on {bad.sum()} pixels "
                            f"({unreached.sum()} of them no particle reaches; first ({x}, {j}): {film[j, x]:.9g} mm, "
                            f"expected {want['exact'][j, x]:.9g} ± {want['allowed'][j, x] + want['edge'][j, x]:.3g})")
        reached = want["pairs"] > 0
        film_pixels += int((film > 0.0).sum())
        edge_pixels += int((want["edge"] > 0.0).sum())
        edge_needed += int(by_edge.sum())
        if reached.any():
            worst_share = max(worst_share, float((error[reached] / want["allowed"][reached]).max()))
        # 5. The film's volume: sum × pixel area against the particles' blood on the panel, to the
        # pixel grid's sampling error (and the rounding allowed above, summed).
        if narrow:
            continue
        volume, clear, cut = expected_volume(settings, scene, positions[i][live], slot_age[live], whole)
        held = film.sum() * pixel_area
        slack = clear_error * clear + cut_error * cut + (want["allowed"] + want["edge"]).sum() * pixel_area
        if abs(held - volume) > slack:
            problems.append(f"key frame {k}: the film holds {held:.6g} mm³, the live particles' blood on the "
                            f"panel is {volume:.6g} mm³ (± {slack:.3g}; {clear:.6g} mm³ of splats clear of "
                            f"the edges, {cut:.6g} mm³ cut by them)")
        elif volume > 0.0:
            worst_volume = max(worst_volume, abs(held - volume) / slack)
    notes.append(f"{int(counts[-1][0])} emitted; film recomputed on {film_pixels} pixels, worst "
                 f"{worst_share:.2f} of the float32 allowance, {edge_pixels} pixels by a splat edge "
                 f"({edge_needed} needing its slack)")
    notes.append("film volume not checked: the splat is wider than the panel" if narrow else
                 f"film volume worst {worst_volume:.2f} of its allowance (sampling error "
                 f"{clear_error:.2%} clear, {cut_error:.2%} at an edge)")
    return films


# ---- the blur --------------------------------------------------------------------------------

FLOAT32_UNIT = 2.0 ** -24       # float32's unit roundoff: one rounding is off by at most this, relatively
FLOAT32_UNDERFLOW = 2.0 ** -150  # and by at most this, absolutely, where it underflows
BLUR_MARGIN = 1.01              # the error bound below is first order in the unit: 1% for the rest


def blur_settings(scenario):
    """The [blur] table's settings (its defaults filled in by scenario_defaults.py)."""
    b = scenario["blur"]
    return b["downsample"], b["radius_px"], b["sigma_px"]


def gaussian_weights(radius, sigma, to_float32=True):
    """exp(−½(k/σ)²) for k = −r … r, in double, normalised by their sum (taken left to right) and
    rounded once to float32, as the reference's are; or, with to_float32 false, left in double."""
    w = [math.exp(-0.5 * (k / sigma) * (k / sigma)) for k in range(-radius, radius + 1)]
    total = 0.0
    for v in w:
        total += v
    w = np.array([v / total for v in w])
    return w.astype(np.float32).astype(np.float64) if to_float32 else w


def blur_operators(n, factor, radius, weights):
    """The blur along one axis of n pixels as matrices, in float64: D (⌈n/f⌉ × n) the block means;
    G (⌈n/f⌉ × ⌈n/f⌉) the Gaussian, taps past the edge reading the edge pixel; U (n × ⌈n/f⌉) the
    bilinear upsample, the panel's pixel i at (i + ½)/f − ½ downsampled pixels. The film blurs as
    Uy · Gy · Dy · S · Dxᵀ · Gxᵀ · Uxᵀ. Returns D, G, then G with each tap's weight times the
    roundings its term meets in the reference's float32 tap sum, U, then U with each lerp's
    roundings (expected_blur's error bound), and each block's pixel count."""
    low = -(-n // factor)
    counts = np.array([min((m + 1) * factor, n) - m * factor for m in range(low)])
    d = np.zeros((low, n))
    for m in range(low):
        d[m, m * factor:m * factor + counts[m]] = 1.0 / counts[m]
    g, rounded = np.zeros((low, low)), np.zeros((low, low))
    taps = 2 * radius + 1
    for k in range(-radius, radius + 1):
        column = np.clip(np.arange(low) + k, 0, low - 1)
        np.add.at(g, (np.arange(low), column), weights[k + radius])
        # Summed left to right from 0: the t-th term (t = 1 … n) is in the partial sums t … n, of
        # which all but the first term's own (0 + it) are rounded; then its product (one u) and
        # its weight (up to an ulp, 2u, off ours: see expected_blur).
        t = k + radius + 1
        np.add.at(rounded, (np.arange(low), column), weights[k + radius] * (taps - t + (0 if t == 1 else 1) + 3))
    x = (np.arange(n) + 0.5) / factor - 0.5   # exact in float32 too: f is a power of two
    x0 = np.floor(x)
    fx = x - x0
    i0 = np.clip(x0.astype(np.int64), 0, low - 1)
    i1 = np.clip(x0.astype(np.int64) + 1, 0, low - 1)
    u = np.zeros((n, low))
    np.add.at(u, (np.arange(n), i0), 1.0 - fx)
    np.add.at(u, (np.arange(n), i1), fx)
    # A lerp a + (b − a)·fx rounds b − a and its product with fx, each by u of |b − a|·fx ≤
    # (a + b)·fx, and the sum by u of the result; with a clamped neighbour (b = a) only the sum,
    # which is then exact too.
    lerp = u.copy()
    apart = i0 != i1
    np.add.at(lerp, (np.arange(n)[apart], i0[apart]), 2.0 * fx[apart])
    np.add.at(lerp, (np.arange(n)[apart], i1[apart]), 2.0 * fx[apart])
    return d, g, rounded, u, lerp, counts


def expected_blur(film, factor, radius, weights):
    """The blurred film recomputed in float64 from the stored film (H × W), and what the
    reference's float32 may differ from it by (H × W), bounded by rounding errors carried through
    the passes. All inputs are ≥ 0 (the magnitudes below are taken of |film| so it holds anyway),
    so each pass's error is a count of roundings times the values it sums, u = 2⁻²⁴:

    downsample  n values summed and divided by n: n·u of the block's mean (n ≤ f²);
    across      each sum rounded, u of the partial sum so far, so the t-th of the n = 2r + 1 terms
                wᵢ·xᵢ meets n − t + 1 of them (n − 1 for the first: 0 + it is exact), and its
                product one more, and its weight an ulp, 2u (the same double rounded the same
                way on one machine, but the golden's libm's exp may differ from this one's by a
                double's ulp, which can tip the rounding to float32); about (r + 4)·u of the tap
                sum for a Gaussian's middle-heavy weights, with the errors coming in carried
                through the taps;
    down        the same;
    upsample    lerps a + (b − a)·fx (fx exact: f is a power of two), across then down: each
                rounds b − a, its product with fx and the sum, u·(2(a + b)·fx + the result)
                (blur_operators), with the errors coming in interpolated;

    then BLUR_MARGIN for the second-order terms, and where any film reaches, an underflow's
    2⁻¹⁵⁰ per rounding. Where none reaches, the reference's blur is exactly 0 (sums of 0 · w), and
    so is the allowance: the blend tests h > 0."""
    h, w = film.shape
    dx, gx, rx, ux, lx, cx = blur_operators(w, factor, radius, weights)
    dy, gy, ry, uy, ly, cy = blur_operators(h, factor, radius, weights)
    s = film.astype(np.float64)
    exact = uy @ (gy @ (dy @ s @ dx.T) @ gx.T) @ ux.T
    u = FLOAT32_UNIT
    low = dy @ np.abs(s) @ dx.T
    error = np.outer(cy, cx) * u * low
    across = low @ gx.T
    error = error @ gx.T + u * (low @ rx.T)
    down = gy @ across
    error = gy @ error + u * (ry @ across)
    top = down @ ux.T   # the rows lerped across: what the lerp down interpolates between
    error = error @ ux.T + u * (down @ lx.T)
    error = uy @ error + u * (ly @ top)
    roundings = factor * factor + 2 * (2 * radius + 2) + 6
    allowed = BLUR_MARGIN * error + np.where(error > 0.0, roundings * FLOAT32_UNDERFLOW, 0.0)
    return exact, allowed


def volume_kept(shape, factor, radius, sigma):
    """How much of each panel pixel's film the blur keeps on the panel, g = gy ⊗ gx: the column sums
    of the blur's matrices, with the Gaussian's exact (double, normalised) weights. Away from the
    edges g = 1 (weights summing to 1, block means, bilinear weights summing to 1 and spreading a
    downsampled pixel over f panel pixels): the blur only moves the film. Near an edge, the
    clamped taps and the partial blocks move some of it in or out. Also how far from the edges
    the blur reaches: f·(r + 2) panel pixels (a block, r taps, the upsample's neighbour)."""
    weights = gaussian_weights(radius, sigma, to_float32=False)
    kept = []
    for n in shape:
        d, g, _, u, _, _ = blur_operators(n, factor, radius, weights)
        kept.append((u @ g @ d).sum(axis=0))
    return np.outer(kept[0], kept[1]), factor * (radius + 2)


def check_blur(scenario, f, keys, films, problems, notes):
    """Checks 6–7: the blurred film against the stored film blurred here, and its volume; returns
    each key frame's blurred film (mm), what the blend lays over the tissue."""
    scene = scenario["scene"]
    factor, radius, sigma = blur_settings(scenario)
    blurred = f["blur/thickness"][:]
    if blurred.shape != films.shape:
        problems.append(f"blur/thickness is {blurred.shape}, splat/thickness {films.shape}")
        return films
    weights = gaussian_weights(radius, sigma)
    kept, reach = volume_kept(films.shape[1:], factor, radius, sigma)
    # 7a. The blur as described keeps the film's volume beyond its reach from the edges (a check
    # of the description, and of this script's matrices, before any data).
    h, w = films.shape[1:]
    if h > 2 * reach and w > 2 * reach:
        off = np.abs(kept[reach:h - reach, reach:w - reach] - 1.0).max()
        if off > 1e-12:
            problems.append(f"the blur as described keeps {1 + off:.12g} of the film more than {reach} px "
                            f"from the edges, not 1")
    pixel_area = scene["width_mm"] / scene["width_px"] * scene["height_mm"] / scene["height_px"]
    film_pixels = 0
    worst_share = worst_volume = edge_share = 0.0
    for i, k in enumerate(keys):
        film, got = films[i].astype(np.float64), blurred[i].astype(np.float64)
        # 6. The blurred film, recomputed from the stored film: within the float32 rounding bound
        # where any film reaches, exactly 0 where none does.
        exact, allowed = expected_blur(film, factor, radius, weights)
        error = np.abs(got - exact)
        bad = ~(error <= allowed)   # NaN is bad too
        if bad.any():
            j, x = np.argwhere(bad)[0]
            problems.append(f"key frame {k}: the blurred film differs from the stored film blurred here on "
                            f"{bad.sum()} pixels (first ({x}, {j}): {got[j, x]:.9g} mm, expected "
                            f"{exact[j, x]:.9g} ± {allowed[j, x]:.3g}; f = {factor}, r = {radius}, σ = {sigma})")
        reached = allowed > 0.0
        film_pixels += int((got > 0.0).sum())
        if reached.any():
            worst_share = max(worst_share, float((error[reached] / allowed[reached]).max()))
        # 7. The volume: the blurred film holds the film's, plus what the edges move, Σ h · (g − 1)
        # (0 but for the film within the blur's reach of an edge), to the rounding allowed above and
        # the float32 weights' (each within 2u of the exact one, in each of two passes, so g within
        # 4u of itself; they sum to 1 only to about that).
        held, before = got.sum() * pixel_area, film.sum() * pixel_area
        moved = (film * (kept - 1.0)).sum() * pixel_area
        slack = (4.0 * FLOAT32_UNIT * (film * kept).sum() + allowed.sum()) * pixel_area + 1e-12 * before
        if not abs(held - (before + moved)) <= slack:
            problems.append(f"key frame {k}: the blurred film holds {held:.9g} mm³; the film holds {before:.9g} mm³ "
                            f"and the blur's edges move {moved:+.6g} mm³ of it (± {slack:.3g})")
        elif before > 0.0:
            worst_volume = max(worst_volume, abs(held - (before + moved)) / slack)
            edge_share = max(edge_share, abs(moved) / before)
    notes.append(f"blur (f = {factor}, r = {radius}, σ = {sigma}) recomputed on {film_pixels} pixels, worst "
                 f"{worst_share:.2f} of the float32 bound; its volume worst {worst_volume:.2f} of its allowance "
                 f"(the edges moved up to {edge_share:.2%} of it)")
    return blurred


# ---- the scene -------------------------------------------------------------------------------
