#!/usr/bin/env python3
"""The key tables of docs/scenario-format.md are generated from the parameter tables in core/.

`bleedsim params --markdown` prints one block per scenario table, and one of the former keys, each
between `<!-- params: NAME ... -->` and `<!-- /params -->`. This checks that the document holds each
block exactly as printed (and no block of a table that no longer exists), or, with --write, puts them
there (scripts/update-param-docs). It also checks that the document's complete example, which sets
every key, is a scenario `bleedsim validate` accepts.

Run: param_docs.py --bleedsim PATH --doc docs/scenario-format.md [--write]
"""
import argparse
import pathlib
import re
import shutil
import subprocess
import sys
import tempfile

BLOCK = re.compile(r"^<!-- params: (\S+).*?^<!-- /params -->\n", re.S | re.M)


def blocks(text):
    return {m.group(1): m for m in BLOCK.finditer(text)}


def example_problems(bleedsim, doc_path, doc, tables):
    """The complete example: every key of every table is in it, and it validates (beside a copy of
    the texture it names, relative to scenarios/ as the document says)."""
    m = re.search(r"## A complete example.*?```toml\n(.*?)```", doc, re.S)
    if not m:
        return [f"{doc_path} has no '## A complete example' with a toml block"]
    example = m.group(1)
    problems = [f"the complete example does not set {name}.{key}" for name, keys in tables.items() for key in keys
                if not re.search(rf"^#? ?{re.escape(key)} = ", example, re.M)]
    with tempfile.TemporaryDirectory() as folder:
        textures = doc_path.resolve().parents[1] / "scenarios" / "textures"
        shutil.copytree(textures, pathlib.Path(folder) / "textures")
        (pathlib.Path(folder) / "example.toml").write_text(example)
        run = subprocess.run([bleedsim, "validate", str(pathlib.Path(folder) / "example.toml")],
                             capture_output=True, text=True)
        if run.returncode != 0:
            problems.append(f"the complete example does not validate: {run.stdout}{run.stderr}")
    return problems


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--bleedsim", required=True)
    parser.add_argument("--doc", required=True)
    parser.add_argument("--write", action="store_true")
    args = parser.parse_args()
    printed = subprocess.run([args.bleedsim, "params", "--markdown"], capture_output=True, text=True, check=True).stdout
    wanted = {name: m.group(0) for name, m in blocks(printed).items()}
    if not wanted:
        print(f"FAIL: `{args.bleedsim} params --markdown` printed no tables")
        return 1
    doc_path = pathlib.Path(args.doc)
    doc = doc_path.read_text()
    present = blocks(doc)
    problems = [f"{doc_path} has a block for [{name}], which no parameter table has" for name in present if name not in wanted]
    problems += [f"{doc_path} has no block for [{name}]: add a line '<!-- params: {name} -->' and "
                 "'<!-- /params -->' where its table goes" for name in wanted if name not in present]
    stale = [name for name, m in present.items() if name in wanted and m.group(0) != wanted[name]]
    keys = {name: re.findall(r"^\| `(\w+)` \|", block, re.M) for name, block in wanted.items()}
    keys.pop("haptics", None)   # its trace file is the example scenarios' business (docs/traces.md)
    keys.pop("former-keys", None)   # keys a file may no longer hold
    problems += example_problems(args.bleedsim, doc_path, doc, keys)
    if args.write and not problems:
        for name in sorted(stale, key=lambda n: present[n].start(), reverse=True):
            m = present[name]
            doc = doc[:m.start()] + wanted[name] + doc[m.end():]
        doc_path.write_text(doc)
        print(f"wrote {len(stale)} of {len(wanted)} tables in {doc_path}")
        return 0
    problems += [f"{doc_path}: the [{name}] table differs from `bleedsim params --markdown`; "
                 "run scripts/update-param-docs" for name in stale]
    for problem in problems:
        print("FAIL", problem)
    if not problems:
        print(f"ok: the {len(wanted)} key tables in {doc_path} are the parameter tables'")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
