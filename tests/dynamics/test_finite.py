"""The four-link model with a finite compressive strength (dynamics.finite): hinges half a
stress block in from the edges at the statics' collapse forces, so that the model's own virtual
work at rest gives the statics' multiplier; infinite strength leaves every number as it was."""

import numpy as np
import pytest

from archrock.dynamics.batch import prepare_batch
from archrock.dynamics.finite import collapse_zones, inset_joint_points
from archrock.dynamics.fourlink import four_link
from archrock.dynamics.response import prepare, respond
from archrock.errors import ArchInputError
from archrock.geometry import family_arch, oppenheim_arch
from archrock.groundmotion import oppenheim_pulse
from archrock.statics.limit import limit_analysis


def _flat():
    """The flat bridge arch of issue 34: span 10 m, rise 1.5 m, t = 0.5 m, 15 voussoirs."""
    return family_arch("circular", 10.0, 1.5, 0.5, 15, exact=False)


def test_inset_moves_each_hinge_half_its_zone_along_the_joint():
    arch = oppenheim_arch()
    lim = limit_analysis(arch, verify=False)
    zones = np.full(arch.n + 1, 0.2)
    pts = inset_joint_points(arch, lim.mechanism_l, zones)
    jp = np.asarray(arch.joint_points, float)
    hinge = {(h.joint, h.edge) for h in lim.mechanism_l.hinges}
    for j in range(arch.n + 1):
        for e, edge in enumerate(("intrados", "extrados")):
            moved = np.hypot(*(pts[j, e] - jp[j, e]))
            assert moved == pytest.approx(0.1 if (j, edge) in hinge else 0.0, abs=1e-12)
            # along the joint: still on the segment between its ends
            t = np.hypot(*(jp[j, 1] - jp[j, 0]))
            far = np.hypot(*(pts[j, e] - jp[j, 1 - e]))
            assert far == pytest.approx(t - moved, abs=1e-12)
    with pytest.raises(ArchInputError, match=r"^zones\[0\]: 2 m; allowed below"):
        inset_joint_points(arch, lim.mechanism_l, np.full(arch.n + 1, 2.0))


def test_infinite_strength_keeps_the_edge_hinges_bit_for_bit():
    arch = oppenheim_arch()
    lim = limit_analysis(arch, verify=False)
    assert collapse_zones(lim, "l") is None
    model = prepare(arch, limit=lim)
    assert np.array_equal(model.mech_l.geo, four_link(arch, lim.mechanism_l).geo)
    assert np.array_equal(model.mech_r.geo, four_link(arch, lim.mechanism_r).geo)


@pytest.mark.parametrize("make", [oppenheim_arch, _flat], ids=["oppenheim", "flat"])
@pytest.mark.parametrize("fc", [2.0, 5.0, 10.0])
def test_inset_four_link_has_the_statics_multiplier(make, fc):
    """F(0)/P(0) of the model on the inset hinges is its virtual work at rest: it must be the
    finite-strength k of the statics (and below Heyman's)."""
    arch = make().with_fc(fc)
    model = prepare(arch)
    assert -model.mech_l.static_multiplier() == pytest.approx(model.k_l, rel=1e-9)
    assert model.mech_r.static_multiplier() == pytest.approx(model.k_r, rel=1e-9)
    heyman = prepare(make())
    assert model.k_l < heyman.k_l and model.phi_unstable_l < heyman.phi_unstable_l


def test_crushing_makes_oppenheims_arch_collapse_under_the_papers_pulse():
    pulse = oppenheim_pulse(-1.0, 0.2)
    rest = respond(prepare(oppenheim_arch()), pulse)
    weak = respond(prepare(oppenheim_arch().with_fc(2.0)), pulse)
    assert rest.status == "rest" and weak.status == "collapsed"
    assert 0.03 < rest.peak < 0.045


def test_the_batch_of_arches_of_finite_strength_is_prepares():
    arches = [oppenheim_arch().with_fc(fc) for fc in (2.0, 5.0)]
    pb = prepare_batch(arches, impact="momentum")
    for b, arch in enumerate(arches):
        model = prepare(arch, "momentum")
        assert pb.k_l[b] == pytest.approx(model.k_l, rel=0, abs=0)
        assert np.array_equal(pb.geo_l[b], model.mech_l.geo)
        assert pb.c_l_to_r[b] == pytest.approx(model.impact.l_to_r, rel=0, abs=0)
    assert pb.ok.all()


def test_a_finite_strength_without_zones_is_refused():
    arch = oppenheim_arch().with_fc(5.0)
    lim = limit_analysis(arch, verify=False)
    bare = type(lim)(**{**{f: getattr(lim, f) for f in lim.__dataclass_fields__},
                        "zones_l": None})
    with pytest.raises(ArchInputError, match=r"^limit: .*f_c = 5 MPa gives no compressed zones "
                                             r"for M_l"):
        collapse_zones(bare, "l")
