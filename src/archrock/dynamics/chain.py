"""The chain of mechanisms an arch rocks through, built once for one arch and for many.

A chain is what :attr:`archrock.dynamics.response.DynamicModel.chain` returns: its four-link
mechanisms (rows 0 and 1: M_l and M_r, opened from rest), their rotation limits [rad], and per
row the row its closing opens with the rate ratio of that impact.  The paper's alternation is the
two-row chain M_l <-> M_r; the least-loss law (Bisegna, Coccia, Como, Nodargi 2023) grows it
with :func:`least_loss_chain`.  :func:`pack_chains` lays chains out as the padded arrays the
compiled kernel reads, for one arch (``respond``) and for many (``SweepArches.from_models``, the
least-loss rows of ``prepare_batch``).  The batch's paper chain is not a list of Python objects
but compiled arrays (``PreparedBatch``): there the two rows are stacked from them directly.
"""

from __future__ import annotations

import math

import numpy as np

from ..errors import ArchInputError
from .fourlink import FourLink, four_link
from .impact import least_loss_mechanism

__all__ = ["rotation_limit", "least_loss_chain", "pack_chains"]


def rotation_limit(fl: FourLink, limit_factor: float | None) -> float:
    """Rotation limit [rad] of a mechanism: ``limit_factor`` times its unstable rotation, short
    of the four-bar's dead point (None: :meth:`FourLink.default_limit`); > 1."""
    if limit_factor is None:
        return fl.default_limit()
    if not math.isfinite(limit_factor) or limit_factor <= 1.0:
        raise ArchInputError(f"limit factor: {limit_factor!r}; allowed > 1 (a multiple of the "
                             f"unstable rotation)")
    return min(limit_factor * fl.phi_unstable, fl.phi_dead * (1 - 1e-6))


def least_loss_chain(arch, m_l: FourLink, m_r: FourLink, limit_factor: float | None):
    """The chain of the least-loss law: from each mechanism, the impact opens the admissible
    mechanism of the other direction that keeps the most kinetic energy (momentum law); new
    mechanisms are added until every closing has its successor.  Returns (mechanisms, rotation
    limits, [(next row, rate ratio)]), rows 0 and 1 M_l and M_r."""
    mechs = [m_l, m_r]
    lims = [rotation_limit(m_l, limit_factor), rotation_limit(m_r, limit_factor)]
    keys = [m_l.mechanism.hinges, m_r.mechanism.hinges]
    trans = []
    k = 0
    while k < len(mechs):
        old = mechs[k]
        best = least_loss_mechanism(old, m_r if old.direction == "l" else m_l)
        key = best.mechanism.hinges
        if key not in keys:
            fl = four_link(arch, best.mechanism)
            mechs.append(fl)
            lims.append(rotation_limit(fl, limit_factor))
            keys.append(key)
        trans.append((keys.index(key), best.rate_ratio))
        k += 1
    return mechs, lims, trans


def pack_chains(chains, size: int | None = None, rows=None, fill: float = 0.0,
                width: int = 0) -> dict:
    """Chains as padded arrays for the kernel.

    chains: a sequence of chains, or a mapping {row b: chain} (rows not in it stay padding);
    size: the number of rows B (default: as many as the chains); rows: per chain, the vector
    of each mechanism the kernel reads (default its four-link vector ``geo``; the tabulated
    vectors for the fast integrator); fill: the padding of the float fields but directions;
    width: the least vector length S.  Returns arrays: ``rows`` (B, R, S), ``limit``,
    ``unstable`` [rad], ``direction`` (+1 l, -1 r; 0 padding), ``next`` (int64, the row opened
    at the row's closing; 0 padding), ``ratio`` (B, R), ``n_rows`` (B,), R at least 2.
    """
    items = dict(chains) if isinstance(chains, dict) else dict(enumerate(chains))
    B = len(items) if size is None else size
    vecs = {b: ([fl.geo for fl in c[0]] if rows is None else list(rows[b]))
            for b, c in items.items()}
    R = max([2] + [len(c[0]) for c in items.values()])
    S = max([width] + [v.size for vs in vecs.values() for v in vs])
    out = {"rows": np.full((B, R, S), fill), "limit": np.full((B, R), fill),
           "unstable": np.full((B, R), fill), "direction": np.zeros((B, R)),
           "next": np.zeros((B, R), dtype=np.int64), "ratio": np.full((B, R), fill),
           "n_rows": np.zeros(B, dtype=np.int64)}
    for b, (mechs, lims, trans) in items.items():
        out["n_rows"][b] = len(mechs)
        for j, (fl, v, lim, (nxt, c)) in enumerate(zip(mechs, vecs[b], lims, trans)):
            out["rows"][b, j, :v.size] = v
            out["limit"][b, j] = lim
            out["unstable"][b, j] = fl.phi_unstable
            out["direction"][b, j] = 1.0 if fl.direction == "l" else -1.0
            out["next"][b, j] = nxt
            out["ratio"][b, j] = c
    return out
