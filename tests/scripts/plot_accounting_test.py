#!/usr/bin/python3
"""Checks scripts/plot-accounting on a small frames.h5 made here, and on broken variants of it:

- a five-count accounting (a scene with suction) with the particle volume in the scenario text
  plots, exit 0, and the same file plots to the same bytes twice;
- a four-count one plots too;
- no accounting, an accounting of the wrong shape, a file that is not HDF5, a scenario text that
  does not parse: exit 2, a message naming the file, and no PNG (not even a partial one).

Run: /usr/bin/python3 tests/scripts/plot_accounting_test.py [repo root]
"""
import pathlib
import subprocess
import sys
import tempfile

import h5py
import numpy as np


def make(path, counts, text='[particles]\nparticle_volume_mm3 = 0.004\n', with_time=True):
    with h5py.File(path, "w") as f:
        if counts is not None:
            f["particles/accounting"] = np.asarray(counts, dtype=np.uint64)
        if with_time:
            f["time"] = (np.arange(len(counts if counts is not None else [0, 0])) + 1) / 30.0
        f.attrs["scenario_text"] = text
        f.attrs["scene_name"] = "fixture"


def plot(root, frames, out):
    return subprocess.run([str(root / "scripts" / "plot-accounting"), str(frames), "--out", str(out)],
                          capture_output=True, text=True)


def main():
    root = pathlib.Path(sys.argv[1]) if len(sys.argv) > 1 else pathlib.Path(__file__).resolve().parents[2]
    failures = []
    with tempfile.TemporaryDirectory() as tmp:
        tmp = pathlib.Path(tmp)
        five = [[10 * k, 10 * k - 3 * k, 0, 0, 3 * k] for k in range(1, 31)]
        four = [[10 * k, 10 * k, 0, 0] for k in range(1, 31)]
        cases = {"five": (five, None), "four": (four, None)}
        for name, (counts, _) in cases.items():
            make(tmp / f"{name}.h5", counts)
            first, second = plot(root, tmp / f"{name}.h5", tmp / f"{name}-1.png"), plot(root, tmp / f"{name}.h5", tmp / f"{name}-2.png")
            if first.returncode != 0 or not (tmp / f"{name}-1.png").exists():
                failures.append(f"{name}: exit {first.returncode}, {first.stderr.strip()}")
            elif (tmp / f"{name}-1.png").read_bytes() != (tmp / f"{name}-2.png").read_bytes():
                failures.append(f"{name}: the same file gave different PNG bytes")
        make(tmp / "none.h5", None)
        make(tmp / "shape.h5", [[1, 1, 0], [2, 2, 0]])
        (tmp / "text.h5").write_text("not HDF5")
        make(tmp / "toml.h5", four, text="[particles\n")
        for name in ("none", "shape", "text", "toml"):
            out = tmp / f"{name}.png"
            result = plot(root, tmp / f"{name}.h5", out)
            leftovers = list(tmp.glob(f"{name}.png*"))
            if result.returncode != 2 or f"{name}.h5" not in result.stderr or leftovers:
                failures.append(f"{name}: exit {result.returncode} (want 2), stderr {result.stderr.strip()!r}, "
                                f"left {[p.name for p in leftovers]}")
    for failure in failures:
        print(f"FAIL {failure}")
    print("ok" if not failures else f"{len(failures)} failed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
