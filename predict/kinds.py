"""What the model knows about each pattern kind, in one table: its constraint and its thread angle.

The geometry facts of a kind (parameters, generator, calibration axis) live in
:mod:`embroact.patterns.kinds`, which knows nothing of the model. This table adds the model's
side, keyed by the same names: which pattern constraint the kind follows (docs/model.md,
section 4) and so how the sleeve's thread angle beta0 follows from the sewn geometry and which
way the strip first bends. Every part of ``predict`` that would otherwise ask "is this the cross
pattern?" asks :func:`model_kind` instead; a third pattern adds one row (:func:`register_model`).

Examples
--------
>>> from embroact.predict.kinds import model_kind
>>> z, c = model_kind("zigzag"), model_kind("cross")
>>> z.constraint.value, c.constraint.value
('fixed-radius', 'pantograph')
>>> z.beta0_deg(7.0, 45.0, 1.5), round(c.beta0_deg(7.0, 45.0, 1.5), 4)
(0.0, 37.2078)
>>> z.bends_positive(0.0), c.bends_positive(37.2078), c.bends_positive(20.0)
(True, False, True)
>>> try:
...     model_kind("satin")
... except ValueError as exc:
...     print(exc)  # doctest: +ELLIPSIS
pattern must be one of 'zigzag', 'cross'..., got 'satin'
"""
from __future__ import annotations

import enum
import math
from dataclasses import dataclass

from ..patterns.base.errors import ParameterError
from ..patterns.kinds import pattern_kind
from .sleeve import thread_angle_deg

__all__ = ["Constraint", "ModelKind", "MODEL_KINDS", "model_kind", "register_model"]


class Constraint(enum.Enum):
    """The pattern constraint: how the sleeve's length and radius move with the bend.

    Examples
    --------
    >>> Constraint("pantograph") is Constraint.PANTOGRAPH
    True
    """

    FIXED_RADIUS = "fixed-radius"
    """``l = l0 + 2 r0 theta, r = r0``: the threads run around the tube (beta0 = 0; zigzag)."""
    PANTOGRAPH = "pantograph"
    """Thread length conserved, the crossing threads scissor (beta from beta0; cross)."""


@dataclass(frozen=True, slots=True)
class ModelKind:
    """The model's facts about one pattern kind.

    Attributes
    ----------
    name : str
        The pattern's name, as in :data:`embroact.patterns.kinds.PATTERN_KINDS`.
    constraint : Constraint
        Its pattern constraint.
    extrapolated_range : tuple of float
        The widest range of the calibration axis (``embroact.patterns.kinds``) a design search may
        extrapolate the calibration to (``allow_extrapolation``) [mm or deg].

    Examples
    --------
    >>> row = ModelKind("zigzag", Constraint.FIXED_RADIUS, (4.0, 14.0))
    >>> row.has_thread_angle, row == model_kind("zigzag")
    (False, True)
    """

    name: str
    constraint: Constraint
    extrapolated_range: tuple[float, float]

    @property
    def has_thread_angle(self) -> bool:
        """True when the sleeve's threads lie at an angle beta0 > 0 to the circumference."""
        return self.constraint is Constraint.PANTOGRAPH

    def beta0_deg(self, width_mm: float, angle_deg: float, outer_radius_mm: float) -> float:
        """Thread angle beta0 [deg] of a sleeve sewn at width ``width_mm`` and angle ``angle_deg`` (0 without one).

        Parameters
        ----------
        width_mm, angle_deg, outer_radius_mm : float
            Realised rail spacing w [mm], embroidery angle alpha0 [deg], tube outer radius r_f [mm].

        Returns
        -------
        float

        Examples
        --------
        >>> round(model_kind("cross").beta0_deg(7.0, 45.0, 1.5), 4), model_kind("zigzag").beta0_deg(7.0, 45.0, 1.5)
        (37.2078, 0.0)
        """
        if not self.has_thread_angle:
            return 0.0
        return float(thread_angle_deg(width_mm, angle_deg, outer_radius_mm))

    def bends_positive(self, beta0_deg: float) -> bool:
        """Initial bending direction: dV/dl > 0 at theta = 0 (always at r = r0; a pantograph if tan beta0 < 1/2).

        Parameters
        ----------
        beta0_deg : float
            The sleeve's thread angle [deg].

        Returns
        -------
        bool

        Examples
        --------
        >>> model_kind("cross").bends_positive(20.0), model_kind("cross").bends_positive(37.2)
        (True, False)
        """
        return not self.has_thread_angle or math.tan(math.radians(beta0_deg)) < 0.5


MODEL_KINDS: dict[str, ModelKind] = {}
"""The model's row for every registered pattern kind."""


def register_model(row: ModelKind) -> None:
    """Add the model's row for a registered pattern kind (one per kind).

    Parameters
    ----------
    row : ModelKind
        Named as a kind registered with :func:`embroact.patterns.kinds.register`.

    Raises
    ------
    ParameterError
        No such kind, or it has a row already.

    Examples
    --------
    >>> try:
    ...     register_model(ModelKind("satin", Constraint.FIXED_RADIUS, (4.0, 14.0)))
    ... except ValueError as exc:
    ...     print(exc)  # doctest: +ELLIPSIS
    pattern must be one of 'zigzag', 'cross'..., got 'satin'
    """
    name = pattern_kind(row.name).name
    if name in MODEL_KINDS:
        raise ParameterError(f"pattern kind {name!r} already has a model row")
    MODEL_KINDS[name] = row


register_model(ModelKind("zigzag", Constraint.FIXED_RADIUS, (4.0, 14.0)))
register_model(ModelKind("cross", Constraint.PANTOGRAPH, (5.0, 80.0)))


def model_kind(name: object) -> ModelKind:
    """The model's facts for pattern ``name``.

    Parameters
    ----------
    name : str
        A registered pattern kind.

    Returns
    -------
    ModelKind

    Raises
    ------
    ParameterError
        No such kind (the message names the registered ones).

    Examples
    --------
    >>> model_kind("cross").constraint.value
    'pantograph'
    """
    return MODEL_KINDS[pattern_kind(name).name]
