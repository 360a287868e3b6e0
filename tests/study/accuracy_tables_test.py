#!/usr/bin/python3
"""Checks scripts/accuracy-tables on the fixture study (tests/study/fixtures/study/) and on edits of it.

- the fixture prints the four sections, one settings row per setting and the noise floor's, a ladder
  row per knob and metric, a check row per knob, and the reference row's verdict;
- the recommendations follow their rule: with every p99 past 33.3 ms nothing fits either budget;
  with one ladder setting at 0.5 ms whose error reaches the noise floor, it is the 1 ms budget's
  recommendation; with none reaching the floor, the most accurate that fits is named instead;
- a malformed study.csv exits 2 naming the file, line and column.

Run: /usr/bin/python3 tests/study/accuracy_tables_test.py [repo root]
"""
import csv
import io
import pathlib
import shutil
import subprocess
import sys
import tempfile

failures = []


def check(condition, what):
    print(("ok   " if condition else "FAIL ") + what)
    if not condition:
        failures.append(what)


def tables(root, folder):
    return subprocess.run([str(root / "scripts" / "accuracy-tables"), str(folder)], capture_output=True, text=True,
                          timeout=120)


def edited(directory, fixture, edit):
    """A copy of the fixture whose study.csv rows pass through edit(row) (a dict; returned changed)."""
    shutil.copytree(fixture, directory)
    reader = csv.DictReader(io.StringIO((fixture / "study.csv").read_text()))
    rows = [edit(dict(row)) for row in reader]
    out = io.StringIO()
    writer = csv.DictWriter(out, fieldnames=reader.fieldnames, lineterminator="\n")
    writer.writeheader()
    writer.writerows(rows)
    (directory / "study.csv").write_text(out.getvalue())
    return directory


def section(text, title):
    """The lines of one '#### title' section."""
    after = text.split(f"#### {title}\n", 1)[1]
    return after.split("####", 1)[0].strip().splitlines()


def main():
    root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).resolve().parents[2])
    fixture = root / "tests" / "study" / "fixtures" / "study"
    study = list(csv.DictReader(io.StringIO((fixture / "study.csv").read_text())))
    result = tables(root, fixture)
    check(result.returncode == 0 and not result.stderr, f"fixture: exit 0 ({result.stderr.strip()!r})")
    out = result.stdout
    for title in ("Settings", "Ladders", "The reference check", "Recommendations per budget"):
        check(f"#### {title}" in out, f"fixture: a section '{title}'")
    settings = [line for line in section(out, "Settings") if line.startswith("| ") and not line.startswith("| setting")]
    check(len(settings) == len(study), f"fixture: {len(study)} settings rows with the floor's (found {len(settings)})")
    check(settings[-1].startswith("| noise floor |"), "fixture: the noise floor last")
    ladders = list(csv.DictReader(io.StringIO((fixture / "ladders.csv").read_text())))
    pairs = {(r["knob"], r["metric"]) for r in ladders}
    ladder_rows = [line for line in section(out, "Ladders") if line.startswith("| ") and not line.startswith("| knob")]
    check(len(ladder_rows) == len(pairs), f"fixture: a ladder row per knob and metric ({len(pairs)})")
    checks = [line for line in section(out, "The reference check") if line.startswith("| ")
              and not line.startswith("| knob")]
    check(len(checks) == len({r["knob"] for r in ladders}), "fixture: a check row per knob")
    verdict = next(r["check"] for r in study if r["role"] == "reference")
    check(f"**Verdict:** {verdict}" in out, "fixture: the reference row's verdict")

    with tempfile.TemporaryDirectory(prefix="accuracy-tables-test-") as temporary:
        temporary = pathlib.Path(temporary)

        def slow(row):
            if row["time_ms_p99"]:
                row["time_ms_p50"], row["time_ms_p99"] = "50", "60"
            return row
        text = tables(root, edited(temporary / "slow", fixture, slow)).stdout
        check(text.count(":** none fits.") == 2, "every p99 past 33.3 ms: none fits either budget")

        floor = next(r for r in study if r["role"] == "noise_floor")

        def fast_one(row):
            row = slow(row)
            if row["knob"] == "resolution" and row["role"] == "ladder":
                row["time_ms_p50"], row["time_ms_p99"] = "0.4", "0.5"
                row["film_l1_mm_lo"] = floor["film_l1_mm"]
            return row
        text = tables(root, edited(temporary / "fast", fixture, fast_one)).stdout
        line = next(l for l in text.splitlines() if l.startswith("- **cpu, 1 ms haptic tick:**"))
        check("as good as the reference within the noise: resolution 0.5 (0.4 ms" in line, f"one fast setting: {line}")

        def far(row):
            row = fast_one(row)
            if row["film_l1_mm_lo"] and row["role"] != "noise_floor":
                row["film_l1_mm_lo"] = str(10 * float(floor["film_l1_mm_hi"]) + float(row["film_l1_mm"]))
            return row
        text = tables(root, edited(temporary / "far", fixture, far)).stdout
        line = next(l for l in text.splitlines() if l.startswith("- **cpu, 1 ms haptic tick:**"))
        check("none reaches the noise floor; the most accurate: resolution 0.5" in line, f"none reaches the floor: {line}")

        def word(row):
            if row["role"] == "scene":
                row["time_ms_p99"] = "quick"
            return row
        broken = tables(root, edited(temporary / "word", fixture, word))
        check(broken.returncode == 2 and "study.csv, line 3, column time_ms_p99: 'quick' is not a number" in broken.stderr,
              f"a word for a number: exit 2 naming the place ({broken.stderr.strip()!r})")

    print(f"{len(failures)} failed" if failures else "all passed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
