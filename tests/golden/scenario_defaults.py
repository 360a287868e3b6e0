"""A scenario as bleedsim reads it: what each table leaves out, filled in from the parameter tables.

The defaults come from `bleedsim params --json` (the tables in core/ that the scenario reader, the
checks and the docs read), never from a copy here. What this file adds is only the documented way
some defaults follow from other keys (docs/scenario-format.md, each key's default column):
fade_s = min(its default, lifetime_s); sigma_px = max(0.5, radius_px / 2); the haptic origin at
the panel's centre; a rate given as volume_mm3_per_s / particle_volume_mm3; a cut's wound from
[spread] and [particles].
"""
import json
import subprocess

TABLES = ("scene", "spread", "particles", "blur", "haptics")


def load_params(bleedsim):
    """{table: {key: parameter}} from `bleedsim params --json`."""
    printed = subprocess.run([bleedsim, "params", "--json"], capture_output=True, text=True, check=True).stdout
    return {t["name"]: {p["key"]: p for p in t["params"]} for t in json.loads(printed)["tables"]}


def defaults(params, table):
    """The struct's default of every key of `table` that has one."""
    return {key: p["default"] for key, p in params[table].items() if p["default"] is not None}


def read_scenario(parsed, params):
    """The parsed TOML (a dict), with every declared table's and every cut's defaults filled in."""
    written = {table: set(parsed[table]) for table in TABLES if table in parsed}
    scenario = dict(parsed)
    for table in written:
        scenario[table] = {**defaults(params, table), **parsed[table]}
    if "particles" in scenario:
        p = scenario["particles"]
        if "volume_mm3_per_s" in p:
            p["rate_per_s"] = p["volume_mm3_per_s"] / p["particle_volume_mm3"]
        if "fade_s" not in written["particles"]:
            p["fade_s"] = min(p["fade_s"], p["lifetime_s"])
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
            "rate_per_s": flow["rate_per_s"], "bleed_s": flow["bleed_s"], **cut}
