"""Read-only numpy arrays for the frozen values embroact returns.

Examples
--------
>>> from embroact.patterns.base.arrays import frozen_array
>>> a = frozen_array([1, 2])
>>> a.dtype.name, a.flags.writeable
('float64', False)
"""
from __future__ import annotations

import numpy as np

__all__ = ["frozen_array"]


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
