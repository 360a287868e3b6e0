"""The independent check of a golden scene on a tissue mesh (docs/mesh.md), from the OBJ file and
the scenario alone (no bleedsim code), in float64:

- the surface maps: each texel's triangle (the first, in file order, whose uv triangle holds the
  texel's centre, edges included), its map J from panel to surface mm written in the tangent
  plane's frame along the panel's x, (a, b, c), and gravity's tangential part in that frame, against
  surface/frame and surface/gravity as stored (float32 of the same formulas: 2 ulps);
- the haptic channel: where the tip is in contact, the proxy the channel's panel_position names (its
  uv's triangle and barycentric weights) lies on the mesh with the tip behind it along the shading
  normal (the corners' area-weighted outward normals by those weights), tip = P − h·n, h the
  penetration; the force is f·n with f = min(clamp(k·h − b·n·Δx/T, 0, cap), √(4B·R/T)), R the
  energy the contact has taken in (docs/haptics.md); out of contact nothing; cutting is contact with
  the cutting button held; and the cuts the strokes lay, once the proxy is cut_spacing_mm from the
  last cut's on the surface;
- the stain, with distances on the surface through each pixel's frame (see check_goldens.py).
What it leaves to the C++ tests and to CPU ≡ CUDA: which proxy the walk picks where the equation has
several (the curl's far wall; tests/haptics/mesh_contact_test.cpp), and the film's recomputation
from the particles, whose footprint on a mesh is an ellipse in the frame of the texel holding each
centre (golden_film.py checks its reach and its volume instead).
"""
import math

import numpy as np

HAPTIC_RATE_HZ = 1000
PROXY_TOLERANCE_MM = 1e-6     # the proxy's Newton converges to 1e-12 relative; panel_position is stored as float64
FORCE_TOLERANCE_N = 1e-9
MAP_ULPS = 2                  # float32 of the same float64 formulas, summed in another order (of a
                              # thousandth of the channel's largest, for values that cancel to ~0)


def read_obj(path):
    """Positions (V, 3), uvs (T, 2), triangles' corner and uv indices (F, 3) each, 0-based; polygons fanned."""
    positions, uvs, corners, uv_index = [], [], [], []
    for line in path.read_text().splitlines():
        words = line.split()
        if not words:
            continue
        if words[0] == "v":
            positions.append([float(v) for v in words[1:4]])
        elif words[0] == "vt":
            uvs.append([float(v) for v in words[1:3]])
        elif words[0] == "f":
            refs = [w.split("/") for w in words[1:]]
            for k in range(1, len(refs) - 1):
                tri = (refs[0], refs[k], refs[k + 1])
                corners.append([int(r[0]) - 1 for r in tri])
                uv_index.append([int(r[1]) - 1 for r in tri])
    return np.array(positions), np.array(uvs), np.array(corners), np.array(uv_index)


def placed(positions, tissue):
    """position + scale · R_z R_y R_x · p (docs/mesh.md)."""
    ax, ay, az = (math.radians(a) for a in tissue["mesh_rotation_deg"])
    rx = np.array([[1, 0, 0], [0, math.cos(ax), -math.sin(ax)], [0, math.sin(ax), math.cos(ax)]])
    ry = np.array([[math.cos(ay), 0, math.sin(ay)], [0, 1, 0], [-math.sin(ay), 0, math.cos(ay)]])
    rz = np.array([[math.cos(az), -math.sin(az), 0], [math.sin(az), math.cos(az), 0], [0, 0, 1]])
    return np.array(tissue["mesh_position_mm"]) + tissue["mesh_scale"] * positions @ (rz @ ry @ rx).T


def read_mesh(root, scenario):
    tissue = scenario["tissue"]
    positions, uvs, corners, uv_index = read_obj((root / "scenarios/golden" / tissue["mesh"]).resolve())
    return {"p": placed(positions, tissue), "uv": uvs, "corner": corners, "uv_index": uv_index}


def triangle_maps(mesh, scene):
    """Per triangle: J from panel to surface mm (F, 3, 2), the outward normal's direction ∂P/∂v × ∂P/∂u
    and its area."""
    p, uv = mesh["p"][mesh["corner"]], mesh["uv"][mesh["uv_index"]]
    size = np.array([scene["width_mm"], scene["height_mm"]])
    dp = np.stack([p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]], axis=2)                 # (F, 3, 2)
    dx = np.stack([(uv[:, 1] - uv[:, 0]) * size, (uv[:, 2] - uv[:, 0]) * size], axis=2)  # (F, 2, 2)
    j = dp @ np.linalg.inv(dx)
    du = np.stack([uv[:, 1] - uv[:, 0], uv[:, 2] - uv[:, 0]], axis=2)
    j_uv = dp @ np.linalg.inv(du)                                                   # [∂P/∂u ∂P/∂v]
    outward = np.cross(j_uv[:, :, 1], j_uv[:, :, 0])
    area = 0.5 * np.linalg.norm(np.cross(dp[:, :, 0], dp[:, :, 1]), axis=1)
    return j, outward / np.linalg.norm(outward, axis=1)[:, None], area


def surface_maps(mesh, scene, gravity):
    """Each texel's values from the first triangle, in file order, whose uv triangle holds its centre
    (edges included): frame (H, W, 4: a, b, c, 1 on the surface) and gravity (H, W, 2) — twice, as
    (first, second): a centre on a uv edge, to rounding, may go to either triangle there, as the
    OBJ's decimals parse to the last bit (tinyobjloader's parser is not correctly rounded), and the
    second is the next triangle that may hold it (the first again where none). Also where the
    surface surely is, and where it may be (a centre on the chart's own edge)."""
    w, h = scene["width_px"], scene["height_px"]
    j, _, _ = triangle_maps(mesh, scene)
    frame, tangential = np.zeros((2, h, w, 4)), np.zeros((2, h, w, 2))
    held = np.zeros((h, w), dtype=np.int64)   # triangles that may hold the centre, up to 2
    surely = np.zeros((h, w), dtype=bool)
    uvs = mesh["uv"][mesh["uv_index"]]
    for t in range(len(uvs)):
        (u0, v0), (u1, v1), (u2, v2) = uvs[t]
        i0, i1 = max(0, math.ceil(min(u0, u1, u2) * w - 0.5) - 1), min(w - 1, math.floor(max(u0, u1, u2) * w - 0.5) + 1)
        j0, j1 = max(0, math.ceil(min(v0, v1, v2) * h - 0.5) - 1), min(h - 1, math.floor(max(v0, v1, v2) * h - 0.5) + 1)
        if i1 < i0 or j1 < j0:
            continue
        u, v = np.meshgrid((np.arange(i0, i1 + 1) + 0.5) / w, (np.arange(j0, j1 + 1) + 0.5) / h)

        def side(ax, ay, bx, by):
            return (bx - ax) * (v - ay) - (by - ay) * (u - ax)
        s = np.stack([side(u0, v0, u1, v1), side(u1, v1, u2, v2), side(u2, v2, u0, v0)])
        edge = 1e-13   # far above the parse's last bits, far below a texel
        maybe = (s >= -edge).all(axis=0) | (s <= edge).all(axis=0)
        sure = (s > edge).all(axis=0) | (s < -edge).all(axis=0)
        box = (slice(j0, j1 + 1), slice(i0, i1 + 1))
        along_x, along_y = j[t][:, 0], j[t][:, 1]
        a = np.linalg.norm(along_x)
        e1 = along_x / a
        b = along_y @ e1
        rest = along_y - b * e1
        c = np.linalg.norm(rest)
        e2 = rest / c
        for k in (0, 1):
            take = maybe & (held[box] <= k) if k == 1 else maybe & (held[box] == 0)
            frame[k][box][take] = [a, b, c, 1.0]
            tangential[k][box][take] = [gravity @ e1, gravity @ e2]
        held[box] += maybe
        surely[box] |= sure
    one = held == 1   # held by one triangle only: its second is its first
    frame[1][one], tangential[1][one] = frame[0][one], tangential[0][one]
    return frame, tangential, surely, held > 0


def device_gravity(scenario, params_defaults):
    """The particles' gravity_mm_s2 (panel x right, y down) in the device frame: (g_x, −g_y, 0)."""
    g = scenario.get("particles", params_defaults)["gravity_mm_s2"]
    return np.array([g[0], -g[1], 0.0])


def check_maps(f, frame, tangential, surely, maybe, problems, notes):
    """surface/frame and surface/gravity against the maps from the OBJ: each covered texel's values
    within MAP_ULPS of one of the triangles that may hold its centre; on the surface where it surely
    is, off it where it cannot be. (An uncovered texel takes its nearest covered texel's values, a
    sweep this check does not repeat.)"""
    stored_frame, stored_gravity = f["surface/frame"][:], f["surface/gravity"][:]   # (keys, H, W, C)
    on = stored_frame[0][..., 3] != 0
    if (surely & ~on).any() or (on & ~maybe).any():
        problems.append("surface/frame marks other texels on the surface than the mesh's uvs cover")
    worst = 0.0
    for stored, want in ((stored_frame[0][..., :3], frame[..., :3]), (stored_gravity[0], tangential)):
        # A value that cancels to near 0 (b on an unsheared texel, gravity across a level one) is
        # held to the ulps of a thousandth of its channel's largest instead.
        floor = 1e-3 * np.abs(want[0][on]).max(axis=0)
        ulps = []
        for k in (0, 1):
            wanted = want[k][on].astype(np.float32).astype(np.float64)
            spacing = np.spacing(np.maximum(np.abs(wanted), floor).astype(np.float32)).astype(np.float64)
            ulps.append((np.abs(stored[on].astype(np.float64) - wanted) / spacing).max(axis=1))
        error = np.minimum(ulps[0], ulps[1])
        worst = max(worst, float(error.max()))
        if error.max() > MAP_ULPS:
            problems.append(f"the surface maps differ from the mesh's by {error.max():.0f} float32 ulps at "
                            f"{(error > MAP_ULPS).sum()} texels")
    if any(not np.array_equal(stored_frame[i], stored_frame[0]) for i in range(len(stored_frame))):
        problems.append("the surface maps change between key frames")
    ties = int((maybe & (frame[0][..., 0] != frame[1][..., 0])).sum())
    notes.append(f"mesh: {on.sum()} of {on.size} texels on the surface, their maps within {worst:.1f} float32 ulps "
                 f"of the OBJ's ({ties} centres on a uv edge, either triangle's)")


def vertex_normals(mesh, outward, area):
    normals = np.zeros_like(mesh["p"])
    for k in range(3):
        np.add.at(normals, mesh["corner"][:, k], area[:, None] * outward)
    length = np.linalg.norm(normals, axis=1)
    return normals / np.where(length > 0, length, 1.0)[:, None]


def proxies_at(mesh, scene, panel_mm):
    """The triangle holding each texture point (panel mm; the first in file order) and its weights."""
    uv = panel_mm / np.array([scene["width_mm"], scene["height_mm"]])
    tri = mesh["uv"][mesh["uv_index"]]                                    # (F, 3, 2)
    e1, e2 = tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]
    det = e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0]
    d = uv[:, None, :] - tri[None, :, 0]                                  # (N, F, 2)
    w1 = (d[..., 0] * e2[:, 1] - d[..., 1] * e2[:, 0]) / det
    w2 = (e1[:, 0] * d[..., 1] - e1[:, 1] * d[..., 0]) / det
    w0 = 1.0 - w1 - w2
    inside = (w0 >= -1e-9) & (w1 >= -1e-9) & (w2 >= -1e-9)
    found = inside.any(axis=1)
    triangle = np.argmax(inside, axis=1)
    rows = np.arange(len(uv))
    return triangle, np.stack([w0[rows, triangle], w1[rows, triangle], w2[rows, triangle]], axis=1), found


def check_mesh_channel(scenario, mesh, got, ticks, trace_tool, problems, notes):
    """The channel's contact, penetration and force against the mesh; returns the cuts and the channel
    as check_goldens.py reads it."""
    s, h = scenario["scene"], scenario["haptics"]
    period = 1.0 / HAPTIC_RATE_HZ
    k, b, cap, device = h["stiffness_N_per_m"], h["damping_Ns_per_m"], h["max_force_N"], h["device_damping_Ns_per_m"]
    _, outward, area = triangle_maps(mesh, s)
    normals = vertex_normals(mesh, outward, area)
    contact, force, depth_mm = got["contact"].astype(bool), got["force"], 1000.0 * got["penetration"]
    tip_mm = 1000.0 * trace_tool
    triangle, weights, found = proxies_at(mesh, s, got["panel_position"])
    corners = mesh["corner"][triangle]
    proxy = np.einsum("nk,nkd->nd", weights, mesh["p"][corners])
    n = np.einsum("nk,nkd->nd", weights, normals[corners])
    n /= np.linalg.norm(n, axis=1)[:, None]
    if not found.all():
        problems.append(f"/haptics/panel_position lies outside the mesh's uvs at {(~found).sum()} ticks")
    residual = np.linalg.norm(tip_mm - (proxy - depth_mm[:, None] * n), axis=1)
    off = contact & (residual > PROXY_TOLERANCE_MM)
    if off.any():
        problems.append(f"at {off.sum()} contact ticks the tip is not behind the proxy along the shading normal "
                        f"(worst {residual[contact].max():.3g} mm, first tick {np.flatnonzero(off)[0]})")
    if (depth_mm[contact] <= 0).any() or (depth_mm[~contact] != 0).any() or np.abs(force[~contact]).max(initial=0) > 0:
        problems.append("/haptics: a contact tick without depth, or a tick out of contact with depth or force")
    # The force: force shading's spring and damper, under the energy bound kept from the trace.
    want = np.zeros_like(force)
    reserve, bound_ticks = 0.0, 0
    for i in range(ticks):
        if not contact[i]:
            reserve = 0.0
            continue
        step = (trace_tool[i] - trace_tool[i - 1]) if i > 0 else np.zeros(3)
        reserve += device * (step @ step) / period - force[i - 1] @ step if i > 0 else 0.0
        shaded = min(max(k * depth_mm[i] / 1000.0 - b * (n[i] @ step) / period, 0.0), cap)
        bounded = math.sqrt(max(0.0, 4.0 * device * reserve / period))
        bound_ticks += bounded < shaded
        want[i] = min(shaded, bounded) * n[i]
    error = np.abs(force - want).max()
    if error > FORCE_TOLERANCE_N:
        problems.append(f"/haptics/force differs from force shading under the energy bound by {error:.3g} N")
    cutting = contact & ((got["buttons"].astype(np.int64) & h["cut_button"]) != 0)
    if not np.array_equal(got["cutting"].astype(bool), cutting):
        problems.append("/haptics/cutting is not contact with the cutting button held")
    # The cuts: a stroke's first cutting tick, then each tick the proxy is cut_spacing_mm from the last
    # cut's on the surface; the wound's direction is the stroke's in the texture.
    cuts, last = [], None
    for i in range(ticks):
        if not cutting[i]:
            last = None
            continue
        if last is None or np.linalg.norm(proxy[i] - last[1]) >= h["cut_spacing_mm"]:
            x, y = got["panel_position"][i]
            angle = math.degrees(math.atan2(y - last[0][1], x - last[0][0])) if last is not None else 0.0
            last = ((x, y), proxy[i])
            cuts.append({"x_mm": float(x), "y_mm": float(y), "start_s": i / HAPTIC_RATE_HZ,
                         "wound_mm": h["cut_spacing_mm"], "wound_angle_deg": angle})
    onsets = np.flatnonzero(np.diff(contact.astype(np.int64)) == 1) + 1
    if len(onsets) == 0:
        problems.append("the stylus never touches the tissue")
    notes.append(f"haptics on the mesh: {ticks} ticks, {len(onsets)} contacts, proxy within "
                 f"{residual[contact].max(initial=0):.2g} mm of x = P − h·n, force up to "
                 f"{np.linalg.norm(force, axis=1).max():.3f} N (cap {cap} N; the energy bound bound on {bound_ticks} "
                 f"ticks), {len(cuts)} cuts")
    channel = {"time": got["time"], "tool_position": trace_tool, "panel_position": got["panel_position"],
               "buttons": got["buttons"], "contact": contact, "penetration": got["penetration"],
               "force": np.linalg.norm(force, axis=1), "cutting": cutting, "spacing": h["cut_spacing_mm"], "cap": cap}
    return cuts, channel
