"""One studio session: the design being edited, its analysis, and what the page may ask of it.

:class:`Studio` knows no web framework (the server in :mod:`.app` is a thin layer over it,
and the benchmark and tests call it directly). It keeps the last *valid* design: an edit
that the design file would refuse raises :class:`~embroact.export.studio.form.FieldError`
and changes nothing, so the page keeps its last good views. Analyses are kept per design
(the last few), so moving the pressure slider re-analyses nothing.

Examples
--------
>>> import tempfile
>>> from embroact.patterns.design import default_design
>>> s = Studio(default_design(), tempfile.mkdtemp())
>>> v = s.edit({"actuator[0].width_mm": 8.0}, pressure_kpa=200.0)
>>> v["actuators"][0]["derived"]["width_mm"], round(v["actuators"][0]["theta_deg"], 2)
(8.0, 61.1)
>>> s.save("wide.toml")["file"]
'wide.toml'
"""
from __future__ import annotations

import contextlib
import copy
import json
import math
import threading
from collections import OrderedDict
from pathlib import Path

from ...patterns.base.errors import EmbroactError, ParameterError, check_range
from ...patterns.design import ActuatorSpec, design_from_dict
from ...patterns.kinds import PATTERN_KINDS, param_values
from .form import FieldError, apply_edits, design_form, fields
from .outputs import output_path

__all__ = ["Studio", "BusyError", "CACHED_ANALYSES", "SEARCH_SECONDS", "SHAPE_SEARCH_S"]

#: Analysed designs kept (undo-like back-and-forth edits and the slider reuse them).
CACHED_ANALYSES = 8
#: Longest the server waits for an inverse search [s]; the answer then says it took too long.
SEARCH_SECONDS = 30.0
#: Time limit of a target-shape search in the studio [s]: it answers with the best design found by then,
#: before the server stops waiting.
SHAPE_SEARCH_S = 20.0


class BusyError(EmbroactError):
    """A request that needs what another request is using (an inverse search): ask again later."""


def _number(name: str, value, *, low: float, high: float, inclusive: bool = True) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float, str)):
        raise ParameterError(f"{name} must be a number, got {value!r:.40}")
    try:
        number = float(value)
    except ValueError:
        raise ParameterError(f"{name} must be a number, got {value!r:.40}") from None
    return check_range(name, number, low=low, high=high, low_inclusive=inclusive, high_inclusive=inclusive)


class Studio:
    """The studio's state: design form, last valid design, output directory.

    Parameters
    ----------
    design : Design
        The design to start from (validated).
    out_dir : path
        The only directory the studio writes into.
    calibration_sets : tuple of CalibrationSet
        Sets the design's calibrations name besides the built-in ones (read from files).
    source : tuple of (path, Design), optional
        The design file the design was read from and the design the file itself gives (before
        any command-line override): :meth:`save` then writes that file's text with only the
        fields that differ changed (:mod:`.roundtrip`), comments and drawing references kept.

    Examples
    --------
    >>> import tempfile
    >>> from embroact.patterns.design import default_design
    >>> out = tempfile.TemporaryDirectory()
    >>> studio = Studio(default_design(), out.name)
    >>> studio.design.name, studio.pressure(None)  # no operating point: 2/3 of 300 kPa
    ('paper-zigzag', 200.0)
    >>> out.cleanup()
    """

    def __init__(self, design, out_dir, calibration_sets: tuple = (), source=None) -> None:
        self.out_dir = Path(out_dir)
        self._source = None if source is None else (Path(source[0]), Path(source[0]).read_text(encoding="utf-8"),
                                                    design_form(source[1]))
        self.calibration_sets = tuple(calibration_sets)
        self._names = tuple(s.source or s.name for s in self.calibration_sets)  # how a saved design names each
        self.form = design_form(design)
        self.design = design
        self._lock = threading.Lock()
        self._search = threading.Lock()
        self._cache: OrderedDict = OrderedDict()
        self._proposal: tuple[int, str, dict] | None = None

    # -------------------------------------------------------------- analysis
    def _analysed(self, design, form):
        """(analysis, findings, stitch preview, worksheet) of ``design`` (from ``form``), kept for the last few."""
        key = json.dumps(form, sort_keys=True)
        if key in self._cache:
            self._cache.move_to_end(key)
            return self._cache[key]
        from ...predict.analysis import analyse
        from ...predict.rules import check_design
        from ..machine.formats import encode
        from ..report.worksheet import worksheet
        from .views import stitches_svg

        analysis = analyse(design, calibration_sets=self.calibration_sets)
        findings = check_design(analysis)
        try:  # the counts, pauses and set-up of the machine file 'build' writes, read back from its bytes
            _, machine = encode(analysis.plan, design.machine.format, cord_stop=design.machine.cord_stop)
        except EmbroactError:  # a file 'build' would refuse (the findings say why): the plan's own counts
            machine = None
        ws = worksheet(analysis.plan, design, speed_spm=design.machine.speed_spm, findings=findings,
                       analysis=analysis, machine=machine)
        entry = (analysis, findings, stitches_svg(analysis.plan, findings), ws)
        self._cache[key] = entry
        while len(self._cache) > CACHED_ANALYSES:
            self._cache.popitem(last=False)
        return entry

    def pressure(self, value) -> float:
        """``value`` checked against the design's pressure range [0, max_pressure_kpa] (None: the design's
        operating point ``target_pressure_kpa``, else 2/3 of the range).

        Parameters
        ----------
        value : object
            A pressure [kPa], or None.

        Returns
        -------
        float
            [kPa].

        Raises
        ------
        ParameterError
            Not a number in the range.

        Examples
        --------
        >>> import tempfile
        >>> from embroact.patterns.design import default_design
        >>> out = tempfile.TemporaryDirectory()
        >>> studio = Studio(default_design(), out.name)
        >>> studio.pressure(150)
        150.0
        >>> out.cleanup()
        """
        top = self.design.operation.max_pressure_kpa
        if value is None:
            target = self.design.operation.target_pressure_kpa
            return float(target) if target is not None else float(round(top * 2.0 / 3.0))
        return _number("pressure_kpa", value, low=0.0, high=top)

    def views(self, pressure_kpa=None) -> dict:
        """Everything the page shows except the 3D picture (:meth:`shape3d`), as JSON-ready data.

        Parameters
        ----------
        pressure_kpa : float or None, optional
            The slider's pressure [kPa] (None: :meth:`pressure`'s default).

        Returns
        -------
        dict
            The design's name, the pressure, the fields, the findings, the pictures, the worksheet, and the
            choices of the target-bend search's pattern (``"any"`` and every kind inverse design searches).

        Examples
        --------
        >>> import tempfile
        >>> from embroact.patterns.design import default_design
        >>> out = tempfile.TemporaryDirectory()
        >>> studio = Studio(default_design(), out.name)
        >>> v = studio.views(150.0)
        >>> v["design"], v["pressure_kpa"], v["chart_svg"].startswith("<svg"), v["inverse_patterns"][:3]
        ('paper-zigzag', 150.0, True, ['any', 'zigzag', 'cross'])
        >>> out.cleanup()
        """
        from ...patterns.base.findings import summary_line
        from .views import bend_at, chart_svg, side_svg, worksheet_figures

        with self._lock:
            design, form = self.design, self.form
            p = self.pressure(pressure_kpa)
            analysis, findings, stitches, ws = self._analysed(design, form)
            bends = bend_at(analysis, p)
            return {
                "design": design.name,
                "out_dir": str(self.out_dir),
                "pressure_kpa": p,
                "max_pressure_kpa": design.operation.max_pressure_kpa,
                "fields": [f.as_dict() for f in fields(form, self._names)],
                "stitches_svg": stitches,
                "chart_svg": chart_svg(analysis, bends, p),
                "side_svg": side_svg(analysis, bends, p),
                "actuators": [{**a.as_dict(), **b} for a, b in zip(analysis.actuators, bends)],
                "findings": [f.as_dict() for f in findings],
                "summary": summary_line(findings),
                "worksheet": worksheet_figures(ws),
                "inverse_patterns": ["any", *(k.name for k in PATTERN_KINDS if k.design_params is not None)],
            }

    def shape3d(self, pressure_kpa=None) -> dict:
        """The 3D picture at ``pressure_kpa`` (a separate request: it takes longest to draw).

        Parameters
        ----------
        pressure_kpa : float or None, optional
            The slider's pressure [kPa].

        Returns
        -------
        dict
            ``pressure_kpa`` and ``svg``.

        Examples
        --------
        >>> import tempfile
        >>> from embroact.patterns.design import default_design
        >>> out = tempfile.TemporaryDirectory()
        >>> studio = Studio(default_design(), out.name)
        >>> sorted(studio.shape3d(150.0))
        ['pressure_kpa', 'svg']
        >>> out.cleanup()
        """
        from .views import bend_at, shape3d_svg

        with self._lock:
            p = self.pressure(pressure_kpa)
            analysis = self._analysed(self.design, self.form)[0]
            return {"pressure_kpa": p, "svg": shape3d_svg(analysis, bend_at(analysis, p), p)}

    # -------------------------------------------------------------- edits
    def edit(self, values, pressure_kpa=None) -> dict:
        """Apply ``values`` (field key -> value); the views of the new design.

        Parameters
        ----------
        values : mapping of str to object
            Field key -> new value.
        pressure_kpa : float or None, optional
            The slider's pressure [kPa].

        Returns
        -------
        dict
            :meth:`views` of the edited design.

        Raises
        ------
        FieldError
            The design file would refuse the edited design (nothing changes).
        ParameterError
            A key that is not a field, or a bad pressure.

        Examples
        --------
        >>> import tempfile
        >>> from embroact.patterns.design import default_design
        >>> out = tempfile.TemporaryDirectory()
        >>> studio = Studio(default_design(), out.name)
        >>> _ = studio.edit({"actuator[0].width_mm": 6.5})
        >>> studio.design.actuators[0].params.width_mm
        6.5
        >>> out.cleanup()
        """
        with self._lock:
            form, design = apply_edits(self.form, values, self._names)
            try:  # a design that cannot be generated fails here, before it is kept
                self._analysed(design, form)
            except FieldError:
                raise
            except EmbroactError as exc:
                raise FieldError(next(iter(values)), str(exc)) from None
            self.form, self.design = form, design
        if pressure_kpa is not None:  # the slider follows a lowered working pressure
            pressure_kpa = min(_number("pressure_kpa", pressure_kpa, low=0.0, high=1e5),
                               design.operation.max_pressure_kpa)
        return self.views(pressure_kpa)

    # -------------------------------------------------------------- outputs
    def save(self, name) -> dict:
        """Write the design as TOML into the output directory: the design file it was read from with
        the edited fields changed (:func:`.roundtrip.edited_toml`), else every field
        (:func:`~embroact.export.files.designfile.save_design`).

        Parameters
        ----------
        name : str
            A plain file name ending in ``.toml``.

        Returns
        -------
        dict
            ``file`` and ``out_dir``.

        Raises
        ------
        OutsideOutputError
            A name that is not a plain ``.toml`` file name inside the output directory.

        Examples
        --------
        >>> import tempfile
        >>> from embroact.patterns.design import default_design
        >>> out = tempfile.TemporaryDirectory()
        >>> studio = Studio(default_design(), out.name)
        >>> studio.save("design.toml")["file"]
        'design.toml'
        >>> out.cleanup()
        """
        from ..files.atomic import write_text_atomic
        from ..files.designfile import save_design

        with self._lock:
            path = output_path(self.out_dir, name, ".toml")
            if self._source is None:
                save_design(self.design, path)
            else:
                from .roundtrip import edited_toml

                file, text, form = self._source
                write_text_atomic(path, edited_toml(text, form, self.form, src_dir=file.parent, dst_dir=path.parent))
        return {"file": path.name, "out_dir": str(self.out_dir)}

    def build(self, *, force: bool = False) -> dict:
        """``embroact build`` of the design into the output directory (machine files, worksheet, previews, report).

        Parameters
        ----------
        force : bool, optional
            Write despite design-rule errors.

        Returns
        -------
        dict
            ``files`` written, ``out_dir``, ``stitch_count`` and the rest of the build's result.

        Raises
        ------
        DesignRuleError
            The rules found errors and ``force`` is false (nothing written).

        Examples
        --------
        >>> import tempfile
        >>> from embroact.patterns.design import default_design
        >>> out = tempfile.TemporaryDirectory()
        >>> studio = Studio(default_design(), out.name)
        >>> studio.build()["files"][:2]
        ['paper-zigzag.dst', 'worksheet.json']
        >>> out.cleanup()
        """
        from ..report.stage import previews_stage
        from ..report.build import build

        if not isinstance(force, bool):
            raise ParameterError(f"force must be true or false, got {force!r:.40}")
        with self._lock:
            analysis = self._analysed(self.design, self.form)[0]
            res = build(self.design, self.out_dir, force=force, analysis=analysis, stages=(previews_stage(),))
        return {"files": list(res.files), "out_dir": res.out_dir, "stitch_count": res.worksheet.stitch_count}

    def _actuator(self, actuator) -> tuple[int, ActuatorSpec]:
        """(index, spec) of the design's actuator number ``actuator``."""
        n = len(self.design.actuators)
        index = actuator if isinstance(actuator, int) and not isinstance(actuator, bool) else -1
        if not 0 <= index < n:
            raise ParameterError(f"actuator must be an index in [0, {n - 1}], got {actuator!r:.40}")
        return index, self.design.actuators[index]

    def inverse(self, bend_deg, pressure_kpa, *, pattern="any", actuator=0) -> dict:
        """Inverse design (:func:`embroact.predict.inverse.design_bend`) for one straight actuator of the design.

        A straight actuator is searched where it lies, over the same sewable designs as ``embroact design``:
        widths in steps of one grid unit, each moved across its path by at most half a unit so that both
        rails lie on the machine grid (:func:`~embroact.patterns.limits.grid_origin_mm`). The answer is kept
        as a proposal when it is met: :meth:`apply_proposal` puts its pattern and that start in the design.

        Parameters
        ----------
        bend_deg : float
            The target bend [deg], |.| <= 720.
        pressure_kpa : float
            At this pressure [kPa], > 0.
        pattern : str, optional
            A registered pattern kind, or ``"any"``.
        actuator : int, optional
            Index of the actuator in the design.

        Returns
        -------
        dict
            The result (:meth:`~embroact.predict.inverse.BendResult.as_dict`), ``values``: the field values
            of the best candidate's pattern parameters, and ``origin_mm``: where the proposal starts the
            actuator (its rails on the grid).

        Raises
        ------
        ParameterError
            A segmented actuator, or a target out of range.

        Examples
        --------
        >>> import tempfile
        >>> from embroact.patterns.design import default_design
        >>> out = tempfile.TemporaryDirectory()
        >>> studio = Studio(default_design(), out.name)
        >>> answer = studio.inverse(90.0, 150.0, pattern="zigzag")
        >>> answer["values"]["actuator[0].width_mm"], answer["origin_mm"]
        (6.1, [0.0, 0.05])
        >>> round(studio.apply_proposal(150.0)["actuators"][0]["derived"]["width_mm"], 9)  # sewn 6.1 mm wide
        6.1
        >>> out.cleanup()
        """
        from ...predict.inverse import design_bend

        with self._lock:
            design = self.design
            index, spec = self._actuator(actuator)
            old = self.form["actuator"][index]
        spec.segments.single(f"actuator {spec.name!r} is segmented: a target bend designs one pattern")
        target = _number("bend_deg", bend_deg, low=-720.0, high=720.0)
        p = _number("pressure_kpa", pressure_kpa, low=0.0, high=10_000.0, inclusive=False)
        start, end = spec.centerline.points_mm[0], spec.centerline.points_mm[-1]
        straight = len(spec.centerline.points_mm) == 2  # else searched as a straight actuator of its length
        origin, rotation = ((float(start[0]), float(start[1])), math.degrees(math.atan2(*(end - start)[::-1]))) \
            if straight else ((0.0, 0.0), 0.0)
        with self._searching():  # the design is not locked meanwhile: views and edits go on
            result = design_bend(target, p, pattern=pattern, length_mm=spec.centerline.length_mm, tube=design.tube,
                                 settings=spec.model, sets=self.calibration_sets, name=spec.name,
                                 operation=design.operation,  # judged by the limits the studio then shows
                                 origin_mm=origin, rotation_deg=rotation)
        best = result.best
        table = design_form(best.design)["actuator"][0]  # the searched actuator: its pattern and its start
        table.update({k: old[k] for k in ("tie_stitch_mm", "tie_count", *(() if straight else ("path",)))
                      if k in old})
        if not straight:
            for k in ("length_mm", "origin_mm", "rotation_deg"):
                table.pop(k, None)
        with self._lock:  # only a met answer is offered: an unmet one is shown, never applied
            self._proposal = (index, spec.name, table) if result.reached else None
        values: dict[str, object] = {f"actuator[{index}].pattern": best.pattern}
        values.update({f"actuator[{index}].{k}": v for k, v in param_values(best.params).items()})
        placed = [float(v) for v in best.design.actuators[0].centerline.points_mm[0]] if straight else None
        return {**result.as_dict(), "values": values, "origin_mm": placed}

    def inverse_shape(self, path_d, pressure_kpa, *, max_segments=6, actuator=0) -> dict:
        """Inverse design of a target shape (:func:`embroact.predict.inverse.design_shape`) for one actuator.

        ``path_d`` is the wanted fabric line as SVG path data in mm (from the clamped end,
        heading +x; y down as in SVG, so bends toward the back of the fabric go up on screen).
        The answer is kept as a proposal: :meth:`apply_proposal` puts it in the design in
        place of the actuator (same name, origin, rotation and model settings).

        Parameters
        ----------
        path_d : str
            SVG path data [mm].
        pressure_kpa : float
            At this pressure [kPa].
        max_segments : int, optional
            At most this many segments, in [1, 12].
        actuator : int, optional
            Index of the actuator in the design.

        Returns
        -------
        dict
            The answer (:meth:`~embroact.predict.inverse.ShapeResult.as_dict`), the actuator's name and the
            overlay picture (``svg``).

        Raises
        ------
        ParameterError
            Bad path data, segment count or pressure.

        Examples
        --------
        >>> import tempfile
        >>> from embroact.patterns.design import default_design
        >>> out = tempfile.TemporaryDirectory()
        >>> studio = Studio(default_design(), out.name)
        >>> answer = studio.inverse_shape("M 0 0 A 95.5 95.5 0 0 0 82.7 -47.7", 150.0, max_segments=1)
        >>> answer["reached"], answer["actuator"], answer["svg"].startswith("<svg")
        (True, 'A1', True)
        >>> out.cleanup()
        """
        from ...patterns.centerline import Centerline
        from ...patterns.limits import grid_origin_mm
        from ...predict.inverse import design_shape

        if not isinstance(path_d, str) or not path_d.strip():
            raise ParameterError(f"path_d must be SVG path data in mm (e.g. 'M 0 0 A 60 60 0 0 0 60 -60'), "
                                 f"got {path_d!r:.40}")
        if isinstance(max_segments, bool) or not isinstance(max_segments, int) or not 1 <= max_segments <= 12:
            raise ParameterError(f"max_segments must be an integer in [1, 12], got {max_segments!r:.40}")
        with self._lock:
            index, spec = self._actuator(actuator)
            tube, operation, old = self.design.tube, self.design.operation, self.form["actuator"][index]
        target = Centerline.from_svg_path(path_d).points_mm
        p = _number("pressure_kpa", pressure_kpa, low=0.0, high=10_000.0, inclusive=False)
        with self._searching():  # the design is not locked meanwhile: views and edits go on
            result = design_shape(target, p, max_segments=max_segments, tube=tube, settings=spec.model,
                                  sets=self.calibration_sets, name=spec.name, time_limit_s=SHAPE_SEARCH_S,
                                  operation=operation)
        table = design_form(result.design)["actuator"][0]
        table.update({k: old[k] for k in ("rotation_deg", "tie_stitch_mm", "tie_count") if k in old})
        table.pop("origin_mm", None)  # the actuator's own start, moved as the search moved its path (rails on the grid)
        start = grid_origin_mm(result.segments[0].params.width_mm, old.get("origin_mm", (0.0, 0.0)),
                               old.get("rotation_deg", 0.0))
        if start != (0.0, 0.0):
            table["origin_mm"] = list(start)
        with self._lock:  # only a reachable answer is offered: an unreachable one is shown, never applied
            self._proposal = (index, spec.name, table) if result.reached else None
        from ..pictures.shapefit import design_shape_svg

        return {**result.as_dict(), "actuator": spec.name, "svg": design_shape_svg(result)}

    @contextlib.contextmanager
    def _searching(self):
        """One inverse search at a time, outside the session lock; a second one is refused, not queued.

        A search may outlive its request (the server stops waiting after ``SEARCH_SECONDS``:
        :mod:`.app`); refusing a second keeps at most one such search running.
        """
        if not self._search.acquire(blocking=False):
            raise BusyError("an inverse search is still running: wait for it (at most "
                            f"{SEARCH_SECONDS:g} s), then ask again")
        try:
            yield
        finally:
            self._search.release()

    def apply_proposal(self, pressure_kpa=None) -> dict:
        """Put the last inverse-design proposal in the design; the new views.

        Parameters
        ----------
        pressure_kpa : float or None, optional
            The slider's pressure [kPa].

        Returns
        -------
        dict
            :meth:`views` of the design with the proposal.

        Raises
        ------
        ParameterError
            No proposal is waiting (none made, or already applied).

        Examples
        --------
        >>> import tempfile
        >>> from embroact.patterns.design import default_design
        >>> out = tempfile.TemporaryDirectory()
        >>> studio = Studio(default_design(), out.name)
        >>> try:
        ...     studio.apply_proposal()
        ... except ValueError as exc:
        ...     print(exc)
        no inverse-design proposal to apply: design a reachable bend or shape first
        >>> out.cleanup()
        """
        with self._lock:
            if self._proposal is None:
                raise ParameterError("no inverse-design proposal to apply: design a reachable bend or shape first")
            index, name, table = self._proposal
            if index >= len(self.form["actuator"]) or self.design.actuators[index].name != name:
                self._proposal = None
                raise ParameterError(f"the proposal was for actuator {name!r}, which the design no longer has "
                                     "there: design the shape again")
            form = copy.deepcopy(self.form)
            form["actuator"][index] = table
            design = design_from_dict(form)
            self._analysed(design, form)
            self.form, self.design, self._proposal = form, design, None
        return self.views(pressure_kpa)
