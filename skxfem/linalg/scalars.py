"""What a scene, a solve or a study takes for one number.

A notebook computes its numbers with numpy as often as it types them: ``np.float32(0.2)``,
``np.int64(40)``, or a 0-d array such as ``np.array(2e11)`` or ``x.sum()`` of an array.
Each is a number to the user, so every check of a scalar argument goes through here, and
a bool (a number to Python) or a string never is one.
"""
from __future__ import annotations

import numpy as np


def scalar(v):
    """``v``'s number (a Python one) if it is a 0-d numpy array: ``np.array(2.0)`` →
    ``2.0``; else ``v`` itself.

    >>> scalar(np.array(2)), scalar(np.ones(2)).shape, scalar("a")
    (2, (2,), 'a')
    """
    return v.item() if isinstance(v, np.ndarray) and v.ndim == 0 else v


def is_number(v) -> bool:
    """Whether ``v`` is a real scalar: a Python or numpy integer or float, or a 0-d numpy
    array of one.  Never a bool, a string, a complex number or an array of several values.

    >>> [is_number(v) for v in (0.2, np.float32(0.2), np.array(0.2), np.array(2))]
    [True, True, True, True]
    >>> [is_number(v) for v in (True, np.bool_(True), "0.2", 1j, np.array([0.2]), np.ones(2))]
    [False, False, False, False, False, False]
    """
    v = scalar(v)
    return isinstance(v, (int, float, np.integer, np.floating)) and not isinstance(v, bool)


def is_integer(v) -> bool:
    """Whether ``v`` is an integer: a Python or numpy one, or a 0-d numpy array of one.
    Never a bool nor a float that happens to be whole (``2.0``: say ``2``).

    >>> [is_integer(v) for v in (2, np.int64(2), np.array(2))]
    [True, True, True]
    >>> [is_integer(v) for v in (True, 2.0, np.array(2.0), "2", np.array([2]))]
    [False, False, False, False, False]
    """
    v = scalar(v)
    return isinstance(v, (int, np.integer)) and not isinstance(v, bool)
