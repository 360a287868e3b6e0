#!/usr/bin/env python3
"""run_jobs over real MPI ranks (tests/scaleout/mpi_check.cpp under mpirun):

1. `mpirun -n 2` gathers on rank 0 exactly what one process makes, bit for bit (the records
   are 0 bytes to 3 MiB, sent in 64 KiB pieces), and so does `mpirun -n 1`;
2. a job that throws on rank 1 ends both ranks with exit 1, rank 0 printing the failure, and
   rank 0 stops before running all of its own jobs; nothing hangs;
3. when rank 0 alone refuses to start (its output folder taken), both ranks end with exit 2
   and neither runs a job;
4. shards 0/3 (one process), 1/3 (over two ranks) and 2/3 (`mpirun -n 1`), merged, equal the
   single process's records.

Run: mpi_check.py --mpirun MPIRUN --check MPI_CHECK --scratch DIR [--mpirun-flag FLAG ...]
                  [--lsan-suppressions FILE]
Every command has a time limit: a hang fails the test instead of holding CI. In a sanitizer build,
LeakSanitizer is given FILE (what Open MPI's runtime never frees) and full stacks to match it on.
"""
import os
import re
import sys

sys.dont_write_bytecode = True  # no __pycache__ in the source tree
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from mpi_harness import Expectations, arguments, environment, run as run_limited  # noqa: E402

LIMIT_S = 120


def run(command, env):
    return run_limited(command, env, LIMIT_S)


def same_bytes(a, b):
    with open(a, "rb") as fa, open(b, "rb") as fb:
        return fa.read() == fb.read()


def main():
    args = arguments("--check", "run_jobs over real MPI ranks")
    scratch = args.scratch
    env = environment(args.lsan_suppressions)

    def mpirun(n, *rest):
        return [args.mpirun, "-n", str(n), *args.mpirun_flag, args.check, *rest]

    tally = Expectations()
    expect = tally.expect

    # 1. One process, then one and two ranks: the same bytes.
    alone = os.path.join(scratch, "alone.dump")
    done = run([args.check, "run", alone], env)
    expect(done.returncode == 0 and os.path.exists(alone), "one process without mpirun gathers every job")
    for n in (1, 2):
        dump = os.path.join(scratch, f"ranks-{n}.dump")
        done = run(mpirun(n, "run", dump), env)
        expect(done.returncode == 0 and os.path.exists(dump), f"mpirun -n {n} ends with exit 0 and rank 0's file")
        expect(os.path.exists(dump) and same_bytes(alone, dump), f"mpirun -n {n} gives one process's records bit for bit")
        if n == 2:
            expect(f"from 2 of 2 ranks" in done.stdout, "both ranks ran jobs")

    # 2. A job that throws on rank 1.
    done = run(mpirun(2, "fail"), env)
    output = done.stdout + done.stderr
    expect(done.returncode != 0, "a failed job ends mpirun with a non-zero exit")
    expect(re.search(r"job \d+ on rank 1 of 2 \(host [^)]*\): toy job \d+ refused on purpose", output) is not None,
           "rank 0 prints the failed job, its rank and host, and its message")
    for rank in (0, 1):
        expect(re.search(rf"rank {rank} of 2: exit 1 after", output) is not None, f"rank {rank} ends with exit 1")
    stopped = re.search(r"rank 0 of 2: exit 1 after (\d+) of its (\d+) jobs", output)
    expect(stopped is not None and int(stopped.group(1)) < int(stopped.group(2)),
           "rank 0 stops before the end of its own jobs once rank 1 has failed")

    # 3. Rank 0 alone refuses before the jobs.
    done = run(mpirun(2, "refuse"), env)
    output = done.stdout + done.stderr
    expect(done.returncode != 0, "a refusal on rank 0 ends mpirun with a non-zero exit")
    for rank in (0, 1):
        expect(f"rank {rank} of 2: exit 2 after 0 jobs" in output, f"rank {rank} ends with exit 2 without running a job")

    # 4. Three shards, written apart (one of them over two ranks), then merged.
    shards = os.path.join(scratch, "shards")
    os.makedirs(shards)
    for command in ([args.check, "shard", "0/3", shards], mpirun(2, "shard", "1/3", shards), mpirun(1, "shard", "2/3", shards)):
        done = run(command, env)
        expect(done.returncode == 0, "shard " + command[-2] + " written")
    expect(sorted(os.listdir(shards)) == [f"shard-{i}-of-3.bleedshard" for i in range(3)],
           "the shard folder holds the three shard files and nothing else")
    merged = os.path.join(scratch, "merged.dump")
    done = run([args.check, "merge", shards, merged], env)
    expect(done.returncode == 0 and os.path.exists(merged) and same_bytes(alone, merged),
           "the merged shards give one process's records bit for bit")

    return tally.verdict()


if __name__ == "__main__":
    sys.exit(main())
