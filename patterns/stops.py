"""How a cord-in stop (the operator lays the next tube) is written for the machine at hand.

A stop-code format (DST, EXP) shares one code for "change needle" and "stop"; what the
machine does at it depends on how it is set up (docs/machine.md):

* a single-needle machine, or a multi-needle machine in manual needle mode, stops at
  every such record;
* a multi-needle Tajima in automatic needle mode only changes to the next needle of its
  programmed sequence and keeps sewing, unless the operator programmes a stop for that
  entry of the sequence; two such records in a row are reported to stop it anyway.

TBF and U01 have a stop code of their own (written after a needle-set record) and the
colour formats (PES, PEC, JEF, VP3, XXX) have no stop at all: the machine pauses at each
colour change, so every later actuator gets its own colour.

Examples
--------
>>> from embroact.patterns.stops import CordStop, cord_stop
>>> cord_stop("double").records_per_stop
2
>>> [m.value for m in CordStop]
['sequence', 'double']
"""
from __future__ import annotations

import enum

from .base.choices import check_choice

__all__ = ["CordStop", "cord_stop"]


class CordStop(str, enum.Enum):
    """How a stop-code format (DST, EXP) writes a cord-in stop.

    Examples
    --------
    >>> CordStop("sequence").records_per_stop, CordStop.DOUBLE.value
    (1, 'double')
    """

    SEQUENCE = "sequence"
    """One stop/colour-change record per cord-in; a multi-needle machine must be in manual
    needle mode or have a stop programmed at every entry of its needle sequence."""
    DOUBLE = "double"
    """Two consecutive stop/colour-change records per cord-in: stops a multi-needle machine
    even in automatic needle mode (it would otherwise change needle and sew on)."""

    @property
    def records_per_stop(self) -> int:
        """Stop records written per cord-in stop in a stop-code format."""
        return 2 if self is CordStop.DOUBLE else 1


def cord_stop(value: object) -> CordStop:
    """The :class:`CordStop` named by ``value``; a one-line error lists the valid names.

    Parameters
    ----------
    value : CordStop or str
        A member or its value (``"sequence"``, ``"double"``).

    Returns
    -------
    CordStop

    Examples
    --------
    >>> cord_stop("sequence")
    <CordStop.SEQUENCE: 'sequence'>
    >>> try:
    ...     cord_stop("triple")
    ... except ValueError as exc:
    ...     print(exc)
    cord_stop must be one of 'sequence', 'double', got 'triple'
    """
    return check_choice("cord_stop", value, CordStop)
