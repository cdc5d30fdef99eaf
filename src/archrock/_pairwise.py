"""numpy's pairwise summation, compiled: ``np.sum`` of a float array in numpy's own order, so a
compiled loop adds up exactly as the numpy code it replaces (bit for bit).  A foundation module:
the geometry's batch drawing and the batch impact laws both use it."""

from __future__ import annotations

import numpy as np

from ._jit import maybe_njit

__all__ = ["np_sum", "pairwise_sum"]


@maybe_njit
def _block(a, lo, n):
    """numpy's pairwise summation of a[lo:lo + n] for n <= 128 (numpy/_core/src/umath/
    loops_utils.h.src): eight running sums, then the rest in order."""
    if n < 8:
        res = 0.0
        for i in range(lo, lo + n):
            res += a[i]
        return res
    r0, r1, r2, r3 = a[lo], a[lo + 1], a[lo + 2], a[lo + 3]
    r4, r5, r6, r7 = a[lo + 4], a[lo + 5], a[lo + 6], a[lo + 7]
    i = 8
    while i < n - (n % 8):
        r0 += a[lo + i]
        r1 += a[lo + i + 1]
        r2 += a[lo + i + 2]
        r3 += a[lo + i + 3]
        r4 += a[lo + i + 4]
        r5 += a[lo + i + 5]
        r6 += a[lo + i + 6]
        r7 += a[lo + i + 7]
        i += 8
    res = ((r0 + r1) + (r2 + r3)) + ((r4 + r5) + (r6 + r7))
    while i < n:
        res += a[lo + i]
        i += 1
    return res


@maybe_njit
def _pairwise(a, lo, n):
    """numpy's pairwise summation of a[lo:lo + n]: above 128 terms the sum of two halves (the
    first a multiple of 8), evaluated here with an explicit stack (numba's cache cannot reload
    a recursive function)."""
    if n <= 128:
        return _block(a, lo, n)
    st_lo = np.empty(64, dtype=np.int64)
    st_n = np.empty(64, dtype=np.int64)
    st_state = np.empty(64, dtype=np.int64)
    st_left = np.empty(64)
    st_lo[0], st_n[0], st_state[0] = lo, n, 0
    sp = 1
    ret = 0.0
    while sp > 0:
        top = sp - 1
        l, m = st_lo[top], st_n[top]
        if m <= 128:
            ret = _block(a, l, m)
            sp -= 1
            continue
        n2 = m // 2
        n2 -= n2 % 8
        if st_state[top] == 0:  # first half
            st_state[top] = 1
            st_lo[sp], st_n[sp], st_state[sp] = l, n2, 0
            sp += 1
        elif st_state[top] == 1:  # second half
            st_left[top] = ret
            st_state[top] = 2
            st_lo[sp], st_n[sp], st_state[sp] = l + n2, m - n2, 0
            sp += 1
        else:
            ret = st_left[top] + ret
            sp -= 1
    return ret


@maybe_njit
def np_sum(a):
    """``np.sum`` of a contiguous 1-d float array, in numpy's order (bit for bit)."""
    return _pairwise(a, 0, a.size)


#: a[lo:lo + n] summed in numpy's order
pairwise_sum = _pairwise
