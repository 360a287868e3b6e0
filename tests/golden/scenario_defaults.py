"""A scenario as bleedsim reads it: what each table leaves out, filled in from the parameter tables.

The defaults come from `bleedsim params --json` (the tables in core/ that the scenario reader, the
checks and the docs read), never from a copy here. What this file adds is only the documented way
some defaults follow from other keys (docs/scenario-format.md, each key's default column):
fade_s = min(its default, lifetime_s); sigma_px = max(0.5, radius_px / 2); the haptic origin at
the panel's centre; a cut's wound from [spread] and [particles]. And, from docs/particles.md's
formulas, the sub-steps a scene with substeps = 0 runs: the fewest inside the contact's stability
limit, the contact's stiffness derived from the deepest pile it must hold.
"""
import json
import math
import subprocess

# The tables `bleedsim params --json` lists that are not one table of defaults a scene fills in: the
# [[cut]] and [[tip]] lists (a cut is filled by fill_cut), the view and the output.
NOT_FILLED = ("cut", "tip", "view", "output")


def load_params(bleedsim):
    """{table: {key: parameter}} from `bleedsim params --json`."""
    printed = subprocess.run([bleedsim, "params", "--json"], capture_output=True, text=True, check=True).stdout
    return {t["name"]: {p["key"]: p for p in t["params"]} for t in json.loads(printed)["tables"]}


def defaults(params, table):
    """The struct's default of every key of `table` that has one."""
    return {key: p["default"] for key, p in params[table].items() if p["default"] is not None}


def read_scenario(parsed, params):
    """The parsed TOML (a dict), with every declared table's and every cut's defaults filled in."""
    written = {table: set(parsed[table]) for table in params if table not in NOT_FILLED and table in parsed}
    scenario = dict(parsed)
    scenario.setdefault("tissue", {})   # every scene has a tissue: the flat panel unless it names a mesh
    written.setdefault("tissue", set())
    for table in written:
        scenario[table] = {**defaults(params, table), **parsed.get(table, {})}
    if "particles" in scenario:
        p = scenario["particles"]
        if "fade_s" not in written["particles"]:
            p["fade_s"] = min(p["fade_s"], p["lifetime_s"])
        if p["film_depth"] and "cohesion_mm3_s2" not in written["particles"]:
            p["cohesion_mm3_s2"] = 0.0   # a film with depth has no cohesion
    if "blur" in scenario and "sigma_px" not in written["blur"]:
        scenario["blur"]["sigma_px"] = max(0.5, scenario["blur"]["radius_px"] / 2.0)
    if "haptics" in scenario and "panel_origin_mm" not in written["haptics"]:
        s = scenario["scene"]
        scenario["haptics"]["panel_origin_mm"] = [s["width_mm"] / 2, s["height_mm"] / 2]
    scenario["cut"] = [fill_cut(cut, scenario, params) for cut in parsed.get("cut", [])]
    return scenario


def fill_cut(cut, scenario, params):
    """A cut's wound: its own keys, else the scene's [spread] and [particles], else their defaults."""
    size = scenario.get("spread", defaults(params, "spread"))
    flow = scenario.get("particles", defaults(params, "particles"))
    return {**defaults(params, "cut"), "radius_mm": size["radius_mm"], "growth_per_s": size["growth_per_s"],
            "flow_mm3_per_s_per_mm": flow["flow_mm3_per_s_per_mm"], "bleed_s": flow["bleed_s"],
            "clot_s": flow["clot_s"], **cut}


def particle_substeps(scenario):
    """The sub-steps per frame the particles run: the scene's, or the fewest inside the stability limit
    z·k·dt² + (2z·c − 2γ)·dt < 4 (z = 8 contacts), with k = (|g|·H + a_coh·d)/(ε·d²), c = ζ·√(2k),
    a_coh = q_c·d/V and H the deepest pile: the panel's extent along gravity, or the whole ring heaped
    hexagonally into a quarter-disc in a corner, whichever is less (docs/particles.md,
    "Incompressible at any depth")."""
    s, p = scenario["scene"], scenario["particles"]
    if p["substeps"] > 0:
        return p["substeps"]
    gx, gy = abs(p["gravity_mm_s2"][0]), abs(p["gravity_mm_s2"][1])
    g, d, v = math.hypot(gx, gy), p["diameter_mm"], p["particle_volume_mm3"]
    along = (gx * s["width_mm"] + gy * s["height_mm"]) / g if g > 0 else s["height_mm"]
    if p["film_depth"]:
        limit = film_depth_step_limit(scenario, g, along)
    else:
        heap_mm2 = p["capacity"] * math.sqrt(3) / 2 * d * d
        depth = p["design_depth_mm"] or min(along, 2 * math.sqrt(heap_mm2 / math.pi))
        k = (g * depth + p["cohesion_mm3_s2"] * d / v * d) / (p["compression"] * d * d)
        c = p["damping_ratio"] * math.sqrt(2 * k)
        a, b = 8 * k, 16 * c - 2 * p["drag_per_s"]
        limit = (-b + math.sqrt(b * b + 16 * a)) / (2 * a)
    n = max(1, math.floor(1 / (limit * s["frame_rate_hz"])))
    while 1 / (s["frame_rate_hz"] * n) >= limit:
        n += 1
    return n


def film_depth_step_limit(scenario, g, along):
    """A film with depth's sub-step limit (docs/particles.md#a-film-with-depth): the shorter of its fastest
    wave's, k·dt² − 2γ·dt < 4 with k = κ·g_n·H/R² (κ = 10.18 for the Wendland C2 kernel, R = 2.6·d,
    g_n the normal gravity or what Earth's 9810 mm/s² leaves after g), H the deepest film: the ring's
    whole volume pooled against the lowest wall, its surface sloping at g/g_n; and the travel, half a
    diameter at the speed limit."""
    s, p = scenario["scene"], scenario["particles"]
    d = p["diameter_mm"]
    normal = p["gravity_normal_mm_s2"] or math.sqrt(max(9810.0 ** 2 - g * g, 0.0))
    across, slope = s["width_mm"] * s["height_mm"] / along, g / normal
    volume = p["capacity"] * p["particle_volume_mm3"]
    if p["design_depth_mm"]:
        depth = p["design_depth_mm"]
    elif volume <= across * slope * along * along / 2:
        depth = math.sqrt(2 * volume * slope / across)
    else:
        depth = volume / (across * along) + slope * along / 2
    support = 2.6 * d
    k, drag = 10.18 * normal * depth / (support * support), p["drag_per_s"]
    waves = (2 * drag + math.sqrt(4 * drag * drag + 16 * k)) / (2 * k)
    return min(waves, d / (2 * p["max_speed_mm_s"]))
