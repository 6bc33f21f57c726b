"""Outputs stay all-or-nothing, signals and pipes end quietly, odd strings stay one line.

Expected behaviour (export/files/atomic.py and export/cli/main.py document it):

* every output of a run is checked before the first is written: two outputs naming one
  file, or a directory where a file goes, are errors with nothing written;
* a failing rename rolls back the ones before it (old files restored from hard-link
  backups, new ones removed); SIGTERM during staging cleans up like Ctrl-C (exit 143), and
  during the commit it waits until the commit is whole;
* new files get 0666 minus the umask, rewritten files keep their mode;
* a closed pipe ends the program with 141 and nothing on stderr; a closed stdout with 0;
* undecodable bytes in an argument are one escaped line, never a UnicodeEncodeError.

Tests that need a real process (signals, pipes, raw argv bytes) run ``python -m
embroact.export`` under the same 500 MB ceiling as the generated cases.
"""
from __future__ import annotations

import contextlib
import errno
import io
import os
import re
import resource
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import pytest

from embroact.export.cli.main import main
from test_hostile_generated import CEILING_BYTES

ZZ = ["zigzag", "--width-mm", "7", "--interval-mm", "1"]


def _run(argv):
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        code = main(argv)
    return code, out.getvalue(), err.getvalue()


def _ceiling():
    resource.setrlimit(resource.RLIMIT_AS, (CEILING_BYTES, CEILING_BYTES))


def _process(argv, **kwargs) -> subprocess.Popen:
    env = {**os.environ, "OPENBLAS_NUM_THREADS": "1"}
    return subprocess.Popen([sys.executable, "-m", "embroact.export", *argv], env=env, preexec_fn=_ceiling, **kwargs)


def _hidden(d: Path) -> list[str]:
    return sorted(p.name for p in d.iterdir() if p.name.startswith("."))


# ------------------------------------------------------------------------------ checked before written
@pytest.mark.parametrize("extra, first, second", [
    (["--preview", "{d}/a.dst"], "a.dst", "a.dst"),
    (["--preview", "{d}/./a.dst"], "a.dst", "./a.dst"),
    (["--preview", "{d}/sub/../a.dst"], "a.dst", "sub/../a.dst"),
    (["--worksheet", "--preview", "{d}/a.worksheet.txt"], "a.worksheet.txt", "a.worksheet.txt"),
    (["--preview", "{d}/link.dst"], "a.dst", "link.dst"),
], ids=["same", "dot", "dotdot", "worksheet", "symlink"])
def test_two_outputs_naming_one_file_are_refused(extra, first, second):
    """The message quotes both paths whole: a short folder, so no path is cut (pytest's own tmp_path
    grows with the xdist worker's name and the test's)."""
    with tempfile.TemporaryDirectory(prefix="two-") as d:
        _two_outputs_refused(Path(d), extra, first, second)


def _two_outputs_refused(tmp_path, extra, first, second):
    (tmp_path / "sub").mkdir()
    (tmp_path / "link.dst").symlink_to(tmp_path / "a.dst")
    code, _, err = _run(ZZ + ["-o", f"{tmp_path}/a.dst"] + [a.replace("{d}", str(tmp_path)) for a in extra])
    shown = {"a.dst": f"{tmp_path}/a.dst", "a.worksheet.txt": f"{tmp_path}/a.worksheet.txt"}
    assert code == 2 and err.count("\n") == 1, err
    assert re.match(rf"embroact: error: two outputs name one file: --\S+ '{re.escape(shown.get(first, first))}' "
                    rf"and --preview '", err), err
    assert second.split("/")[-1] in err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["link.dst", "sub"]


def test_a_directory_in_the_way_fails_before_anything_is_written(tmp_path):
    """build --out d where d/preview.svg is a directory: nothing in d changes (was: earlier files replaced)."""
    assert _run(["build", "--out", str(tmp_path), "--no-previews"])[0] == 0
    old = {p.name: p.read_bytes() for p in tmp_path.iterdir()}
    (tmp_path / "preview.svg").unlink()
    (tmp_path / "preview.svg").mkdir()
    code, _, err = _run(["build", "--out", str(tmp_path), "--no-previews", "--speed-spm", "500"])
    assert code == 3 and err.endswith(f"embroact: error: cannot write '{tmp_path}/preview.svg': it is a directory\n")
    assert {p.name: p.read_bytes() for p in tmp_path.iterdir() if p.is_file()} == {
        k: v for k, v in old.items() if k != "preview.svg"}


def test_build_out_empty_is_an_error(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert _run(["build", "--out", ""]) == (2, "", "embroact: error: --out must be a non-empty file name, got ''\n")
    assert not list(tmp_path.iterdir())


def test_failed_rename_rolls_back_new_files_too(tmp_path, monkeypatch):
    """Into an empty directory: the third rename fails, the two files already renamed are removed."""
    real, calls = os.replace, []

    def replace(src, dst):
        calls.append(dst)
        if len(calls) == 3:
            raise OSError(errno.EXDEV, "Invalid cross-device link")
        return real(src, dst)

    monkeypatch.setattr(os, "replace", replace)
    code, _, err = _run(["build", "--out", str(tmp_path), "--no-previews"])
    monkeypatch.undo()
    assert code == 3 and "Invalid cross-device link" in err and err.count("\n") == 1, err
    assert len(calls) == 3 and not list(tmp_path.iterdir())


def test_failed_rename_restores_old_files_from_their_backups(tmp_path, monkeypatch):
    """Old contents differ from the new ones (another speed): after the failure every file has its old bytes."""
    assert _run(["build", "--out", str(tmp_path), "--no-previews", "--speed-spm", "300"])[0] == 0
    old = {p.name: p.read_bytes() for p in tmp_path.iterdir()}
    real, calls = os.replace, []

    def replace(src, dst):
        calls.append(dst)
        if len(calls) == len(old):  # the last one fails: all earlier ones were new worksheets
            raise OSError(errno.EPERM, "Operation not permitted")
        return real(src, dst)

    monkeypatch.setattr(os, "replace", replace)
    code, _, err = _run(["build", "--out", str(tmp_path), "--no-previews", "--speed-spm", "900"])
    monkeypatch.undo()
    assert code == 3 and "Operation not permitted" in err, err
    assert {p.name: p.read_bytes() for p in tmp_path.iterdir()} == old  # no .part, no .old, old bytes


# ------------------------------------------------------------------------------ signals
def test_sigterm_while_staging_cleans_up_like_ctrl_c(tmp_path, monkeypatch):
    target = tmp_path / "a.dst"
    target.write_bytes(b"old")
    real = os.fsync

    def fsync(fd):
        os.kill(os.getpid(), signal.SIGTERM)
        return real(fd)

    monkeypatch.setattr(os, "fsync", fsync)
    code, _, err = _run(ZZ + ["-o", str(target), "--preview", f"{tmp_path}/p.svg"])
    monkeypatch.undo()
    assert code == 143 and err.splitlines()[-1] == "embroact: terminated" and ": error:" not in err, err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.dst"] and target.read_bytes() == b"old"


def test_sigterm_during_the_commit_waits_for_it(tmp_path, monkeypatch):
    """The signal arrives at the first rename; it is held until every file is renamed (no mix of old and new)."""
    for name in ("a.dst", "p.svg"):
        (tmp_path / name).write_bytes(b"old")
    real = os.replace

    def replace(src, dst):
        os.kill(os.getpid(), signal.SIGTERM)
        return real(src, dst)

    monkeypatch.setattr(os, "replace", replace)
    code, _, err = _run(ZZ + ["-o", f"{tmp_path}/a.dst", "--preview", f"{tmp_path}/p.svg"])
    monkeypatch.undo()
    assert code == 143 and err.splitlines()[-1] == "embroact: terminated" and ": error:" not in err, err
    assert (tmp_path / "a.dst").read_bytes()[:3] == b"LA:" and (tmp_path / "p.svg").read_bytes().startswith(b"<")
    assert _hidden(tmp_path) == []


def test_sigterm_at_any_moment_leaves_no_staged_files(tmp_path):
    """Real processes terminated at spread-out moments of a build: never a .part or .old file left."""
    procs = []
    for k, delay in enumerate((0.3, 0.8, 1.3, 1.8, 2.4, 3.0)):
        d = tmp_path / f"run{k}"
        d.mkdir()
        procs.append((d, delay, _process(["build", "--out", str(d)], stdout=subprocess.DEVNULL,
                                         stderr=subprocess.PIPE)))
    start = time.monotonic()
    for d, delay, p in procs:
        time.sleep(max(0.0, start + delay - time.monotonic()))
        p.send_signal(signal.SIGTERM)
    for d, delay, p in procs:
        _, err = p.communicate(timeout=60)
        assert p.returncode in (0, 143, -signal.SIGTERM), (delay, p.returncode, err)
        assert b"Traceback" not in err, err
        assert _hidden(d) == [], (delay, _hidden(d))


# ------------------------------------------------------------------------------ modes
def test_new_files_follow_the_umask_and_rewritten_files_keep_their_mode(tmp_path):
    old = os.umask(0o027)
    try:
        assert _run(ZZ + ["-o", f"{tmp_path}/a.dst"])[0] == 0
        assert (tmp_path / "a.dst").stat().st_mode & 0o777 == 0o640
        os.chmod(tmp_path / "a.dst", 0o600)
        os.umask(0o022)
        assert _run(ZZ + ["-o", f"{tmp_path}/a.dst", "--preview", f"{tmp_path}/p.svg"])[0] == 0
        assert (tmp_path / "a.dst").stat().st_mode & 0o777 == 0o600  # a private file stays private
        assert (tmp_path / "p.svg").stat().st_mode & 0o777 == 0o644
    finally:
        os.umask(old)


# ------------------------------------------------------------------------------ pipes and odd argv bytes
def test_a_reader_that_goes_away_ends_the_program_quietly():
    p = _process(["check", "--rules"], stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    p.stdout.close()  # before anything is written: every write meets a closed pipe
    _, err = p.communicate(timeout=60)
    assert (p.returncode, err) == (141, b"")


def test_a_closed_stdout_ends_the_program_quietly():
    """Started with stdout closed (``embroact ... >&-``): Python has no sys.stdout; nothing fails."""
    def closed_stdout():
        os.close(1)
        _ceiling()

    q = subprocess.run([sys.executable, "-m", "embroact.export", "check", "--rules"], stderr=subprocess.PIPE,
                       timeout=60, preexec_fn=closed_stdout)
    assert (q.returncode, q.stderr) == (0, b"")


def test_undecodable_bytes_in_arguments_are_one_escaped_line(tmp_path):
    p = _process(ZZ + ["-o", os.fsencode(tmp_path / "a.dst"), b"--preview=\xff\xfe.svg"], stdout=subprocess.PIPE,
                 stderr=subprocess.PIPE)
    out, err = p.communicate(timeout=60)
    assert p.returncode == 2 and out == b""
    assert err == (b"embroact: error: --preview must be a UTF-8 file name without control characters, "
                   b"got '\\udcff\\udcfe.svg'\n")
    assert not list(tmp_path.iterdir())  # the machine file was not written first
    q = _process(["check", os.fsencode(tmp_path) + b"/\xff.dst"], stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    _, err = q.communicate(timeout=60)
    assert q.returncode == 2 and err == (b"embroact: error: " + os.fsencode(tmp_path)
                                         + b"/\\udcff.dst: cannot read embroidery file: No such file or directory\n"), err


# ------------------------------------------------------------------------------ usage and names
@pytest.mark.parametrize("argv, message", [
    (ZZ[:1] + ["--widht-mm", "7", "--interval-mm", "1", "-o", "a.dst"],
     "embroact zigzag: error: unrecognized arguments: --widht-mm 7 (did you mean --width-mm?) "
     "(see 'embroact zigzag --help')"),
    (ZZ[:1] + ["--wid", "7", "--interval-mm", "1", "-o", "a.dst"],  # no abbreviations
     "embroact zigzag: error: unrecognized arguments: --wid 7 (did you mean --width-mm?) (see 'embroact zigzag --help')"),
    (["predict", "zigzag", "--width-mm", "7", "--pressure-kpa=--"],
     "embroact predict: error: argument --pressure-kpa: expected a value, got '--' (an option, not a value) "
     "(see 'embroact predict --help')"),
], ids=["typo-before-missing", "abbreviation", "dashdash"])
def test_usage_errors_name_the_real_problem(tmp_path, monkeypatch, argv, message):
    monkeypatch.chdir(tmp_path)
    assert _run(argv) == (2, "", message + "\n")


def test_a_long_design_name_builds_with_a_capped_file_stem(tmp_path):
    name = "n" * 300
    (tmp_path / "d.toml").write_text(f'name = "{name}"\n[[actuator]]\nname = "A"\npattern = "zigzag"\n'
                                     'width_mm = 7\ninterval_mm = 1\nlength_mm = 100\n')
    out = tmp_path / "out"
    out.mkdir()
    code, _, err = _run(["build", str(tmp_path / "d.toml"), "--out", str(out), "--no-previews"])
    assert code == 0, err
    assert f"{'n' * 100}.dst" in {p.name for p in out.iterdir()}


def test_arc_radii_that_square_to_zero_or_infinity(tmp_path):
    """SVG: radii too small for the chord are scaled up (1e-300 -> the semicircle of radius 25); the short arc
    of a radius past 1e150 is a straight line; the long way round leaves the coordinate range."""
    def dst(path):
        f = tmp_path / "x.dst"
        code, _, err = _run(ZZ + ["-o", str(f), "--path", path, "--force"])
        assert code == 0, err
        return f.read_bytes()

    assert dst("M 0 0 A 1e-300 1e-300 0 0 1 50 0") == dst("M 0 0 A 25 25 0 0 1 50 0")
    assert dst("m 0 0 a 1e-300 2e-300 0 0 1 50 0") == dst("M 0 0 A 25 50 0 0 1 50 0")
    assert dst("M 0 0 A 1e308 1e308 0 0 1 50 0") == dst("M 0 0 L 50 0")
    code, _, err = _run(ZZ + ["-o", str(tmp_path / "y.dst"), "--path", "M 0 0 A 1e308 1e308 0 1 1 50 0"])
    assert (code, err) == (2, "embroact: error: SVG path: an arc of radius 1e+308 mm taking the large way round "
                              "(large-arc-flag 1) leaves the coordinate range [-1e+07, 1e+07] mm\n")


def test_control_characters_in_an_input_file_name_are_escaped_on_stdout(tmp_path):
    """A file named with an ESC sequence is reported as ``\\x1b[2J``: it cannot clear the terminal."""
    from test_hostile_generated import _machine_bytes

    f = tmp_path / "e\x1b[2Jx.dst"
    f.write_bytes(_machine_bytes("dst"))
    code, out, err = _run(["check", str(f)])
    assert code == 0 and "\x1b" not in out + err, (out, err)
    assert out.startswith(f"{tmp_path}/e\\x1b[2Jx.dst: embroidery file, format dst"), out


@pytest.mark.parametrize("sig, code, word", [(signal.SIGTERM, 143, "terminated"), (signal.SIGINT, 130, "interrupted")])
def test_a_signal_a_library_turns_into_its_own_error_still_ends_as_the_signal(tmp_path, monkeypatch, sig, code, word):
    """SIGTERM while numpy was being imported ended with exit 1 and numpy's ImportError traceback: the import
    machinery replaced the handler's exception with its own. A command ends as the signal asks, one line."""
    real = os.fsync

    def fsync(fd):
        try:
            os.kill(os.getpid(), sig)
            time.sleep(5.0)  # the handler raises here
        except KeyboardInterrupt:  # Terminated is one: what PyCapsule_Import does to it
            raise ImportError('PyCapsule_Import could not import module "datetime"') from None
        return real(fd)

    monkeypatch.setattr(os, "fsync", fsync)
    rc, _, err = _run(ZZ + ["-o", str(tmp_path / "a.dst")])
    monkeypatch.undo()
    assert (rc, err.splitlines()[-1]) == (code, f"embroact: {word}") and "Traceback" not in err, err
    assert list(tmp_path.iterdir()) == []
