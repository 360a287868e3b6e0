"""What the tests that run programs under mpirun share (tests/scaleout/mpi_check.py,
tests/study/study_ranks_check.py): their arguments, the environment mpirun needs in CI, commands
with a time limit, and a tally of expectations."""
import argparse
import os
import shutil
import subprocess
import sys


def arguments(program_flag, description):
    """--mpirun, --mpirun-flag (repeat), `program_flag`, --scratch (made empty) and
    --lsan-suppressions."""
    parser = argparse.ArgumentParser(description=description)
    parser.add_argument("--mpirun", required=True)
    parser.add_argument("--mpirun-flag", action="append", default=[], help="a flag for mpirun (repeat)")
    parser.add_argument(program_flag, required=True)
    parser.add_argument("--scratch", required=True)
    parser.add_argument("--lsan-suppressions")
    args = parser.parse_args()
    shutil.rmtree(args.scratch, ignore_errors=True)
    os.makedirs(args.scratch)
    return args


def environment(lsan_suppressions):
    # CI runs as root, which Open MPI's mpirun refuses unless told.
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    if lsan_suppressions:
        env["LSAN_OPTIONS"] = f"suppressions={lsan_suppressions}:print_suppressions=0"
        # Open MPI is built without frame pointers: the fast unwinder stops in its first frame, too
        # early to see which library allocated.
        env["ASAN_OPTIONS"] = ":".join(filter(None, [env.get("ASAN_OPTIONS"), "fast_unwind_on_malloc=0"]))
    return env


def run(command, env, limit_s):
    """Runs `command`, echoing it and its output; a hang (a rank waiting for another that will never
    answer) fails the test instead of holding CI."""
    print("$", " ".join(command), flush=True)
    try:
        done = subprocess.run(command, env=env, capture_output=True, text=True, timeout=limit_s)
    except subprocess.TimeoutExpired:
        print(f"FAIL: still running after {limit_s} s")
        sys.exit(1)
    sys.stdout.write(done.stdout)
    sys.stdout.write(done.stderr)
    return done


class Expectations:
    def __init__(self):
        self.failures = []

    def expect(self, condition, what):
        print(("ok   " if condition else "FAIL ") + what, flush=True)
        if not condition:
            self.failures.append(what)

    def verdict(self):
        if self.failures:
            print(f"{len(self.failures)} check(s) failed")
            return 1
        print("all checks passed")
        return 0
