"""The blur's part of the independent golden check (check_goldens.py): the blurred film recomputed
from the splatted film in float64 with NumPy (no bleedsim code), within float32's error bound, and
the volume the blur keeps. See check_goldens.py for what each check demands.
"""
import math

import numpy as np

from golden_film import FLOAT32_UNIT


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
