#!/usr/bin/env python3
"""Checks that no source file includes from a floor above its own.

The floors are the table under "## Floors" in docs/architecture.md, read from there, so the docs and
the check cannot disagree: each row names a floor and its folders, lowest first. A file (.h, .cpp,
.cu) in a floor's folder may include files of its own floor and of the floors below; an include of a
file in a floor above fails, with the file, its line and both floors. Every folder of core/ must
belong to a floor, so a new folder is placed before it is used.

Run: floors.py ROOT           the tree at ROOT
     floors.py ROOT --self-test
                              that the check fails on an upward include: the tree's own files, with
                              one include added that goes up (core/physics/hd.h including
                              core/simulation/simulation.h), must give exactly that one failure
"""
import pathlib
import re
import sys

INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"')
SOURCES = (".h", ".cpp", ".cu")


def read_floors(root):
    """[(floor name, [folder, ...])], lowest first, from docs/architecture.md's "## Floors" table."""
    text = (root / "docs" / "architecture.md").read_text(encoding="utf-8")
    section = text.split("\n## Floors\n", 1)
    if len(section) != 2:
        sys.exit("floors: docs/architecture.md has no '## Floors' section")
    floors = []
    for line in section[1].splitlines():
        if line.startswith("## "):
            break
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if not line.startswith("|") or len(cells) < 2 or set(cells[0]) <= set("-: "):
            continue
        folders = re.findall(r"`([^`]+/)`", cells[1])
        if folders:
            floors.append((cells[0], folders))
    if not floors:
        sys.exit("floors: docs/architecture.md's '## Floors' table names no folders")
    return floors


def floor_of(path, floors):
    """The index of the floor whose folder holds `path` (the longest folder that does), or None."""
    best, level = "", None
    for index, (_, folders) in enumerate(floors):
        for folder in folders:
            if path.startswith(folder) and len(folder) > len(best):
                best, level = folder, index
    return level


def includes(root, floors):
    """{file: [(line number, included path)]} for every source file in a floor's folders."""
    found = {}
    for _, folders in floors:
        for folder in folders:
            for path in sorted((root / folder).rglob("*")):
                if path.suffix in SOURCES:
                    lines = path.read_text(encoding="utf-8").splitlines()
                    found[path.relative_to(root).as_posix()] = [
                        (n, m.group(1)) for n, line in enumerate(lines, 1) if (m := INCLUDE.match(line))]
    return found


def violations(found, floors):
    """One line for each include of a file on a floor above the including file's."""
    problems = []
    for path, lines in sorted(found.items()):
        own = floor_of(path, floors)
        for n, included in lines:
            theirs = floor_of(included, floors)
            if own is not None and theirs is not None and theirs > own:
                problems.append(f"{path}:{n}: includes {included}, on the {floors[theirs][0]} floor, above its own "
                                f"({floors[own][0]})")
    return problems


def unplaced(root, floors):
    """The folders of core/ that no floor names."""
    return [d.relative_to(root).as_posix() + "/" for d in sorted((root / "core").iterdir())
            if d.is_dir() and floor_of(d.relative_to(root).as_posix() + "/", floors) is None]


def main():
    root = pathlib.Path(sys.argv[1]).resolve()
    floors = read_floors(root)
    found = includes(root, floors)
    if "--self-test" in sys.argv[2:]:
        upward = ("core/physics/hd.h", "core/simulation/simulation.h")
        found.setdefault(upward[0], []).append((0, upward[1]))
        problems = violations(found, floors)
        expected = [p for p in problems if p.startswith(f"{upward[0]}:0: includes {upward[1]}")]
        if len(problems) != 1 or len(expected) != 1:
            print("floors self-test: an added upward include should be the one failure; got:\n  " +
                  "\n  ".join(problems or ["no failure"]))
            return 1
        print(f"floors self-test: the added include is caught: {expected[0]}")
        return 0
    problems = violations(found, floors) + [f"{d}: a folder of core/ on no floor (docs/architecture.md, "
                                            f"'## Floors')" for d in unplaced(root, floors)]
    for problem in problems:
        print(problem)
    count = sum(len(lines) for lines in found.values())
    print(f"floors: {len(floors)} floors, {len(found)} files, {count} includes; {len(problems)} problems")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
