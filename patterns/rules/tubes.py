"""Rules on the tube paths and their placement (EA3xx).

Conventions
-----------
* Minimum turning radius (EA301): ``turning_radius_factor`` x the tube's outer
  diameter (default 3 x 2 r_f = 9 mm for the default tube), against
  :meth:`Centerline.min_radius_mm` (a vertex turning by more than
  ``MAX_SMOOTH_TURN_DEG`` is a corner of radius 0, as for the generators).
* Tube pairs (EA303, EA304) are found with one spatial index over every tube's
  laid length, so only tubes that come close are compared.
* The hoop (EA306) is centred on the bounding box of the records and the machine's start
  point (0, 0) of the file's frame (a design's plan is moved there by its origin policy).
* Couching (EA307): a leg holds the tube where it lies over it, the stretch of the
  axis within r_f of the leg's crossing measured along the axis (r_f |cot phi| on
  each side for a leg at angle phi to the axis, at most the leg's own extent
  along the axis). Every stretch of the tube path that no leg holds, between two
  held stretches or between an end of the path and the nearest held stretch, must
  be at most ``couching_gap_factor`` x the tube's outer diameter (default
  3 x 3 mm = 9 mm for r_f = 1.5 mm; EA203 warns from one diameter). A generated
  cross pattern leaves (w/2 - r_f) tan(alpha0) at each end (5.5 mm for w = 7 mm,
  alpha0 = 70 deg). Every leg of thread counts, whichever actuator it belongs to,
  except a placement line's (sewn along the axis before the tube is laid: it holds nothing).

Examples
--------
>>> from embroact.patterns.rules.tubes import TUBE_RULES
>>> [r.code for r in TUBE_RULES]
['EA301', 'EA302', 'EA303', 'EA304', 'EA305', 'EA306', 'EA307', 'EA308']
"""
from __future__ import annotations

import numpy as np
import shapely

from ..base.findings import RULES, Finding, Inputs, Severity
from ..centerline import MAX_SMOOTH_TURN_DEG
from ..plan import Command
from ..spatial import SegmentIndex, self_crossings
from .engine import Hits, Subject

__all__ = ["TUBE_RULES", "hoop_window", "hoop_centre_mm", "hoop_overflow", "HOOP_PRECHECK_SLACK_MM"]

_DF = Inputs.DESIGNS | Inputs.FILES


@RULES.rule("EA301", Severity.ERROR, "turn tighter than the tube allows",
            "The tube path's curvature radius falls below the minimum turning radius "
            "(turning_radius_factor x tube outer diameter, default 3 x 2 r_f): the tube kinks.",
            "Smooth the path: larger bend radii.", _DF)
def turning(s: Subject) -> list[Finding]:
    cfg = s.settings
    out = []
    for k, tube in enumerate(s.layout.tubes):
        cl = tube.centerline
        if cl is None:
            continue  # a path that crosses itself: EA302 reports it
        r_min = cfg.turning_radius_factor * 2.0 * tube.outer_radius_mm
        radius = cl.min_radius_mm()
        if radius >= r_min - cfg.tolerances.length_mm:
            continue
        pts = cl.points_mm
        kappa = np.abs(cl.segment_curvature())
        worst = pts[1 + int(np.argmax(kappa[1:] + kappa[:-1]))] if len(kappa) > 1 else pts[0]
        kind = "a corner (turn > %g deg)" % MAX_SMOOTH_TURN_DEG if radius == 0.0 else f"radius {radius:.2f} mm"
        out.append(s.tube_finding(
            k, "EA301", f"the tube of {tube.name} turns with {kind}; minimum turning radius {r_min:g} mm "
            f"({cfg.turning_radius_factor:g} x outer diameter)", xy=worst))
    return out


@RULES.rule("EA302", Severity.ERROR, "tube path crosses itself",
            "The tube path intersects itself: the tube would be laid over itself.",
            "Change the path so that it does not cross itself.", _DF)
def self_intersection(s: Subject) -> list[Finding]:
    out = []
    for k, tube in enumerate(s.layout.tubes):
        if tube.centerline is not None:
            continue  # a valid centerline is open and simple
        xy = np.asarray(tube.path.coords, dtype=np.float64)[:, :2]
        pairs, where = self_crossings(xy)
        closed = np.hypot(*(xy[-1] - xy[0])) <= s.settings.tolerances.length_mm
        if len(pairs) == 0 and not closed:
            continue
        what = f"crosses itself {len(pairs)} time(s)" if len(pairs) else "is closed (a tube has two ends)"
        where = xy[0] if where is None else where
        out.append(s.tube_finding(
            k, "EA302", f"the tube path of {tube.name} {what}, first at ({where[0]:.2f}, {where[1]:.2f}) mm", xy=where))
    return out


def _close_pairs(s: Subject) -> list[tuple[int, int, float, np.ndarray]]:
    """Tube pairs (a < b) whose laid lengths come within reach of EA303 or EA304: a, b, gap, closest point."""
    return s.shared("tube pairs", lambda: _find_close_pairs(s))


def _find_close_pairs(s: Subject) -> list[tuple[int, int, float, np.ndarray]]:
    tubes = s.layout.tubes
    if len(tubes) < 2:
        return []
    laid = list(s.laid_paths)
    corridor = max(t.corridor_radius_mm for t in tubes)
    half = max((t.half_width_mm or 0.0) for t in tubes)
    reach = max(2.0 * corridor, 2.0 * half + s.settings.actuator_clearance_mm)
    a, b = shapely.STRtree(laid).query(laid, predicate="dwithin", distance=reach)
    keep = a < b
    a, b = a[keep], b[keep]
    order = np.lexsort((b, a))
    a, b = a[order], b[order]
    ga, gb = np.array(laid, dtype=object)[a], np.array(laid, dtype=object)[b]
    gap = shapely.distance(ga, gb)
    where = [shapely.get_coordinates(line)[0] for line in shapely.shortest_line(ga, gb)]
    return list(zip(a.tolist(), b.tolist(), gap.tolist(), where))


@RULES.rule("EA303", Severity.ERROR, "tube corridors overlap",
            "Two tubes' corridors (r_f + clearance around each path) overlap.",
            "Move the actuators apart.", _DF)
def corridors_overlap(s: Subject) -> list[Finding]:
    tubes, tol = s.layout.tubes, s.settings.tolerances.length_mm
    out = []
    for a, b, gap, where in _close_pairs(s):
        need = tubes[a].corridor_radius_mm + tubes[b].corridor_radius_mm
        if gap < need - tol:
            out.append(s.tube_finding(
                b, "EA303", f"the tubes of {tubes[a].name} and {tubes[b].name} are {gap:.2f} mm apart (axis to axis); "
                f"their corridors need {need:.2f} mm", xy=where))
    return out


@RULES.rule("EA304", Severity.WARNING, "actuators too close",
            "The stitched bands (w/2 around each path) of two actuators are closer than "
            "actuator_clearance_mm.",
            "Move the actuators apart.", _DF)
def actuators_close(s: Subject) -> list[Finding]:
    tubes, cfg = s.layout.tubes, s.settings
    out = []
    for a, b, gap, where in _close_pairs(s):
        ta, tb = tubes[a], tubes[b]
        if gap < ta.corridor_radius_mm + tb.corridor_radius_mm - cfg.tolerances.length_mm:
            continue  # EA303 reports it
        if ta.half_width_mm is None or tb.half_width_mm is None:
            continue
        band_gap = float(shapely.distance(ta.path, tb.path)) - ta.half_width_mm - tb.half_width_mm
        if band_gap < cfg.actuator_clearance_mm - cfg.tolerances.length_mm:
            out.append(s.tube_finding(
                b, "EA304", f"stitched bands of {ta.name} and {tb.name} are {band_gap:.2f} mm apart, clearance "
                f"{cfg.actuator_clearance_mm:g} mm", xy=where))
    return out


def hoop_centre_mm(xy_mm: np.ndarray, commands: np.ndarray) -> np.ndarray:
    """Where the hoop's centre goes [mm]: the middle of the bounding box of the needle points and the
    start point (the origin, where the needle is when the machine starts).  Jumps do not move it: a
    stray travel must not push good stitches out of the hoop.

    Parameters
    ----------
    xy_mm : numpy.ndarray, shape (n, 2)
        Record positions [mm], in the machine's frame.
    commands : numpy.ndarray, shape (n,)
        :class:`Command` per record.

    Returns
    -------
    numpy.ndarray, shape (2,)
        The centre [mm].

    Examples
    --------
    >>> S, J = Command.STITCH, Command.JUMP
    >>> hoop_centre_mm(np.array([[10.0, -5.0], [100.0, 5.0], [400.0, 0.0]]), np.array([S, S, J])).tolist()
    [50.0, 0.0]
    """
    xy = np.asarray(xy_mm, dtype=np.float64).reshape(-1, 2)
    xy = np.vstack([np.zeros((1, 2)), xy[np.asarray(commands) == Command.STITCH]])
    return (xy.min(axis=0) + xy.max(axis=0)) / 2.0


def hoop_window(s: Subject):
    """(low, high) corners of the hoop's sewing field centred as :func:`hoop_centre_mm` [mm], or None without a hoop.

    Parameters
    ----------
    s : Subject
        The check; its settings give the hoop.

    Returns
    -------
    tuple of numpy.ndarray or None
        The corners [mm]; None when the settings name no hoop or there are no records.

    Examples
    --------
    >>> from embroact.patterns.rules import Layout, RuleSettings
    >>> lay = Layout.from_points([(10, 0), (30, 0)], [0, 0], [-1, -1], tubes=())
    >>> lo, hi = hoop_window(Subject(lay, RuleSettings(hoop_width_mm=100.0, hoop_height_mm=50.0)))
    >>> lo.tolist(), hi.tolist()
    ([-35.0, -25.0], [65.0, 25.0])
    """
    cfg, xy = s.settings, s.layout.xy_mm
    if cfg.hoop_width_mm is None or cfg.hoop_height_mm is None or len(xy) == 0:
        return None
    centre = hoop_centre_mm(xy, s.layout.commands)
    half = np.array([cfg.hoop_width_mm, cfg.hoop_height_mm]) / 2.0
    return centre - half, centre + half


@RULES.rule("EA305", Severity.WARNING, "tube end margin missing",
            "The free tube beyond an end (end_margin_mm along the end tangent, for the connector) leaves the "
            "hoop or runs into needle points.",
            "Move the actuator inward, shorten it, or reduce tube.end_margin_mm.", _DF)
def end_margins(s: Subject) -> list[Finding]:
    window = hoop_window(s)
    if window is None:
        return []
    lo, hi = window
    cfg, tol = s.settings, s.settings.tolerances.length_mm
    out = []
    for k, tube in enumerate(s.layout.tubes):
        if tube.end_margin_mm <= 0.0:
            continue
        ends = np.asarray(s.laid_paths[k].coords)[[0, -1]]
        for end, label in zip(ends, ("start", "end")):
            if np.any(end < lo - tol) or np.any(end > hi + tol):
                out.append(s.tube_finding(
                    k, "EA305", f"the {tube.end_margin_mm:g} mm free tube beyond the {label} of {tube.name} reaches "
                    f"({end[0]:.1f}, {end[1]:.1f}) mm, outside the {cfg.hoop_width_mm:g} x {cfg.hoop_height_mm:g} mm "
                    "hoop", xy=end))
    return out


@RULES.rule("EA306", Severity.ERROR, "outside the hoop",
            "A record (stitch, jump or trim excursion) lies outside the hoop's sewing field "
            "(machine.hoop_width_mm x machine.hoop_height_mm, centred on the needle points and the start point; "
            "embroidery files get the default machine's 200 x 200 mm hoop unless told otherwise). A run of jumps outside is one "
            "finding, on its first record.",
            "Use a larger hoop or make the design smaller.", _DF)
def hoop(s: Subject) -> Hits:
    window = hoop_window(s)
    xy, cfg = s.layout.xy_mm, s.settings
    if window is None:
        return Hits(np.zeros(0, np.int64), str)
    lo, hi = window
    tol = cfg.tolerances.length_mm
    cmds = s.layout.commands
    out = np.any((xy < lo - tol) | (xy > hi + tol), axis=1)
    # a travel outside is one finding, on its first record: the jumps after it in the same run are not
    jump = cmds == Command.JUMP
    outside = np.flatnonzero(out & ~(jump & np.concatenate([[False], out[:-1] & jump[:-1]])))
    needles = xy[cmds == Command.STITCH]
    size = np.ptp(needles if len(needles) else xy, axis=0)

    def message(j: int) -> str:
        i = outside[j]
        run = 1
        while jump[i] and i + run < len(xy) and jump[i + run] and out[i + run]:
            run += 1
        far = float(np.abs(xy[i:i + run] - (lo + hi) / 2.0).max())
        what = f"a travel of {run} jump records" if run > 1 else f"{Command(int(cmds[i])).name.lower()} record"
        return (f"{what} outside the {cfg.hoop_width_mm:g} x {cfg.hoop_height_mm:g} mm hoop (up to {far:.1f} mm "
                f"from its centre); the needle points span {size[0]:.1f} x {size[1]:.1f} mm")
    return Hits(outside, message)


#: How far a design's records may stay inside its paths' bounding box at each end [mm] (the unstitched
#: start and end of a path, and the half width): :func:`hoop_overflow` refuses only past this.
HOOP_PRECHECK_SLACK_MM = 50.0


def hoop_overflow(design) -> Finding | None:
    """EA306 decided before anything is generated: a finding when the actuator paths alone span more than
    the hoop by more than each actuator's width and :data:`HOOP_PRECHECK_SLACK_MM` at both ends (the
    records cannot fit then); None when the design may fit (the rule itself then decides on the records).

    Parameters
    ----------
    design : Design
        A design; its machine settings give the hoop.

    Returns
    -------
    Finding or None

    Examples
    --------
    >>> from embroact.patterns.design import design_from_dict
    >>> d = design_from_dict({"name": "x", "machine": {"hoop_width_mm": 200.0, "hoop_height_mm": 200.0},
    ...                       "actuator": [{"name": "A", "pattern": "zigzag", "width_mm": 7.0, "interval_mm": 1.0,
    ...                                     "length_mm": 900.0}]})
    >>> hoop_overflow(d).message
    'the actuator paths alone span 900.0 x 0.0 mm, more than the 200 x 200 mm hoop; nothing generated'
    >>> from embroact.patterns.design import default_design
    >>> hoop_overflow(default_design()) is None
    True
    """
    machine = design.machine
    if machine.hoop_width_mm is None or machine.hoop_height_mm is None or not design.actuators:
        return None
    pts = [a.centerline.points_mm for a in design.actuators]
    lo = np.min([p.min(axis=0) for p in pts], axis=0)
    hi = np.max([p.max(axis=0) for p in pts], axis=0)
    slack = 2.0 * HOOP_PRECHECK_SLACK_MM + max(seg.params.width_mm for a in design.actuators for seg in a.segments)
    size = hi - lo
    if not np.any(size - slack > np.array([machine.hoop_width_mm, machine.hoop_height_mm])):
        return None
    return RULES.finding("EA306", f"the actuator paths alone span {size[0]:.1f} x {size[1]:.1f} mm, more than the "
                                  f"{machine.hoop_width_mm:g} x {machine.hoop_height_mm:g} mm hoop; nothing generated")


def _held_gaps(s_mm: np.ndarray, half_mm: np.ndarray, length_mm: float) -> list[tuple[float, float]]:
    """Stretches [from, to] of [0, length] not covered by the intervals s +- half [mm], in order."""
    if len(s_mm) == 0:
        return [(0.0, length_mm)]
    lo, hi = s_mm - half_mm, s_mm + half_mm
    order = np.argsort(lo, kind="stable")
    lo, reach = lo[order], np.maximum.accumulate(hi[order])
    starts = np.concatenate([[0.0], reach])
    stops = np.concatenate([lo, [length_mm]])
    return [(float(a), float(b)) for a, b in zip(starts, stops) if b > a]


@RULES.rule("EA307", Severity.ERROR, "tube not couched",
            "Legs must cross the tube from one side to the other along its whole embroidered length: no "
            "stretch of the tube path without a leg over it (between legs, or from an end of the path) may be "
            "longer than couching_gap_factor x the tube's outer diameter (default 3 x 2 r_f = 9 mm); a tube "
            "no leg crosses is not held at all (a wrong tube path, or stitches beside the tube). A placement "
            "line, sewn before the tube is laid, holds nothing.",
            "Check the tube path against the stitches, or add legs where the tube is not held.", _DF)
def couching(s: Subject) -> list[Finding]:
    c, tubes = s.crossings, s.layout.tubes
    out = []
    bounds = np.searchsorted(c.tube, np.arange(len(tubes) + 1))
    for k, tube in enumerate(tubes):
        mine = slice(bounds[k], bounds[k + 1])
        length = float(tube.path.length)
        allowed = s.settings.couching_gap_mm(tube.outer_radius_mm)
        if bounds[k] == bounds[k + 1]:
            out.append(s.tube_finding(
                k, "EA307", f"no leg crosses the tube of {tube.name} ({length:.1f} mm path): it is not held; "
                "check the tube path against the stitches", xy=np.asarray(tube.path.coords)[0][:2]))
            continue
        half = np.minimum(tube.outer_radius_mm * c.cot[mine], c.along_mm[mine])
        for a, b in _held_gaps(c.s_mm[mine], half, length):
            if b - a > allowed + s.settings.tolerances.length_mm:
                where = shapely.get_coordinates(tube.path.interpolate(a))[0]
                out.append(s.tube_finding(
                    k, "EA307", f"the tube of {tube.name} is not held for {b - a:.1f} mm, from {a:.1f} to {b:.1f} mm "
                    f"along its {length:.1f} mm path (longest allowed {allowed:g} mm = "
                    f"{s.settings.couching_gap_factor:g} x tube diameter)", xy=where))
    return out


def _past_an_end(xy: np.ndarray, a: np.ndarray, b: np.ndarray, tol: float) -> np.ndarray:
    """Which legs a -> b have both ends past the same end of the path through ``xy`` (nearest path point within
    ``tol`` of that end): only points behind the end's own segment can be (a half-plane test), and those are
    located on the path's segment index.

    Examples
    --------
    >>> xy = np.array([(0.0, 0.0), (10.0, 0.0)])
    >>> _past_an_end(xy, np.array([(-3.0, 1.0), (5.0, 1.0), (12.0, 0.0)]), np.array([(-1.0, -4.0), (-2.0, 1.0), (11.0, 3.0)]),
    ...              1e-9).tolist()
    [True, False, True]
    """
    near = np.zeros(len(a), dtype=bool)
    for end, inward in ((xy[0], xy[1] - xy[0]), (xy[-1], xy[-2] - xy[-1])):
        size = float(np.hypot(*inward))
        if size <= tol:  # an end segment shorter than the tolerance: no half-plane to go by
            near[:] = True
            break
        near |= ((a - end) @ inward <= tol * size) & ((b - end) @ inward <= tol * size)
    out = np.zeros(len(a), dtype=bool)
    there = np.flatnonzero(near)
    if len(there):
        index = SegmentIndex(xy)
        sa, sb, length = index.locate(a[there]), index.locate(b[there]), index.length_mm
        out[there] = ((sa <= tol) & (sb <= tol)) | ((sa >= length - tol) & (sb >= length - tol))
    return out


@RULES.rule("EA308", Severity.ERROR, "legs over no tube",
            "Legs of thread longer than the tube's outer diameter that lie wholly beyond an end of every tube "
            "(an embroidery file checked against a tube path shorter than its embroidery): nothing is couched "
            "there. A run of such legs is one finding.",
            "Give the tube path the embroidery was made for, or remove the legs that couch nothing.", Inputs.FILES)
def uncovered_legs(s: Subject) -> Hits:
    lay = s.layout
    legs = np.flatnonzero(s.consecutive)
    if not lay.tubes or not len(legs):
        return Hits(np.zeros(0, np.int64), str)
    legs = legs[np.hypot(*(lay.xy_mm[legs] - lay.xy_mm[legs - 1]).T) > 2.0 * min(t.outer_radius_mm for t in lay.tubes)]
    if not len(legs):
        return Hits(np.zeros(0, np.int64), str)
    a, b = lay.xy_mm[legs - 1], lay.xy_mm[legs]
    tol = s.settings.tolerances.length_mm
    on_some = np.isin(legs, s.legs[s.crossings.leg])  # a leg crossing an axis lies on that tube's body
    rest = np.flatnonzero(~on_some)
    on_some[rest] = s.axes.legs_near(a[rest], b[rest], [t.outer_radius_mm for t in lay.tubes])
    bad = np.flatnonzero(~on_some)
    for t in lay.tubes:  # beyond every tube: both ends past the same end of each one's path
        bad = bad[_past_an_end(shapely.get_coordinates(t.path), a[bad], b[bad], tol)]
    if not len(bad) or not on_some.any():  # no leg on any tube: a wrong tube path, EA307's finding
        return Hits(np.zeros(0, np.int64), str)
    starts = bad[np.concatenate([[True], np.diff(bad) > 1])]  # runs of neighbouring legs (among all legs)
    ends = bad[np.concatenate([np.diff(bad) > 1, [True]])]
    index = legs[starts]

    def message(j: int) -> str:
        n = int(ends[j] - starts[j] + 1)
        first, last = lay.xy_mm[legs[starts[j]] - 1], lay.xy_mm[legs[ends[j]]]
        span = float(np.hypot(*(last - first)))
        return (f"{n} leg{'s' * (n != 1)} from here ({span:.1f} mm of embroidery) beyond the end of every tube "
                "cross no tube: nothing is couched there")
    return Hits(index, message, owner=np.full(len(index), -1))


TUBE_RULES = (turning, self_intersection, corridors_overlap, actuators_close, end_margins, hoop, couching,
              uncovered_legs)
"""The EA3xx rules, in code order."""
