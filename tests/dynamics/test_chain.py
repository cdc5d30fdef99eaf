"""The chain of mechanisms, built once for one arch and for many (archrock.dynamics.chain)."""

from __future__ import annotations

import numpy as np
import pytest

from archrock.dynamics.batch import prepare_batch
from archrock.dynamics.chain import least_loss_chain, pack_chains, rotation_limit
from archrock.dynamics.response import prepare
from archrock.errors import ArchInputError


def test_pack_chains_lays_out_the_least_loss_and_paper_chains(oppenheim):
    """Oppenheim's least-loss chain has four rows (M_l, M_r, 0e-2i-5e-7i both ways, successors
    2, 3, 3, 2: test_response's figures); packed beside the paper's two-row chain it keeps its
    rows, and the shorter chain is padded (``fill``; directions and successors 0)."""
    ll, paper = prepare(oppenheim.arch, "least-loss"), prepare(oppenheim.arch, "paper")
    c = pack_chains({0: ll.chain, 2: paper.chain}, size=3, fill=np.nan, width=30)
    assert c["rows"].shape == (3, 4, 30) and c["n_rows"].tolist() == [4, 0, 2]
    assert c["next"][0].tolist() == [2, 3, 3, 2] and c["next"][2].tolist() == [1, 0, 0, 0]
    assert c["direction"][0].tolist() == [1.0, -1.0, -1.0, 1.0]
    assert c["direction"][2].tolist() == [1.0, -1.0, 0.0, 0.0]
    assert np.isnan(c["rows"][1]).all() and np.isnan(c["limit"][2, 2:]).all()
    assert np.isnan(c["rows"][0, :, 21:]).all()  # a four-link vector is 21 numbers
    assert c["ratio"][2, :2].tolist() == [paper.impact.l_to_r, paper.impact.r_to_l]
    mechs, lims, trans = ll.chain
    for j, fl in enumerate(mechs):
        assert np.array_equal(c["rows"][0, j, :21], fl.geo)
        assert c["unstable"][0, j] == fl.phi_unstable and c["limit"][0, j] == lims[j]
    # the one-arch builder of the chain is the model's
    again = least_loss_chain(oppenheim.arch, ll.mech_l, ll.mech_r, None)
    assert again[1] == lims and again[2] == list(trans)
    # the tabulated rows the fast integrator reads, zero-padded
    t = pack_chains([paper.chain], rows=[paper.tables])
    assert t["rows"].shape[:2] == (1, 2) and t["rows"].shape[2] == max(x.size for x in paper.tables)


def test_batch_least_loss_chain_is_the_packed_one_arch_chain(oppenheim):
    """prepare_batch's least-loss rows are the one-arch chain, packed: successors exactly, the
    numbers to rounding (the compiled batch and the one-arch model are two paths)."""
    b = prepare_batch([oppenheim.arch], impact="least-loss")
    c = pack_chains([prepare(oppenheim.arch, "least-loss").chain], fill=np.nan, width=21)
    scale = float(np.nanmax(np.abs(c["rows"])))
    np.testing.assert_allclose(b.chain_geo, c["rows"], rtol=1e-12, atol=1e-12 * scale,
                               equal_nan=True)
    np.testing.assert_array_equal(b.chain_next, c["next"])
    np.testing.assert_allclose(b.chain_ratio, c["ratio"], rtol=1e-12)
    assert b.n_mechanisms.tolist() == [4]


def test_rotation_limit_checks_its_factor(oppenheim):
    fl = prepare(oppenheim.arch).mech_l
    assert rotation_limit(fl, 2.0) == pytest.approx(min(2 * fl.phi_unstable, fl.phi_dead))
    with pytest.raises(ArchInputError, match="limit factor"):
        rotation_limit(fl, 1.0)
