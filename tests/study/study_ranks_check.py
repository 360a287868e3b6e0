#!/usr/bin/env python3
"""bleedsim study over MPI ranks and over shards gives one process's data, bit for bit (issue 18):

1. the same small study in one process, under `mpirun -n 1` and under `mpirun -n 2`;
2. the same study as three shards (0/3 in one process, 1/3 over two ranks, 2/3 under `mpirun -n 1`)
   and `bleedsim study merge`;
each must equal the single process in every dataset and attribute of study.h5 outside /timing, in
study.csv without its time_* columns, and in ladders.csv. jobs.csv (provenance) must show both
ranks of the two-rank run. That the comparison can fail is shown on a study with other seeds.

Run: study_ranks_check.py --bleedsim CLI --mpirun MPIRUN --scratch DIR [--mpirun-flag FLAG ...]
                          [--lsan-suppressions FILE]
"""
import csv
import glob
import os
import sys

import h5py
import numpy as np

sys.dont_write_bytecode = True  # no __pycache__ in the source tree
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scaleout"))
from mpi_harness import Expectations, arguments, environment, run as run_limited  # noqa: E402

LIMIT_S = 300
SCENE = """[scene]
name = "tiny"
width_px = 32
height_px = 24
width_mm = 8.0
height_mm = 6.0
duration_s = 0.2
[spread]
radius_mm = 2.0
[particles]
capacity = 1024
flow_mm3_per_s_per_mm = 3.2
[blur]
[[cut]]
x_mm = 4.0
y_mm = 2.0
"""
STUDY = ["--backend", "cpu", "--threads", "1", "--knob", "resolution=0.5,1", "--knob", "substeps=190,380",
         "--no-plots", "--quiet"]


def run(command, env):
    return run_limited(command, env, LIMIT_S)


def h5_contents(path):
    """Every dataset's bytes and every attribute outside /timing, by name."""
    contents = {}

    def take(name, obj):
        if name == "timing" or name.startswith("timing/"):
            return
        for key, value in obj.attrs.items():
            contents[f"{name}@{key}"] = np.asarray(value).tobytes()
        if isinstance(obj, h5py.Dataset):
            contents[name] = (obj.dtype.str, obj.shape, np.asarray(obj[()]).tobytes())

    with h5py.File(path, "r") as f:
        for key, value in f.attrs.items():
            contents[f"@{key}"] = np.asarray(value).tobytes()
        f.visititems(take)
    return contents


def csv_without_timings(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    keep = [i for i, name in enumerate(rows[0]) if not name.startswith("time_")]
    return [[row[i] for i in keep] for row in rows]


def study_data(folder):
    with open(os.path.join(folder, "ladders.csv"), "rb") as f:
        ladders = f.read()
    return h5_contents(os.path.join(folder, "study.h5")), csv_without_timings(os.path.join(folder, "study.csv")), ladders


def differences(a, b):
    h5a, csva, la = a
    h5b, csvb, lb = b
    found = [name for name in sorted(set(h5a) | set(h5b)) if h5a.get(name) != h5b.get(name)]
    if csva != csvb:
        found.append("study.csv (timings aside)")
    if la != lb:
        found.append("ladders.csv")
    return found


def main():
    args = arguments("--bleedsim", "bleedsim study over MPI ranks and shards")
    scratch = args.scratch
    scene = os.path.join(scratch, "tiny.toml")
    with open(scene, "w") as f:
        f.write(SCENE)
    env = environment(args.lsan_suppressions)

    def mpirun(n, *rest):
        return [args.mpirun, "-n", str(n), *args.mpirun_flag, args.bleedsim, *rest]

    tally = Expectations()
    expect = tally.expect

    def study(command, out):
        done = run(command + ["--out", out], env)
        expect(done.returncode == 0, " ".join(command[:4]) + " ends with exit 0")
        return done.returncode == 0

    alone = os.path.join(scratch, "alone")
    if not study([args.bleedsim, "study", scene, "--seeds", "3", *STUDY], alone):
        return 1
    reference = study_data(alone)

    for n in (1, 2):
        out = os.path.join(scratch, f"ranks-{n}")
        if study(mpirun(n, "study", scene, "--seeds", "3", *STUDY), out):
            found = differences(reference, study_data(out))
            expect(not found, f"mpirun -n {n} gives one process's data bit for bit (differs: {found[:5]})")
            with open(os.path.join(out, "jobs.csv"), newline="") as f:
                ranks = sorted({row["rank"] for row in csv.DictReader(f)})
            expect(ranks == [str(r) for r in range(n)], f"jobs.csv names the {n} rank(s) that ran the jobs ({ranks})")

    shards = os.path.join(scratch, "shards")
    shard_study = ["study", scene, "--seeds", "3", *STUDY, "--shard"]
    study([args.bleedsim, *shard_study, "0/3"], shards)
    study(mpirun(2, *shard_study, "1/3"), shards)
    study(mpirun(1, *shard_study, "2/3"), shards)
    files = sorted(glob.glob(os.path.join(shards, "*.bleedshard")))
    expect(len(files) == 3, f"three shard files written ({len(files)})")
    merged = os.path.join(scratch, "merged")
    if study([args.bleedsim, "study", "merge", *reversed(files), "--no-plots", "--quiet"], merged):
        found = differences(reference, study_data(merged))
        expect(not found, f"the merged shards give one process's data bit for bit (differs: {found[:5]})")

    # The comparison sees a difference where there is one: a study with a fourth seed.
    other = os.path.join(scratch, "other-seeds")
    if study([args.bleedsim, "study", scene, "--seeds", "4", *STUDY], other):
        expect(differences(reference, study_data(other)), "a study with other seeds is told apart")

    return tally.verdict()


if __name__ == "__main__":
    sys.exit(main())
