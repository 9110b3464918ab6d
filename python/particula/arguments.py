"""Checks of the arguments the C++ core takes as numbers: a wrong type raises TypeError, a value
out of range ValueError naming the argument, before anything reaches the solver or OpenMP."""
import numbers
import operator

from . import _core

MAX_THREADS = _core.MAX_THREADS  # the most OpenMP threads particula runs (the CLI's --threads bound)


def threads_argument(threads):
    """The OpenMP thread count for the core: None gives 0 (OpenMP's default: OMP_NUM_THREADS, else
    all cores); otherwise an integer in [1, MAX_THREADS]."""
    if threads is None:
        return 0
    if isinstance(threads, bool):
        raise TypeError("threads: an integer (or None), not a bool")
    try:
        n = operator.index(threads)
    except TypeError:
        raise TypeError("threads: an integer (or None), not %s" % type(threads).__name__) from None
    if not 1 <= n <= MAX_THREADS:
        raise ValueError("threads = %d: must be 1 .. %d (None: OpenMP's default)" % (n, MAX_THREADS))
    return n


def seconds_argument(name, value):
    """A time argument as a float; TypeError for a non-number (bools included), ValueError for
    a number beyond a float. The core checks the value itself (finite, in range)."""
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise TypeError("%s: a number of seconds, not %s" % (name, type(value).__name__))
    try:
        return float(value)
    except OverflowError:
        raise ValueError("%s = %.6s...e%d s: beyond a float, not a finite time" % (name, value, len(str(value)) - 1)) from None
