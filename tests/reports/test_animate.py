"""Animation of a response: frames follow the exact four-bar kinematics."""

import numpy as np
import pytest

from archrock import geometry, groundmotion as gm
from archrock.errors import ArchInputError
from archrock.dynamics.response import prepare, respond

pytest.importorskip("matplotlib")
PIL = pytest.importorskip("PIL.Image")


@pytest.fixture(scope="module")
def collapsing():
    model = prepare(geometry.random_arch(seed=315), 0.8753811790524912)
    res = respond(model, gm.oppenheim_pulse(-1.0, 0.2), t_end=3.0)
    assert res.collapsed
    return res


def test_gif_frames(tmp_path, collapsing):
    from archrock.reports.animate import animate_response

    path = animate_response(collapsing, tmp_path / "a.gif", max_frames=6, dpi=40)
    with PIL.open(path) as im:
        assert im.n_frames == 6


def test_displaced_outlines_move_links_rigidly(collapsing):
    """Voussoirs outside the mechanism stay; each link's voussoirs keep their shape and the
    ground hinges A and D stay put."""
    from archrock.reports.plots import displaced_outlines

    model = collapsing.model
    fl = model.mech_r
    rest = displaced_outlines(model, "rest", 0.0)
    moved = displaced_outlines(model, "r", 0.05)
    inside = {i for link in fl.link_voussoirs for i in link}
    for i in range(model.arch.n):
        outline = model.arch.outline(i)
        assert np.allclose(rest[i], np.vstack([outline, outline[:1]]))
        if i not in inside:
            assert np.allclose(moved[i], rest[i])
        else:  # rigid motion: all pairwise distances kept
            d0 = np.linalg.norm(rest[i][:, None] - rest[i][None], axis=-1)
            d1 = np.linalg.norm(moved[i][:, None] - moved[i][None], axis=-1)
            assert np.allclose(d0, d1, atol=1e-9)
            assert not np.allclose(moved[i], rest[i])


def test_bad_extension(tmp_path, collapsing):
    from archrock.reports.animate import animate_response

    with pytest.raises(ArchInputError, match="allowed extensions"):
        animate_response(collapsing, tmp_path / "a.avi")


def test_response_figure(tmp_path, collapsing):
    from archrock.reports.plots import save_response_figure

    path = save_response_figure([collapsing], tmp_path / "r.png", labels=["RA-2 type"])
    assert path.stat().st_size > 10_000


def test_displaced_outlines_take_chain_rows():
    """A chain row, its FourLink and (for rows 0/1) 'l'/'r' draw the same thing; least-loss's
    row 2 (0e-2i-5e-7i) is not M_r."""
    from archrock.reports.plots import displaced_hinges, displaced_outlines

    model = prepare(geometry.oppenheim_arch(), "least-loss")
    mechs = model.chain[0]
    for row, letter in ((0, "l"), (1, "r")):
        a = displaced_outlines(model, row, 0.05)
        for b in (displaced_outlines(model, letter, 0.05), displaced_outlines(model, mechs[row], 0.05)):
            assert all(np.array_equal(x, y) for x, y in zip(a, b))
    r2, mr = displaced_outlines(model, 2, 0.05), displaced_outlines(model, "r", 0.05)
    assert not all(np.allclose(x, y) for x, y in zip(r2, mr))
    rest = displaced_outlines(model, "rest", 0.0)
    assert all(np.array_equal(x, y) for x, y in zip(rest, displaced_outlines(model, -1, 0.05)))
    # the hinges drawn for row 2 are its own: joints 0e, 2i, 5e, 7i at phi = 0
    arch = model.arch
    want = np.array([arch.joint_point(h.joint, h.edge) for h in mechs[2].mechanism.hinges])
    got = np.asarray(displaced_hinges(model, 2, 0.0))
    # the same points in any order, to 1e-9 m (two computations of a joint corner; rounding
    # both to 9 decimals could split a pair straddling a rounding boundary)
    dist = np.linalg.norm(got[:, None, :] - want[None, :, :], axis=-1)
    assert got.shape == want.shape
    assert np.all(dist.min(axis=0) < 1e-9) and np.all(dist.min(axis=1) < 1e-9)
    assert mechs[2].mechanism.label == "0e-2i-5e-7i"
    assert displaced_hinges(model, -1, 0.1).shape == (0, 2)
    with pytest.raises(ArchInputError, match="mechanism row"):
        displaced_outlines(model, 7, 0.05)


def test_least_loss_animation(tmp_path):
    from archrock.reports.animate import animate_response

    model = prepare(geometry.oppenheim_arch(), "least-loss")
    res = respond(model, gm.oppenheim_pulse(-1.0, 0.2), t_end=1.0)
    path = animate_response(res, tmp_path / "ll.gif", max_frames=4, dpi=30)
    with PIL.open(path) as im:
        assert im.n_frames == 4


def test_unwritable_animation_and_folders_are_input_errors(tmp_path, collapsing):
    """PIL's and the OS's errors become one ArchInputError naming the file, not a traceback."""
    from archrock.reports.animate import animate_response, animation_path

    with pytest.raises(ArchInputError, match="is a folder"):
        animation_path(tmp_path)
    (tmp_path / "ro").mkdir()
    (tmp_path / "ro" / "x.gif").mkdir()  # a folder with an animation's name
    with pytest.raises(ArchInputError, match="x.gif"):
        animate_response(collapsing, tmp_path / "ro" / "x.gif", max_frames=2, dpi=20)


def test_figures_refuse_unknown_formats_and_bound_the_pixel_count(tmp_path):
    from archrock.reports.plots import MAX_FIGURE_PIXELS, figure_path, new_figure, save_figure

    assert figure_path(tmp_path / "f") == tmp_path / "f.png"
    with pytest.raises(ArchInputError, match="cannot be written"):
        figure_path(tmp_path / "f.xyz")
    fig, _ = new_figure(figsize=(10.0, 5.0))
    top = int((MAX_FIGURE_PIXELS / 50.0) ** 0.5)
    with pytest.raises(ArchInputError, match=f"allowed 10 to {top}"):
        save_figure(fig, tmp_path / "big.png", dpi=top + 1)
    assert save_figure(fig, tmp_path / "small", dpi=20) == tmp_path / "small.png"
    assert (tmp_path / "small.png").is_file() and not (tmp_path / "big.png").exists()
