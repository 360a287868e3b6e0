#!/usr/bin/env python3
"""Runs the tests that read the source tree or run a command, as the GPU machine runs them
(scripts/gpu-check): the tree copied to another folder and named by BLEEDSIM_SOURCE_DIR, the
original out of sight, and no HDF5 command-line tools (the bundle has none). A test that reads the
source path compiled into it, or runs a tool only a development machine has, fails here (issue 38,
item 17: four tests failed on the GPU machine this way, one with exit 127).

The original is hidden in a mount namespace of this check's own (unshare --user --map-root-user
--mount): an empty tmpfs over each of its folders but the one holding the build. Where user
namespaces are not allowed the check skips (exit 77).

Which tests: those of every test file that names source_dir(), python() or runs a shell command,
or includes a helper that does; the slow ones (--skip) left out.

Run: source_elsewhere_check.py --source DIR --build DIR --scratch DIR --binary PATH... [--skip-list 'A.b;C.d']
"""
import argparse
import os
import re
import shlex
import shutil
import subprocess
import sys

SKIPPED = 77
READS_THE_TREE_OR_RUNS = re.compile(r"source_dir\(\)|BLEEDSIM_SOURCE_DIR|python\(\)|run_shell\(|run_cli\(|std::system\(")
TEST_SUITE = re.compile(r"\bTEST(?:_F|_P)?\(\s*(\w+)\s*,")
INCLUDE = re.compile(r'#include "(tests/[^"]+)"')


def test_files(source):
    """Every .cpp and .h under tests/, by its path from the source root."""
    found = {}
    for folder, _, names in os.walk(os.path.join(source, "tests")):
        for name in names:
            if name.endswith((".cpp", ".h")):
                path = os.path.join(folder, name)
                with open(path, encoding="utf-8") as f:
                    found[os.path.relpath(path, source)] = f.read()
    return found


def suites_to_run(source):
    """The suites of the test files that read the tree or run a command, themselves or through the
    helpers they include."""
    files = test_files(source)
    reading = {path for path, text in files.items() if READS_THE_TREE_OR_RUNS.search(text)}
    grew = True
    while grew:
        more = {path for path, text in files.items() if set(INCLUDE.findall(text)) & reading} - reading
        reading |= more
        grew = bool(more)
    return sorted({suite for path in reading for suite in TEST_SUITE.findall(files[path])})


def is_build_folder(source, path):
    """A CMake build folder (any preset's, not only the one under test), or the presets' build/ at
    the top of the tree: their test outputs hold named pipes, and sparse files a copy fills out."""
    return os.path.exists(os.path.join(path, "CMakeCache.txt")) or path == os.path.join(source, "build")


def copy_of_tree(source, build, scratch):
    """The source tree without .git and any build folder, in scratch/elsewhere."""
    copy = os.path.join(scratch, "elsewhere")
    build = os.path.realpath(build)
    shutil.copytree(source, copy, ignore=lambda folder, names: [
        n for n in names if n == ".git" or os.path.realpath(os.path.join(folder, n)) == build
        or is_build_folder(source, os.path.join(folder, n))])
    return copy


def hiding_script(source, build, commands):
    """Shell lines that hide the original tree's folders (but the build's) and h5dump, then run
    `commands`, failing if any fails."""
    build = os.path.realpath(build)
    lines = ["set -u", "status=0"]
    for name in sorted(os.listdir(source)):
        path = os.path.realpath(os.path.join(source, name))
        if os.path.isdir(path) and not (build + os.sep).startswith(path + os.sep):
            lines.append(f"mount -t tmpfs none {shlex.quote(path)}")
    h5dump = shutil.which("h5dump")
    if h5dump:
        lines.append(f"mount --bind /dev/null {shlex.quote(os.path.realpath(h5dump))}")
    lines += [" ".join(map(shlex.quote, command)) + " || status=1" for command in commands]
    lines.append("exit $status")
    return "\n".join(lines) + "\n"


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--source", required=True)
    parser.add_argument("--build", required=True)
    parser.add_argument("--scratch", required=True)
    parser.add_argument("--binary", action="append", required=True, help="a test executable (repeat)")
    parser.add_argument("--skip-list", default="", help="the tests left out, Suite.Name, separated by ';'")
    args = parser.parse_args()
    source = os.path.realpath(args.source)
    if subprocess.run(["unshare", "--user", "--map-root-user", "--mount", "true"],
                      capture_output=True).returncode != 0:
        print("skipped: unshare cannot make a user and mount namespace here")
        return SKIPPED
    shutil.rmtree(args.scratch, ignore_errors=True)
    os.makedirs(args.scratch)
    copy = copy_of_tree(source, args.build, args.scratch)
    suites = suites_to_run(source)
    gtest_filter = ":".join(f"*{suite}.*" for suite in suites) + "-" + ":".join(args.skip_list.split(";"))
    print(f"{len(suites)} suites, the tree at {copy}, {source} hidden: {' '.join(suites)}", flush=True)
    commands = [[binary, "--gtest_color=no", f"--gtest_filter={gtest_filter}"] for binary in args.binary]
    script = os.path.join(args.scratch, "hidden.sh")
    with open(script, "w") as f:
        f.write(hiding_script(source, args.build, commands))
    env = dict(os.environ, BLEEDSIM_SOURCE_DIR=copy)
    done = subprocess.run(["unshare", "--user", "--map-root-user", "--mount", "sh", script], env=env,
                          stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    kept = [line for line in done.stdout.splitlines()
            if not line.startswith(("[ RUN", "[       OK", "Note: Google Test filter"))]
    print("\n".join(kept))
    print("ok" if done.returncode == 0 else "FAIL: a test needs the tree where it was built, or a tool the GPU "
          "machine lacks")
    return 0 if done.returncode == 0 else 1


if __name__ == "__main__":
    sys.exit(main())
