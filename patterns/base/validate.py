"""Input limits and the checks every boundary runs before any arithmetic or allocation.

Numbers are checked by :func:`embroact.patterns.base.errors.check_range` (finite, inside
the bounds; integers too large for a float are out of range, not an ``OverflowError``);
every reader (command line, design file, calibration and marker CSV, SVG path data,
embroidery file) calls these checks first, so hostile input ends in one line of the same
form everywhere::

    <what> must be <allowed>, got <value>

with the value shown by ``repr`` (control characters and undecodable bytes escaped, long
values cut to :data:`SHOWN_CHARS` characters), never a traceback, a NaN or a huge allocation.

Limits
------
The documented sizes, checked before a file is read into memory (:func:`read_limited`
reads only regular files, refusing FIFOs and devices at once, and at most ``limit + 1``
bytes, so a growing file cannot exhaust memory either):

=========================  ==================  =============================================
limit                      value               applies to
=========================  ==================  =============================================
``TEXT_FILE_BYTES``        4 MiB               design, tube and calibration TOML files, SVG files
``CSV_FILE_BYTES``         16 MiB              measurement and marker CSV files
``CSV_ROWS``               30,000              data rows of one CSV file (fit of 30,000: ~2 s, ~110 MB)
``CSV_COLUMNS``            1,000               columns of one CSV row
``CSV_FIELD_CHARS``        1,000               characters of one CSV field
``MACHINE_FILE_BYTES``     1.5 MiB             embroidery files given to ``check`` (520,000 DST records)
``MACHINE_FILE_RECORDS``   500,000             records of an embroidery file (every format)
``PATH_CHARS``             1,000,000           characters of one SVG path ``d`` string
``PATH_SEGMENTS``          5,000               drawing commands of one SVG path (check: 4 s)
``NAME_CHARS``             1,000               design and actuator names (file stems: 100)
``DESIGN_ACTUATORS``       1,000               actuators of one design (check: 14 s)
``ACTUATOR_SEGMENTS``      200                 ``[[actuator.segment]]`` tables of one actuator (check: 3 s)
``DESIGN_SEGMENTS``        1,000               segment tables of all actuators of a design (check: ~15 s)
``COORD_MM``               1e7 mm (10 km)      abs(coordinate) of a path point, SVG or not
=========================  ==================  =============================================

An embroidery file of more than ``MACHINE_FILE_RECORDS`` records is far beyond any hoop (a
200 x 200 mm hoop filled at 0.5 mm holds 160,000 stitches). Both caps keep ``check``
under 500 MB: pystitch decodes about 0.3 KB per record, and 500,000 records (a 1 MB EXP
file) take 270 MB and 4.5 s to check.

Examples
--------
>>> from embroact.patterns.base.validate import check_count, check_name
>>> try:
...     check_count("markers_per_side", 10**40, low=2, high=1000)
... except ValueError as exc:
...     print(exc)
markers_per_side must be an integer in [2, 1000], got an integer of 41 digits
>>> try:
...     check_name("name", "A\\x01")
... except ValueError as exc:
...     print(exc)
name must not contain control characters, got 'A\\x01'
"""
from __future__ import annotations

import os
import unicodedata

from .errors import DesignFileError, EmbroactError, ParameterError, PathError

__all__ = [
    "TEXT_FILE_BYTES",
    "CSV_FILE_BYTES",
    "CSV_ROWS",
    "CSV_COLUMNS",
    "CSV_FIELD_CHARS",
    "MACHINE_FILE_BYTES",
    "MACHINE_FILE_RECORDS",
    "PATH_CHARS",
    "PATH_SEGMENTS",
    "PATH_POINTS",
    "NAME_CHARS",
    "DESIGN_ACTUATORS",
    "ACTUATOR_SEGMENTS",
    "DESIGN_SEGMENTS",
    "COORD_MM",
    "SHOWN_CHARS",
    "shown",
    "check_count",
    "check_name",
    "check_output_name",
    "check_coordinates",
    "read_limited",
    "read_input",
]

TEXT_FILE_BYTES = 4 * 1024 * 1024
CSV_FILE_BYTES = 16 * 1024 * 1024
CSV_ROWS = 30_000
CSV_COLUMNS = 1_000
CSV_FIELD_CHARS = 1_000
MACHINE_FILE_BYTES = 1536 * 1024
MACHINE_FILE_RECORDS = 500_000
PATH_CHARS = 1_000_000
PATH_SEGMENTS = 5_000
#: Largest number of points a path may have (a centerline's vertices, a flattened SVG path's points).
PATH_POINTS = 2_000_000
NAME_CHARS = 1_000
DESIGN_ACTUATORS = 1_000
ACTUATOR_SEGMENTS = 200
DESIGN_SEGMENTS = 1_000
#: Largest |coordinate| of a path point [mm] (10 km: far beyond any hoop, far below float overflow).
COORD_MM = 1e7
#: Longest value an error message repeats (longer ones are cut and marked with '...').
SHOWN_CHARS = 80


def shown(value: object) -> str:
    """``repr`` of ``value`` cut to :data:`SHOWN_CHARS` characters: safe for one terminal line.

    Parameters
    ----------
    value : object
        Anything a user gave.

    Returns
    -------
    str
        Its ``repr``, ending in ``...`` when cut.

    Examples
    --------
    >>> shown("x" * 100)
    "'xxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxx...'"
    >>> shown("caf\\udce9")
    "'caf\\\\udce9'"
    """
    if isinstance(value, str) and len(value) > SHOWN_CHARS:
        return repr(value[: SHOWN_CHARS - 2] + "...")
    text = repr(value)
    return text if len(text) <= SHOWN_CHARS else text[: SHOWN_CHARS - 3] + "..."


def check_count(name: str, value: object, *, low: int, high: int) -> int:
    """Return ``value`` as an int in ``[low, high]``, or raise :class:`ParameterError`.

    Counts size allocations (markers, states, rows), so the upper bound is always finite.

    Parameters
    ----------
    name : str
        Parameter name for the message.
    value : object
        The value to check; bools and non-integers are refused.
    low, high : int
        Inclusive bounds.

    Returns
    -------
    int
        ``value``.

    Examples
    --------
    >>> check_count("markers", 7, low=2, high=64)
    7
    >>> try:
    ...     check_count("markers", 7.0, low=2, high=64)
    ... except ValueError as exc:
    ...     print(exc)
    markers must be an integer in [2, 64], got 7.0
    """
    if isinstance(value, bool) or not isinstance(value, int):
        raise ParameterError(f"{name} must be an integer in [{low}, {high}], got {shown(value)}")
    if not low <= value <= high:
        digits = len(str(abs(value)))
        got = str(value) if digits <= 24 else f"an integer of {digits} digits"
        raise ParameterError(f"{name} must be an integer in [{low}, {high}], got {got}")
    return value


def _control(text: str) -> str | None:
    return next((c for c in text if unicodedata.category(c) in ("Cc", "Cs")), None)


def check_name(name: str, value: object, *, max_chars: int = NAME_CHARS) -> str:
    """Return ``value`` if it is a printable, non-empty string of at most ``max_chars`` characters.

    Names end up in SVG (XML 1.0 allows no control characters), worksheets and the
    terminal, so control characters (``\\x00``, ``\\x01``, escape sequences) are refused.

    Parameters
    ----------
    name : str
        Parameter name for the message.
    value : object
        The name to check.
    max_chars : int, optional
        Longest name allowed [characters].

    Returns
    -------
    str
        ``value``.

    Examples
    --------
    >>> check_name("name", "A1")
    'A1'
    >>> try:
    ...     check_name("name", "A" * 9, max_chars=8)
    ... except ValueError as exc:
    ...     print(exc)
    name must be at most 8 characters, got 9
    """
    if not isinstance(value, str) or not value.strip():
        raise ParameterError(f"{name} must be a non-empty string, got {shown(value)}")
    if _control(value) is not None:
        raise ParameterError(f"{name} must not contain control characters, got {shown(value)}")
    if len(value) > max_chars:
        raise ParameterError(f"{name} must be at most {max_chars} characters, got {len(value)}")
    return value


def check_output_name(flag: str, value: object) -> str:
    """Return ``value`` if it can name an output file: non-empty, not option-like, UTF-8, printable.

    ``-o --preview`` or ``--out=--`` are typos, not file names (write ``./-x`` for a file
    that starts with ``-``); names that are not UTF-8 (``$'\\xff'`` from a shell) or carry
    control characters cannot be printed or written into a worksheet faithfully.

    Parameters
    ----------
    flag : str
        The option that names the output, for the message (``"--out"``).
    value : object
        The file name given.

    Returns
    -------
    str
        ``value``.

    Examples
    --------
    >>> check_output_name("--out", "out")
    'out'
    >>> try:
    ...     check_output_name("--preview", "\\udcff\\udcfe")
    ... except ValueError as exc:
    ...     print(exc)
    --preview must be a UTF-8 file name without control characters, got '\\udcff\\udcfe'
    """
    if not isinstance(value, str) or not value:
        raise ParameterError(f"{flag} must be a non-empty file name, got {shown(value)}")
    if value.startswith("-"):
        raise ParameterError(f"{flag} must be a file name, not an option, got {shown(value)} "
                             f"(write ./{value} for a file starting with '-')")
    if _control(value) is not None:
        raise ParameterError(f"{flag} must be a UTF-8 file name without control characters, got {shown(value)}")
    return value


def check_coordinates(name: str, worst_mm: float) -> None:
    """Refuse a largest absolute coordinate ``worst_mm`` beyond :data:`COORD_MM` (or NaN), before arithmetic.

    Parameters
    ----------
    name : str
        What the coordinates belong to, for the message (``"path"``).
    worst_mm : float
        The largest absolute coordinate [mm].

    Raises
    ------
    PathError
        ``worst_mm`` is NaN or beyond :data:`COORD_MM`.

    Examples
    --------
    >>> try:
    ...     check_coordinates("path", 2e7)
    ... except ValueError as exc:
    ...     print(exc)
    path coordinates must be in [-1e+07, 1e+07] mm, got 2e+07
    """
    if not worst_mm <= COORD_MM:
        raise PathError(f"{name} coordinates must be in [-{COORD_MM:g}, {COORD_MM:g}] mm, got {worst_mm:g}")


#: What a file that is no regular file is, by the ``stat`` test that recognises it.
_SPECIAL_FILES = (("S_ISFIFO", "a FIFO"), ("S_ISCHR", "a character device"), ("S_ISBLK", "a block device"),
                  ("S_ISSOCK", "a socket"))


def read_limited(path: str | os.PathLike, limit: int, what: str) -> bytes:
    """The bytes of the regular file ``path``, refusing files larger than ``limit`` without reading them whole.

    Only regular files are read: the file is opened without blocking (a FIFO with no writer
    would otherwise wait forever) and a FIFO, a device (``/dev/zero``, a terminal) or a
    socket is refused before a byte is read. At most ``limit + 1`` bytes are read, so a file
    that grows while read is bounded too.

    Parameters
    ----------
    path : str or os.PathLike
        The file.
    limit : int
        Largest size accepted [bytes].
    what : str
        What the file is, for the messages (``"design file"``).

    Returns
    -------
    bytes
        The file's content.

    Raises
    ------
    DesignFileError
        ``<path>: <what> must be at most <limit> bytes, got <size>`` (``more than`` when the
        file grew), or ``<path>: cannot read <what>: not a regular file (a FIFO)``.
    OSError
        When the file cannot be opened or read (the caller words it); a directory is
        ``IsADirectoryError``.

    Examples
    --------
    >>> try:
    ...     read_limited("/dev/zero", 10, "design file")
    ... except ValueError as exc:
    ...     print(exc)
    /dev/zero: cannot read design file: not a regular file (a character device)
    """
    import stat

    fd = os.open(path, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_CLOEXEC", 0)
                 | getattr(os, "O_BINARY", 0))
    with open(fd, "rb") as fh:
        mode = os.fstat(fd).st_mode
        if stat.S_ISDIR(mode):
            raise IsADirectoryError(21, "Is a directory", os.fsdecode(path))
        kind = next((text for test, text in _SPECIAL_FILES if getattr(stat, test)(mode)), None)
        if kind is not None or not stat.S_ISREG(mode):
            raise DesignFileError(f"{os.fsdecode(path)}: cannot read {what}: not a regular file ({kind or 'special'})")
        size = os.fstat(fd).st_size
        if size > limit:
            raise DesignFileError(f"{os.fsdecode(path)}: {what} must be at most {limit:,} bytes, got {size:,}")
        data = fh.read(limit + 1)
    if len(data) > limit:
        raise DesignFileError(f"{os.fsdecode(path)}: {what} must be at most {limit:,} bytes, got more")
    return data


def read_input(path: str | os.PathLike, limit: int, what: str, *, encoding: str | None = None,
               error: type[EmbroactError] = DesignFileError):
    """An input file's bytes (or its text in ``encoding``), every failure one line naming the file.

    :func:`read_limited` with the messages every reader gives: ``<path>: cannot read <what>:
    <reason>``, ``<path>: <what> must be at most <limit> bytes, got <size>`` and ``<path>:
    <what> is not <encoding> text (byte <n>)``, raised as ``error``.

    Parameters
    ----------
    path, limit, what
        As for :func:`read_limited`.
    encoding : str or None, optional
        Decode the bytes with it; None: return the bytes.
    error : type, optional
        The :class:`EmbroactError` subclass every failure is raised as.

    Returns
    -------
    bytes or str
        The bytes, or the text when ``encoding`` is given.

    Examples
    --------
    >>> read_input("missing.toml", TEXT_FILE_BYTES, "design file", encoding="utf-8")
    Traceback (most recent call last):
    ...
    embroact.patterns.base.errors.DesignFileError: missing.toml: cannot read design file: No such file or directory
    """
    name = os.fsdecode(path)
    try:
        data = read_limited(path, limit, what)
    except DesignFileError as exc:
        raise (exc if error is DesignFileError else error(str(exc))) from None
    except OSError as exc:
        raise error(f"{name}: cannot read {what}: {exc.strerror or exc}") from None
    if encoding is None:
        return data
    try:
        return data.decode(encoding)
    except UnicodeDecodeError as exc:
        label = "UTF-8" if encoding.lower().startswith("utf") else encoding
        raise error(f"{name}: {what} is not {label} text (byte {exc.start})") from None
