#!/usr/bin/python3
"""Checks a bleedsim HDF5 output file the way a user sees it through h5py.

    /usr/bin/python3 tests/check_hdf5_layout.py FILE [--frames N] [--fields a,b]
                                                [--width W --height H] [--arrays c,d]
                                                [--haptics TICKS [--max-force F]]

--fields names image fields, (T, H, W[, C]); --arrays names fields that are not images:
per-element arrays such as particle state or counters, (T, N[, C]), with no image attributes.
--haptics expects the haptic channel of that many 1 kHz ticks under /haptics, and checks what any
channel must hold: tick n at n / 1000 s; the force along the surface normal only, within
[0, --max-force] N (default the Falcon's 8.9 N), zero out of contact; cutting only in contact; and
/haptics/quality, the force's quality per contact, whose contacts, depths and peak forces must be the
channel's own.

The layout is docs/output-format.md. Prints one line per failed check and exits 1 on any
failure; otherwise prints a one-line summary and exits 0. Needs h5py and numpy (Debian's
python3-h5py installs them for /usr/bin/python3).
"""
import argparse
import sys

import h5py
import numpy as np

PROVENANCE = ("bleedsim_version", "git_sha", "backend", "device", "build_flags", "scenario_text")
FIELD_TYPES = (np.float32, np.uint8, np.uint32, np.uint64)
IMAGE_ATTRIBUTES = ("CLASS", "IMAGE_VERSION", "IMAGE_SUBCLASS", "INTERLACE_MODE",
                    "IMAGE_WHITE_IS_ZERO")
FRAME_IMAGE_ATTRIBUTES = {"CLASS": "IMAGE", "IMAGE_VERSION": "1.2",
                          "IMAGE_SUBCLASS": "IMAGE_TRUECOLOR", "INTERLACE_MODE": "INTERLACE_PIXEL"}


class Checker:
    def __init__(self):
        self.failures = []

    def expect(self, condition, message):
        if not condition:
            self.failures.append(message)
        return condition


def text(value):
    """An attribute as str: variable-length strings come back as str, fixed-length as bytes."""
    if isinstance(value, (bytes, np.bytes_)):
        return value.decode("ascii", errors="replace")
    return value if isinstance(value, str) else None


def dataset(check, file, path):
    node = file.get(path)
    if not check.expect(isinstance(node, h5py.Dataset), f"{path}: missing (or not a dataset)"):
        return None
    return node


def check_text_attribute(check, node, name, nonempty=True):
    value = text(node.attrs.get(name))
    if not check.expect(value is not None, f"{node.name}: attribute {name} missing or not text"):
        return
    if nonempty:
        check.expect(value != "", f"{node.name}: attribute {name} is empty")


def check_frame_chunks_and_filters(check, node):
    """Each frame one chunk, compressed with shuffle + gzip (any level the run chose)."""
    expected_chunks = (1,) + node.shape[1:]
    check.expect(node.chunks == expected_chunks,
                 f"{node.name}: chunks {node.chunks}, expected {expected_chunks}")
    check.expect(node.compression == "gzip",
                 f"{node.name}: compression {node.compression!r}, expected 'gzip'")
    check.expect(node.shuffle, f"{node.name}: no shuffle filter")
    check.expect(node.maxshape[0] is None, f"{node.name}: cannot grow along time")


def check_frame(check, file, args):
    """/frame: (T, H, W, 4) uint8, an image HDFView can show. Returns T, H, W."""
    frame = dataset(check, file, "/frame")
    if frame is None:
        return None
    if not check.expect(frame.ndim == 4 and frame.shape[3] == 4,
                        f"/frame: shape {frame.shape}, expected (T, H, W, 4)"):
        return None
    check.expect(frame.dtype == np.uint8, f"/frame: type {frame.dtype}, expected uint8")
    for name, expected in FRAME_IMAGE_ATTRIBUTES.items():
        value = text(frame.attrs.get(name))
        check.expect(value == expected, f"/frame: attribute {name} is {value!r}, expected {expected!r}")
    check_frame_chunks_and_filters(check, frame)

    frames, height, width = frame.shape[:3]
    for given, actual, what in ((args.frames, frames, "frames"), (args.height, height, "height"),
                                (args.width, width, "width")):
        if given is not None:
            check.expect(given == actual, f"/frame: {actual} {what}, expected {given}")
    return frames, height, width


def check_time(check, file, frames):
    time = dataset(check, file, "/time")
    if time is None:
        return
    if not check.expect(time.ndim == 1 and time.dtype == np.float64,
                        f"/time: {time.dtype} {time.shape}, expected float64 (T,)"):
        return
    if frames is not None:
        check.expect(time.shape[0] == frames, f"/time: {time.shape[0]} entries for {frames} frames")
    check.expect(text(time.attrs.get("unit")) == "s",
                 f"/time: unit {time.attrs.get('unit')!r}, expected 's'")
    values = time[()]
    check.expect(bool(np.all(np.diff(values) > 0)), "/time: not strictly increasing")


def check_field(check, file, name, shape):
    node = dataset(check, file, "/" + name)
    if node is None:
        return
    check.expect(node.dtype in FIELD_TYPES,
                 f"{node.name}: type {node.dtype}, expected float32, uint8, uint32 or uint64")
    if shape is not None:
        check.expect(node.shape == shape, f"{node.name}: shape {node.shape}, expected {shape}")
    elif not check.expect(node.ndim == 3, f"{node.name}: shape {node.shape}, expected (T, H, W)"):
        return
    check_text_attribute(check, node, "unit", nonempty=False)  # "" is a fine unit for a count
    check_text_attribute(check, node, "description")
    check_frame_chunks_and_filters(check, node)


def check_array(check, file, name, frames):
    """A field that is not an image: (T, N) or (T, N, C), one frame per chunk, no image attributes."""
    node = dataset(check, file, "/" + name)
    if node is None:
        return
    check.expect(node.dtype in FIELD_TYPES,
                 f"{node.name}: type {node.dtype}, expected float32, uint8, uint32 or uint64")
    if not check.expect(node.ndim in (2, 3),
                        f"{node.name}: shape {node.shape}, expected (T, N) or (T, N, C)"):
        return
    if frames is not None:
        check.expect(node.shape[0] == frames,
                     f"{node.name}: {node.shape[0]} frames, but /frame holds {frames}")
    check_text_attribute(check, node, "unit", nonempty=False)
    check_text_attribute(check, node, "description")
    for attribute in IMAGE_ATTRIBUTES:
        check.expect(attribute not in node.attrs,
                     f"{node.name}: has image attribute {attribute}, but is not an image")
    check_frame_chunks_and_filters(check, node)


HAPTIC_COLUMNS = {"time": (np.float64, ()), "tool_position": (np.float64, (3,)),
                  "panel_position": (np.float64, (2,)), "buttons": (np.uint8, ()), "contact": (np.uint8, ()),
                  "penetration": (np.float64, ()), "force": (np.float64, (3,)), "cutting": (np.uint8, ())}


def check_haptics(check, file, ticks, max_force):
    columns = {}
    for name, (dtype, row) in HAPTIC_COLUMNS.items():
        node = dataset(check, file, "/haptics/" + name)
        if node is None:
            return
        if not check.expect(node.dtype == dtype and node.shape == (ticks,) + row,
                            f"{node.name}: {node.dtype} {node.shape}, expected {np.dtype(dtype)} {(ticks,) + row}"):
            return
        check_text_attribute(check, node, "unit", nonempty=False)
        check_text_attribute(check, node, "description")
        columns[name] = node[()]
    check.expect(np.array_equal(columns["time"], np.arange(ticks) / 1000.0), "/haptics/time: not n / 1000 s")
    force, contact = columns["force"], columns["contact"].astype(bool)
    check.expect(not force[:, :2].any(), "/haptics/force: has components across the surface normal")
    check.expect(force[:, 2].min() >= 0 and force[:, 2].max() <= max_force,
                 f"/haptics/force: {force[:, 2].min()} to {force[:, 2].max()} N, outside [0, {max_force}] N")
    check.expect(not force[~contact].any() and not columns["penetration"][~contact].any(),
                 "/haptics: force or penetration out of contact")
    check.expect(not (columns["cutting"].astype(bool) & ~contact).any(), "/haptics/cutting: cuts out of contact")
    check_quality(check, file, columns)


QUALITY_PER_CONTACT = {"first_tick": (np.int64, ()), "last_tick": (np.int64, ()), "released": (np.int64, ()),
                       "max_penetration": (np.float64, ()), "peak_force": (np.float64, ()),
                       "rise_time": (np.float64, ()), "force_rate": (np.float64, (3,)),
                       "oscillation_rms": (np.float64, ()), "oscillation_share": (np.float64, ()),
                       "overshoot": (np.float64, ()), "margin_end": (np.float64, ()), "worst_margin": (np.float64, ()),
                       "worst_margin_tick": (np.int64, ()), "ticks_at_force_limit": (np.int64, ()),
                       "unavailable": (object, ())}
QUALITY_ATTRIBUTES = ("cutoff_hz", "stiffness_N_per_m", "max_force_N", "device_damping_Ns_per_m")
QUALITY_OPTIONAL = {"rise_time": "rise_time", "oscillation_rms": "oscillation_rms",
                    "oscillation_share": "oscillation_share", "worst_margin": "worst_margin"}


def contact_runs(contact):
    """The contacts as the docs define them: maximal runs of ticks in contact, (first, last)."""
    edges = np.diff(np.concatenate(([0], contact.astype(np.int8), [0])))
    return list(zip(np.flatnonzero(edges == 1), np.flatnonzero(edges == -1) - 1))


def check_quality(check, file, columns):
    """/haptics/quality against the channel beside it: its contacts are the channel's runs of contact,
    their depth and peak force the channel's largest, the margin zero out of contact, a metric NaN
    exactly where the contact says why it lacks it."""
    group = file.get("/haptics/quality")
    if not check.expect(isinstance(group, h5py.Group), "/haptics/quality: missing (or not a group)"):
        return
    for name in QUALITY_ATTRIBUTES:
        check.expect(np.isscalar(group.attrs.get(name)), f"/haptics/quality: attribute {name} missing")
    runs = contact_runs(columns["contact"].astype(bool))
    q = {}
    for name, (dtype, row) in QUALITY_PER_CONTACT.items():
        node = dataset(check, file, "/haptics/quality/" + name)
        if node is None:
            return
        if not check.expect((node.dtype == dtype or (dtype is object and node.dtype.kind == "O"))
                            and node.shape == (len(runs),) + row,
                            f"{node.name}: {node.dtype} {node.shape}, expected {(len(runs),) + row} for "
                            f"{len(runs)} contacts"):
            return
        q[name] = node[()]
    margin = dataset(check, file, "/haptics/quality/margin")
    ticks = columns["time"].size
    if margin is None or not check.expect(margin.shape == (ticks,), f"{margin.name}: {margin.shape}, expected ({ticks},)"):
        return
    margin = margin[()]
    contact = columns["contact"].astype(bool)
    check.expect(not margin[~contact].any(), "/haptics/quality/margin: non-zero out of contact")
    check.expect([(int(a), int(b)) for a, b in zip(q["first_tick"], q["last_tick"])] == [(int(a), int(b)) for a, b in runs],
                 "/haptics/quality: first_tick/last_tick are not the channel's runs of contact")
    force = np.linalg.norm(columns["force"], axis=1)
    for i, (a, b) in enumerate(runs):
        check.expect(q["max_penetration"][i] == columns["penetration"][a:b + 1].max(),
                     f"/haptics/quality/max_penetration[{i}]: not the contact's deepest tick")
        check.expect(q["peak_force"][i] == force[a:b + 1].max(), f"/haptics/quality/peak_force[{i}]: not its largest force")
        check.expect(bool(q["released"][i]) == (b + 1 < ticks), f"/haptics/quality/released[{i}]: wrong")
        check.expect(q["force_rate"][i][0] <= q["force_rate"][i][1] <= q["force_rate"][i][2],
                     f"/haptics/quality/force_rate[{i}]: p50, p99, max out of order")
        why = text(q["unavailable"][i]) or ""
        for name, label in QUALITY_OPTIONAL.items():
            check.expect(np.isnan(q[name][i]) == (label + ":" in why),
                         f"/haptics/quality/{name}[{i}]: NaN where no reason is given, or a reason for a value")


def check_root(check, file, frames):
    for name in PROVENANCE:
        check_text_attribute(check, file["/"], name)
    complete = file.attrs.get("complete")
    check.expect(complete is not None and int(complete) == 1, f"/: complete is {complete!r}, expected 1")
    written = file.attrs.get("frames_written")
    if frames is not None:
        check.expect(written is not None and int(written) == frames,
                     f"/: frames_written is {written!r}, but /frame holds {frames} frames")


def check_file(path, args):
    check = Checker()
    try:
        file = h5py.File(path, "r")
    except OSError as error:
        return [f"{path}: cannot open as HDF5 ({error})"], None
    with file:
        shape = check_frame(check, file, args)
        frames = shape[0] if shape else None
        check_time(check, file, frames)
        for field in args.fields:
            check_field(check, file, field, shape)
        for array in args.arrays:
            check_array(check, file, array, frames)
        if args.haptics is not None:
            check_haptics(check, file, args.haptics, args.max_force)
        else:
            check.expect("haptics" not in file, "/haptics: present, but no haptic channel was expected")
        check_root(check, file, frames)
    return check.failures, shape


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("file")
    parser.add_argument("--frames", type=int, help="expected number of frames")
    parser.add_argument("--fields", default="",
                        help="comma-separated fields expected besides /frame, e.g. spread/stain")
    parser.add_argument("--width", type=int, help="expected frame width in pixels")
    parser.add_argument("--height", type=int, help="expected frame height in pixels")
    parser.add_argument("--arrays", default="",
                        help="comma-separated fields expected that are not images (per-element "
                             "arrays, (T, N[, C])), e.g. particles/position")
    parser.add_argument("--haptics", type=int, help="expected haptic ticks under /haptics")
    parser.add_argument("--max-force", type=float, default=8.9, help="the force cap, N (default 8.9)")
    args = parser.parse_args()
    args.fields = [field.strip("/") for field in args.fields.split(",") if field.strip()]
    args.arrays = [array.strip("/") for array in args.arrays.split(",") if array.strip()]

    failures, shape = check_file(args.file, args)
    for failure in failures:
        print(f"FAIL {failure}")
    if failures:
        return 1
    frames, height, width = shape
    fields = ", ".join(args.fields) if args.fields else "no fields"
    arrays = f"; arrays {', '.join(args.arrays)}" if args.arrays else ""
    haptics = f"; {args.haptics} haptic ticks" if args.haptics is not None else ""
    print(f"OK {args.file}: {frames} frames of {width}x{height}, {fields}{arrays}{haptics}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
