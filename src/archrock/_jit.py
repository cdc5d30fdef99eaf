"""Optional numba compilation: the physics runs with numpy alone, faster with numba.

Set ARCHROCK_NO_NUMBA=1 to run the pure-Python versions (used to check that both agree).

numba keys its on-disk cache on the source file of the cached function alone, so a cached
kernel would keep a stale inlined copy of a function from another module after that module
changed.  Every dispatcher made here is therefore stamped with a hash of all the package's
sources: any change to the package recompiles every cached function once.
"""

import hashlib
import os
from pathlib import Path

try:  # numba is an optional extra ("fast")
    if os.environ.get("ARCHROCK_NO_NUMBA"):
        raise ImportError
    import numba

    HAVE_NUMBA = True
except ImportError:  # pragma: no cover - exercised when numba is absent
    numba = None
    HAVE_NUMBA = False


def _package_digest(root=None) -> str:
    """sha256 of every ``*.py`` file under the package folder (or ``root``), subpackages included.

    Files are taken in the order of their relative paths written with '/', so the digest is the
    same on every platform; each path and length is hashed before the contents, so moving code
    between files changes it too.
    """
    base = Path(__file__).parent if root is None else Path(root)
    h = hashlib.sha256()
    for rel in sorted(p.relative_to(base).as_posix() for p in base.rglob("*.py")):
        data = (base / rel).read_bytes()
        h.update(f"{rel}\0{len(data)}\0".encode())
        h.update(data)
    return h.hexdigest()


_DIGEST = _package_digest() if HAVE_NUMBA else ""


def _bind_cache(dispatcher):
    """Add the package digest to the cache stamp of a numba dispatcher (numba internals; where
    they differ, caching is turned off rather than risking a stale kernel)."""
    try:
        cache_file = dispatcher._cache._cache_file
        stamp = cache_file._source_stamp
        if not (isinstance(stamp, tuple) and stamp[-1:] == (_DIGEST,)):
            cache_file._source_stamp = (stamp, _DIGEST)
    except AttributeError:  # pragma: no cover - other numba versions
        dispatcher.enable_caching = lambda: None
        dispatcher._cache = getattr(numba.core.caching, "NullCache", lambda: None)()
    return dispatcher


def maybe_njit(func=None, **options):
    """numba.njit(cache=True, **options) when numba is available, otherwise the function itself.

    Usable bare (``@maybe_njit``) or with options (``@maybe_njit(parallel=True)``).
    """
    def wrap(f):
        if not HAVE_NUMBA:
            return f
        return _bind_cache(numba.njit(cache=True, **options)(f))
    return wrap if func is None else wrap(func)
