"""Irregular piers (issue 19): piers out of plumb, stepped buttresses, the pier-tilt defect and
the pier spreads of the sampler (docs/piers.md, Irregular piers; Stepped buttresses)."""

from __future__ import annotations

import json

import numpy as np
import pytest

from archrock.cli import main
from archrock.errors import ArchInputError, InvalidSampleError
from archrock.geometry import Defect, apply_defect, nominal_arch, with_piers
from archrock.geometry.piers import lean_pier, parse_steps, pier_sizes, reshape_piers
from archrock.geometry.sampling import ArchSampler, Spreads
from archrock.geometry.survey import perturb_survey
from archrock.geometry.surveybatch import survey_lines, survey_plan
from archrock.statics.limit import limit_analysis


@pytest.fixture(scope="module")
def ref():
    """Issue 19's reference semicircle (R = 5 m, t = 0.8 m, 9 voussoirs) on piers 4 x 2 m of
    2 courses, and its limit analysis (k = 0.168899, D of M_l at the right pier's outer foot)."""
    arch = nominal_arch(radius=5.0, embrace_deg=180, thickness=0.8, voussoirs=9)
    ap = with_piers(arch, 4.0, 2.0, courses=2)
    return arch, ap, limit_analysis(ap)


def _same_lines(a, b):
    return len(a.intrados) == len(b.intrados) and all(
        np.array_equal(p, q) for p, q in zip(a.intrados + a.extrados, b.intrados + b.extrados))


# ------------------------------------------------------------------------- a leaning pier
def test_lean_zero_is_the_plumb_pier_and_small_leans_are_continuous(ref):
    """A lean of 0 is the plumb pier (the same arch); +-1e-7 deg changes k by O(1e-7 deg)
    only (the rotation and the voussoirs' following are continuous at 0)."""
    _, ap, res = ref
    assert lean_pier(ap, "right", 0.0) is ap
    for d in (1e-7, -1e-7):
        r = limit_analysis(lean_pier(ap, "right", d))
        assert r.k_l == pytest.approx(res.k_l, abs=1e-8)
        assert r.k_r == pytest.approx(res.k_r, abs=1e-8)


def test_leaning_pier_turns_rigidly_about_its_outer_foot(ref):
    """The leaning pier is the plumb one turned about its outer foot corner: its blocks' areas
    unchanged (to 1e-12), the foot corner fixed, each block's centroid turned by the angle; the
    other pier untouched (to the bit); the arch's springing joint on the pier top."""
    _, ap, _ = ref
    th = 3.0
    lp = lean_pier(ap, "left", th)
    c = ap.extrados[0][0]
    t = np.deg2rad(th)
    rot = np.array([[np.cos(t), -np.sin(t)], [np.sin(t), np.cos(t)]])
    for i in ap.piers[0]:
        assert lp.areas[i] == pytest.approx(ap.areas[i], rel=1e-12)
        assert np.allclose(lp.centroids[i], c + rot @ (ap.centroids[i] - c), atol=1e-12)
    assert np.array_equal(lp.extrados[0][0], c)
    # outward (left pier): the top moves toward -x by about H sin(theta)
    top = ap.intrados[1][-1]
    assert lp.intrados[1][-1][0] - top[0] == pytest.approx(-(top[1] - c[1]) * np.sin(t)
                                                          + (top[0] - c[0]) * (np.cos(t) - 1),
                                                          abs=1e-12)
    size = pier_sizes(lp)["left"]
    assert size["lean_deg"] == pytest.approx(th, abs=1e-12)
    assert size["height"] == pytest.approx(4.0, abs=1e-12)
    assert size["width_top"] == pytest.approx(2.0, abs=1e-12)
    assert pier_sizes(lean_pier(ap, "right", -th))["right"]["lean_deg"] == pytest.approx(-th)
    for i in ap.piers[1]:
        assert np.array_equal(lp.intrados[i], ap.intrados[i])
        assert np.array_equal(lp.extrados[i], ap.extrados[i])
    jp = lp.joint_points  # checked: the springing faces still on one line and overlapping
    assert np.allclose(jp[2][0], rot @ (ap.joint_points[2][0] - c) + c, atol=1e-12)


def test_outward_lean_lowers_k_toward_that_side(ref):
    """M_l's hinge D is at the right pier's outer foot: the right pier leaning outward lowers
    k_l, inward raises it, monotonically; M_r (D at the left pier) moves far less.  The
    kinematic and static (LP) multipliers agree on every leaning chain."""
    _, ap, res = ref
    kl = {}
    for d in (-2.0, -0.5, 0.5, 2.0, 5.0):
        r = limit_analysis(lean_pier(ap, "right", d))
        assert r.discrepancy < 1e-9
        assert r.static_k_l == pytest.approx(r.k_l, abs=1e-9)
        assert abs(r.k_r - res.k_r) < 0.01
        kl[d] = r.k_l
    assert kl[-2.0] > kl[-0.5] > res.k_l > kl[0.5] > kl[2.0] > kl[5.0]
    # measured: 0.206225, 0.178730, (0.168899), 0.159149, 0.130355, 0.074603
    assert kl[2.0] == pytest.approx(0.130355, abs=1e-6)
    # the mirror image: the left pier leaning outward is the same for M_r
    m = limit_analysis(lean_pier(ap, "left", 2.0))
    assert m.k_r == pytest.approx(kl[2.0], rel=1e-9)


def test_lean_refused_by_name(ref):
    arch, ap, _ = ref
    with pytest.raises(ArchInputError, match="pier tilt: 16 is out of range"):
        lean_pier(ap, "left", 16.0)
    with pytest.raises(ArchInputError, match="side: 'up'"):
        lean_pier(ap, "up", 1.0)
    with pytest.raises(ArchInputError, match="has no piers"):
        lean_pier(arch, "left", 1.0)


# ------------------------------------------------------------------------- reshaped piers
def test_reshaped_piers_have_the_drawn_sizes(ref):
    """Width and height factors and bed-joint shifts give the piers those sizes; the springing
    and the arch stay where they were (to the bit)."""
    _, ap, _ = ref
    ch = reshape_piers(ap, ap.block_kinds, left={"width": 1.1, "height": 0.9, "shifts": [0.3]})
    size = pier_sizes(ch)
    assert size["left"]["height"] == pytest.approx(3.6, abs=1e-12)
    assert size["left"]["width_top"] == pytest.approx(2.2, abs=1e-12)
    assert size["left"]["width_foot"] == pytest.approx(2.2, abs=1e-12)
    assert size["right"] == pier_sizes(ap)["right"]
    # the bed joint 2 m above the foot, moved up 0.3 m, then the pier shortened about its top
    assert ch.intrados[1][0][1] == pytest.approx(-(4.0 - 2.3) * 0.9, abs=1e-12)
    for i in range(2, 11):
        assert np.array_equal(ch.intrados[i], ap.intrados[i])
    res = limit_analysis(ch)
    assert res.discrepancy < 1e-9
    with pytest.raises(ArchInputError, match="narrower than its springing"):
        reshape_piers(ap, ap.block_kinds, right={"width": 0.3})
    with pytest.raises(ArchInputError, match="bed joints cross"):
        reshape_piers(ap, ap.block_kinds, left={"shifts": [2.5]})
    with pytest.raises(ArchInputError, match=r"shift \[m\] per interior bed joint \(1\)"):
        reshape_piers(ap, ap.block_kinds, left={"shifts": [0.1, 0.2]})
    with pytest.raises(ArchInputError, match="left pier width factor: -1 is out of range"):
        reshape_piers(ap, ap.block_kinds, left={"width": -1})


# ------------------------------------------------------------------------- stepped buttresses
def test_stepped_buttress_of_equal_steps_is_the_rectangle(ref):
    """Steps of one width are the rectangular pier cut into those courses (polylines to
    1e-12; measured: equal), of kind "pier"; one step is the monolithic pier."""
    arch, ap, res = ref
    st = with_piers(arch, None, None, steps=((2.0, 2.0), (2.0, 2.0)))
    assert st.block_kinds == ap.block_kinds
    for p, q in zip(st.intrados + st.extrados, ap.intrados + ap.extrados):
        assert np.allclose(p, q, rtol=0, atol=1e-12)
    assert limit_analysis(st).k_l == pytest.approx(res.k_l, rel=1e-12)
    one = with_piers(arch, None, None, steps=((4.0, 2.0),))
    assert _same_lines(one, with_piers(arch, 4.0, 2.0))


def test_stepped_buttress_hinges_in_its_bed_joints():
    """A stepped buttress (3 m, 2.5 m and 2 m wide from the foot up, 1.5 + 1.5 + 1 m) of
    kind "buttress": its blocks are the steps, their bed joints the overlap of each step on the
    one below; the kinematic and static multipliers agree, and a hinge that leaves the arch
    is at a step's outer corner (D at the top step's foot on a tall narrow buttress)."""
    arch = nominal_arch(radius=5.0, embrace_deg=180, thickness=0.8, voussoirs=9)
    sb = with_piers(arch, None, None, steps=((1.5, 3.0), (1.5, 2.5), (1.0, 2.0)))
    assert sb.block_kinds[:3] == ("buttress",) * 3
    assert pier_sizes(sb)["left"]["width_foot"] == pytest.approx(3.0, abs=1e-12)
    jp = sb.joint_points
    assert np.hypot(*(jp[1][1] - jp[1][0])) == pytest.approx(2.5, abs=1e-12)
    r = limit_analysis(sb)
    assert r.discrepancy < 1e-9
    tall = with_piers(arch, None, None, steps=((2.0, 3.0), (6.0, 2.0)))
    rt = limit_analysis(tall)
    assert rt.discrepancy < 1e-9
    # the thrust overturns the top step on its bed joint over the wide base (joint n - 1 on
    # the right), not the base: k (measured 0.105890) between the rectangle 8 x 2 m (hinge at
    # its foot) and the buttress 3 m wide throughout (the arch's own mechanism)
    assert rt.mechanism_l.label.endswith(f"-{tall.n - 1}e")
    assert rt.k_l == pytest.approx(0.105890, abs=1e-6)
    rect = limit_analysis(with_piers(arch, 8.0, 2.0, courses=4))
    assert rect.mechanism_l.label.endswith(f"-{4 + 9 + 4}e") and rect.k_l < rt.k_l
    assert rt.k_l < limit_analysis(with_piers(arch, None, None,
                                              steps=((2.0, 3.0), (6.0, 3.0)))).k_l


def test_steps_refused_by_name():
    arch = nominal_arch(radius=5.0, embrace_deg=180, thickness=0.8, voussoirs=9)
    with pytest.raises(ArchInputError, match=r"steps\[1\]: width 2.5 m is wider"):
        with_piers(arch, None, None, steps=((1.0, 2.0), (1.0, 2.5)))
    with pytest.raises(ArchInputError, match="height: 4.0 given with steps"):
        with_piers(arch, 4.0, None, steps=((1.0, 2.0),))
    with pytest.raises(ArchInputError, match="narrower than the left springing"):
        with_piers(arch, None, None, steps=((1.0, 2.0), (1.0, 0.5)))
    with pytest.raises(ArchInputError, match="--pier-steps: 'x'"):
        parse_steps("1:2,x")
    assert parse_steps("1.5:3,1:2") == ((1.5, 3.0), (1.0, 2.0))


def test_pier_steps_flag(capsys):
    code = main(["limit", "--radius", "5", "--embrace", "180", "--thickness", "0.8",
                 "--voussoirs", "9", "--pier-steps", "2:2,2:2", "--json"])
    out = json.loads(capsys.readouterr().out)
    assert code == 0 and out["k_l"] == pytest.approx(0.168899, abs=1e-6)
    code = main(["limit", "--radius", "5", "--embrace", "180", "--thickness", "0.8",
                 "--pier-height", "4", "--pier-steps", "2:2"])
    assert code != 0 and "--pier-height: given with --pier-steps" in capsys.readouterr().err


# ------------------------------------------------------------------------- the pier-tilt defect
def test_pier_tilt_defect(ref, capsys):
    """`pier-tilt=DEG[,side=...]`: parsed, written back, described, applied as lean_pier (to
    the bit), refused without piers and with an index; the flag applies it once the arch stands
    on its piers."""
    arch, ap, _ = ref
    d = Defect.parse("pier-tilt=2,side=right")
    assert (d.kind, d.index, d.value, d.side) == ("pier-tilt", 0, 2.0, "right")
    assert d.spec() == "pier-tilt=2,side=right"
    assert Defect.parse("pier-tilt=-1").spec() == "pier-tilt=-1"
    assert Defect.from_dict(d.to_dict()) == d
    assert "right pier out of plumb by 2 deg (outward" in d.describe()
    damaged = apply_defect(ap, d)
    assert _same_lines(damaged, lean_pier(ap, "right", 2.0))
    assert damaged.name.endswith("[pier-tilt=2,side=right]")
    with pytest.raises(ArchInputError, match="has no left pier"):
        apply_defect(arch, "pier-tilt=2")
    with pytest.raises(ArchInputError, match="allowed VOUSSOIR"):
        Defect.parse("3:pier-tilt=2")
    with pytest.raises(ArchInputError, match="-15 <= tilt <= 15"):
        Defect.parse("pier-tilt=15.5")
    code = main(["limit", "--radius", "5", "--embrace", "180", "--thickness", "0.8",
                 "--voussoirs", "9", "--pier-height", "4", "--pier-width", "2",
                 "--pier-courses", "2", "--defect", "pier-tilt=2,side=right"])
    out = capsys.readouterr().out
    assert code == 0 and "[pier-tilt=2,side=right]" in out and "0.1304" in out


# ------------------------------------------------------------------------- the sampler
SPREADS = Spreads(0.0, 0.1, 0.05)
IRREGULAR = Spreads(0.0, 0.1, 0.05, pier_lean=1.0, pier_width=0.1, pier_height=0.1,
                    pier_course=0.2)


def test_zero_pier_spreads_are_the_arches_on_piers_bit_for_bit(ref):
    """With the pier spreads 0 each sample is the surveyed arch's draw as before (the object
    path; the batch path's compiled lines to 1e-12 of the span: another path, which rounds
    differently by CPU), and the configuration's dict has no pier keys."""
    _, ap, _ = ref
    s = ArchSampler(ap, SPREADS, 3)
    u = s.uniforms(0, 2)
    plan = survey_plan(ap)
    for i, a in enumerate(s.arches(0, 2)):
        b = perturb_survey(ap, u[i], 0.1, 0.05)
        assert _same_lines(a, b)
        intr, extr = survey_lines(plan, u[i], SPREADS)
        for p, q in zip(a.intrados + a.extrados, intr + extr):
            np.testing.assert_allclose(q, p, rtol=0, atol=1e-12 * ap.size)
    assert set(SPREADS.legacy_dict()) == {"spread_span", "spread_thickness", "spread_radius"}
    assert not SPREADS.piers


def test_pier_spreads_draw_each_pier_from_its_own_stream(ref):
    """The voussoir draws are unchanged by the pier spreads; each pier reads its own row of a
    child stream (left and right differ); a tiny pier spread gives the plumb samples' k to
    1e-9 (the object path against the survey batch path); samples are ArchOnPiers whose k
    the static LP confirms."""
    _, ap, _ = ref
    s0, s1 = ArchSampler(ap, SPREADS, 0), ArchSampler(ap, IRREGULAR, 0)
    assert np.array_equal(s0.uniforms(0, 5), s1.uniforms(0, 5))
    pl, pr = s1.pier_uniforms(0, 5, "left"), s1.pier_uniforms(0, 5, "right")
    assert pl.shape == pr.shape == (5, 4) and not np.array_equal(pl, pr)
    assert np.array_equal(pl[3], s1.pier_uniforms(3, 1, "left")[0])  # sample i alone
    # one pier's draws do not depend on the other's courses
    other = ArchSampler(with_piers(ref[0], 4.0, 2.0, courses=2, courses_right=5), IRREGULAR, 0)
    assert np.array_equal(other.pier_uniforms(0, 5, "left"), pl)
    assert other.pier_uniforms(0, 5, "right").shape == (5, 7)
    tiny = ArchSampler(ap, Spreads(0.0, 0.1, 0.05, pier_width=1e-12), 0)
    for i in range(2):
        k0 = limit_analysis(s0.arch(i)).k_l
        assert limit_analysis(tiny.arch(i)).k_l == pytest.approx(k0, abs=1e-9)
        a = s1.arch(i)
        assert a.block_kinds == ap.block_kinds
        r = limit_analysis(a)
        assert r.discrepancy < 1e-8
        assert abs(r.k_l - k0) > 1e-4  # the piers were drawn


def test_pier_spreads_refused_by_name(ref, capsys):
    arch, ap, _ = ref
    with pytest.raises(ArchInputError, match=r"pier_lean: 16.0; allowed 0 <= pier_lean <= 15"):
        Spreads(pier_lean=16.0)
    with pytest.raises(ArchInputError, match=r"pier_course: 0.5; allowed 0 <= pier_course < 0.5"):
        Spreads(pier_course=0.5)
    with pytest.raises(ArchInputError, match="stands on no piers"):
        ArchSampler(arch, Spreads(0.1, 0.1, 0.05, pier_width=0.1))
    d = IRREGULAR.to_dict()
    assert d["pier_lean"] == 1.0 and Spreads.from_dict(d) == IRREGULAR
    code = main(["ensemble", "--radius", "5", "--embrace", "180", "--thickness", "0.8",
                 "--pier-height", "4", "--pier-width", "2", "--spread-span", "0",
                 "--spread-pier-width", "1.5", "--samples", "2", "--pulse", "oppenheim",
                 "--amplitude", "-0.3", "--pulse-duration", "0.2"])
    assert code != 0 and "--spread-pier-width: 1.5; allowed" in capsys.readouterr().err


def test_invalid_pier_draw_is_an_invalid_sample(ref):
    """A draw whose pier comes out narrower than its springing is an invalid sample (named),
    not an error of the study."""
    arch, _, _ = ref
    narrow = with_piers(arch, 4.0, 0.85, courses=2)  # the springing joint is 0.8 m wide
    s = ArchSampler(narrow, Spreads(0.0, 0.0, 0.0, pier_width=0.5), 0)
    out = s.arches(0, 8)
    bad = [a for a in out if isinstance(a, InvalidSampleError)]
    assert bad and all("narrower than its springing" in str(e) for e in bad)
    assert len(bad) < 8


def test_ensemble_configuration_keeps_the_pier_spreads(ref):
    """An ensemble's configuration writes the pier spreads under their field names and reads
    them back; without them its dict is as before."""
    from archrock.groundmotion import PulseSpec
    from archrock.studies.ensemble import EnsembleConfig

    _, ap, _ = ref
    cfg = EnsembleConfig.from_arch(ap, samples=3, spreads=IRREGULAR,
                                   motion=PulseSpec("oppenheim", -0.3, 0.2))
    d = cfg.to_dict()
    assert d["spreads"]["pier_course"] == 0.2 and d["spreads"]["pier_lean"] == 1.0
    back = EnsembleConfig.from_dict(d)
    assert back.spreads == IRREGULAR and back.to_json() == cfg.to_json()
    plain = EnsembleConfig.from_arch(ap, samples=3, spreads=SPREADS)
    assert not any(k.startswith("pier_") for k in plain.to_dict()["spreads"])
    assert isinstance(back.sampler.arch(1), type(ap))
