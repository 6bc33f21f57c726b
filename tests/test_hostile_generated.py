"""Generated hostile inputs, every case under a 500 MB memory ceiling, each with its exact message.

The classes of the second robustness round, each generated rather than listed:

* extreme numbers for every numeric flag: 1e308, -1e308, 1e309 (inf), a 321-digit integer,
  and the doubles just past each flag's bounds (read from the flag's own range message, then
  ``math.nextafter`` past them); subnormals (5e-324) end in one line or succeed;
* option-like values for every flag that takes one (``--flag=--``, ``--flag --other``);
* output names: undecodable bytes, control characters, option-like, empty, ``.``, ``..``;
* size bombs for every reader: design and tube TOML, CSV (bytes, rows, columns, field
  length), embroidery files of every readable format (bytes, records), SVG path data
  (characters, numbers, segments);
* design files: 321-digit integers in every numeric key, control characters in names;
* tiny mesh tolerances (the refusal names a tolerance, which then works);
* stitches piled on one spot (``check`` stays linear).

All cases of one class run in one worker process (tests/hostile_worker.py) with
``RLIMIT_AS`` at :data:`CEILING_BYTES`: a case that tries to allocate past it fails there,
and the test fails with it. Every error case must give its documented exit code and exactly
one stderr line ``embroact...: error: <message>``; no case may print a warning or a traceback
or take more than :data:`CASE_SECONDS`.
"""
from __future__ import annotations

import json
import math
import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

from embroact.export.cli.main import commands
from test_hostile import FIT, NUMERIC_FLAGS, ZZ, _hostile_files

#: Memory ceiling of every hostile case [bytes] (address space of the worker process).
CEILING_BYTES = 500 * 2**20
#: Longest any one case may take [s].
CASE_SECONDS = 8.0
WORKER = Path(__file__).with_name("hostile_worker.py")
#: Cases run per class, filled as the classes run (test_generated_case_count reads it).
RAN: dict[str, int] = {}


def run_cases(cases: list[dict], timeout: float = 120.0) -> dict[str, dict]:
    """Run ``cases`` ({"id", "argv", "cwd"}) in one worker under the ceiling; results by id."""
    env = {**os.environ, "OPENBLAS_NUM_THREADS": "1", "OMP_NUM_THREADS": "1"}
    proc = subprocess.run([sys.executable, str(WORKER), str(CEILING_BYTES)], input=json.dumps(cases),
                          capture_output=True, text=True, timeout=timeout, env=env)
    lines = [json.loads(line) for line in proc.stdout.splitlines() if line.startswith("{")]
    results = {r["id"]: r for r in lines if "id" in r}
    started = [r["start"] for r in lines if "start" in r]
    assert len(results) == len(cases), (f"worker died in case {started[-1] if started else None!r} "
                                        f"(exit {proc.returncode}): {proc.stderr[-1500:]}")
    return results


def check_error(r: dict, code: int, message: str | None = None, *, pattern: str | None = None) -> None:
    """One case's result: exit ``code``, one stderr line that is ``message`` (after the prefix) or matches."""
    assert r["code"] == code, r
    lines = r["err"].splitlines()
    assert len(lines) == 1 and r["err"].endswith("\n"), r
    prefix, sep, text = lines[0].partition(": error: ")
    assert sep and prefix.startswith("embroact"), r
    if message is not None:
        assert text == message, (r["id"], text, message)
    if pattern is not None:
        assert re.fullmatch(pattern, text), (r["id"], text, pattern)


def check_clean(results: dict[str, dict], cls: str) -> None:
    """No case printed a warning or a traceback or ran past CASE_SECONDS; record the count."""
    for r in results.values():
        assert "Warning" not in r["err"] and "Traceback" not in r["err"] + r["out"], r
        assert r["s"] < CASE_SECONDS, (r["id"], r["s"])
    RAN[cls] = len(results)


def _expand(argv, tmp: Path) -> list[str]:
    return [a.replace("{tmp}", str(tmp)) for a in argv]


def _set_flag(argv: list[str], flag: str, value: str) -> list[str]:
    argv = list(argv)
    if flag in argv:
        i = argv.index(flag)
        return argv[:i] + [f"{flag}={value}"] + argv[i + 2:]
    return argv + [f"{flag}={value}"]


# ------------------------------------------------------------------------------ extreme numbers
_RANGE = re.compile(r"(?P<name>[\w-]+) must be (?:a finite number )?in (?P<lo_b>[\(\[])(?P<lo>[^,]+), "
                    r"(?P<hi>[^\)\]]+)(?P<hi_b>[\)\]])(?P<note> \([^)]*\))?, got ")


def _fmt(v: float) -> str:
    return f"{v:g}"


def _got(v: float, lo: float, hi: float) -> str:
    """How check_range shows a value: %g, in full when %g would print the bound it breaks."""
    text = _fmt(v)
    return repr(v) if v not in (lo, hi) and text in (_fmt(lo), _fmt(hi)) else text


def test_extreme_numbers_for_every_numeric_flag(tmp_path):
    """1e308, -1e308, 1e309, a 321-digit integer and subnormals, then just past each bound."""
    _hostile_files(tmp_path)
    probes, cases = {}, []
    for k, (prefix, flag, name, _) in enumerate(NUMERIC_FLAGS):
        argv = _expand(prefix, tmp_path)
        for tag, value in (("big", "1e308"), ("neg", "-1e308"), ("inf", "1e309"), ("digits", "1" + "0" * 320),
                           ("tiny", "5e-324"), ("negtiny", "-5e-324")):
            cases.append({"id": f"{k}{flag}={tag}", "argv": _set_flag(argv, flag, value), "cwd": str(tmp_path)})
            probes[cases[-1]["id"]] = (k, flag, name, tag)
    results = run_cases(cases)
    bounds = {}
    for cid, r in results.items():
        k, flag, name, tag = probes[cid]
        if tag in ("tiny", "negtiny"):  # a subnormal is in range for some flags: one line or success
            assert r["code"] in (0, 1, 2), r
            if r["code"] == 2:
                check_error(r, 2)
            continue
        m = _RANGE.search(r["err"])
        assert m and m["name"] == name, r
        rng = f"{m['lo_b']}{m['lo']}, {m['hi']}{m['hi_b']}{m['note'] or ''}"
        lo, hi = float(m["lo"]), float(m["hi"])
        if tag == "inf" or tag == "digits":
            check_error(r, 2, f"{name} must be a finite number in {rng}, got inf")
        else:
            v = 1e308 if tag == "big" else -1e308
            check_error(r, 2, f"{name} must be in {rng}, got {_got(v, lo, hi)}")
        bounds[k] = (name, rng, lo, m["lo_b"] == "[", hi, m["hi_b"] == "]")
    past = []
    for k, (name, rng, lo, lo_in, hi, hi_in) in bounds.items():
        prefix, flag, _, _ = NUMERIC_FLAGS[k]
        for tag, v in (("above", math.nextafter(hi, math.inf) if hi_in else hi),
                       ("below", math.nextafter(lo, -math.inf) if lo_in else lo)):
            if math.isfinite(v):
                past.append({"id": f"{k}{flag}={tag}", "argv": _set_flag(_expand(prefix, tmp_path), flag, repr(v)),
                             "cwd": str(tmp_path), "want": f"{name} must be in {rng}, got {_got(v, lo, hi)}"})
    past_results = run_cases([{k: c[k] for k in ("id", "argv", "cwd")} for c in past])
    for c in past:
        check_error(past_results[c["id"]], 2, c["want"])
    check_clean({**results, **past_results}, "extreme numbers")


def test_no_floating_point_warning_at_its_source(tmp_path):
    """With --debug main shows RuntimeWarnings instead of hiding them: extreme but valid-looking values for
    every numeric flag raise none (the one source found, a 1e-300 kPa shape's curvature squared to 0, is fixed)."""
    _hostile_files(tmp_path)
    cases = [{"id": f"{k}{flag}={v}", "argv": ["--debug"] + _set_flag(_expand(prefix, tmp_path), flag, v),
              "cwd": str(tmp_path)}
             for k, (prefix, flag, _, _) in enumerate(NUMERIC_FLAGS) for v in ("1e-300", "1e-9", "1e9", "1e300")]
    results = run_cases(cases)
    for r in results.values():
        assert "RuntimeWarning" not in r["err"], r
    RAN["debug warnings"] = len(results)


# ------------------------------------------------------------------------------ option-like values
def _value_flags() -> list[tuple[str, str, str]]:
    """(command, flag, argparse's name for it) for every option of every command that takes one value."""
    import argparse

    from embroact.export.cli.main import _command_parser

    out = []
    for name in commands():
        _, parser = _command_parser(name)
        for action in parser._actions:
            if action.option_strings and action.nargs is None and not isinstance(
                    action, (argparse._StoreTrueAction, argparse._HelpAction)):
                out.append((name, action.option_strings[-1], "/".join(action.option_strings)))
    return out


def test_option_like_values_for_every_flag(tmp_path):
    """``--flag=--`` (argparse drops a bare '--' value) and ``--flag --json`` (a value that is an option)."""
    cases, want = [], {}
    for cmd, flag, shown in _value_flags():
        for tag, argv, msg in (
            ("dashdash", [cmd, f"{flag}=--"], f"argument {flag}: expected a value, got '--' (an option, not a value)"),
            ("option", [cmd, flag, "--debug"], f"argument {shown}: expected one argument"),
        ):
            cases.append({"id": f"{cmd}{flag}:{tag}", "argv": argv, "cwd": str(tmp_path)})
            want[cases[-1]["id"]] = f"{msg} (see 'embroact {cmd} --help')"
    results = run_cases(cases)
    for cid, r in results.items():
        check_error(r, 2, want[cid])
        assert r["err"].startswith(f"embroact {cid.split('-')[0]}: error: "), r
    assert not list(tmp_path.iterdir())
    check_clean(results, "option-like values")


# ------------------------------------------------------------------------------ output names
BAD_NAMES = [
    ("undecodable", os.fsdecode(b"\xff\xfe.svg"), "{flag} must be a UTF-8 file name without control characters, "
                                                    "got '\\udcff\\udcfe.svg'"),
    ("control", "a\x01.svg", "{flag} must be a UTF-8 file name without control characters, got 'a\\x01.svg'"),
    ("nul-escape", "a\x1b[2J.svg", "{flag} must be a UTF-8 file name without control characters, got 'a\\x1b[2J.svg'"),
    ("option", "-x.svg", "{flag} must be a file name, not an option, got '-x.svg' (write ./-x.svg for a file "
                         "starting with '-')"),
    ("empty", "", "{flag} must be a non-empty file name, got ''"),
]
OUTPUT_FLAGS = [  # (argv prefix, flag as the message names it, flag to set)
    (ZZ + ["-o", "{tmp}/a.dst"], "--preview", "--preview"),
    (ZZ, "--output", "-o"),
    (["cross", "--width-mm", "7", "--interval-mm", "1.4", "--angle-deg", "45"], "--output", "-o"),
    (["build"], "--out", "--out"),
    (["fit", "{tmp}/good.csv", *FIT], "--output", "-o"),
    (["preview", "stitches"], "--output", "-o"),
    (["preview", "mesh"], "--output", "-o"),
]


def test_bad_output_names_refused_before_anything_is_written(tmp_path):
    _hostile_files(tmp_path)
    before = sorted(p.name for p in tmp_path.iterdir())
    cases, want = [], {}
    for k, (prefix, shown, flag) in enumerate(OUTPUT_FLAGS):
        for tag, value, msg in BAD_NAMES:
            value = value.replace(".svg", ".dst") if flag == "-o" and prefix[0] in ("zigzag", "cross") else value
            msg = msg.replace(".svg", ".dst") if value.endswith(".dst") else msg
            argv = _expand(prefix, tmp_path) + [f"{flag}={value}"]
            cases.append({"id": f"{k}{prefix[0]}{flag}:{tag}", "argv": argv, "cwd": str(tmp_path)})
            want[cases[-1]["id"]] = msg.format(flag=shown)
        for tag, value in (("dot", "."), ("dotdot", ".."), ("dir", str(tmp_path / "dir.dst"))):
            if flag == "--out":
                continue  # build's --out is a directory
            cases.append({"id": f"{k}{prefix[0]}{flag}:{tag}", "argv": _expand(prefix, tmp_path) + [flag, value],
                          "cwd": str(tmp_path)})
            want[cases[-1]["id"]] = (3, f"cannot write {value!r}: it is a directory")
            if flag == "-o" and prefix[0] in ("zigzag", "cross") and tag != "dir":  # the suffix picks the format
                want[cases[-1]["id"]] = (2, "file suffix must be one of .dst, .tbf, .pes, .pec, .jef, .exp, .vp3, "
                                            f".xxx, .u01, got {value!r}")
    results = run_cases(cases)
    for cid, r in results.items():
        code, msg = want[cid] if isinstance(want[cid], tuple) else (2, want[cid])
        check_error(r, code, msg)
    assert sorted(p.name for p in tmp_path.iterdir()) == before  # a.dst was not written before --preview failed
    check_clean(results, "output names")


# ------------------------------------------------------------------------------ size bombs
def _sparse(path: Path, size: int) -> Path:
    with open(path, "wb") as fh:
        fh.truncate(size)
    return path


def _csv_rows(n: int) -> bytes:
    return b"pressure_kpa,angle_deg\n" + b"".join(b"%d,%d\n" % (i % 300, max(0, i % 300 - 85) // 2) for i in range(n))


def test_size_bombs_for_every_reader(tmp_path):
    from embroact.export.machine.filecheck import readable_suffixes
    from embroact.patterns.base import validate as lim

    _hostile_files(tmp_path)
    t = tmp_path
    big_toml = _sparse(t / "big.toml", lim.TEXT_FILE_BYTES + 1)
    big_csv = _sparse(t / "big.csv", lim.CSV_FILE_BYTES + 1)
    (t / "rows.csv").write_bytes(_csv_rows(lim.CSV_ROWS + 1))
    (t / "short.csv").write_bytes(b"p\n" + b"0\n" * (lim.CSV_FILE_BYTES // 2 - 1))
    (t / "cols.csv").write_text(",".join(f"c{i}" for i in range(lim.CSV_COLUMNS + 1)) + "\n1\n")
    (t / "field.csv").write_text("pressure_kpa,angle_deg\n0," + "1" * (lim.CSV_FIELD_CHARS + 1) + "\n")
    (t / "mfield.csv").write_text("pressure_kpa,m1_x\n0," + "1" * (lim.CSV_FIELD_CHARS + 1) + "\n")
    design = '[[actuator]]\nname = "A"\npattern = "zigzag"\nwidth_mm = 7\ninterval_mm = 1\npath = "{}"\n'
    long_d = "M 0 0 " + "L 1 0 " * (lim.PATH_CHARS // 6 + 1)
    (t / "chars.toml").write_text(design.format(long_d))
    many = "M 0 0 " + " ".join(f"L {i} {i % 2}" for i in range(1, lim.PATH_SEGMENTS * 7 // 2 + 2))
    (t / "numbers.toml").write_text(design.format(many))
    seg = "M 0 0 " + " ".join(f"L {i * 0.01:.2f} {(i % 2) * 0.01}" for i in range(1, lim.PATH_SEGMENTS + 1))
    (t / "segments.toml").write_text(design.format(seg))
    n_numbers = 2 + 2 * (lim.PATH_SEGMENTS * 7 // 2 + 1)
    (t / "tubes.toml").write_text("".join(f'[[tube]]\npath_mm = "0,{i} 100,{i}"\n'
                                          for i in range(lim.DESIGN_ACTUATORS + 1)))
    (t / "segments-tables.toml").write_text('[[actuator]]\nname = "A"\n' + "".join(
        '[[actuator.segment]]\npattern = "zigzag"\nwidth_mm = 7\ninterval_mm = 1\nlength_mm = 5\n'
        for _ in range(lim.ACTUATOR_SEGMENTS + 1)))
    (t / "actuators.toml").write_text("".join(
        f'[[actuator]]\nname = "A{i}"\npattern = "zigzag"\nwidth_mm = 7\ninterval_mm = 1\nlength_mm = 20\n'
        for i in range(lim.DESIGN_ACTUATORS + 1)))
    big_svg = _sparse(t / "big.svg", lim.TEXT_FILE_BYTES + 1)
    (t / "many.svg").write_text('<svg xmlns="http://www.w3.org/2000/svg" width="200mm" height="200mm" '
                                f'viewBox="0 0 200 200"><path id="t" d="{seg} L 0 5"/></svg>')
    cases = [
        ("design-bytes", ["check", str(big_toml)], f"{big_toml}: design file must be at most "
                                                    f"{lim.TEXT_FILE_BYTES:,} bytes, got {lim.TEXT_FILE_BYTES + 1:,}"),
        ("tube-bytes", ["check", f"{t}/good.dst", "--tube", str(big_toml)],
         f"{big_toml}: tube file must be at most {lim.TEXT_FILE_BYTES:,} bytes, got {lim.TEXT_FILE_BYTES + 1:,}"),
        ("calibration-bytes", ["predict", "zigzag", "--width-mm", "7", "--calibration", str(big_toml),
                               "--pressure-kpa", "200"],
         f"{big_toml}: calibration file must be at most {lim.TEXT_FILE_BYTES:,} bytes, got "
         f"{lim.TEXT_FILE_BYTES + 1:,}"),
        ("csv-bytes", ["fit", str(big_csv), *FIT],
         f"{big_csv}: CSV file must be at most {lim.CSV_FILE_BYTES:,} bytes, got {lim.CSV_FILE_BYTES + 1:,}"),
        ("csv-rows", ["fit", f"{t}/rows.csv", *FIT],
         f"{t}/rows.csv must have at most {lim.CSV_ROWS:,} data rows, got more (line {lim.CSV_ROWS + 2} is data row "
         f"{lim.CSV_ROWS + 1:,})"),
        ("csv-many-short-rows", ["fit", f"{t}/short.csv", *FIT],  # 2 bytes a row up to the byte limit
         f"{t}/short.csv must have at most {lim.CSV_ROWS:,} data rows, got more (line {lim.CSV_ROWS + 2} is data row "
         f"{lim.CSV_ROWS + 1:,})"),
        ("csv-columns", ["fit", f"{t}/cols.csv", *FIT],
         f"{t}/cols.csv line 1: a row must have at most {lim.CSV_COLUMNS:,} columns, got {lim.CSV_COLUMNS + 1:,}"),
        ("csv-field", ["fit", f"{t}/field.csv", *FIT],
         f"{t}/field.csv line 2: not CSV: field larger than field limit ({lim.CSV_FIELD_CHARS}) "
         f"(at most {lim.CSV_FIELD_CHARS:,} characters per field)"),
        ("shape-csv-rows", ["design", "--target-shape", f"{t}/rows.csv", "--at-kpa", "200", "-o", f"{t}/d.toml"],
         f"{t}/rows.csv must have at most {lim.CSV_ROWS:,} data rows, got more (line {lim.CSV_ROWS + 2} is data row "
         f"{lim.CSV_ROWS + 1:,})"),
        ("marker-csv-field", ["fit", f"{t}/mfield.csv", *FIT, "--markers", "--markers-per-side", "3", "--sides", "1"],
         f"{t}/mfield.csv line 2: not CSV: field larger than field limit ({lim.CSV_FIELD_CHARS}) "
         f"(at most {lim.CSV_FIELD_CHARS:,} characters per field)"),
        ("path-chars", ["check", f"{t}/chars.toml"],
         f"{t}/chars.toml: actuator[0].path: SVG path must be at most {lim.PATH_CHARS:,} characters, got {len(long_d):,}"),
        ("path-numbers", ["check", f"{t}/numbers.toml"],
         f"{t}/numbers.toml: actuator[0].path: SVG path must have at most {lim.PATH_SEGMENTS:,} segments, got "
         f"{n_numbers:,} numbers (at least {-(-n_numbers // 7):,} segments)"),
        ("path-segments", ["check", f"{t}/segments.toml"],  # a move-to and PATH_SEGMENTS lines
         f"{t}/segments.toml: actuator[0].path: SVG path must have at most {lim.PATH_SEGMENTS:,} segments, "
         f"got {lim.PATH_SEGMENTS + 1:,}"),
        ("design-actuators", ["check", f"{t}/actuators.toml"],
         f"{t}/actuators.toml: actuator: a design must have at most {lim.DESIGN_ACTUATORS:,} actuators, "
         f"got {lim.DESIGN_ACTUATORS + 1:,}"),
        ("actuator-segments", ["check", f"{t}/segments-tables.toml"],
         f"{t}/segments-tables.toml: actuator[0].segment: an actuator must have at most {lim.ACTUATOR_SEGMENTS:,} "
         f"segments, got {lim.ACTUATOR_SEGMENTS + 1:,}"),
        ("tube-tables", ["check", f"{t}/good.dst", "--tube", f"{t}/tubes.toml"],
         f"{t}/tubes.toml: must have at most {lim.DESIGN_ACTUATORS:,} [[tube]] tables (one per actuator), "
         f"got {lim.DESIGN_ACTUATORS + 1:,}"),
        ("svg-bytes", ZZ + ["-o", f"{t}/a.dst", "--path", str(big_svg)],
         f"{big_svg}: SVG file must be at most {lim.TEXT_FILE_BYTES:,} bytes, got {lim.TEXT_FILE_BYTES + 1:,}"),
        ("svg-segments", ZZ + ["-o", f"{t}/a.dst", "--path", f"{t}/many.svg#t"],  # a move-to and the lines
         f"{t}/many.svg#t: SVG path must have at most {lim.PATH_SEGMENTS:,} segments, got {lim.PATH_SEGMENTS + 2:,}"),
    ]
    for suffix in readable_suffixes():
        f = _sparse(t / f"big.{suffix}", lim.MACHINE_FILE_BYTES + 1)
        cases.append((f"machine-bytes-{suffix}", ["check", str(f)],
                      f"{f}: embroidery file must be at most {lim.MACHINE_FILE_BYTES:,} bytes, "
                      f"got {lim.MACHINE_FILE_BYTES + 1:,}"))
    good_exp = _machine_bytes("exp")
    extra = 2 * (lim.MACHINE_FILE_RECORDS + 1)  # EXP: 2 bytes per stitch, (0, 0) is a stitch in place
    (t / "records.exp").write_bytes(good_exp + bytes(extra))
    results = run_cases([{"id": cid, "argv": argv, "cwd": str(t)} for cid, argv, _ in cases]
                        + [{"id": "machine-records-exp", "argv": ["check", f"{t}/records.exp"], "cwd": str(t)}])
    for cid, _, msg in cases:
        check_error(results[cid], 2, msg)
    check_error(results["machine-records-exp"], 2, pattern=re.escape(
        f"{t}/records.exp: embroidery file must have at most {lim.MACHINE_FILE_RECORDS:,} records, got ") + r"[\d,]+")
    got = int(results["machine-records-exp"]["err"].rsplit("got ", 1)[1].replace(",", ""))
    assert got >= extra // 2 + 100, got  # every zero pair a record, plus the design's own
    check_clean(results, "size bombs")


def _machine_bytes(fmt: str) -> bytes:
    from embroact.export.machine.formats import encode
    from embroact.patterns import Centerline, ZigzagParams, zigzag

    return encode(zigzag(Centerline.straight(100.0), ZigzagParams(7.0, 1.0)), fmt)[0]


def test_stitches_piled_on_one_spot_are_checked_in_linear_time(tmp_path):
    """Zero records (a stitch in place) appended to real files: the density rule counts coincident
    stitches once with their multiplicity, so check stays in seconds and under the ceiling."""
    cases = []
    for fmt, per_record in (("dst", 3), ("exp", 2)):
        good = _machine_bytes(fmt)
        body = good[:-3] + bytes(per_record * 150_000) + good[-3:] if fmt == "dst" else good + bytes(2 * 150_000)
        (tmp_path / f"piled.{fmt}").write_bytes(body)
        cases.append({"id": fmt, "argv": ["check", f"{tmp_path}/piled.{fmt}", "--tube-path", "0,0 100,0"],
                      "cwd": str(tmp_path)})
    results = run_cases(cases)
    for r in results.values():
        assert r["code"] == 1 and "EA" in r["out"], r  # rule errors found (the pile), reported
    check_clean(results, "piled stitches")


MUTATIONS = ("flip", "zero-run", "ff-run", "truncate", "duplicate", "shuffle")


def _mutate(data: bytes, how: str, rng) -> bytes:
    """One seeded mutation of a machine file (the fuzzing round's operators)."""
    b = bytearray(data)
    i = rng.randrange(len(b))
    n = rng.randrange(1, max(2, len(b) // 8))
    if how == "flip":
        for k in rng.sample(range(len(b)), min(len(b), 40)):
            b[k] ^= 1 << rng.randrange(8)
    elif how in ("zero-run", "ff-run"):
        b[i:i + n] = bytes([0 if how == "zero-run" else 0xFF]) * n
    elif how == "truncate":
        del b[i:]
    elif how == "duplicate":
        b[i:i] = b[i:i + n] * 20
    else:
        chunk = b[i:i + n]
        rng.shuffle(chunk)
        b[i:i + n] = chunk
    return bytes(b)


def test_mutated_machine_files_of_every_format(tmp_path):
    """Seeded mutations of a real file of every format embroact writes: each is read and checked, or one
    line (exit 2), within the ceiling and a few seconds."""
    import random

    from embroact.export.machine.formats import FORMATS

    rng = random.Random(18)
    cases = []
    for fmt in FORMATS:
        good = _machine_bytes(fmt)
        for how in MUTATIONS:
            for k in range(2):
                f = tmp_path / f"{how}{k}.{fmt}"
                f.write_bytes(_mutate(good, how, rng))
                cases.append({"id": f.name, "argv": ["check", str(f), "--tube-path", "0,0 100,0"], "cwd": str(tmp_path)})
    results = run_cases(cases)
    for r in results.values():
        assert r["code"] in (0, 1, 2), r
        if r["code"] == 2:
            check_error(r, 2, pattern=re.escape(f"{tmp_path}/{r['id']}: ") + r".+")
    check_clean(results, "mutated machine files")


# ------------------------------------------------------------------------------ design-file numbers and names
DESIGN = ('{top}[[actuator]]\nname = "{name}"\npattern = "zigzag"\nwidth_mm = {width}\ninterval_mm = 1\n'
          'length_mm = {length}\norigin_mm = [{ox}, 0]\n{extra}')
NUMBER_KEYS = [  # (where as the message names it, design text fields)
    ("actuator[0].width_mm", {"width": "{v}"}),
    ("actuator[0].length_mm", {"length": "{v}"}),
    ("actuator[0].origin_mm[0]", {"ox": "{v}"}),
    ("actuator[0].rotation_deg", {"extra": "rotation_deg = {v}\n"}),
    ("actuator[0].tie_count", {"extra": "tie_count = {v}\n"}),
    ("actuator[0].tie_stitch_mm", {"extra": "tie_stitch_mm = {v}\n"}),
    ("actuator[0].model.g_mpa", {"extra": "[actuator.model]\ng_mpa = {v}\n"}),
    ("tube.outer_radius_mm", {"top": "[tube]\nouter_radius_mm = {v}\n"}),
    ("machine.speed_spm", {"top": "[machine]\nspeed_spm = {v}\n"}),
    ("operation.max_pressure_kpa", {"top": "[operation]\nmax_pressure_kpa = {v}\n"}),
]
CONTROL_CHARS = ["\x00", "\x01", "\x1b", "\x7f", "\x9b"]


def _design(**fields) -> str:
    base = {"top": "", "name": "A", "width": "7", "length": "100", "ox": "0", "extra": ""}
    return DESIGN.format(**{**base, **fields})


def test_design_file_numbers_and_names(tmp_path):
    cases, want = [], {}
    for k, (where, fields) in enumerate(NUMBER_KEYS):
        for tag, v in (("digits", "1" + "0" * 320), ("negdigits", "-1" + "0" * 320)):
            f = tmp_path / f"n{k}{tag}.toml"
            f.write_text(_design(**{key: text.format(v=v) for key, text in fields.items()}))
            cases.append({"id": f.stem, "argv": ["check", str(f)], "cwd": str(tmp_path)})
            want[f.stem] = f"{f}: {where}: must be a finite number, got an integer of 321 digits"
    for k, ch in enumerate(CONTROL_CHARS):
        esc = f"\\u{ord(ch):04x}"
        for tag, fields, where in (("actuator", {"name": f"A{esc}"}, "actuator[0]: name"),
                                   ("design", {"top": f'name = "D{esc}"\n'}, "name: name")):
            f = tmp_path / f"c{k}{tag}.toml"
            f.write_text(_design(**fields))
            cases.append({"id": f.stem, "argv": ["build", str(f), "--out", str(tmp_path)], "cwd": str(tmp_path)})
            shown = repr(("A" if tag == "actuator" else "D") + ch)
            want[f.stem] = f"{f}: {where} must not contain control characters, got {shown}"
        cases.append({"id": f"cli{k}", "argv": ZZ + ["-o", f"{tmp_path}/x.dst", "--name", f"A{ch}"],
                      "cwd": str(tmp_path)})
        want[f"cli{k}"] = f"name must not contain control characters, got {repr('A' + ch)}"
    before = sorted(p.name for p in tmp_path.iterdir())
    results = run_cases(cases)
    for cid, r in results.items():
        check_error(r, 2, want[cid])
    assert sorted(p.name for p in tmp_path.iterdir()) == before
    check_clean(results, "design numbers and names")


# ------------------------------------------------------------------------------ mesh tolerance
def test_tiny_tolerances_refused_with_a_tolerance_that_works(tmp_path):
    """Every refused tolerance names the smallest that fits; building with it then succeeds under the ceiling."""
    values = ["5e-324", "1e-300", "1e-7", "1e-5", "0.0005"]
    cases = [{"id": f"{cmd}={v}", "argv": argv + ["--tolerance-mm", v], "cwd": str(tmp_path)}
             for v in values for cmd, argv in (("build", ["build", "--out", str(tmp_path)]),
                                                ("mesh", ["preview", "mesh", "-o", f"{tmp_path}/m.glb"]))]
    results = run_cases(cases)
    fits = set()
    for cmd in ("build", "mesh"):  # a subnormal never reaches arithmetic
        check_error(results.pop(f"{cmd}=5e-324"), 2, "tolerance_mm must be in (0, 10] and not subnormal "
                                                     "(0 or of size >= 2.22507e-308), got 4.94066e-324")
    for r in results.values():
        check_error(r, 2, pattern=r"tolerance_mm=\S+ would make (about \S+|more than 1e308) triangles for 'A1', "
                                  r"more than the limit 60,000; use tolerance_mm >= (\S+)")
        fits.add(r["err"].rsplit(">= ", 1)[1].strip())
    assert len(fits) == 1 and not list(tmp_path.iterdir()), fits  # one answer for the design; nothing written
    again = run_cases([{"id": "fit", "argv": ["preview", "mesh", "-o", f"{tmp_path}/m.glb", "--tolerance-mm",
                                                fits.pop()], "cwd": str(tmp_path)}])
    assert again["fit"]["code"] == 0, again
    check_clean({**results, **again}, "mesh tolerance")


# ------------------------------------------------------------------------------ hypothesis properties
def test_hostile_properties_under_the_ceiling():
    """tests/hostile_props.py: check_range, SVG arcs and output names on generated extreme values."""
    import hostile_props

    env = {**os.environ, "OPENBLAS_NUM_THREADS": "1"}
    proc = subprocess.run([sys.executable, str(Path(hostile_props.__file__)), str(CEILING_BYTES)],
                          capture_output=True, text=True, timeout=300, env=env)
    assert proc.returncode == 0, proc.stdout[-3000:] + proc.stderr[-3000:]
    ran = re.findall(r"(\w+): (\d+) examples", proc.stdout)
    assert len(ran) == 3, proc.stdout
    RAN["hypothesis properties"] = sum(int(n) for _, n in ran)


# ------------------------------------------------------------------------------ count
def test_generated_case_count():
    """Runs last in this module (pytest keeps file order): every class ran; the total is printed."""
    if not RAN:
        pytest.skip("no generated class ran in this session")
    assert all(n > 0 for n in RAN.values()), RAN
    print(f"generated hostile cases: {sum(RAN.values())} {RAN}")
