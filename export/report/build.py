"""Build a design: machine files, worksheet, stitch preview, and whatever later stages add.

Order of work (nothing is written until every output is ready in memory)::

    design --analyse--> DesignAnalysis (plan, derived geometry, models, memoised curves)
                              |
                              +--check(analysis)--> findings --gate--+
                                                                     |
        machine files (one per format) <-- encode(plan) -------------+
        worksheet.json / worksheet.txt <-- worksheet(plan, findings, models)
        preview.svg                    <-- plan_svg(plan)            |
        template.svg                   <-- template_svg(plan, hoop)  |
        template-a4.html, -letter.html <-- the template on sheets     |
        stage outputs                  <-- stage(context) for each stage (context.analysis)
                                                  |
                         write every file atomically into out_dir

The design is analysed once (:func:`embroact.predict.analysis.analyse`); the rules, the
worksheet and every stage read that one analysis and its curves, so a build never derives
or predicts an actuator twice.

Plug-in points
--------------
``check``
    ``check(analysis) -> sequence of Finding``: the design-rule checks (default
    :func:`embroact.predict.rules.check_design`).  Any finding whose ``is_error`` is
    true stops the build with :class:`DesignRuleError` (nothing written) unless
    ``force=True``.  The findings are listed on the worksheet either way.
``stages``
    Callables ``stage(context: BuildContext) -> {file name: str | bytes}`` for the
    bend chart, side view, 3D model, report...  They run after the built-in
    outputs and see them in ``context.outputs``; their files are written with the
    rest.  A stage that raises stops the build before anything is written.

Examples
--------
>>> import tempfile, os
>>> from embroact.patterns.plan import Command, Role, StitchPlan
>>> plan = StitchPlan.from_records([
...     (0, 3.5, Command.STOP, Role.CONTROL), (0, 3.5, Command.STITCH, Role.TIE_IN),
...     (1, -3.5, Command.STITCH, Role.LEG), (1, -3.5, Command.TRIM, Role.CONTROL),
...     (1, -3.5, Command.END, Role.CONTROL, -1)], name="demo")
>>> out = tempfile.mkdtemp()
>>> res = build_plan_outputs(plan, out, formats=("dst", "pes"))
>>> sorted(os.listdir(out))
['demo.dst', 'demo.pes', 'preview.svg', 'template-a4.html', 'template-letter.html', 'template.svg', 'worksheet.json', 'worksheet.txt']
"""
from __future__ import annotations

import json
import os
import re
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Callable, Mapping, Sequence

from ...patterns.base.errors import ParameterError, PatternError
from ...patterns.plan import StitchPlan
from ..files.atomic import check_command_files, check_writable_dir, write_files_atomic
from ..machine.formats import FORMATS, WriteResult, encode
from .worksheet import DEFAULT_SPEED_SPM, Worksheet, worksheet

__all__ = [
    "DEFAULT_SPEED_SPM",
    "SPLIT_LONG_IGNORES",
    "forced_split",
    "DesignRuleError",
    "BuildContext",
    "BuildResult",
    "Stage",
    "parse_formats",
    "safe_stem",
    "write_outputs",
    "build",
    "build_plan_outputs",
]


#: Rules left out when the writer splits over-long legs on request (``split_long``): the split
#: pieces stay within the format's per-record limit (EA102) and so within a machine maximum
#: stitch (EA103) that is not below it.
SPLIT_LONG_IGNORES = ("EA102", "EA103")


def forced_split(findings, force: bool) -> bool:
    """True when ``force`` writes a design whose legs exceed a format's record limit (EA102 errors):
    the writer then splits them as ``split_long`` does (stitches outside the tube corridor) instead
    of refusing, so that ``--force`` writes what the rules refused.

    Parameters
    ----------
    findings : iterable of Finding
        The design's findings.
    force : bool
        The build writes despite errors.

    Returns
    -------
    bool

    Examples
    --------
    >>> from embroact.patterns.base.findings import RULES
    >>> import embroact.patterns.rules  # declares EA102
    >>> forced_split([RULES.finding("EA102", "leg 14 mm")], True), forced_split([], True)
    (True, False)
    """
    return force and any(f.code == "EA102" and f.is_error for f in findings)


class DesignRuleError(PatternError):
    """The design-rule checks found errors; ``findings`` holds all findings."""

    def __init__(self, findings: Sequence) -> None:
        errors = [f for f in findings if f.is_error]
        first = errors[0]
        more = f" (and {len(errors) - 1} more errors)" if len(errors) > 1 else ""
        super().__init__(f"design-rule error {first.code}: {first.message}{more}; "
                         "nothing written (use --force to write anyway)")
        self.findings = tuple(findings)


@dataclass(frozen=True, slots=True)
class BuildContext:
    """What a stage sees.

    Attributes
    ----------
    design : object or None
        The design built (None for a bare plan).
    plan : StitchPlan
        Its stitch plan.
    analysis : DesignAnalysis or None
        The build's one analysis (None for :func:`build_plan_outputs` of a bare plan).
    findings : tuple
        The design-rule findings.
    worksheet : Worksheet
        The production worksheet.
    out_dir : Path
        Where the files go.
    outputs : Mapping[str, bytes]
        Files prepared so far (name -> bytes), read-only view.

    Examples
    --------
    A stage is a function of the context; this one lists what is prepared before it:

    >>> import tempfile
    >>> from embroact.predict.analysis import analyse
    >>> from embroact.patterns.design import default_design
    >>> seen = []
    >>> def stage(context):
    ...     seen.append((type(context).__name__, sorted(context.outputs)[:2]))
    ...     return {}
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     _ = build_plan_outputs(analyse(default_design()).plan, tmp, stages=[stage])
    >>> seen
    [('BuildContext', ['paper-zigzag.dst', 'preview.svg'])]
    """

    design: object
    plan: StitchPlan
    analysis: object
    findings: tuple
    worksheet: object
    out_dir: Path
    outputs: Mapping[str, bytes]


Stage = Callable[[BuildContext], Mapping[str, "str | bytes"]]


@dataclass(frozen=True, slots=True)
class BuildResult:
    """What :func:`build` wrote.

    Attributes
    ----------
    out_dir : str
    files : tuple of str
        File names written, in order.
    machine_files : tuple of WriteResult
    worksheet : Worksheet
    findings : tuple
    plan : StitchPlan
    analysis : DesignAnalysis or None

    Examples
    --------
    >>> import tempfile
    >>> from embroact.patterns.design import default_design
    >>> res = build(default_design(), tempfile.mkdtemp())
    >>> res.files[0], [m.format for m in res.machine_files], res.plan.stitch_count
    ('paper-zigzag.dst', ['dst'], 106)
    """

    out_dir: str
    files: tuple[str, ...]
    machine_files: tuple[WriteResult, ...]
    worksheet: Worksheet = field(compare=False)
    findings: tuple = ()
    plan: StitchPlan | None = field(default=None, compare=False)
    analysis: object = field(default=None, compare=False)

    def as_dict(self) -> dict:
        """JSON-ready summary (unit-suffixed keys inside the worksheet).

        Returns
        -------
        dict
            ``out_dir``, ``files``, ``machine_files``, ``stitch_count``, ``stop_count``,
            ``findings`` and ``actuators``.

        Examples
        --------
        >>> import tempfile
        >>> from embroact.patterns.design import default_design
        >>> d = build(default_design(), tempfile.mkdtemp()).as_dict()
        >>> d["stitch_count"], d["stop_count"], [f["code"] for f in d["findings"]]
        (106, 1, ['EA403', 'EA406'])
        """
        return {
            "out_dir": self.out_dir,
            "files": list(self.files),
            "machine_files": [m.as_dict() for m in self.machine_files],
            "stitch_count": self.worksheet.stitch_count,
            "stop_count": self.worksheet.stop_count,
            "findings": [f.as_dict() for f in self.findings],
            "actuators": self.worksheet.as_dict()["actuators"],
        }


def parse_formats(text: str | Sequence[str]) -> tuple[str, ...]:
    """``"dst,pes"`` or ``["dst", "pes"]`` -> ``("dst", "pes")``; unknown names list the valid ones.

    Parameters
    ----------
    text : str or sequence of str
        Format names, any case, with or without the dot.

    Returns
    -------
    tuple of str
        Each once, in order.

    Examples
    --------
    >>> parse_formats("DST, pes")
    ('dst', 'pes')
    """
    items = text.split(",") if isinstance(text, str) else list(text)
    out = []
    for item in items:
        key = str(item).strip().lower().lstrip(".")
        if key not in FORMATS:
            raise ParameterError(f"format must be one of {', '.join(FORMATS)}, got {item!r}")
        if key not in out:
            out.append(key)
    if not out:
        raise ParameterError(f"format must name at least one of {', '.join(FORMATS)}, got {text!r}")
    return tuple(out)


def safe_stem(name: str) -> str:
    """A file-name stem from a design name (letters, digits, ``-``, ``_``, ``.``), at most
    :data:`STEM_CHARS` characters (file systems allow 255 bytes per name, with room left
    for the suffix and the hidden staging name).

    Parameters
    ----------
    name : str
        A design name.

    Returns
    -------
    str
        ``"design"`` when nothing is left.

    Examples
    --------
    >>> safe_stem("paper zigzag / w=7")
    'paper_zigzag_w_7'
    >>> len(safe_stem("n" * 300))
    100
    """
    stem = re.sub(r"[^A-Za-z0-9._-]+", "_", name)[:STEM_CHARS].strip("._")
    return stem or "design"


#: Longest file-name stem :func:`safe_stem` makes from a design name.
STEM_CHARS = 100


def write_outputs(out_dir: str | os.PathLike, outputs: Mapping[str, "str | bytes"]) -> tuple[str, ...]:
    """Write prepared files atomically into ``out_dir``; return their names in order.

    Every file is prepared (written and synced to a temporary file) before the first is
    replaced, so a failure while writing changes none of them
    (:func:`embroact.export.files.atomic.write_files_atomic`); the error names the file.

    Parameters
    ----------
    out_dir : str or os.PathLike
        An existing, writable directory.
    outputs : mapping of str to str or bytes
        File name -> content (text is written as UTF-8).

    Returns
    -------
    tuple of str

    Examples
    --------
    >>> import tempfile
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     write_outputs(tmp, {"a.txt": "r0 2.581 mm", "b.bin": b"\\x00"})
    ('a.txt', 'b.bin')
    """
    d = check_writable_dir(out_dir)
    write_files_atomic({d / name: data.encode("utf-8") if isinstance(data, str) else data
                        for name, data in outputs.items()})
    return tuple(outputs)


def build_plan_outputs(
    plan: StitchPlan,
    out_dir: str | os.PathLike,
    *,
    design=None,
    analysis=None,
    findings: Sequence = (),
    formats: Sequence[str] = ("dst",),
    force: bool = False,
    split_long: bool = False,
    speed_spm: float = DEFAULT_SPEED_SPM,
    stages: Sequence[Stage] = (),
    cord_stop: str | None = None,
    inputs: Sequence[tuple[str, str | os.PathLike]] = (),
    out_flag: str = "out_dir",
) -> BuildResult:
    """Build the outputs of an existing plan and its findings (see the module docstring).

    ``analysis`` (when the plan came from one) gives the worksheet its models and the stages
    their curves.  ``cord_stop`` (default: the design's ``machine.cord_stop``, else
    ``"sequence"``) says how DST/EXP write a cord-in stop; the worksheet's counts, pauses and
    machine set-up are those of the first machine file, read back from its bytes.

    Parameters
    ----------
    plan : StitchPlan
        The records.
    out_dir : str or os.PathLike
        An existing, writable directory.
    design, analysis : optional
        The design and its analysis, when the plan came from one.
    findings : sequence of Finding, optional
        The plan's design-rule findings.
    formats : sequence of str, optional
        Machine formats to write.
    force, split_long : bool, optional
        Write despite errors; split legs over a format's record limit.
    speed_spm : float, optional
        Machine speed for the worksheet [stitches/min].
    stages : sequence of callable, optional
        Further outputs, ``stage(BuildContext) -> {name: contents}``.
    cord_stop : str or None, optional
        How DST/EXP write a cord-in stop.
    inputs : sequence of (what, path), optional
        The files the run read (the design file, its drawings and calibration files): an
        output that would replace one is refused once every output is named, before any is
        written (:func:`~embroact.export.files.atomic.check_command_files`).
    out_flag : str, optional
        The name of ``out_dir`` in that error (``"--out"`` on the command line).

    Returns
    -------
    BuildResult

    Raises
    ------
    DesignRuleError
        The findings hold errors and ``force`` is false.
    ParameterError
        An output names one of ``inputs`` (nothing written).

    Examples
    --------
    >>> import tempfile
    >>> from embroact.predict.analysis import analyse
    >>> from embroact.patterns.design import default_design
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     result = build_plan_outputs(analyse(default_design()).plan, tmp, formats=("dst", "pes"))
    >>> result.files[:3]
    ('paper-zigzag.dst', 'paper-zigzag.pes', 'worksheet.json')
    """
    from ..pictures.stitches import plan_svg
    from ..pictures.pages import PAPERS, template_pages_html
    from ..pictures.template import template_svg

    d = check_writable_dir(out_dir)
    fmts = parse_formats(formats)
    findings = tuple(findings)
    if not force and any(f.is_error for f in findings):
        raise DesignRuleError(findings)
    stem = safe_stem(getattr(design, "name", None) or plan.name)
    outputs: dict[str, bytes] = {}
    machine = []
    if cord_stop is None:
        cord_stop = getattr(getattr(design, "machine", None), "cord_stop", "sequence")
    split_long = split_long or forced_split(findings, force)
    for fmt in fmts:
        data, res = encode(plan, fmt, split_long=split_long, cord_stop=cord_stop)
        name = f"{stem}.{fmt}"
        outputs[name] = data
        machine.append(replace(res, path=name))
    ws = worksheet(plan, design, speed_spm=speed_spm, findings=findings, analysis=analysis, machine=machine[0])
    outputs["worksheet.json"] = (json.dumps(ws.as_dict(), indent=2, sort_keys=True) + "\n").encode("utf-8")
    outputs["worksheet.txt"] = ws.as_text().encode("utf-8")
    outputs["preview.svg"] = plan_svg(plan, machine=machine[0]).encode("utf-8")  # the first format's pauses
    template = template_svg(plan, getattr(design, "machine", None))  # 1:1 layout
    outputs["template.svg"] = template.encode("utf-8")
    for paper in PAPERS:  # the same on printable sheets, overlapping, each with a check square
        outputs[f"template-{paper}.html"] = template_pages_html(template, paper, title=plan.name).encode("utf-8")
    for stage in stages:
        ctx = BuildContext(design, plan, analysis, findings, ws, d, dict(outputs))
        for name, content in stage(ctx).items():
            outputs[name] = content.encode("utf-8") if isinstance(content, str) else bytes(content)
    check_command_files([(out_flag, d / name) for name in outputs], inputs)
    files = write_outputs(d, outputs)
    return BuildResult(str(d), files, tuple(machine), ws, findings, plan, analysis)


def build(
    design,
    out_dir: str | os.PathLike,
    *,
    formats: Sequence[str] | None = None,
    force: bool = False,
    split_long: bool = False,
    speed_spm: float | None = None,
    calibration_sets: Sequence = (),
    analysis=None,
    check: Callable | None = None,
    stages: Sequence[Stage] | None = None,
    cord_stop: str | None = None,
    inputs: Sequence[tuple[str, str | os.PathLike]] = (),
    out_flag: str = "out_dir",
) -> BuildResult:
    """Build ``design`` into ``out_dir``: ``<name>.<fmt>`` per format, worksheet, preview, stage outputs.

    Parameters
    ----------
    design : Design
        From :func:`embroact.patterns.design.default_design` or
        :func:`embroact.export.files.designfile.load_design`.
    out_dir : path
        Existing, writable directory (else :class:`ExportError`, nothing written).
    formats : sequence of str, optional
        Machine formats; default the design's ``machine.format`` (DST by default).
    force : bool
        Write even when ``check`` reports errors.
    split_long : bool
        Split legs above a format's per-record limit (see :func:`embroact.export.machine.formats.write`).
    speed_spm : float, optional
        Machine speed for the worksheet [stitches/min]; default the design's ``machine.speed_spm``.
    calibration_sets : sequence of CalibrationSet
        Sets the design's calibrations may name (e.g. read from calibration files).
    analysis : DesignAnalysis, optional
        ``analyse(design, calibration_sets=...)`` when already made.
    check : callable, optional
        ``check(analysis) -> findings``; default :func:`embroact.predict.rules.check_design`
        for every format (:data:`SPLIT_LONG_IGNORES` left out with ``split_long``).
    stages : sequence, optional
        Plug-in points (module docstring); default what ``embroact build`` runs: the previews and
        the report (:func:`embroact.export.report.stage.previews_stage`). ``()``: machine files,
        worksheet and stitch preview only.
    cord_stop : str, optional
        ``"sequence"`` or ``"double"``; default the design's ``machine.cord_stop``.
    inputs, out_flag : optional
        The files the run read, none of which an output may replace, and the name of
        ``out_dir`` in that error (:func:`build_plan_outputs`).

    Returns
    -------
    BuildResult
        The files written (atomically, all or none) and what went into them.

    Raises
    ------
    DesignRuleError
        ``check`` found errors and ``force`` is false (nothing written).
    ExportError
        ``out_dir`` missing or not writable.
    ParameterError
        An output names one of ``inputs`` (nothing written).

    Examples
    --------
    >>> import os, tempfile
    >>> from embroact.patterns.design import default_design
    >>> out = tempfile.mkdtemp()
    >>> res = build(default_design(), out, formats=["dst", "exp"])
    >>> [f for f in res.files if f.startswith("paper-zigzag")], os.path.isfile(os.path.join(out, "worksheet.txt"))
    (['paper-zigzag.dst', 'paper-zigzag.exp'], True)
    """
    from ...predict.analysis import analyse

    check_writable_dir(out_dir)
    machine = getattr(design, "machine", None)
    formats = parse_formats(formats if formats is not None else (getattr(machine, "format", "dst"),))
    speed_spm = speed_spm if speed_spm is not None else getattr(machine, "speed_spm", DEFAULT_SPEED_SPM)
    analysis = analyse(design, calibration_sets=calibration_sets) if analysis is None else analysis
    if stages is None:
        from .stage import previews_stage

        stages = (previews_stage(),)
    if check is None:
        from ...predict.rules import check_design

        ignore = SPLIT_LONG_IGNORES if split_long else ()
        findings = check_design(analysis, format=formats, ignore=ignore)
    else:
        findings = tuple(check(analysis))
    return build_plan_outputs(analysis.plan, out_dir, design=design, analysis=analysis, findings=findings,
                              formats=formats, force=force, split_long=split_long, speed_spm=speed_spm, stages=stages,
                              cord_stop=cord_stop, inputs=inputs, out_flag=out_flag)
