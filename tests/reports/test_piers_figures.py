"""Figures of arches on piers: k against the piers' height (archrock.statics.buttress)."""

from __future__ import annotations

import numpy as np
import pytest

from archrock.geometry import nominal_arch
from archrock.statics.buttress import k_against_pier_height

pytest.importorskip("matplotlib")


def test_k_against_pier_height_figure(tmp_path):
    from archrock.reports.plots import new_figure, plot_k_against_pier_height

    arch = nominal_arch(radius=5.0, embrace_deg=180, thickness=0.8, voussoirs=9)
    table = k_against_pier_height(arch, 2.0, [0.0, 2.3, 4.6])
    path = plot_k_against_pier_height(table, tmp_path / "k.png")
    assert path.exists() and path.stat().st_size > 10_000
    fig, axes = new_figure()
    ax = plot_k_against_pier_height(table, ax=axes[0][0])
    line = next(ln for ln in ax.get_lines() if ln.get_label() == "$k_l$")
    x, y = line.get_data()
    assert np.allclose(x, [0.0, 0.25, 0.5]) and np.array_equal(y, table.k_l)
    # the first two keep the rigid ground's k (hinge D at the springing, marked), then it falls
    marked = next(ln for ln in ax.get_lines() if ln.get_label().startswith("hinge D not"))
    assert np.allclose(marked.get_data()[0], [0.0, 0.25])
    assert table.k_l[1] == pytest.approx(table.k_l[0], rel=1e-6)
    assert table.k_l[2] == pytest.approx(0.1451, abs=1e-4)


def test_displaced_mechanism_draws_piers_in_their_colour():
    """The mechanism figure (draw_displaced: the arch with its mechanism open): the pier blocks
    keep the pier colour and the far pier turns about its outer foot corner."""
    from matplotlib.colors import to_hex

    from archrock.dynamics.response import prepare
    from archrock.geometry import with_piers
    from archrock.reports.plots import STYLE, displaced_outlines, draw_displaced, new_figure

    arch = nominal_arch(radius=5.0, embrace_deg=180, thickness=0.8, voussoirs=9)
    ap = with_piers(arch, 4.0, 2.0, courses=2)
    model = prepare(ap)
    fig, axes = new_figure()
    patches = draw_displaced(axes[0][0], model, "l", 0.02)
    faces = [to_hex(p.get_facecolor()) for p in patches]
    assert faces == [STYLE["pier_face"]] * 2 + [STYLE["voussoir_face"]] * 9 + [STYLE["pier_face"]] * 2
    out = displaced_outlines(model, "l", 0.02)
    foot = ap.joint_point(ap.n, "extrados")
    # the last block (the right pier's foot course) rotates about its outer foot corner
    assert np.min(np.hypot(*(out[-1] - foot).T)) < 1e-9
    assert not np.allclose(out[-1][:-1], ap.outline(ap.n - 1))
    assert np.allclose(out[0][:-1], ap.outline(0))          # the left pier stays
