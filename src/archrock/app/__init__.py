"""``archrock app``: the arch in the browser (a local web application; docs/app.md).

:func:`create_app` builds the ASGI application (Starlette); :mod:`.api` holds what its
endpoints compute, calling the same library functions as the command line (an opened record
or DXF survey is read by the library's readers); :mod:`.jobs` runs the ensemble, the curve and
the assessment report in the background.  Needs the ``app`` extra: ``pip install 'archrock[app]'``.
"""

from __future__ import annotations

#: Said when the web framework is missing.
MISSING = ("archrock app needs the web server packages (starlette, uvicorn): "
           "pip install 'archrock[app]'")


def require_app_extra() -> None:
    """ImportError naming the ``app`` extra where starlette or uvicorn is missing."""
    import importlib.util

    missing = [m for m in ("starlette", "uvicorn", "pandas") if importlib.util.find_spec(m) is None]
    if missing:
        raise ImportError(f"{MISSING} (missing: {', '.join(missing)})")


def create_app(*args, **kwargs):
    """The ASGI application (:func:`archrock.app.server.create_app`)."""
    require_app_extra()
    from .server import create_app as create

    return create(*args, **kwargs)
