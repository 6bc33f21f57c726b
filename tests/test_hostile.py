"""Hostile inputs and faults: a catalogue of command lines with the exact error each must produce.

Every case runs ``embroact.export.cli.main.main`` in a fresh ``tmp_path`` holding the hostile files
(:func:`_hostile_files`) and asserts: the documented exit code (0 ok, 1 rule errors, 2 bad
input, 3 cannot write, 4 solver failure); for errors exactly one line on stderr, starting
``embroact...: error:``, containing the expected fragment (parameter, value and range where
there is one), no traceback; and that nothing new was left in the directory (no output, no
partial ``.part`` file) unless the case succeeds.

Read-only output directories: the tests run as root, for whom ``chmod`` does not stop writes,
so "cannot write" is produced by (a) a path under a regular file, (b) ``/proc``, where root
cannot create files, and (c) monkeypatching ``os.replace`` / ``os.fsync`` to fail mid-write.
"""
from __future__ import annotations

import contextlib
import errno
import functools
import io
import os
import random
import tracemalloc
from pathlib import Path

import pytest

from embroact.export.cli.main import main

ZZ = ["zigzag", "--width-mm", "7", "--interval-mm", "1"]
CR = ["cross", "--width-mm", "7", "--interval-mm", "1.4", "--angle-deg", "45"]
FIT = ["--pattern", "zigzag", "--width-mm", "7"]
PRED = ["predict", "zigzag", "--width-mm", "7"]
GOOD_CSV = "pressure_kpa,angle_deg\n0,0\n100,10\n150,40\n200,100\n"


def _garbage(n: int, seed: int) -> bytes:
    return random.Random(seed).randbytes(n)


@functools.lru_cache(maxsize=1)
def _machine_files() -> dict[str, bytes]:
    """A good DST and truncated files of every format with an end marker (encoded once)."""
    from embroact.export.machine.formats import encode
    from embroact.patterns import Centerline, ZigzagParams, zigzag

    plan = zigzag(Centerline.straight(100.0), ZigzagParams(7.0, 1.0))
    good = encode(plan, "dst")[0]
    out = {"good.dst": good, "truncated.dst": good[:-10]}
    for fmt in ("pes", "vp3", "tbf", "jef", "pec", "u01"):
        data = encode(plan, fmt)[0]
        out[f"half.{fmt}"] = data[: len(data) // 2]
    return out


def _hostile_files(d: Path) -> None:
    """Every file the catalogue refers to, written fresh into ``d``."""
    files = {
        "empty.dst": b"", "empty.pes": b"", "short.dst": b"LA:x" + b" " * 90,
        "header.dst": b"LA:x\r\x1a".ljust(512, b" "), "garbage.dst": _garbage(3000, 1),
        "garbage.pes": _garbage(3000, 2), "garbage.jef": _garbage(3000, 3), "garbage.vp3": _garbage(3000, 4),
        "zeros.pes": bytes(3000), "zeros.pec": bytes(3000), "zeros.jef": bytes(3000),
        "notes.xyz": b"hello",
        "empty.csv": b"", "header.csv": b"pressure_kpa,angle_deg\n", "binary.csv": _garbage(200, 5),
        "columns.csv": b"p,a\n1,2\n", "text.csv": b"pressure_kpa,angle_deg\n100,abc\n",
        "nan.csv": b"pressure_kpa,angle_deg\n100,nan\n200,5\n", "negative.csv": b"pressure_kpa,angle_deg\n-100,1\n",
        "ragged.csv": b"pressure_kpa,angle_deg\n100\n200,5\n", "dup.csv": b"pressure_kpa,pressure_kpa,angle_deg\n1,1,2\n",
        "branch.csv": b"pressure_kpa,angle_deg,branch\n100,1,up\n", "one.csv": b"pressure_kpa,angle_deg\n100,1\n",
        "flat.csv": b"pressure_kpa,angle_deg\n100,0\n200,0\n300,0\n", "good.csv": GOOD_CSV.encode(),
        "syntax.toml": b"[[actuator]\n", "latin1.toml": 'name = "caf\xe9"\n'.encode("latin-1"),
        "tubes-nopath.toml": b'[[tube]]\nname = "x"\n',
        "design.toml": b'[[actuator]]\nname = "A1"\npattern = "zigzag"\nwidth_mm = 7\ninterval_mm = 1\nlength_mm = 100\n',
        "widht.toml": b'[[actuator]]\nname = "A1"\npattern = "zigzag"\nwidht_mm = 7\ninterval_mm = 1\nlength_mm = 100\n',
        "dupname.toml": (b'[[actuator]]\nname = "A"\npattern = "zigzag"\nwidth_mm = 7\ninterval_mm = 1\nlength_mm = 50\n'
                         b'[[actuator]]\nname = "A"\npattern = "zigzag"\nwidth_mm = 7\ninterval_mm = 1\nlength_mm = 50\n'
                         b'origin_mm = [0, 30]\n'),
        "nanwidth.toml": b'[[actuator]]\nname = "A1"\npattern = "zigzag"\nwidth_mm = nan\ninterval_mm = 1\nlength_mm = 100\n',
        "tenmillion.toml": (b'[[actuator]]\nname = "A1"\npattern = "zigzag"\nwidth_mm = 7\ninterval_mm = 0.1\n'
                            b'length_mm = 999999\n'),
        "sixmillion.toml": b"".join(b'[[actuator]]\nname = "A%d"\npattern = "zigzag"\nwidth_mm = 7\ninterval_mm = 0.5\n'
                                    b'length_mm = 999999\norigin_mm = [0, %d]\n' % (i, 20 * i) for i in range(3)),
        "afile": b"a regular file, not a directory",
    }
    for name, data in {**files, **_machine_files()}.items():
        (d / name).write_bytes(data)
    (d / "dir.dst").mkdir()


#: (id, argv with {tmp}, exit code, exact fragment of the one stderr line ({tmp} expanded)).
CATALOGUE = [
    # --- embroidery files given to check: empty, zero-length, truncated, garbage ------------------------
    ("check-empty-dst", ["check", "{tmp}/empty.dst"], 2, "{tmp}/empty.dst: empty file"),
    ("check-empty-pes", ["check", "{tmp}/empty.pes"], 2, "{tmp}/empty.pes: empty file"),
    ("check-dst-shorter-than-header", ["check", "{tmp}/short.dst"], 2,
     "not a DST file: 94 bytes, shorter than the 512-byte header"),
    ("check-dst-header-only", ["check", "{tmp}/header.dst"], 2, "truncated DST file: no end record among 0 records"),
    ("check-dst-truncated", ["check", "{tmp}/truncated.dst", "--tube-path", "0,0 100,0"], 2,
     "{tmp}/truncated.dst: truncated DST file: no end record among"),
    ("check-dst-garbage", ["check", "{tmp}/garbage.dst"], 2, "not a DST file: the header does not start with 'LA:'"),
    ("check-pes-garbage", ["check", "{tmp}/garbage.pes"], 2,
     "{tmp}/garbage.pes: not a PES file: it does not start with '#PES'"),
    ("check-pes-zeros", ["check", "{tmp}/zeros.pes"], 2,
     "{tmp}/zeros.pes: not a PES file: it does not start with '#PES'"),
    ("check-pec-zeros", ["check", "{tmp}/zeros.pec"], 2,
     "{tmp}/zeros.pec: not a PEC file: it does not start with '#PEC0001'"),
    ("check-jef-garbage", ["check", "{tmp}/garbage.jef"], 2,
     "{tmp}/garbage.jef: truncated or garbage JEF file: no end code (0x80 0x10) after the stitches"),
    ("check-jef-zeros", ["check", "{tmp}/zeros.jef"], 2,
     "{tmp}/zeros.jef: truncated or garbage JEF file: no end code (0x80 0x10) after the stitches"),
    ("check-jef-truncated", ["check", "{tmp}/half.jef"], 2,
     "{tmp}/half.jef: truncated or garbage JEF file: no end code (0x80 0x10) after the stitches"),
    ("check-vp3-garbage", ["check", "{tmp}/garbage.vp3"], 2,
     "{tmp}/garbage.vp3: not a VP3 file: it does not start with '%vsm%'"),
    ("check-pes-truncated", ["check", "{tmp}/half.pes"], 2, "{tmp}/half.pes: unreadable PES file ("),
    ("check-vp3-truncated", ["check", "{tmp}/half.vp3"], 2,
     "{tmp}/half.vp3: truncated or garbage VP3 file: the data ends before the end-of-design code"),
    ("check-tbf-truncated", ["check", "{tmp}/half.tbf"], 2,
     "{tmp}/half.tbf: truncated or garbage TBF file: the data ends before the end-of-design code"),
    ("check-pec-truncated", ["check", "{tmp}/half.pec"], 2,
     "{tmp}/half.pec: truncated or garbage PEC file: the data ends before the end-of-design code"),
    ("check-u01-truncated", ["check", "{tmp}/half.u01"], 2,
     "{tmp}/half.u01: truncated or garbage U01 file: the data ends before the end-of-design code"),
    ("check-missing-file", ["check", "{tmp}/missing.dst"], 2,
     "{tmp}/missing.dst: cannot read embroidery file: No such file or directory"),
    ("check-directory", ["check", "{tmp}/dir.dst"], 2, "{tmp}/dir.dst: cannot read embroidery file: Is a directory"),
    ("check-unknown-suffix", ["check", "{tmp}/notes.xyz"], 2,
     "{tmp}/notes.xyz: cannot read '.xyz' embroidery files; readable: 100, "),
    ("check-unknown-format-flag", ["check", "{tmp}/good.dst", "--format", "xyz"], 2,
     "embroact check: error: argument --format: invalid choice: 'xyz'"),
    # --- tube paths for check ----------------------------------------------------------------------------
    ("tube-path-one-point", ["check", "{tmp}/good.dst", "--tube-path", "0,0"], 2,
     "tube_path must be 'x1,y1 x2,y2 ...' with at least 2 points in mm, or SVG path data ('M 0 0 L 100 0'), got '0,0'"),
    ("tube-path-svg-data-cut-short", ["check", "{tmp}/good.dst", "--tube-path", "M 0 0 Q 1"], 2,
     "tube_path: SVG path 'M 0 0 Q 1': 'Q' at character 6 needs numbers in groups of 4, got 1"),
    ("tube-path-svg-data-move-only", ["check", "{tmp}/good.dst", "--tube-path", "M 0 0"], 2,
     "tube_path: SVG path draws nothing (only move-to commands)"),
    ("tube-path-repeated-point", ["check", "{tmp}/good.dst", "--tube-path", "0,0 0,0 0,0"], 2,
     "tube path of tube 1 must have a length > 0, got 0 mm"),
    ("tube-path-nan", ["check", "{tmp}/good.dst", "--tube-path", "0,0 nan,1"], 2,
     "tube_path must hold finite numbers, got '0,0 nan,1'"),
    ("tube-path-words", ["check", "{tmp}/good.dst", "--tube-path", "a,b c,d"], 2,
     "tube_path must be 'x1,y1 x2,y2 ...' with at least 2 points in mm, or SVG path data ('M 0 0 L 100 0'), got 'a,b c,d'"),
    ("tube-path-3d", ["check", "{tmp}/good.dst", "--tube-path", "0,0,0 1,1,1"], 2,
     "tube_path must be 'x1,y1 x2,y2 ...' with at least 2 points in mm, or SVG path data ('M 0 0 L 100 0'), got '0,0,0 1,1,1'"),
    ("tube-both-sources", ["check", "{tmp}/good.dst", "--tube-path", "0,0 1,0", "--tube", "{tmp}/tubes-nopath.toml"], 2,
     "give either --tube TUBES.toml or --tube-path, not both"),
    ("tube-file-no-path", ["check", "{tmp}/good.dst", "--tube", "{tmp}/tubes-nopath.toml"], 2,
     "{tmp}/tubes-nopath.toml: [[tube]] 1 has no path_mm"),
    ("tube-file-syntax", ["check", "{tmp}/good.dst", "--tube", "{tmp}/syntax.toml"], 2,
     "{tmp}/syntax.toml: TOML syntax error: Expected ']]' at the end of an array declaration (at line 1, column 11)"),
    ("check-no-input", ["check"], 2, "check needs an input: DESIGN.toml or an embroidery file (or --rules)"),
    ("check-design-with-tube", ["check", "{tmp}/design.toml", "--tube-path", "0,0 1,0"], 2,
     "--tube-path and --tube apply to embroidery files; a design file carries its tubes"),
    # --- design files ----------------------------------------------------------------------------------
    ("design-toml-syntax", ["build", "{tmp}/syntax.toml", "--out", "{tmp}"], 2,
     "{tmp}/syntax.toml: TOML syntax error: Expected ']]' at the end of an array declaration (at line 1, column 11)"),
    ("design-not-utf8", ["build", "{tmp}/latin1.toml", "--out", "{tmp}"], 2,
     "{tmp}/latin1.toml: design file is not UTF-8 text (byte 11)"),
    ("design-missing", ["predict", "{tmp}/missing.toml"], 2,
     "{tmp}/missing.toml: cannot read design file: No such file or directory"),
    ("design-unknown-key", ["check", "{tmp}/widht.toml"], 2,
     "{tmp}/widht.toml: actuator[0].widht_mm: unknown key; allowed: name,"),
    ("design-duplicate-names", ["build", "{tmp}/dupname.toml", "--out", "{tmp}"], 2,
     "actuator[1].name: duplicate actuator name 'A' (also actuator[0])"),
    ("design-nan-width", ["build", "{tmp}/nanwidth.toml", "--out", "{tmp}"], 2,
     "{tmp}/nanwidth.toml: actuator[0].width_mm: must be a finite number, got nan"),
    ("design-ten-million-stitches", ["build", "{tmp}/tenmillion.toml", "--out", "{tmp}"], 2,
     "actuator 'A1': pattern would need about 1e+07 records, more than the limit 5,000,000; "
     "use a larger interval_mm or a shorter path"),
    ("design-millions-over-three-actuators", ["check", "{tmp}/sixmillion.toml"], 2,
     "design would need about 6.21e+06 records (2.08e+05 of them travel jumps between actuators) over 3 actuators, "
     "more than the limit 5,000,000"),
    # --- paths with repeated points, zero-length segments, self-touching curves --------------------------
    ("path-single-repeated-point", ZZ + ["-o", "{tmp}/a.dst", "--path", "M 0 0 L 0 0"], 2,
     "path needs at least 2 distinct points, got 1"),
    ("path-degenerate-curve", ZZ + ["-o", "{tmp}/a.dst", "--path", "M 0 0 C 0 0 0 0 0 0"], 2,
     "path needs at least 2 distinct points, got 1"),
    ("path-doubles-back", ZZ + ["-o", "{tmp}/a.dst", "--path", "M 0 0 L 100 0 L 50 0"], 2,
     "path crosses or touches itself near (50.00, 0.00) mm; give a path that does not"),
    ("path-self-crossing", ZZ + ["-o", "{tmp}/a.dst", "--path", "M 0 0 L 100 0 L 100 50 L 50 -50"], 2,
     "path crosses or touches itself near (75.00, 0.00) mm"),
    ("path-closed", ZZ + ["-o", "{tmp}/a.dst", "--path", "M 0 0 L 100 0 L 100 100 Z"], 2,
     "path must be open (a tube has two ends), got a closed path"),
    ("path-comes-back-near-itself", ZZ + ["-o", "{tmp}/a.dst", "--path", "M 0 0 C 100 100 -100 100 0 1"], 2,
     "the path comes too close to itself"),
    ("path-corner", ZZ + ["-o", "{tmp}/a.dst", "--path", "M 0 0 L 50 0 L 50 50"], 2,
     "path has a corner at (50.00, 0.00) mm (turn 90.0 deg > 10 deg), which counts as curvature radius 0 "
     "< width_mm/2 = 3.5 mm"),
    ("path-too-tight", ZZ + ["-o", "{tmp}/a.dst", "--path", "M 0 0 C 4 0 4 4 0 4"], 2,
     "path curvature radius must be >= width_mm/2 = 3.5 mm, got 1.5 mm"),
    ("cross-subnormal-interval", CR[:3] + ["--angle-deg", "45", "--interval-mm", "1e-320", "-o", "{tmp}/a.dst"], 2,
     "interval_mm must be in (0, 100) and not subnormal (0 or of size >= 2.22507e-308), got 9.99989e-321"),
    ("path-too-short", ZZ[:3] + ["--interval-mm", "6", "--length-mm", "10", "-o", "{tmp}/a.dst"], 2,
     "path length_mm must be >= 12 for a zigzag with interval_mm=6 (at least 2 legs), got 10"),
    ("path-two-subpaths", ZZ + ["-o", "{tmp}/a.dst", "--path", "M 0 0 L 100 0 M 0 10 L 100 10"], 2,
     "SVG path has 2 subpaths with a gap of 100.5 mm between them"),
    ("path-bad-command", ZZ + ["-o", "{tmp}/a.dst", "--path", "M 0 0 X 5"], 2,
     "SVG path: unsupported character 'X' at position 6; supported commands: M m L l H h V v C c"),
    ("path-missing-number", ZZ + ["-o", "{tmp}/a.dst", "--path", "M 0 0 L 10"], 2, "SVG path 'M 0 0 L 10': 'L' at character 6 needs numbers in groups of 2, got 1"),
    ("path-empty", ZZ + ["-o", "{tmp}/a.dst", "--path", ""], 2, "SVG path must be a non-empty string, got ''"),
    ("path-huge-coordinates", ZZ + ["-o", "{tmp}/a.dst", "--path", "M 1e308 0 L -1e308 0"], 2,
     "path coordinates must be in [-1e+07, 1e+07] mm, got 1e+308"),  # bug B4: was an OverflowError traceback
    ("path-ten-million-stitches", ZZ + ["-o", "{tmp}/a.dst", "--path", "M 0 0 L 1e7 0"], 2,
     "pattern would need about 1e+07 records, more than the limit 5,000,000"),
    ("path-repeated-points-are-fine", ZZ + ["-o", "{tmp}/a.dst", "--path", "M 0 0 L 50 0 L 50 0 L 100 0"], 0, ""),
    # --- outputs: missing, not a directory, not writable, unknown suffixes ------------------------------
    ("out-missing-dir", ZZ + ["-o", "{tmp}/missing/a.dst"], 3, "output directory '{tmp}/missing' does not exist"),
    ("out-under-regular-file", ZZ + ["-o", "{tmp}/afile/a.dst"], 3, "output directory '{tmp}/afile' is not a directory"),
    ("out-proc", ZZ + ["-o", "/proc/embroact-h8.dst"], 3, "cannot write '/proc/embroact-h8.dst': No such file or directory"),
    ("out-preview-missing-dir", ZZ + ["-o", "{tmp}/a.dst", "--preview", "{tmp}/missing/p.svg"], 3,
     "output directory '{tmp}/missing' does not exist"),
    ("build-out-missing", ["build", "--out", "{tmp}/missing"], 3, "output directory '{tmp}/missing' does not exist"),
    ("build-out-regular-file", ["build", "--out", "{tmp}/afile"], 3,
     "output directory '{tmp}/afile' is not a directory"),
    ("build-out-proc", ["build", "--out", "/proc"], 3, "cannot write '/proc/paper-zigzag.dst'"),
    ("fit-out-missing-dir", ["fit", "{tmp}/good.csv", *FIT, "-o", "{tmp}/missing/cal.toml"], 3,
     "output directory '{tmp}/missing' does not exist"),
    ("preview-out-proc", ["preview", "stitches", "-o", "/proc/embroact-h8.svg"], 3,
     "cannot write '/proc/embroact-h8.svg'"),
    ("suffix-unknown", ZZ + ["-o", "{tmp}/a.png"], 2,
     "file suffix must be one of .dst, .tbf, .pes, .pec, .jef, .exp, .vp3, .xxx, .u01, got '.png'"),
    ("suffix-none", ZZ + ["-o", "{tmp}/a"], 2, "file suffix must be one of .dst, .tbf, .pes"),
    ("format-flag-unknown", ZZ + ["-o", "{tmp}/a.dst", "--format", "gcode"], 2,
     "format must be one of dst, tbf, pes, pec, jef, exp, vp3, xxx, u01, got 'gcode'"),
    ("build-format-unknown", ["build", "--out", "{tmp}", "--format", "dst,xyz"], 2,
     "format must be one of dst, tbf, pes, pec, jef, exp, vp3, xxx, u01, got 'xyz'"),
    ("build-format-empty", ["build", "--out", "{tmp}", "--format", ""], 2,
     "format must be one of dst, tbf, pes, pec, jef, exp, vp3, xxx, u01, got ''"),
    ("preview-stitches-png", ["preview", "stitches", "-o", "{tmp}/x.png"], 2,
     "output of preview stitches must end in .svg, got 'x.png'"),
    ("preview-mesh-suffix", ["preview", "mesh", "-o", "{tmp}/x.xyz"], 2,
     "output of preview mesh must end in one of .glb, .stl, .obj, .ply, .svg, got 'x.xyz'"),
    ("long-leg-refused", ["zigzag", "--width-mm", "20", "--interval-mm", "1", "-o", "{tmp}/a.dst"], 1,
     "EA102"),  # the rule gate refuses it (exit 1, nothing written)
    # --- bad range strings for --pressure-kpa --------------------------------------------------------------
    ("pressure-negative-step", PRED + ["--pressure-kpa", "0:300:-10"], 2,
     "--pressure-kpa: step must be > 0 in 'start:stop:step', got '0:300:-10'"),
    ("pressure-zero-step", PRED + ["--pressure-kpa", "0:300:0"], 2,
     "--pressure-kpa: step must be > 0 in 'start:stop:step', got '0:300:0'"),
    ("pressure-reversed", PRED + ["--pressure-kpa", "300:0:10"], 2,
     "--pressure-kpa: stop must be >= start in 'start:stop:step', got '300:0:10'"),
    ("pressure-words", PRED + ["--pressure-kpa", "a:b:c"], 2, "--pressure-kpa: 'a' is not a number in 'a:b:c'"),
    ("pressure-two-fields", PRED + ["--pressure-kpa", "0:300"], 2,
     "--pressure-kpa must be 'start:stop:step' or a comma-separated list, got '0:300'"),
    ("pressure-four-fields", PRED + ["--pressure-kpa", "0:300:10:5"], 2,
     "--pressure-kpa must be 'start:stop:step' or a comma-separated list, got '0:300:10:5'"),
    ("pressure-billions", PRED + ["--pressure-kpa", "0:1e5:1e-9"], 2, "--pressure-kpa: at most 100000 pressures, '0:1e5:1e-9' gives"),
    ("pressure-nan", PRED + ["--pressure-kpa", "nan:300:10"], 2,
     "--pressure-kpa: pressures must be finite and >= 0 kPa, got 'nan' in 'nan:300:10'"),
    ("pressure-inf", PRED + ["--pressure-kpa", "0:inf:10"], 2,
     "--pressure-kpa: pressures must be finite and >= 0 kPa, got 'inf' in '0:inf:10'"),
    ("pressure-overflow", PRED + ["--pressure-kpa", "1e400"], 2,
     "--pressure-kpa: pressures must be finite and >= 0 kPa, got '1e400' in '1e400'"),
    ("pressure-negative-list", PRED + ["--pressure-kpa=-5,10"], 2,
     "--pressure-kpa: pressures must be finite and >= 0 kPa, got '-5' in '-5,10'"),
    ("pressure-empty", PRED + ["--pressure-kpa", ""], 2, "--pressure-kpa must list 1 to 100000 pressures, got ''"),
    ("pressure-only-commas", PRED + ["--pressure-kpa", ","], 2, "--pressure-kpa must list 1 to 100000 pressures, got ','"),
    ("preview-pressure-reversed", ["preview", "bend", "-o", "{tmp}/b.svg", "--pressure-kpa", "300:0:10"], 2,
     "--pressure-kpa: stop must be >= start in 'start:stop:step', got '300:0:10'"),
    ("preview-pressure-zero-step", ["preview", "bend", "-o", "{tmp}/b.svg", "--pressure-kpa", "0:300:0"], 2,
     "--pressure-kpa: step must be > 0 in 'start:stop:step', got '0:300:0'"),
    ("preview-pressure-billions", ["preview", "bend", "-o", "{tmp}/b.svg", "--pressure-kpa", "0:1e5:1e-9"], 2,
     "--pressure-kpa: at most 100000 pressures, '0:1e5:1e-9' gives"),
    ("preview-pressure-empty", ["preview", "bend", "-o", "{tmp}/b.svg", "--pressure-kpa", ""], 2,
     "--pressure-kpa must list 1 to 100000 pressures, got ''"),
    ("preview-pressure-huge", ["preview", "bend", "-o", "{tmp}/b.svg", "--pressure-kpa", "1e400"], 2,
     "--pressure-kpa: pressures must be finite and >= 0 kPa, got '1e400' in '1e400'"),
    # --- unreadable CSVs for fit ---------------------------------------------------------------------------
    ("fit-empty-csv", ["fit", "{tmp}/empty.csv", *FIT], 2,
     "{tmp}/empty.csv is empty: expected a header line and data rows"),
    ("fit-header-only", ["fit", "{tmp}/header.csv", *FIT], 2, "{tmp}/header.csv has a header but no data rows"),
    ("fit-binary-csv", ["fit", "{tmp}/binary.csv", *FIT], 2, "{tmp}/binary.csv: CSV file is not UTF-8 text (byte "),
    ("fit-missing-column", ["fit", "{tmp}/columns.csv", *FIT], 2,
     "{tmp}/columns.csv: missing column 'pressure_kpa' (header has: p, a)"),
    ("fit-text-value", ["fit", "{tmp}/text.csv", *FIT], 2,
     "{tmp}/text.csv line 2: angle_deg must be a finite number, got 'abc'"),
    ("fit-nan-value", ["fit", "{tmp}/nan.csv", *FIT], 2,
     "{tmp}/nan.csv line 2: angle_deg must be a finite number, got 'nan'"),
    ("fit-negative-pressure", ["fit", "{tmp}/negative.csv", *FIT], 2,
     "{tmp}/negative.csv line 2: pressure_kpa must be >= 0 (gauge pressure), got -100"),
    ("fit-ragged-row", ["fit", "{tmp}/ragged.csv", *FIT], 2, "{tmp}/ragged.csv line 2: column 'angle_deg' is empty"),
    ("fit-duplicate-column", ["fit", "{tmp}/dup.csv", *FIT], 2,
     "{tmp}/dup.csv: column 'pressure_kpa' appears more than once in the header"),
    ("fit-bad-branch", ["fit", "{tmp}/branch.csv", *FIT], 2,
     "{tmp}/branch.csv line 2: branch must be 'loading' or 'unloading', got 'up'"),
    ("fit-one-point", ["fit", "{tmp}/one.csv", *FIT], 2,
     "loading data: fitting 2 parameter(s) needs more than 2 points and at least 2 bent (>= 1 deg), got 1 points, 1 bent"),
    ("fit-no-bending", ["fit", "{tmp}/flat.csv", *FIT], 2,
     "angle_deg: all 3 loading points bend less than 1 deg (up to 300 kPa); no deformation phase to fit G and P0 to"),
    ("fit-missing-csv", ["fit", "{tmp}/missing.csv", *FIT], 2,
     "{tmp}/missing.csv: cannot read CSV file: No such file or directory"),
    ("fit-directory", ["fit", "{tmp}", *FIT], 2, "{tmp}: cannot read CSV file: Is a directory"),
    ("fit-bad-fit-list", ["fit", "{tmp}/good.csv", *FIT, "--fit", "q"], 2,
     "--fit must list parameters from g, p0, g_e, got 'q'"),
    # --- usage errors are one line too -----------------------------------------------------------------
    ("usage-unknown-command", ["bogus"], 2, "embroact: error: argument COMMAND: invalid choice: 'bogus'"),
    ("usage-float-text", ZZ[:1] + ["--width-mm", "abc", "--interval-mm", "1", "-o", "{tmp}/a.dst"], 2,
     "embroact zigzag: error: argument --width-mm: invalid float value: 'abc' (see 'embroact zigzag --help')"),
    ("usage-missing-required", ["zigzag", "--interval-mm", "1", "-o", "{tmp}/a.dst"], 2,
     "embroact zigzag: error: the following arguments are required: --width-mm"),
    ("predict-unknown-method", PRED + ["--method", "newton"], 2, "method must be one of auto, stable-analytic-trace"),
    ("predict-unknown-actuator", ["predict", "{tmp}/design.toml", "--actuator", "nope"], 2,
     "--actuator must be one of A1, got 'nope'"),
    ("predict-missing-width", ["predict", "zigzag"], 2, "--width-mm is required for a zigzag design"),
]


def _run(argv):
    """Exit code, stdout and stderr; the rule gate's one-line summary of warnings ("design rules: ...",
    printed before a machine file is written) is not an error line and is left out of stderr."""
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        code = main(argv)
    lines = err.getvalue().splitlines(keepends=True)
    return code, out.getvalue(), "".join(ln for ln in lines if not ln.startswith("design rules: "))


def _listing(d: Path) -> set[str]:
    return {str(p.relative_to(d)) for p in d.rglob("*")}


def test_catalogue_has_at_least_40_hostile_inputs():
    ids = [c[0] for c in CATALOGUE]
    assert len(ids) == len(set(ids)) and sum(c[2] != 0 for c in CATALOGUE) >= 40


@pytest.mark.parametrize("case_id, argv, code, fragment", CATALOGUE, ids=[c[0] for c in CATALOGUE])
def test_hostile_input(tmp_path, case_id, argv, code, fragment):
    _hostile_files(tmp_path)
    before = _listing(tmp_path)
    t = str(tmp_path)
    got, out, err = _run([a.replace("{tmp}", t) for a in argv])
    assert got == code, (got, err)
    assert "Traceback" not in err + out
    if code == 0:
        return
    if code != 1:
        assert err.count("\n") == 1 and err.endswith("\n"), err  # exactly one line
        assert err.startswith("embroact") and ": error: " in err, err
        assert fragment.replace("{tmp}", t) in err, err
    assert _listing(tmp_path) == before  # no output, no partial file


# ------------------------------------------------------------------------------ memory and time bounds
def test_ten_million_stitches_refused_before_allocating():
    """A 1 km path at 0.1 mm asks for 1e7 records: refused with under 5 MB allocated."""
    from embroact.patterns import Centerline, PatternError, ZigzagParams, zigzag

    tracemalloc.start()
    try:
        with pytest.raises(PatternError, match=r"about 1e\+07 records, more than the limit 5,000,000"):
            zigzag(Centerline.straight(999_999.0), ZigzagParams(7.0, 0.1))
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    assert peak < 5_000_000, peak


def test_billions_of_stitches_over_many_actuators_refused_before_allocating():
    """Found by this catalogue (bug B3): the cap was per actuator, so 1000 actuators of 4.5 million records
    each were generated one after another (~1.6 GB each). Now the design total is refused up front."""
    from embroact.patterns import PatternError, build_plan, design_from_dict

    acts = [dict(name=f"A{i}", pattern="zigzag", width_mm=7, interval_mm=0.2, length_mm=900000,
                 origin_mm=[0, 20 * i]) for i in range(1000)]
    design = design_from_dict({"actuator": acts})
    tracemalloc.start()
    try:
        with pytest.raises(PatternError, match=r"design would need about 4.57e\+09 records \(7.5e\+07 of them travel "
                                               r"jumps between actuators\) over 1000 actuators, more than the limit 5,000,000"):
            build_plan(design)
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    assert peak < 5_000_000, peak


# ------------------------------------------------------------------------------ nothing lost
OLD = b"old machine file, must survive byte for byte\n"


@pytest.mark.parametrize("argv, code", [
    (["zigzag", "--width-mm", "-1", "--interval-mm", "1"], 2),  # bad parameter
    (["zigzag", "--width-mm", "20", "--interval-mm", "1"], 1),  # long leg refused by the rule gate
    (ZZ + ["--path", "M 0 0 L 50 0 L 50 50"], 2),  # path error while generating
    (ZZ + ["--preview", "/proc/embroact-h8.svg"], 3),  # second output cannot be written
], ids=["bad-parameter", "long-leg", "bad-path", "second-output-unwritable"])
def test_existing_file_survives_a_failed_run(tmp_path, argv, code):
    target = tmp_path / "act.dst"
    target.write_bytes(OLD)
    got, _, err = _run(argv + ["-o", str(target)])
    assert got == code and (code == 1 or err.count("\n") == 1), err  # a rule refusal lists its errors
    assert target.read_bytes() == OLD
    assert sorted(p.name for p in tmp_path.iterdir()) == ["act.dst"]


@pytest.mark.parametrize("where, exc, code, fragment", [
    ("replace", OSError(errno.ENOSPC, "No space left on device"), 3, "No space left on device"),
    ("fsync", OSError(errno.EIO, "Input/output error"), 3, "Input/output error"),
    ("replace", KeyboardInterrupt(), 130, "embroact: interrupted"),
], ids=["disk-full", "io-error", "interrupted"])
def test_failure_mid_write_leaves_old_file_and_no_partial(tmp_path, monkeypatch, where, exc, code, fragment):
    """Monkeypatched faults inside the atomic write (root ignores chmod, so permissions cannot make them)."""
    target = tmp_path / "act.dst"
    target.write_bytes(OLD)

    def fail(*args, **kwargs):
        raise exc

    monkeypatch.setattr(os, where, fail)
    got, _, err = _run(ZZ + ["-o", str(target)])
    monkeypatch.undo()
    assert got == code and fragment in err and err.count("\n") == 1, err
    assert target.read_bytes() == OLD
    assert sorted(p.name for p in tmp_path.iterdir()) == ["act.dst"]  # no .part file left


def test_build_failure_mid_way_keeps_old_outputs(tmp_path, monkeypatch):
    """A build whose third file fails to write: earlier files complete, the failing one's old bytes intact."""
    assert _run(["build", "--out", str(tmp_path)])[0] == 0
    old = {p.name: p.read_bytes() for p in tmp_path.iterdir()}
    real = os.replace
    calls = []

    def replace(src, dst):
        calls.append(dst)
        if len(calls) == 3:
            raise OSError(errno.ENOSPC, "No space left on device")
        return real(src, dst)

    monkeypatch.setattr(os, "replace", replace)
    code, _, err = _run(["build", "--out", str(tmp_path)])
    monkeypatch.undo()
    assert code == 3 and "No space left on device" in err and err.count("\n") == 1
    assert {p.name: p.read_bytes() for p in tmp_path.iterdir()} == old  # same bytes; no .part left


# ------------------------------------------------------------------------------ every numeric flag
#: (command argv prefix, flag, parameter name in the message, values that are valid and must be skipped)
NUMERIC_FLAGS = [
    (ZZ + ["-o", "{tmp}/a.dst"], "--width-mm", "width_mm", ()),
    (ZZ + ["-o", "{tmp}/a.dst"], "--interval-mm", "interval_mm", ()),
    (ZZ + ["-o", "{tmp}/a.dst"], "--length-mm", "length_mm", ()),
    (ZZ + ["-o", "{tmp}/a.dst"], "--tube-radius-mm", "outer_radius_mm", ()),
    (ZZ + ["-o", "{tmp}/a.dst"], "--tube-inner-radius-mm", "inner_radius_mm", ("0",)),
    (ZZ + ["-o", "{tmp}/a.dst"], "--tube-g-mpa", "g_e_mpa", ()),
    (ZZ + ["-o", "{tmp}/a.dst"], "--clearance-mm", "clearance_mm", ("0",)),
    (ZZ + ["-o", "{tmp}/a.dst"], "--end-margin-mm", "end_margin_mm", ("0",)),
    (ZZ + ["-o", "{tmp}/a.dst", "--worksheet"], "--speed-spm", "speed_spm", ()),
    (CR + ["-o", "{tmp}/a.dst"], "--angle-deg", "angle_deg", ()),
    (CR + ["-o", "{tmp}/a.dst"], "--interval-mm", "interval_mm", ()),
    (["build", "--out", "{tmp}"], "--speed-spm", "speed_spm", ()),
    (["check", "{tmp}/good.dst", "--tube-path", "0,0 100,0"], "--tube-radius-mm", "outer_radius_mm", ()),
    (["check", "{tmp}/good.dst", "--tube-path", "0,0 100,0"], "--clearance-mm", "clearance_mm", ("0",)),
    (["check", "{tmp}/good.dst", "--tube-path", "0,0 100,0"], "--end-margin-mm", "end_margin_mm", ("0",)),
    (PRED + ["--pressure-kpa", "100"], "--width-mm", "width_mm", ()),
    (PRED + ["--pressure-kpa", "100"], "--interval-mm", "interval_mm", ()),
    (PRED + ["--pressure-kpa", "100"], "--length-mm", "length_mm", ()),
    (PRED + ["--pressure-kpa", "100"], "--tube-radius-mm", "outer_radius_mm", ()),
    (PRED + ["--pressure-kpa", "100"], "--tube-inner-radius-mm", "inner_radius_mm", ("0",)),
    (PRED + ["--pressure-kpa", "100"], "--tube-g-mpa", "g_e_mpa", ()),
    (PRED + ["--pressure-kpa", "100"], "--g-mpa", "g_mpa", ()),
    (PRED + ["--pressure-kpa", "100"], "--p0-kpa", "p0_kpa", ("0",)),
    (["predict", "cross", "--width-mm", "7", "--pressure-kpa", "100"], "--angle-deg", "angle_deg", ()),
    (["fit", "{tmp}/good.csv", *FIT], "--width-mm", "width_mm", ()),
    (["fit", "{tmp}/good.csv", *FIT], "--interval-mm", "interval_mm", ()),
    (["fit", "{tmp}/good.csv", *FIT], "--length-mm", "length_mm", ()),
    (["fit", "{tmp}/good.csv", *FIT], "--tube-radius-mm", "outer_radius_mm", ()),
    (["fit", "{tmp}/good.csv", *FIT], "--tube-g-mpa", "g_e_mpa", ()),
    (["fit", "{tmp}/good.csv", *FIT], "--g-mpa", "g_mpa", ()),
    (["fit", "{tmp}/good.csv", *FIT, "--fit", "g"], "--p0-kpa", "p0_kpa", ("0",)),
    (["fit", "{tmp}/good.csv", "--pattern", "cross", "--width-mm", "7"], "--angle-deg", "angle_deg", ()),
    (["preview", "mesh", "-o", "{tmp}/m.stl", "--pressure-kpa", "0:200:100"], "--shape-pressure-kpa",
     "shape_pressure_kpa", ("0",)),
    (["preview", "mesh", "-o", "{tmp}/m.stl", "--pressure-kpa", "0:200:100"], "--tolerance-mm", "tolerance_mm", ()),
    (["design", "--at-kpa", "150", "-o", "{tmp}/d.toml"], "--bend-deg", "bend_deg", ("0", "-1")),
    (["design", "--bend-deg", "90", "-o", "{tmp}/d.toml"], "--at-kpa", "--at-kpa", ()),
    (["design", "--bend-deg", "90", "--at-kpa", "150", "-o", "{tmp}/d.toml"], "--length-mm", "length_mm", ()),
]
BAD_VALUES = ("0", "-1", "nan", "inf", "abc")
NUMERIC_CASES = [(pre, flag, name, v) for pre, flag, name, ok in NUMERIC_FLAGS for v in BAD_VALUES if v not in ok]
INT_FLAGS = [
    (["preview", "shape", "-o", "{tmp}/s.svg", "--pressure-kpa", "0:200:100"], "--states", "states"),
    (["fit", "{tmp}/good.csv", *FIT, "--markers"], "--markers-per-side", "markers_per_side"),
    (["fit", "{tmp}/good.csv", *FIT, "--markers"], "--sides", "sides"),
]


def _set_flag(argv, flag, value):
    argv = list(argv)
    if flag in argv:
        argv[argv.index(flag) + 1] = value
    else:
        argv += [flag, value]
    return argv


@pytest.mark.parametrize("prefix, flag, name, value", NUMERIC_CASES,
                         ids=[f"{p[0]}{flag}={v}" for p, flag, _, v in NUMERIC_CASES])
def test_every_numeric_flag_refuses_bad_numbers(tmp_path, prefix, flag, name, value):
    _hostile_files(tmp_path)
    before = _listing(tmp_path)
    argv = _set_flag([a.replace("{tmp}", str(tmp_path)) for a in prefix], flag, f"{value}")
    code, out, err = _run(argv)
    assert code == 2, (code, err)
    assert err.count("\n") == 1 and "Traceback" not in err, err
    if value == "abc":
        assert f"argument {flag}: invalid float value: 'abc'" in err, err
    else:
        assert f"{name} must" in err and value in err, err  # parameter and value
        assert ("(" in err or "[" in err) and ")" in err or "]" in err, err  # and the allowed range
    assert _listing(tmp_path) == before


@pytest.mark.parametrize("prefix, flag, name", INT_FLAGS, ids=[f for _, f, _ in INT_FLAGS])
@pytest.mark.parametrize("value", ["0", "-1", "2.5", "abc"])
def test_integer_flags_refuse_bad_numbers(tmp_path, prefix, flag, name, value):
    _hostile_files(tmp_path)
    argv = _set_flag([a.replace("{tmp}", str(tmp_path)) for a in prefix], flag, value)
    code, _, err = _run(argv)
    assert code == 2 and err.count("\n") == 1 and "Traceback" not in err, (code, err)
    if value in ("2.5", "abc"):
        assert f"argument {flag}: invalid int value: '{value}'" in err, err
    else:
        assert f"{name} must be an integer" in err and value in err, err


def test_debug_shows_the_traceback(tmp_path):
    """--debug re-raises the error (Python prints the traceback); without it, one line."""
    from embroact.patterns.base.errors import ParameterError

    argv = ["zigzag", "--width-mm", "-1", "--interval-mm", "1", "-o", str(tmp_path / "a.dst")]
    with pytest.raises(ParameterError, match=r"width_mm must be in \(0, 200\), got -1"):
        main(["--debug"] + argv)
    assert _run(argv)[0] == 2
