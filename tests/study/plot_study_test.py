#!/usr/bin/python3
"""Checks scripts/plot-study on the fixture study and on broken and unusual variants of it.

- the fixture (tests/study/fixtures/study/: a `bleedsim study` of a tiny scene, three seeds, with a
  refinement the time step refused) gives one PNG per knob, pareto.png and distributions.png, valid
  PNGs of a sensible size, and the same bytes when run again;
- a study.csv without a column, a ladders.csv with a word where a number must be, or no study at
  all exits 2 with a message naming the file, line and column, and writes nothing into plots/;
- a study where every setting was refused, and one without the film (the stain only), still give
  every figure.

Run: /usr/bin/python3 tests/study/plot_study_test.py [repo root [KEEP_DIR]]
(KEEP_DIR: where to copy the studies and their figures, to look at them.)
"""
import csv
import io
import pathlib
import shutil
import struct
import subprocess
import sys
import tempfile

FIXTURE_KNOBS = ("particle_size", "blur_radius", "resolution")
PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"
FILES = ("study.csv", "ladders.csv", "study.h5")

failures = []


def check(condition, what):
    print(("ok   " if condition else "FAIL ") + what)
    if not condition:
        failures.append(what)


def run_plot(root, study_dir):
    return subprocess.run([str(root / "scripts" / "plot-study"), str(study_dir)],
                          capture_output=True, text=True, timeout=300)


def png_size(path):
    """(width, height) from the IHDR chunk, or None if the file is not a PNG."""
    data = path.read_bytes()
    if not data.startswith(PNG_SIGNATURE) or data[12:16] != b"IHDR" or not data.endswith(b"IEND\xaeB`\x82"):
        return None
    return struct.unpack(">II", data[16:24])


def study_with(directory, fixture, name="study.csv", edit=None):
    """A study folder: the fixture's files, `name` passed through edit(header, rows)."""
    directory.mkdir()
    for file in FILES:
        shutil.copy(fixture / file, directory / file)
    if edit:
        header, *rows = list(csv.reader(io.StringIO((fixture / name).read_text())))
        header, rows = edit(header, rows)
        out = io.StringIO()
        csv.writer(out, lineterminator="\n").writerows([header] + rows)
        (directory / name).write_text(out.getvalue())
    return directory


def expect_figures(directory, result, knobs, what):
    expected = sorted([f"{knob}.png" for knob in knobs] + ["pareto.png", "distributions.png"])
    written = sorted(p.name for p in (directory / "plots").iterdir())  # no temporaries left behind
    check(result.returncode == 0 and not result.stderr,
          f"{what}: exit 0, nothing on stderr ({result.stderr.strip()!r})")
    check(written == expected, f"{what}: wrote {', '.join(expected)} (found {written})")
    check(len(result.stdout.splitlines()) == len(expected), f"{what}: one line per written file")
    for name in expected:
        path = directory / "plots" / name
        size = png_size(path) if path.exists() else None
        check(size is not None and 800 <= size[0] <= 2500 and 600 <= size[1] <= 2000
              and path.stat().st_size > 20_000, f"{what}: {name} is a PNG of a sensible size ({size})")


def expect_refusal(directory, result, words, what):
    check(result.returncode == 2, f"{what}: exit 2 (got {result.returncode})")
    for word in words:
        check(word in result.stderr, f"{what}: the message names {word!r} ({result.stderr.strip()!r})")
    plots = directory / "plots"
    check(not plots.exists() or not any(plots.iterdir()), f"{what}: nothing written into plots/")


def without_column(name):
    def edit(header, rows):
        at = header.index(name)
        return header[:at] + header[at + 1:], [row[:at] + row[at + 1:] for row in rows]
    return edit


def with_cell(line, name, text):
    """Line counts the header as 1, as the error messages do."""
    def edit(header, rows):
        rows[line - 2][header.index(name)] = text
        return header, rows
    return edit


def all_refused(header, rows):
    """Every setting refused: its numbers empty (the noise floor's row stays, as the study writes it)."""
    status = header.index("status")
    refused = []
    for row in rows:
        if row[header.index("role")] != "noise_floor":
            row = row[:status] + ["refused: no CUDA device"] + [""] * (len(row) - status - 1)
        refused.append(row)
    return header, refused


def stain_only(header, rows):
    """The fixture as a scene without particles: no film columns."""
    for row in rows:
        for name in header:
            if name.startswith(("film_", "front_", "covered_", "volume_", "pile_")):
                row[header.index(name)] = ""
    return header, rows


def main():
    root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).resolve().parents[2])
    fixture = root / "tests" / "study" / "fixtures" / "study"
    with tempfile.TemporaryDirectory(prefix="plot-study-test-") as temporary:
        temporary = pathlib.Path(temporary)

        study = study_with(temporary / "fixture", fixture)
        expect_figures(study, run_plot(root, study), FIXTURE_KNOBS, "fixture")
        first = {p.name: p.read_bytes() for p in (study / "plots").glob("*.png")}
        expect_figures(study, run_plot(root, study), FIXTURE_KNOBS, "fixture again")
        again = {p.name: p.read_bytes() for p in (study / "plots").glob("*.png")}
        check(first == again, "fixture again: the same bytes")

        broken = study_with(temporary / "no-column", fixture, "study.csv", without_column("time_ms_p50_lo"))
        expect_refusal(broken, run_plot(root, broken), ["study.csv", "line 1", "time_ms_p50_lo"], "missing column")
        broken = study_with(temporary / "word", fixture, "ladders.csv", with_cell(5, "difference", "small"))
        expect_refusal(broken, run_plot(root, broken), ["ladders.csv", "line 5", "difference", "small"],
                       "a word for a number")
        check(not (temporary / "no-study").exists() and run_plot(root, temporary / "no-study").returncode == 2,
              "no study: exit 2")

        refused = study_with(temporary / "all-refused", fixture, "study.csv", all_refused)
        expect_figures(refused, run_plot(root, refused), FIXTURE_KNOBS, "every setting refused")
        stain = study_with(temporary / "stain-only", fixture, "study.csv", stain_only)
        expect_figures(stain, run_plot(root, stain), FIXTURE_KNOBS, "stain only")
        if len(sys.argv) > 2:  # a folder to keep the figures in, to look at them
            for directory in (study, refused, stain):
                shutil.copytree(directory, pathlib.Path(sys.argv[2]) / directory.name, dirs_exist_ok=True)

    print(f"{len(failures)} failed" if failures else "all passed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
