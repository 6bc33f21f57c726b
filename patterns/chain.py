"""The chain type: an actuator's segments in order along its path, one or more.

Every actuator is a path and a chain of segments; a single-pattern actuator is a chain of
one. The request (:attr:`~embroact.patterns.design.ActuatorSpec.segments`), the plan
(:attr:`~embroact.patterns.plan.ActuatorPlan.segments`) and the analysis
(:attr:`~embroact.predict.analysis.ActuatorAnalysis.segments`) each hold a :class:`Chain`.
Outputs that show a chain of one as one block (its segment *is* the actuator) ask the
chain, not the length of a tuple: :meth:`Chain.shown` is the one place that decides it
(:meth:`Chain.one_or_all`, :attr:`Chain.listed`, :meth:`Chain.label`, :meth:`Chain.where`,
:meth:`Chain.ref` and :meth:`Chain.part_name` ask it).

The whole strip's value of a quantity has one definition for any chain length, so an output
gives it in the same keys for one segment as for five: a length is the sum of the
segments' (:func:`math.fsum`), the pattern the kinds in chain order (:func:`strip_pattern`),
and any other value the one every segment has (:func:`common`: equal within float noise),
``None`` where they differ (each segment's own value is under ``segments``). A chain of
one's whole-strip values are its segment's, to the last digit.

Examples
--------
>>> from embroact.patterns.chain import Chain
>>> one, three = Chain(["z"]), Chain(["z", "x", "z"])
>>> one.listed, one.label(0), one.part_name("A1", 0)
((), '', 'A1')
>>> three.listed, three.label(1), three.where(1), three.part_name("A1", 2)
(('z', 'x', 'z'), 'segment 1: ', 'segment[1]: ', 'A1 segment 2')
>>> Chain([])
Traceback (most recent call last):
...
embroact.patterns.base.errors.ParameterError: segments must hold at least one segment, got none
"""
from __future__ import annotations

import math
from itertools import groupby
from typing import Iterable

from .base.errors import ParameterError

__all__ = ["Chain", "UNGIVEN", "common", "strip_pattern", "COMMON_REL_TOL"]

#: Two segments' floats are the same value when they differ by no more than this, relative (float noise).
COMMON_REL_TOL = 1e-9


def common(values: Iterable):
    """The value every segment has, ``None`` where they differ (the whole strip's value of an intensive quantity).

    Floats agree within :data:`COMMON_REL_TOL` (relative; 1e-12 absolute near zero) and the first segment's is returned, so
    a chain of one gives its segment's value unchanged; other values agree when equal.

    Parameters
    ----------
    values : iterable
        One value per segment, in chain order (at least one).

    Returns
    -------
    object or None

    Examples
    --------
    >>> common([7.0]), common([7.0, 7.0 + 1e-12]), common([7.0, 9.0]), common(["paper", "paper"])
    (7.0, 7.0, None, 'paper')
    >>> common([True, False]), common([None, None])
    (None, None)
    """
    items = list(values)
    if not items:
        raise ParameterError("values must hold one value per segment, got none")
    first = items[0]
    for v in items[1:]:
        if isinstance(first, float) and isinstance(v, float) and not isinstance(v, bool):
            if not math.isclose(v, first, rel_tol=COMMON_REL_TOL, abs_tol=1e-12):
                return None
        elif v != first or type(v) is not type(first):
            return None
    return first


def strip_pattern(patterns: Iterable[str]) -> str:
    """The whole strip's pattern: its segments' kinds in chain order, a run of one kind named once.

    Parameters
    ----------
    patterns : iterable of str
        Each segment's pattern kind, in chain order.

    Returns
    -------
    str
        ``"zigzag"`` for a chain of zigzag segments (of one or more), ``"zigzag+cross"`` for a
        zigzag then a cross segment.

    Examples
    --------
    >>> strip_pattern(["zigzag"]), strip_pattern(["zigzag"] * 4), strip_pattern(["zigzag", "cross", "cross", "zigzag"])
    ('zigzag', 'zigzag', 'zigzag+cross+zigzag')
    """
    return "+".join(kind for kind, _ in groupby(patterns))


class Chain(tuple):
    """A non-empty tuple of segments (requests, plans or analyses) in order along the path.

    Parameters
    ----------
    segments : iterable
        One or more segments.

    Raises
    ------
    ParameterError
        No segment given.

    Examples
    --------
    >>> c = Chain(("a", "b"))
    >>> c == ("a", "b"), len(c)
    (True, 2)
    """

    __slots__ = ()

    def __new__(cls, segments=()):
        chain = super().__new__(cls, segments)
        if not chain:
            raise ParameterError("segments must hold at least one segment, got none")
        return chain

    @classmethod
    def given_or_one(cls, segments, whole) -> "Chain":
        """``segments`` as a chain, or when none are given a chain of one: ``whole()``, the segment over the whole path.

        A chain made here from ``whole`` is made again each time (a single-pattern actuator
        copied with other parameters or another path gets the segment of its new ones).

        Parameters
        ----------
        segments : iterable
            The segments a constructor was given (may be empty, or a chain of one made here).
        whole : callable
            Makes the one segment of a single-pattern actuator.

        Returns
        -------
        Chain

        Examples
        --------
        >>> one = Chain.given_or_one((), lambda: "z")
        >>> one, Chain.given_or_one(one, lambda: "y"), Chain.given_or_one(("a", "b"), lambda: "z")
        (('z',), ('y',), ('a', 'b'))
        >>> Chain.given_or_one((s for s in "ab"), lambda: "z")
        ('a', 'b')
        """
        segs = () if isinstance(segments, _Whole) else tuple(segments)  # read once: a generator is used up
        return cls(segs) if segs else _Whole((whole(),))

    @property
    def listed(self) -> tuple:
        """The segments an output lists beside the whole strip: none for a chain of one, else all of them."""
        return self.one_or_all((), tuple(self))

    def one_or_all(self, whole, each):
        """``whole`` for a chain of one (its segment is the whole actuator), ``each`` otherwise.

        What an output shows for the actuator: a chain of one as one block, a longer chain
        segment by segment. Given callables, only the chosen one is called.

        Parameters
        ----------
        whole, each : object or callable
            What to show for a chain of one, and for a longer chain.

        Returns
        -------
        object

        Examples
        --------
        >>> Chain("a").one_or_all("plain", "segments"), Chain("ab").one_or_all(lambda: "plain", lambda: "segments")
        ('plain', 'segments')
        """
        return Chain.shown(self, whole, each)

    @staticmethod
    def shown(segments, whole, each):
        """:meth:`one_or_all` for any sequence of segments, also none (an actuator read from a machine file,
        whose chain is not known, shows as one block).

        Parameters
        ----------
        segments : sequence
            A chain, or the segments an output holds (may be empty).
        whole, each : object or callable
            As for :meth:`one_or_all`.

        Returns
        -------
        object

        Examples
        --------
        >>> Chain.shown((), "plain", "segments"), Chain.shown([{}, {}], "plain", "segments")
        ('plain', 'segments')
        """
        chosen = whole if len(segments) < 2 else each
        return chosen() if callable(chosen) else chosen

    def single(self, message: str):
        """The one segment of a chain of one; :class:`ParameterError` with ``message`` for a longer chain.

        Parameters
        ----------
        message : str
            Why a longer chain is refused (one line).

        Returns
        -------
        object

        Examples
        --------
        >>> Chain("a").single("one pattern only")
        'a'
        >>> Chain("ab").single("one pattern only")
        Traceback (most recent call last):
        ...
        embroact.patterns.base.errors.ParameterError: one pattern only
        """
        return self.one_or_all(lambda: self[0], lambda: _refuse(message))

    def check_parts(self, parts, owner: str, reason: str) -> None:
        """:class:`ParameterError` unless ``parts`` holds one item per segment.

        Parameters
        ----------
        parts : sequence
            One item per segment (e.g. a whole strip's segment curves).
        owner, reason : str
            Who has the chain and what is wrong, for the message.

        Examples
        --------
        >>> Chain("ab").check_parts([1], "actuator 'A1'", "give one curve per segment")
        Traceback (most recent call last):
        ...
        embroact.patterns.base.errors.ParameterError: actuator 'A1' has 2 segments: give one curve per segment
        """
        if len(parts) != len(self):
            raise ParameterError(f"{owner} has {len(self)} segments: {reason}")

    def label(self, k: int) -> str:
        """Message prefix of segment ``k`` (``"segment 1: "``; ``""`` in a chain of one).

        Parameters
        ----------
        k : int
            Index of the segment.

        Returns
        -------
        str

        Examples
        --------
        >>> Chain("ab").label(0), Chain("a").label(0)
        ('segment 0: ', '')
        """
        return self.one_or_all("", f"segment {k}: ")

    def where(self, k: int) -> str:
        """Error and note prefix of segment ``k`` (``"segment[1]: "``; ``""`` in a chain of one).

        Parameters
        ----------
        k : int
            Index of the segment.

        Returns
        -------
        str

        Examples
        --------
        >>> Chain("ab").where(1), Chain("a").where(0)
        ('segment[1]: ', '')
        """
        return self.one_or_all("", f"segment[{k}]: ")

    def ref(self, actuator: str, k: int) -> str:
        """How a value of segment ``k`` of ``actuator`` is named (``"A1[0]"``; the actuator's name in a chain of one).

        Parameters
        ----------
        actuator : str
            The actuator's name.
        k : int
            Index of the segment.

        Returns
        -------
        str

        Examples
        --------
        >>> Chain("ab").ref("A1", 1), Chain("a").ref("A1", 0)
        ('A1[1]', 'A1')
        """
        return self.one_or_all(actuator, f"{actuator}[{k}]")

    def part_name(self, actuator: str, k: int) -> str:
        """The name a row or a legend gives segment ``k`` of ``actuator`` (the actuator's own in a chain of one).

        Parameters
        ----------
        actuator : str
            The actuator's name.
        k : int
            Index of the segment.

        Returns
        -------
        str

        Examples
        --------
        >>> Chain("ab").part_name("A1", 1), Chain("a").part_name("A1", 0)
        ('A1 segment 1', 'A1')
        """
        return self.one_or_all(actuator, f"{actuator} segment {k}")


def _refuse(message: str):
    raise ParameterError(message)


class _Whole(Chain):
    """A chain of one made from a single-pattern actuator's own pattern (:meth:`Chain.given_or_one`)."""

    __slots__ = ()


UNGIVEN: Chain = tuple.__new__(_Whole, ())
"""The default of a chain field: no segments given, so :meth:`Chain.given_or_one` makes the chain of one."""
