"""Animation of a response: frames follow the exact four-bar kinematics."""

import numpy as np
import pytest

from archrock import geometry, groundmotion as gm
from archrock.errors import ArchInputError
from archrock.response import prepare, respond

pytest.importorskip("matplotlib")
PIL = pytest.importorskip("PIL.Image")


@pytest.fixture(scope="module")
def collapsing():
    model = prepare(geometry.random_arch(seed=315), 0.8753811790524912)
    res = respond(model, gm.oppenheim_pulse(-1.0, 0.2), t_end=3.0)
    assert res.collapsed
    return res


def test_gif_frames(tmp_path, collapsing):
    from archrock.animate import animate_response

    path = animate_response(collapsing, tmp_path / "a.gif", max_frames=6, dpi=40)
    with PIL.open(path) as im:
        assert im.n_frames == 6


def test_displaced_outlines_move_links_rigidly(collapsing):
    """Voussoirs outside the mechanism stay; each link's voussoirs keep their shape and the
    ground hinges A and D stay put."""
    from archrock.plots import displaced_outlines, voussoir_outline

    model = collapsing.model
    fl = model.mech_r
    rest = displaced_outlines(model, "rest", 0.0)
    moved = displaced_outlines(model, "r", 0.05)
    inside = {i for link in fl.link_voussoirs for i in link}
    for i in range(model.arch.n):
        assert np.allclose(rest[i], voussoir_outline(model.arch, i))
        if i not in inside:
            assert np.allclose(moved[i], rest[i])
        else:  # rigid motion: all pairwise distances kept
            d0 = np.linalg.norm(rest[i][:, None] - rest[i][None], axis=-1)
            d1 = np.linalg.norm(moved[i][:, None] - moved[i][None], axis=-1)
            assert np.allclose(d0, d1, atol=1e-9)
            assert not np.allclose(moved[i], rest[i])


def test_bad_extension(tmp_path, collapsing):
    from archrock.animate import animate_response

    with pytest.raises(ArchInputError, match="allowed extensions"):
        animate_response(collapsing, tmp_path / "a.avi")


def test_response_figure(tmp_path, collapsing):
    from archrock.plots import save_response_figure

    path = save_response_figure([collapsing], tmp_path / "r.png", labels=["RA-2 type"])
    assert path.stat().st_size > 10_000
