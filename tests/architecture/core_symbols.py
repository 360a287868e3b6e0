#!/usr/bin/env python3
"""Checks that the core library (bleedsim::core) holds no file formats and no study.

A host simulator links the core alone: the simulation, the physics and both backends. Every symbol
of the archive, defined or needed, is listed with nm; any that belongs to HDF5, toml++, stb, the
scenario reader, the output writers or the study fails the check, with the object that has it.

Run: core_symbols.py path/to/libbleedsim_core.a
"""
import re
import subprocess
import sys

FORBIDDEN = {
    "HDF5": re.compile(r"\bH5[A-Z]\w*|\bH5T_\w+|hdf5", re.I),
    "toml++": re.compile(r"\btoml::"),
    "stb": re.compile(r"\bstbi_?\w*"),
    "the scenario reader": re.compile(r"bleedsim::(load|parse)_scenario\b"),
    "the output writers": re.compile(r"bleedsim::(Hdf5FrameWriter|write_png_rgba|ContactSheet)\b"),
    "the study": re.compile(r"bleedsim::(Study\w*|find_knob|knobs)\b"),
}


def main():
    archive = sys.argv[1]
    listing = subprocess.run(["nm", "-C", "-A", archive], capture_output=True, text=True, check=True).stdout
    symbols = 0
    problems = []
    for line in listing.splitlines():
        symbols += 1
        for what, pattern in FORBIDDEN.items():
            if pattern.search(line.split(":", 2)[-1]):
                problems.append(f"{what}: {line.strip()}")
    if symbols < 100:
        print(f"FAIL: only {symbols} symbols listed in {archive}: not the core library?")
        return 1
    for problem in problems[:20]:
        print("FAIL", problem)
    if problems:
        print(f"{len(problems)} symbols of libraries the core must not use")
        return 1
    print(f"ok: {symbols} symbols in {archive}, none of HDF5, toml++, stb, the scenario reader, "
          "the writers or the study")
    return 0


if __name__ == "__main__":
    sys.exit(main())
