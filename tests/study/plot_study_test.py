#!/usr/bin/python3
"""Checks scripts/plot-study on the fixture study and on broken and unusual variants of it.

- the fixture (tests/study/fixtures/study.csv) gives one PNG per knob and pareto.png, valid PNGs
  of a sensible size, and the same bytes when run again;
- a study.csv without a column, or with a word where a number must be, exits 2 with a message
  naming the file, line and column, and writes nothing into plots/;
- a study where every row was refused, and one without the film (stain only, frames identical to
  the reference's: infinite PSNR), still give every figure.

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

FIXTURE_KNOBS = ("substeps", "particle_size", "blur_downsample", "resolution")
PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"

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


def study_with(directory, fixture, edit):
    """A study folder whose study.csv is the fixture's rows passed through edit(header, rows)."""
    header, *rows = list(csv.reader(io.StringIO(fixture.read_text())))
    header, rows = edit(header, rows)
    out = io.StringIO()
    csv.writer(out, lineterminator="\n").writerows([header] + rows)
    directory.mkdir()
    (directory / "study.csv").write_text(out.getvalue())
    return directory


def expect_figures(directory, result, knobs, what):
    expected = sorted([f"{knob}.png" for knob in knobs] + ["pareto.png"])
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
    status = header.index("status")
    return header, [row[:status] + ["refused: no CUDA device"] + [""] * (len(row) - status - 1) for row in rows]


def stain_only(header, rows):
    """The fixture as a scene without particles: no film columns, and the knobs that only touch the
    particles leave the frame identical to the reference's."""
    keep = []
    for row in rows:
        cells = dict(zip(header, row))
        if cells["status"] != "ok":
            continue
        for name in ("film_l1_mm", "film_l2_mm", "pile_height_error_mm"):
            cells[name] = ""
        if cells["knob"] in ("substeps", "particle_size", "blur_downsample"):
            cells["frame_psnr_db"], cells["stain_l1"] = "inf", "0"
        keep.append([cells[name] for name in header])
    return header, keep


def main():
    root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).resolve().parents[2])
    fixture = root / "tests" / "study" / "fixtures" / "study.csv"
    with tempfile.TemporaryDirectory(prefix="plot-study-test-") as temporary:
        temporary = pathlib.Path(temporary)

        study = temporary / "fixture"
        study.mkdir()
        shutil.copy(fixture, study / "study.csv")
        expect_figures(study, run_plot(root, study), FIXTURE_KNOBS, "fixture")
        first = {p.name: p.read_bytes() for p in (study / "plots").glob("*.png")}
        expect_figures(study, run_plot(root, study), FIXTURE_KNOBS, "fixture again")
        again = {p.name: p.read_bytes() for p in (study / "plots").glob("*.png")}
        check(first == again, "fixture again: the same bytes")

        broken = study_with(temporary / "no-column", fixture, without_column("ms_per_frame_p99"))
        expect_refusal(broken, run_plot(root, broken), ["study.csv", "line 1", "ms_per_frame_p99"],
                       "missing column")
        broken = study_with(temporary / "word", fixture, with_cell(5, "ms_per_frame_p50", "fast"))
        expect_refusal(broken, run_plot(root, broken), ["study.csv", "line 5", "ms_per_frame_p50", "fast"],
                       "a word for a number")
        check(not (temporary / "no-study").exists() and run_plot(root, temporary / "no-study").returncode == 2,
              "no study.csv: exit 2")

        refused = study_with(temporary / "all-refused", fixture, all_refused)
        expect_figures(refused, run_plot(root, refused), FIXTURE_KNOBS, "every row refused")
        stain = study_with(temporary / "stain-only", fixture, stain_only)
        expect_figures(stain, run_plot(root, stain), FIXTURE_KNOBS, "stain only, infinite PSNR")
        if len(sys.argv) > 2:  # a folder to keep the figures in, to look at them
            for directory in (study, refused, stain):
                shutil.copytree(directory, pathlib.Path(sys.argv[2]) / directory.name, dirs_exist_ok=True)

    print(f"{len(failures)} failed" if failures else "all passed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
