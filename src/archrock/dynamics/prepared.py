"""What the batch's preparation hands its response: :class:`PreparedBatch`, the arrays of a batch
of arches ready for the compiled kernels (:func:`archrock.dynamics.batch.prepare_batch` makes
it; :func:`archrock.dynamics.batch.simulate_batch` reads it, on the CPU or the GPU)."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

__all__ = ["PreparedBatch"]


@dataclass
class PreparedBatch:
    """Everything the response kernel needs for a batch of B arches (arrays of length B).

    error: '' for usable arches, otherwise the reason (such arches are not integrated).
    mech_l / mech_r: compact hinge labels ('0i-3e-5i-7e'); geo_l / geo_r (B, 21): flat four-link
    vectors; phi_unstable_* / phi_limit_* [rad]; c_l_to_r / c_r_to_l: impact rate ratios out of
    M_l / M_r; v_rest [rad/s]; table_l / table_r (B, 2): the
    range [start, top] of phi [rad] of the tables of M, L/M, F/M, P/M used by the fast kernel
    (as FourLink.tabulated(phi_limit)); seconds: time spent preparing.

    The chain of mechanisms that the kernel runs (as ``DynamicModel.chain``), padded to R >= 2
    rows (rows 0 and 1: M_l and M_r, opened from rest): chain_geo (B, R, 21), chain_limit and
    chain_unstable (B, R) [rad], chain_direction (B, R) (+1 for direction l, -1 for r),
    chain_next (B, R) (row opened when the row closes), chain_ratio (B, R) (its rate ratio),
    chain_table (B, R, 2) (table ranges [rad]), n_mechanisms (B,) (rows used; 0 for an
    unusable arch).  Left out, they are built from the two-row fields (the paper's alternation).

    impact_fallback (B,): '' where the row's impact law is the one asked for; otherwise why it
    is the momentum law's (the default spec's paper model cannot be used on that arch, or on
    the nominal arch whose c_v the row gets), the note of ``ImpactLaw.fallback`` of the same
    arch through :func:`archrock.dynamics.response.prepare`.  Left out, '' for every row.
    """

    k_l: np.ndarray
    k_r: np.ndarray
    mech_l: np.ndarray
    mech_r: np.ndarray
    geo_l: np.ndarray
    geo_r: np.ndarray
    phi_unstable_l: np.ndarray
    phi_unstable_r: np.ndarray
    phi_limit_l: np.ndarray
    phi_limit_r: np.ndarray
    c_l_to_r: np.ndarray
    c_r_to_l: np.ndarray
    v_rest: np.ndarray
    error: np.ndarray
    table_l: np.ndarray = None
    table_r: np.ndarray = None
    seconds: dict = field(default_factory=dict)
    chain_geo: np.ndarray = None
    chain_limit: np.ndarray = None
    chain_unstable: np.ndarray = None
    chain_direction: np.ndarray = None
    chain_next: np.ndarray = None
    chain_ratio: np.ndarray = None
    chain_table: np.ndarray = None
    n_mechanisms: np.ndarray = None
    impact_fallback: np.ndarray = None

    def __post_init__(self):
        if self.impact_fallback is None:
            self.impact_fallback = np.full(self.k_l.size, "", dtype=object)
        if self.chain_geo is None:
            B = self.k_l.size
            tab_l = np.full((B, 2), np.nan) if self.table_l is None else self.table_l
            tab_r = np.full((B, 2), np.nan) if self.table_r is None else self.table_r
            self.chain_geo = np.ascontiguousarray(np.stack([self.geo_l, self.geo_r], axis=1))
            self.chain_limit = np.column_stack([self.phi_limit_l, self.phi_limit_r])
            self.chain_unstable = np.column_stack([self.phi_unstable_l, self.phi_unstable_r])
            self.chain_direction = np.tile(np.array([1.0, -1.0]), (B, 1))
            self.chain_next = np.tile(np.array([1, 0], dtype=np.int64), (B, 1))
            self.chain_ratio = np.column_stack([self.c_l_to_r, self.c_r_to_l])
            self.chain_table = np.ascontiguousarray(np.stack([tab_l, tab_r], axis=1))
            self.n_mechanisms = np.where(self.error == "", 2, 0).astype(np.int64)

    @property
    def ok(self) -> np.ndarray:
        return self.error == ""

    def __len__(self) -> int:
        return int(self.k_l.size)
