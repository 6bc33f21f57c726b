"""Named tolerances, in one documented place.

Every numerical threshold an algorithm in embroact uses comes from a
:class:`Tolerances` value; no bare ``1e-9`` in algorithms.

Examples
--------
>>> from embroact.patterns.base.tolerances import DEFAULT_TOLERANCES as tol
>>> tol.angle_deg, tol.spacing_rel
(0.1, 0.01)
"""
from __future__ import annotations

from dataclasses import dataclass

__all__ = ["Tolerances", "DEFAULT_TOLERANCES"]


@dataclass(frozen=True, slots=True)
class Tolerances:
    """Thresholds shared by generators, rules and the model.

    Attributes
    ----------
    length_mm : float
        Two lengths closer than this are equal [mm] (geometry snapping).
    angle_deg : float
        Allowed difference between requested and realised leg angle [deg].
    spacing_rel : float
        Allowed relative difference between requested and realised interval [-].
    machine_grid_mm : float
        Resolution of machine files (0.1 mm for every pystitch format) [mm].
    curve_flatness_mm : float
        Maximum chordal error when flattening smooth curves to polylines [mm].
    model_rtol : float
        Default relative tolerance of the deformation model's solvers [-].
    angle_solution_deg : float
        Default absolute tolerance on predicted bend angles [deg].

    Examples
    --------
    >>> DEFAULT_TOLERANCES.machine_grid_mm, Tolerances(angle_deg=0.5).angle_deg
    (0.1, 0.5)
    """

    length_mm: float = 1e-9
    angle_deg: float = 0.1
    spacing_rel: float = 0.01
    machine_grid_mm: float = 0.1
    curve_flatness_mm: float = 0.005
    model_rtol: float = 1e-10
    angle_solution_deg: float = 1e-7


DEFAULT_TOLERANCES = Tolerances()
