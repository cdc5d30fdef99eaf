"""Fixtures of the command-line tests."""

from __future__ import annotations

import numpy as np
import pytest


@pytest.fixture
def fake_engine():
    """A factory of stand-ins for ``contact.motion.engine_respond`` (the engine takes tens of
    seconds on the heavy piers): each collapses at 2.5 s and records its arguments in the list
    it is given."""
    return _fake_engine


def _fake_engine(calls):
    from archrock.contact.motion import ContactResponse

    def engine_respond(arch, motion, settings, *, model=None, t_end=3.0, dt_out=0.005,
                       t_free=20.0, collapse_drop=0.2, progress=None):
        calls.append({"arch": arch, "friction": settings.friction, "t_end": t_end,
                      "dt_out": dt_out, "t_free": t_free, "progress": progress})
        k, n = 4, arch.n
        t = np.linspace(0.0, t_end, k)
        return ContactResponse(t, np.zeros((k, n)), np.zeros((k, n + 1)), np.zeros((k, n + 1)),
                               np.linspace(0.0, 0.3, k), np.zeros((k, n, 2)),
                               np.full(n + 1, 1e-3), 0.3, "collapsed", 2.5, 2.5, settings,
                               {"t_end": t_end, "dt_out": dt_out, "t_free": t_free,
                                "collapse_drop": collapse_drop, "dt": 1e-3,
                                "motion": motion.name})

    return engine_respond
