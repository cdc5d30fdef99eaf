"""Fixtures of the command-line tests."""

from __future__ import annotations

import numpy as np
import pytest


#: the pulse the heavy piers are run under (their geometry file's metadata: Oppenheim's, -0.95 g)
HEAVY_PIERS_PULSE = ("--pulse", "oppenheim", "--pulse-duration", "0.2", "--amplitude", "-0.95")


@pytest.fixture
def on_heavy_piers(heavy_piers_file):
    """``argv(command, *more)``: the command line of ``command`` on tests/data/heavy_piers.json
    under :data:`HEAVY_PIERS_PULSE`, ``more`` options after."""
    def argv(command: str, *more: str) -> list[str]:
        return [command, "--geometry", str(heavy_piers_file), *HEAVY_PIERS_PULSE, *more]

    return argv


@pytest.fixture
def engine_calls(monkeypatch):
    """The contact engine replaced by a stand-in (it takes tens of seconds on the heavy piers)
    wherever the commands import it (``archrock.contact`` for dem, ``contact.motion`` for
    respond): each run collapses at 2.5 s and appends its arguments to the list returned."""
    import archrock.contact as contact
    from archrock.contact import motion

    calls = []
    fake = _fake_engine(calls)
    monkeypatch.setattr(contact, "engine_respond", fake)
    monkeypatch.setattr(motion, "engine_respond", fake)
    return calls


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
