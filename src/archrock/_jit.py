"""Optional numba compilation: the physics runs with numpy alone, faster with numba.

Set ARCHROCK_NO_NUMBA=1 to run the pure-Python versions (used to check that both agree).
"""

import os

try:  # numba is an optional extra ("fast")
    if os.environ.get("ARCHROCK_NO_NUMBA"):
        raise ImportError
    import numba

    HAVE_NUMBA = True
except ImportError:  # pragma: no cover - exercised when numba is absent
    numba = None
    HAVE_NUMBA = False


def maybe_njit(func):
    """numba.njit(cache=True) when numba is available, otherwise the function itself."""
    if HAVE_NUMBA:
        return numba.njit(cache=True, fastmath=False)(func)
    return func
