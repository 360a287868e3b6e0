# README.md's Python example, the shell lines under "## From Python" as they are, runs: from the tree,
# with this build's module where the README names build/default's (the folder the two README commands
# build), and prints what it says.
import os
import re
import subprocess

from conftest import SOURCE

README_MODULE = "PYTHONPATH=build/default/python"


def readme_example():
    section = (SOURCE / "README.md").read_text().split("## From Python\n", 1)[1].split("\n## ", 1)[0]
    blocks = re.findall(r"```sh\n(.*?)```\n", section, re.S)
    assert len(blocks) == 1
    return blocks[0]


def test_the_readme_example_runs_and_prints_the_frame():
    example = readme_example()
    assert example.count(README_MODULE) == 1
    module = os.environ["PYTHONPATH"]
    done = subprocess.run(["bash", "-euo", "pipefail", "-c", example.replace(README_MODULE, f"PYTHONPATH={module}")],
                          cwd=SOURCE, capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    last = done.stdout.rstrip().splitlines()[-1]  # the progress line, overwritten in place, then the print
    assert last.startswith("frame 30/30 (480, 640, 4) ['spread/stain', "), last
