"""Reading a `bleedsim study` folder's tables (study.csv, ladders.csv: docs/accuracy.md, "Files"), for
scripts/plot-study and scripts/accuracy-tables. Every problem is a StudyError naming the file, line
and column."""
import csv
import io
import math
import re

STUDY_TEXT = ("scene", "knob", "role", "backend", "status", "check")
STUDY_COLUMNS = ("scene", "knob", "value", "role", "backend", "status", "seeds", "film_l1_mm", "film_l1_mm_lo",
                 "film_l1_mm_hi", "frame_psnr_db", "frame_psnr_db_lo", "frame_psnr_db_hi", "stain_l1", "stain_l1_lo",
                 "stain_l1_hi", "check", "time_ms_p50", "time_ms_p99", "time_ms_p50_lo", "time_ms_p50_hi")
LADDER_TEXT = ("knob", "metric", "unit", "role", "status", "asymptotic", "statement", "check")
LADDER_COLUMNS = ("knob", "metric", "unit", "level", "value", "role", "status", "mean", "mean_lo", "mean_hi",
                  "difference", "difference_lo", "difference_hi", "order", "order_lo", "order_hi", "asymptotic",
                  "statement", "extrapolated", "extrapolated_lo", "extrapolated_hi", "limit_distance",
                  "limit_distance_lo", "limit_distance_hi", "seed_spread", "check")
ROLES = ("reference", "scene", "ladder", "refinement", "noise_floor")
# The distribution metrics after the field (film or stain), as the files name them: those measured
# every frame (study.h5 holds their curves), then the run's rest time.
PER_FRAME_METRICS = ("front_mm", "covered_area_mm2", "volume_mm3", "pile_height_mm")
METRICS = PER_FRAME_METRICS + ("rest_s",)
KNOB_NAME = re.compile(r"[A-Za-z0-9_.-]+")


class StudyError(Exception):
    """A problem with the study's files, its message naming the file, line and column."""


def parse_number(text, where):
    if text == "":
        return None
    try:
        number = float(text)
    except ValueError:
        raise StudyError(f"{where}: '{text}' is not a number") from None
    if math.isnan(number):
        raise StudyError(f"{where}: '{text}' is not a number")
    return number


def read_table(path, required, text_columns):
    """Rows of a CSV as dicts, every column but the text ones parsed as a number (None where empty)."""
    try:
        text = path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as e:
        raise StudyError(f"{path}: cannot read: {e}") from None
    reader = csv.reader(io.StringIO(text))
    header = next(reader, None)
    if not header:
        raise StudyError(f"{path}, line 1: no header")
    for column in required:
        if column not in header:
            raise StudyError(f"{path}, line 1, column {column}: missing from the header")
    rows = []
    for fields in reader:
        if not fields:
            continue
        if len(fields) != len(header):
            raise StudyError(f"{path}, line {reader.line_num}: {len(fields)} fields, the header has {len(header)}")
        row = {}
        for name, cell in zip(header, fields):
            where = f"{path}, line {reader.line_num}, column {name}"
            row[name] = cell if name in text_columns else parse_number(cell, where)
        row["line"] = reader.line_num
        rows.append(row)
    if not rows:
        raise StudyError(f"{path}, line 2: no rows after the header")
    return rows


class StudyTables:
    """study.csv's rows (a setting on a backend, and the noise floor) and ladders.csv's (a knob, a metric
    and a level), checked; the field the study compares (the film, or the stain without one)."""

    def __init__(self, folder):
        self.rows = read_table(folder / "study.csv", STUDY_COLUMNS, STUDY_TEXT)
        self.ladder_rows = read_table(folder / "ladders.csv", LADDER_COLUMNS, LADDER_TEXT)
        for row in self.rows:
            where = f"{folder / 'study.csv'}, line {row['line']}"
            if row["role"] not in ROLES:
                raise StudyError(f"{where}, column role: '{row['role']}' is none of {', '.join(ROLES)}")
            if row["role"] in ("ladder", "refinement") and (not KNOB_NAME.fullmatch(row["knob"]) or
                                                            row["knob"] in ("pareto", "distributions")):
                raise StudyError(f"{where}, column knob: '{row['knob']}' cannot name a plot")
            if row["role"] != "noise_floor" and row["status"] == "ok" and not (row["time_ms_p50"] or 0) > 0:
                raise StudyError(f"{where}, column time_ms_p50: not > 0 (the time axis is logarithmic)")
        self.scene = self.rows[0]["scene"]
        self.seeds = int(self.rows[0]["seeds"] or 0)
        self.backends = list(dict.fromkeys(r["backend"] for r in self.rows if r["backend"]))
        self.knobs = list(dict.fromkeys(r["knob"] for r in self.rows if r["role"] in ("ladder", "refinement")))
        self.knobs += [k for k in dict.fromkeys(r["knob"] for r in self.ladder_rows) if k not in self.knobs]
        has_film = any(r["film_l1_mm"] is not None for r in self.rows if r["role"] != "noise_floor")
        self.error = "film_l1_mm" if has_film else "stain_l1"
        self.field = "film_mm" if has_film else "stain"
        self.floor = next((r for r in self.rows if r["role"] == "noise_floor"), None)
        self.reference = next((r for r in self.rows if r["role"] == "reference"), None)

    def settings(self, backend, with_reference=False):
        """The settings that ran on this backend (the reference, whose error is 0, only when asked)."""
        roles = ("scene", "ladder", "refinement") + (("reference",) if with_reference else ())
        return [r for r in self.rows if r["backend"] == backend and r["status"] == "ok" and r["role"] in roles
                and r[self.error] is not None]

    def ladder(self, knob, metric):
        return [r for r in self.ladder_rows if r["knob"] == knob and r["metric"] == metric]
