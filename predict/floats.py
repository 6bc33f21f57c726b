"""numpy's names on Python floats, for the lean path of a handful of values.

Every numpy operation costs about a microsecond whatever the size of its arrays; a
formula of fifty operations on one value is twenty times cheaper on Python floats.
The fast formulas take the namespace they compute with as ``xp`` (``numpy`` or
:data:`SCALAR`), so one text serves both, with the same operations in the same
order: the same bits (IEEE 754 rounds ``+ - * /`` and ``sqrt`` correctly in both;
``arcsin`` and ``cos`` are numpy's own on one float, since numpy's need not be libm's).

Examples
--------
>>> import numpy as np
>>> from embroact.predict.floats import SCALAR
>>> SCALAR.sqrt(2.0) == float(np.sqrt(2.0)), SCALAR.where(1.0 > 0.0, "a", "b")
(True, 'a')
>>> [str(f(a, b)) for f in (SCALAR.maximum, np.maximum) for a, b in ((-0.0, 0.0), (0.0, -0.0))]
['0.0', '-0.0', '0.0', '-0.0']
"""
from __future__ import annotations

import math

import numpy as np

__all__ = ["SCALAR"]


class _ScalarMath:
    """``sqrt``, ``cos``, ``sin``, ``arcsin``, ``minimum``, ``maximum``, ``where`` and ``real`` on floats
    (module docstring)."""

    __slots__ = ()
    sqrt = staticmethod(math.sqrt)

    @staticmethod
    def minimum(a, b):
        """numpy's ``minimum``: NaN if either is, ``b`` on a tie (``min`` keeps ``a``: -0.0 against 0.0)."""
        return a if a < b or a != a else b

    @staticmethod
    def maximum(a, b):
        """numpy's ``maximum`` (as :meth:`minimum`)."""
        return a if a > b or a != a else b

    @staticmethod
    def arcsin(x):
        """numpy's arcsin as a float: numpy's may not be libm's (they differ in the last bit)."""
        return float(np.arcsin(x))

    @staticmethod
    def cos(x):
        """numpy's cos as a float (as :meth:`arcsin`)."""
        return float(np.cos(x))

    @staticmethod
    def sin(x):
        """numpy's sin as a float (as :meth:`arcsin`)."""
        return float(np.sin(x))

    @staticmethod
    def where(condition, a, b):
        """``a`` if ``condition`` else ``b`` (both already evaluated, as with numpy)."""
        return a if condition else b

    @staticmethod
    def real(x):
        """``x`` (floats are real)."""
        return x


#: ``xp=SCALAR``: the fast formulas on Python floats (``xp=numpy``: on arrays).
SCALAR = _ScalarMath()
