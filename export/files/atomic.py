"""Atomic file output: the files of one run are all written, or none is changed.

How, and where the file system sets limits
------------------------------------------
1. **Check** every target before anything is written (:func:`prepare_outputs`): its directory
   exists and is writable, the target is not a directory, and no two outputs name one file
   (``-o a.dst --preview a.dst``, or two spellings of one path).
2. **Stage**: each file is written and synced to a hidden temporary file
   ``.NAME.XXXX.part`` next to its target. A failure here (disk full, I/O error, Ctrl-C,
   SIGTERM: the command line turns it into an interrupt) removes every staged file and
   leaves every target untouched.
3. **Commit**: with SIGINT and SIGTERM held back (their handlers run once the commit is
   over), each existing target is first hard-linked to a hidden ``.NAME.XXXX.old`` backup,
   then the staged files are renamed over their targets. If a rename fails (a file of
   another user in a sticky directory, a full inode table), the ones already renamed are
   rolled back from their backups (or removed if they are new) and the error is raised.
   Backups are removed at the end, and each directory is synced.

The commit cannot be all-or-nothing where the file system offers no hard links (FAT, some
network mounts): a target replaced before the failing one then keeps its new content. A
power loss during the commit can leave a mix of old and new files (the renames are atomic
one by one, not together), and a ``kill -9`` can leave ``.part``/``.old`` files behind.

File modes: a new file gets ``0666`` minus the umask, as ``open()`` would create it; a file
that is rewritten keeps its permission bits (a private ``0600`` file stays private).

Examples
--------
>>> import os, tempfile
>>> from embroact.export.files.atomic import write_bytes_atomic, write_files_atomic
>>> d = tempfile.mkdtemp()
>>> write_bytes_atomic(os.path.join(d, "a.txt"), b"hello")
>>> open(os.path.join(d, "a.txt"), "rb").read()
b'hello'
>>> try:
...     write_files_atomic({os.path.join(d, "a.txt"): b"1", os.path.join(d, ".", "a.txt"): b"2"})
... except ValueError as exc:
...     print(str(exc).replace(d, "D"))
two outputs name one file: 'D/a.txt' and 'D/./a.txt'
"""
from __future__ import annotations

import contextlib
import os
import signal
import threading
from pathlib import Path
from typing import Iterable, Iterator, Mapping, Sequence

from ...patterns.base.errors import ExportError, ParameterError

__all__ = [
    "write_bytes_atomic",
    "write_text_atomic",
    "write_files_atomic",
    "prepare_outputs",
    "check_command_files",
    "check_output_dir",
    "check_writable_dir",
    "abandon_staged",
    "NAME_BYTES",
]


def check_output_dir(path: str | os.PathLike) -> Path:
    """Return ``path`` as a Path whose parent directory exists and is writable, and that is no directory.

    Parameters
    ----------
    path : str or os.PathLike
        An output file.

    Returns
    -------
    pathlib.Path

    Raises
    ------
    ExportError
        One line naming the directory when it is missing or not writable, or the target when
        it is a directory (``--preview .``).

    Examples
    --------
    >>> import tempfile
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     check_output_dir(f"{tmp}/a.dst").name
    ...     try:
    ...         check_output_dir(tmp)
    ...     except ExportError as exc:
    ...         print(str(exc).replace(tmp, "TMP"))
    'a.dst'
    cannot write 'TMP': it is a directory
    """
    p = Path(path)
    check_writable_dir(p.parent)
    if p.is_dir() or os.fspath(path) in ("", ".", "..") or os.fspath(path).endswith(os.sep):
        raise ExportError(f"cannot write {os.fspath(path)!r}: it is a directory")
    return p


def check_writable_dir(path: str | os.PathLike) -> Path:
    """Return ``path`` as a Path if it is an existing directory files can be created in.

    Parameters
    ----------
    path : str or os.PathLike
        An output directory.

    Returns
    -------
    pathlib.Path

    Raises
    ------
    ExportError
        One line naming the directory when it is missing, not a directory or not writable.

    Examples
    --------
    >>> try:
    ...     check_writable_dir("no-such-dir")
    ... except ExportError as exc:
    ...     print(exc)
    output directory 'no-such-dir' does not exist
    """
    if os.fspath(path) == "":
        raise ExportError("output directory must be a non-empty path, got ''")
    d = Path(path)
    if not d.is_dir():
        what = "is not a directory" if d.exists() else "does not exist"
        raise ExportError(f"output directory {str(d)!r} {what}")
    if not os.access(d, os.W_OK | os.X_OK):
        raise ExportError(f"output directory {str(d)!r} is not writable")
    return d


def prepare_outputs(paths: Iterable[str | os.PathLike]) -> list[Path]:
    """Check every output of one run before any is written; return them as Paths.

    Parameters
    ----------
    paths : iterable of str or os.PathLike
        The outputs.

    Returns
    -------
    list of pathlib.Path

    Raises
    ------
    ExportError
        A directory is missing or not writable, or a target is a directory.
    ParameterError
        Two outputs name one file (after resolving ``.``, ``..`` and symbolic links).

    Examples
    --------
    >>> import tempfile
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     [p.name for p in prepare_outputs([f"{tmp}/a.dst", f"{tmp}/b.svg"])]
    ['a.dst', 'b.svg']
    """
    paths = list(paths)
    targets = [check_output_dir(p) for p in paths]
    seen: dict[str, int] = {}
    for i, p in enumerate(targets):
        key = os.path.realpath(p)
        if key in seen:
            raise ParameterError(f"two outputs name one file: {os.fspath(paths[seen[key]])!r} and {os.fspath(paths[i])!r}")
        seen[key] = i
    return targets


def _same_file(a: Path, b: Path) -> bool:
    """True when ``a`` and ``b`` name one file: one real path, or one inode (a hard link)."""
    if os.path.realpath(a) == os.path.realpath(b):
        return True
    try:
        return os.path.samefile(a, b)
    except OSError:  # either does not exist (yet): only the real paths could have matched
        return False


def check_command_files(outputs: Sequence[tuple[str, str | os.PathLike]],
                        inputs: Sequence[tuple[str, str | os.PathLike | None]] = ()) -> list[Path]:
    """Check the output files of one command before any work; return them as Paths.

    Every command runs this first, so that a clash is one line and no search runs in vain:
    each output is a file name (:func:`~embroact.patterns.base.validate.check_output_name`)
    in a writable directory and no directory itself (``-o .``, ``-o /``), no two outputs
    name one file (``-o a.toml --svg ./a.toml``), and no output names an input of the run
    (``fit data.csv -o data.csv``), which the command would replace before the user noticed.

    Parameters
    ----------
    outputs : sequence of (flag, path)
        Each output with the option that named it (or the file it derives from).
    inputs : sequence of (flag, path or None)
        The files the command reads; None entries are skipped.

    Returns
    -------
    list of pathlib.Path
        The outputs, in order.

    Raises
    ------
    ParameterError
        A bad name, two outputs naming one file, or an output naming an input.
    ExportError
        A directory is missing or not writable, or a target is a directory.

    Examples
    --------
    >>> import os, tempfile
    >>> d = tempfile.mkdtemp()
    >>> a = os.path.join(d, "a.toml")
    >>> try:
    ...     check_command_files([("--output", a), ("--svg", os.path.join(d, ".", "a.toml"))])
    ... except ValueError as exc:
    ...     print(str(exc).replace(d, "D"))
    two outputs name one file: --output 'D/a.toml' and --svg 'D/./a.toml'
    """
    from ...patterns.base.validate import check_output_name, shown

    targets = [check_output_dir(check_output_name(flag, os.fspath(p))) for flag, p in outputs]
    for i, p in enumerate(targets):
        for j in range(i):
            if _same_file(p, targets[j]):
                raise ParameterError(f"two outputs name one file: {outputs[j][0]} {shown(os.fspath(outputs[j][1]))} "
                                     f"and {outputs[i][0]} {shown(os.fspath(outputs[i][1]))}")
        for flag, source in inputs:
            if source is not None and _same_file(p, Path(source)):
                raise ParameterError(f"{outputs[i][0]} {shown(os.fspath(outputs[i][1]))} would replace the input "
                                     f"{flag} {shown(os.fspath(source))}: write the output to another file")
    return targets


def _cannot_write(p: Path, exc: OSError) -> ExportError:
    return ExportError(f"cannot write {str(p)!r}: {exc.strerror or exc}")


def _new_file_mode() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return 0o666 & ~mask


#: Flags of a staged file: created here and now (never an existing file or a symbolic link), not inherited.
_NEW_FILE = (os.O_WRONLY | os.O_CREAT | os.O_EXCL
             | getattr(os, "O_NOFOLLOW", 0) | getattr(os, "O_CLOEXEC", 0) | getattr(os, "O_BINARY", 0))
#: Random names tried for one hidden file before giving up (each collision is one in 2**32).
_NAME_TRIES = 8


#: Longest file name most file systems take [bytes]; a hidden name's copy of its target's name is cut to fit.
NAME_BYTES = 255


def _cut_name(name: str, limit: int) -> str:
    """``name`` cut to at most ``limit`` bytes in the file system's encoding, at a character boundary.

    >>> _cut_name("ab\u00e9cd", 3), _cut_name("ab\u00e9cd", 4), _cut_name("abc", 10)
    ('ab', 'ab', 'abc')
    """
    data = os.fsencode(name)
    if len(data) <= limit:
        return name
    cut = data[:limit]
    while cut and cut[-1] >= 0x80:  # a multi-byte character may be cut: drop trailing non-ASCII bytes
        cut = cut[:-1]
    return os.fsdecode(cut)


def _hidden_name(p: Path, suffix: str, create):
    """``(create(name), name)`` for the first free hidden name ``.NAME.XXXXXXXX<suffix>`` next to ``p``.

    ``create`` makes the file (or link) and raises FileExistsError when the name is taken; the
    standard library's tempfile module would do the same for the staged file, but importing it
    (with shutil, random and the compression modules) costs a few milliseconds at every start.
    """
    stem = _cut_name(p.name, NAME_BYTES - len(f"..{'0' * 8}{suffix}"))

    def attempt():
        name = str(p.parent / f".{stem}.{os.urandom(4).hex()}{suffix}")
        return create(name), name

    for _ in range(_NAME_TRIES - 1):
        with contextlib.suppress(FileExistsError):
            return attempt()
    return attempt()


#: Staged files not yet renamed or removed: what :func:`abandon_staged` removes when the process must end now.
_STAGED: set[str] = set()
#: Held while staged files are renamed over their targets (a forced end waits for it).
_COMMITTING = threading.Lock()


def abandon_staged() -> None:
    """Remove every staged file of this process, after a rename in progress: the process is about to end.

    The command line's watchdog (:mod:`embroact.export.cli.signals`) calls this from its own
    thread when the main thread did not answer a signal in time. The commit lock is taken
    and kept, so no rename starts afterwards.

    Examples
    --------
    >>> import subprocess, sys
    >>> code = "from embroact.export.files.atomic import abandon_staged, _STAGED; abandon_staged(); print(len(_STAGED))"
    >>> subprocess.run([sys.executable, "-c", code], capture_output=True, text=True).stdout.split()  # its own process
    ['0']
    """
    _COMMITTING.acquire(timeout=5.0)
    for name in list(_STAGED):
        _remove(name)


def _stage(p: Path, data: bytes, mode: int) -> str:
    """Write ``data`` to a synced temporary file next to ``p``; return its name (removed on failure)."""
    def create(name):
        fd = os.open(name, _NEW_FILE, 0o600)
        _STAGED.add(name)
        return fd

    try:  # a directory root may not write to (/proc, a read-only mount) passes os.access
        fd, tmp = _hidden_name(p, ".part", create)
    except OSError as exc:
        raise _cannot_write(p, exc) from exc
    try:
        with os.fdopen(fd, "wb") as fh:
            fh.write(data)
            fh.flush()
            os.fsync(fh.fileno())
        os.chmod(tmp, mode)
    except BaseException as exc:
        _remove(tmp)
        if isinstance(exc, OSError):
            raise _cannot_write(p, exc) from exc
        raise
    return tmp


def _remove(name: str) -> None:
    with contextlib.suppress(FileNotFoundError):
        os.unlink(name)
    _STAGED.discard(name)


def _mode(p: Path, new: int) -> int:
    try:
        return p.stat().st_mode & 0o7777
    except OSError:
        return new


def _backup(p: Path) -> str | None:
    """A hard link to the existing target ``p`` (None if there is none or links are unsupported)."""
    if not p.exists():
        return None
    try:
        return _hidden_name(p, ".old", lambda name: os.link(p, name))[1]
    except OSError:
        return None


@contextlib.contextmanager
def _signals_held() -> Iterator[None]:
    """Hold SIGINT and SIGTERM back while the files are renamed; deliver them afterwards.

    Python runs signal handlers in the main thread whichever thread the signal reached, so
    the handlers are swapped for one that only records (an OS-level mask would not do: a
    process-directed signal goes to any thread that does not mask it). Elsewhere than in the
    main thread, where handlers cannot be set, the renames run unprotected.
    """
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    pending: list[signal.Signals] = []
    old = {s: signal.signal(s, lambda signum, frame: pending.append(signal.Signals(signum)))
           for s in (signal.SIGINT, signal.SIGTERM)}
    try:
        yield
    finally:
        for s, handler in old.items():
            signal.signal(s, handler)
        if pending:
            first = old[pending[0]]
            if callable(first):
                first(pending[0], None)
            elif first == signal.SIG_DFL:
                signal.raise_signal(pending[0])


def _sync_dirs(dirs: set[Path]) -> None:
    for d in dirs:
        with contextlib.suppress(OSError):  # not every file system syncs directories
            fd = os.open(d, os.O_RDONLY)
            try:
                os.fsync(fd)
            finally:
                os.close(fd)


def _commit(staged: list[tuple[str, Path]]) -> None:
    """Rename every staged file over its target; on a failure roll back the ones done."""
    done: list[tuple[Path, str | None]] = []
    backups: list[str] = []
    try:
        for tmp, p in staged:
            backup = _backup(p)
            if backup is not None:
                backups.append(backup)
            try:
                os.replace(tmp, p)
            except OSError as exc:
                raise _cannot_write(p, exc) from exc
            done.append((p, backup))
    except BaseException:
        for p, backup in reversed(done):
            with contextlib.suppress(OSError):
                if backup is not None:
                    os.rename(backup, p)
                else:
                    os.unlink(p)
        raise
    finally:
        for name in backups:
            _remove(name)


def write_files_atomic(outputs: Mapping[str | os.PathLike, bytes]) -> None:
    """Write several files so that a failed run changes none of them (see the module docstring).

    Parameters
    ----------
    outputs : mapping of path to bytes
        Each file and its content.

    Raises
    ------
    ExportError
        One line naming the file that could not be written or the directory that is missing.
    ParameterError
        Two outputs name one file.

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     write_files_atomic({f"{tmp}/a.txt": b"a", f"{tmp}/b.txt": b"b"})
    ...     sorted(p.name for p in Path(tmp).iterdir())
    ['a.txt', 'b.txt']
    """
    targets = prepare_outputs(outputs)
    new_mode = _new_file_mode()
    staged: list[tuple[str, Path]] = []
    try:
        for p, data in zip(targets, outputs.values()):
            staged.append((_stage(p, data, _mode(p, new_mode)), p))
        with _signals_held(), _COMMITTING:
            _commit(staged)
            _STAGED.difference_update(tmp for tmp, _ in staged)
        _sync_dirs({p.parent for p in targets})
    finally:
        for tmp, _ in staged:
            _remove(tmp)


def write_bytes_atomic(path: str | os.PathLike, data: bytes) -> None:
    """Write ``data`` to ``path`` via a temporary file in the same directory and ``os.replace``.

    Parameters
    ----------
    path : str or os.PathLike
        The file.
    data : bytes
        Its content.

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     write_bytes_atomic(f"{tmp}/a.bin", b"\\x00\\x01")
    ...     Path(tmp, "a.bin").read_bytes()
    b'\\x00\\x01'
    """
    write_files_atomic({path: data})


def write_text_atomic(path: str | os.PathLike, text: str) -> None:
    """UTF-8 text version of :func:`write_bytes_atomic` (newlines kept as given).

    Parameters
    ----------
    path : str or os.PathLike
        The file.
    text : str
        Its content.

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     write_text_atomic(f"{tmp}/a.txt", "r0 = 2.6 mm")
    ...     Path(tmp, "a.txt").read_text()
    'r0 = 2.6 mm'
    """
    write_bytes_atomic(path, text.encode("utf-8"))
