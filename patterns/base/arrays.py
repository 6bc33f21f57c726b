"""Read-only numpy arrays for the frozen values embroact returns, :func:`median`, and whole-array maxima and minima.

Examples
--------
>>> import numpy as np
>>> from embroact.patterns.base.arrays import frozen_array
>>> a = frozen_array([1, 2])
>>> a.dtype.name, a.flags.writeable
('float64', False)
>>> from embroact.patterns.base.arrays import array_max
>>> float(array_max(np.array([[1.0, 3.0], [2.0, 0.5]]), axis=None)), bool(np.isnan(array_max(np.array([1.0, np.nan]))))
(3.0, True)
"""
from __future__ import annotations

import numpy as np

__all__ = ["frozen_array", "median", "array_max", "array_min"]

#: ``a.max()`` and ``a.min()`` as the ufuncs' own reductions, without ndarray's Python-level wrapper (a first curve
#: makes a dozen); ``axis=None`` reduces an array of any shape to one value, NaN if any is.
array_max, array_min = np.maximum.reduce, np.minimum.reduce


def frozen_array(values, dtype=np.float64) -> np.ndarray:
    """A read-only copy of ``values``.

    Parameters
    ----------
    values : array_like
        The values to copy.
    dtype : numpy dtype or None, optional
        The copy's dtype (float64 by default); None keeps the input's.

    Returns
    -------
    numpy.ndarray
        A new array whose ``flags.writeable`` is False.

    Examples
    --------
    >>> a = frozen_array([1, 2], dtype=None)
    >>> a.dtype.kind, a.flags.writeable, a.tolist()
    ('i', False, [1, 2])
    """
    a = np.array(values, dtype=dtype, copy=True)
    a.setflags(write=False)
    return a


def median(values) -> float:
    """The median of finite numbers, as ``numpy.median`` gives it (the mean of the two middle ones for an even
    count), without its first call's import of ``numpy.ma`` (30 ms of a command's start).

    Parameters
    ----------
    values : array_like
        At least one finite number.

    Returns
    -------
    float

    Examples
    --------
    >>> median([3.0, 1.0, 2.0]), median([4, 1, 3, 2])
    (2.0, 2.5)
    """
    v = np.asarray(values, dtype=np.float64).ravel()
    k = len(v) // 2
    if len(v) % 2:
        return float(np.partition(v, k)[k])
    low, high = np.partition(v, (k - 1, k))[k - 1:k + 1]
    return float(np.mean([low, high]))
