"""Impact laws: the paper's and the momentum c_v on Oppenheim's arch, energy bounds, the fixed
c_v in its energy and literal readings, the energy guard of the paper model, bad input."""

from __future__ import annotations

import math
import warnings

import pytest

from archrock import geometry
from archrock.statics import limit
from archrock.errors import ArchInputError, EnergyGainError, ImpactModelError
from archrock.dynamics.impact import (EnergyGainWarning, impact_law, momentum_rate_ratio,
                                      paper_rate_ratio)
from archrock.dynamics.fourlink import four_link


def _mechs(arch):
    lim = limit.limit_analysis(arch, verify=False)
    return four_link(arch, lim.mechanism_l), four_link(arch, lim.mechanism_r)


def _m0(fl):
    return fl.coefficients(0.0)[0]


@pytest.fixture(scope="module")
def opp(oppenheim):
    return oppenheim.left, oppenheim.right


@pytest.fixture(scope="module")
def randoms():
    return [_mechs(geometry.random_arch(seed=s)) for s in range(40)]


# ------------------------------------------------------------------------- the paper's figures
def test_paper_model_oppenheim(opp):
    law = impact_law(*opp, "paper")
    # the paper prints c_v = 0.8754: any value that rounds to it (the last digits of the five
    # equations' solution follow the numpy/LAPACK build)
    assert law.l_to_r == pytest.approx(0.8754, abs=5e-5)
    assert law.r_to_l == pytest.approx(0.8754, abs=5e-5)
    assert law.l_to_r == pytest.approx(law.r_to_l, rel=1e-12)
    # symmetric arch: M_l(0) = M_r(0), so the energy ratio is c^2 < 1
    assert law.energy_l_to_r == pytest.approx(law.l_to_r**2, rel=1e-12)
    assert law.energy_l_to_r < 1


def test_momentum_model_oppenheim(opp):
    law = impact_law(*opp, "momentum")
    # 0.64496 to the 4 decimals quoted beside the paper's 0.8754
    assert law.l_to_r == pytest.approx(0.6450, abs=5e-5)
    assert law.r_to_l == pytest.approx(0.6450, abs=5e-5)
    assert law.energy_r_to_l == pytest.approx(law.r_to_l**2, rel=1e-12)


def test_models_differ(opp):
    # a swap of the two models would not go unnoticed
    assert impact_law(*opp, "paper").l_to_r - impact_law(*opp, "momentum").l_to_r > 0.2


# ------------------------------------------------------------------------- momentum model
def test_momentum_never_creates_energy(randoms):
    ratios = []
    for ml, mr in randoms:
        law = impact_law(ml, mr, "momentum")
        assert 0 <= law.energy_l_to_r <= 1
        assert 0 <= law.energy_r_to_l <= 1
        # the projection is symmetric: both directions lose the same fraction of energy
        assert law.energy_l_to_r == pytest.approx(law.energy_r_to_l, rel=1e-10)
        # energy ratio from the rate ratio and the two M(0)
        assert law.energy_l_to_r == pytest.approx(law.l_to_r**2 * _m0(mr) / _m0(ml), rel=1e-12)
        ratios.append(law.energy_l_to_r)
    # the rate ratios themselves differ on irregular arches
    assert max(abs(impact_law(ml, mr, "momentum").l_to_r - impact_law(ml, mr, "momentum").r_to_l)
               for ml, mr in randoms) > 1e-3
    assert 0.2 < min(ratios) < max(ratios) < 0.8


def test_momentum_never_creates_energy_wide_spreads():
    for n in (5, 6, 8, 9):
        nominal = geometry.nominal_arch(voussoirs=n)
        for seed in range(15):
            arch = geometry.random_arch(nominal, seed=seed, spread_span=0.2,
                                        spread_thickness=0.2, spread_radius=0.1)
            ml, mr = _mechs(arch)
            e1 = momentum_rate_ratio(ml, mr) ** 2 * _m0(mr) / _m0(ml)
            e2 = momentum_rate_ratio(mr, ml) ** 2 * _m0(ml) / _m0(mr)
            assert e1 <= 1 and e2 <= 1
            assert e1 == pytest.approx(e2, rel=1e-10)


# ------------------------------------------------------------------------- fixed c_v
@pytest.mark.parametrize("cv", [0.5, 0.8754, 1.0])
def test_fixed_cv_energy_reading(randoms, cv):
    for ml, mr in randoms[:10]:
        with warnings.catch_warnings():
            warnings.simplefilter("error", EnergyGainWarning)
            law = impact_law(ml, mr, "fixed", cv=cv)
        assert law.energy_l_to_r == pytest.approx(cv**2, rel=1e-12)
        assert law.energy_r_to_l == pytest.approx(cv**2, rel=1e-12)
        assert law.l_to_r == pytest.approx(cv * math.sqrt(_m0(ml) / _m0(mr)), rel=1e-12)
        assert law.l_to_r * law.r_to_l == pytest.approx(cv**2, rel=1e-12)
        assert law.cv == cv and not law.literal


def test_fixed_cv_literal_reading(randoms):
    cv = 0.8754
    gained = 0
    for ml, mr in randoms[:10]:
        with warnings.catch_warnings(record=True) as rec:
            warnings.simplefilter("always")
            law = impact_law(ml, mr, "fixed", cv=cv, literal=True)
        assert law.l_to_r == cv and law.r_to_l == cv and law.literal
        assert law.energy_l_to_r == pytest.approx(cv**2 * _m0(mr) / _m0(ml), rel=1e-12)
        assert law.energy_r_to_l == pytest.approx(cv**2 * _m0(ml) / _m0(mr), rel=1e-12)
        gains = max(law.energy_l_to_r, law.energy_r_to_l) > 1
        warned = any(issubclass(w.category, EnergyGainWarning) for w in rec)
        assert warned == gains
        gained += gains
    assert gained >= 1  # the default spreads do produce literal energy gains


def test_fixed_cv_literal_warns_on_gain():
    # find an irregular arch with unequal M(0) where cv = 1 literally gains energy
    ml, mr = _mechs(geometry.random_arch(seed=0))
    assert not math.isclose(_m0(ml), _m0(mr), rel_tol=1e-3)
    with pytest.warns(EnergyGainWarning, match="gains kinetic energy"):
        impact_law(ml, mr, "fixed", cv=1.0, literal=True)


def test_fixed_cv_symmetric_readings_agree(opp):
    a = impact_law(*opp, "fixed", cv=0.7)
    b = impact_law(*opp, "fixed", cv=0.7, literal=True)
    assert a.l_to_r == pytest.approx(b.l_to_r, rel=1e-12)
    assert a.r_to_l == pytest.approx(0.7, rel=1e-12)


@pytest.mark.parametrize("cv", [-1e-12, -0.2, 1.0001, 2.0, float("nan"), float("inf"), None])
def test_fixed_cv_out_of_range(opp, cv):
    with pytest.raises(ArchInputError, match="cv"):
        impact_law(*opp, "fixed", cv=cv)


def test_unknown_model(opp):
    with pytest.raises(ArchInputError, match="impact model"):
        impact_law(*opp, "housner")


# ------------------------------------------------------------------------- the energy guard
# Found by a search over random arches with spreads 0.2/0.2/0.1 (n = 5): on these the paper
# model creates energy in one direction only (energy ratio l_to_r ~ 1.100, r_to_l ~ 1.061).
WIDE = dict(spread_span=0.2, spread_thickness=0.2, spread_radius=0.1)


def _wide(seed, n=5):
    return geometry.random_arch(geometry.nominal_arch(voussoirs=n), seed=seed, **WIDE)


@pytest.mark.parametrize("seed,direction,ratio", [(8, "l_to_r", 1.1002), (15, "r_to_l", 1.0612)])
def test_paper_energy_guard(seed, direction, ratio):
    ml, mr = _mechs(_wide(seed))
    c_lr, c_rl = paper_rate_ratio(ml, mr), paper_rate_ratio(mr, ml)
    e = {"l_to_r": c_lr**2 * _m0(mr) / _m0(ml), "r_to_l": c_rl**2 * _m0(ml) / _m0(mr)}
    assert e[direction] == pytest.approx(ratio, abs=1e-4)
    other = "r_to_l" if direction == "l_to_r" else "l_to_r"
    assert e[other] < 1
    with pytest.raises(EnergyGainError, match=f"impact {direction}") as info:
        impact_law(ml, mr, "paper")
    assert other not in str(info.value)
    assert isinstance(info.value, ImpactModelError) and not isinstance(info.value, ArchInputError)
    # the momentum model stays usable on the same arch
    law = impact_law(ml, mr, "momentum")
    assert law.energy_l_to_r <= 1 and law.energy_r_to_l <= 1


def test_paper_model_fine_on_method_spreads(randoms):
    # with the default spreads (0.1/0.1/0.05) the paper model loses energy on every arch tried
    for ml, mr in randoms:
        law = impact_law(ml, mr, "paper")
        assert 0 < law.energy_l_to_r < 1 and 0 < law.energy_r_to_l < 1
        # a rate ratio may exceed 1 where M_new(0) < M_old(0); the energy is what is bounded
        assert law.l_to_r > 0 and law.r_to_l > 0


def test_paper_model_gains_energy_often_on_wide_spreads():
    gains = 0
    for seed in range(20):
        ml, mr = _mechs(_wide(seed))
        try:
            impact_law(ml, mr, "paper")
        except EnergyGainError:
            gains += 1
    assert gains >= 3


def test_nominal_cv_is_one_rule_for_every_command():
    """The paper's c_v of a nominal arch is the rate ratio on a symmetric arch, and on an
    asymmetric one the c_v with the same mean kinetic-energy loss; curves, IDA and ensembles
    all use this one function (through the paper's-practice ImpactSpec)."""
    from archrock import geometry
    from archrock.dynamics.impact import PAPER_PRACTICE, nominal_cv
    from archrock.dynamics.response import prepare

    assert nominal_cv(geometry.oppenheim_arch()) == pytest.approx(0.8753811790524912, rel=1e-12)
    ra = geometry.random_arch(seed=5)
    law = prepare(ra, "paper").impact
    cv = nominal_cv(ra)
    assert cv == pytest.approx(((law.energy_l_to_r + law.energy_r_to_l) / 2) ** 0.5, rel=1e-12)
    assert law.energy_l_to_r != pytest.approx(law.energy_r_to_l, rel=1e-3)
    assert PAPER_PRACTICE.resolved(ra).cv == cv
    fixed = prepare(ra, cv).impact
    assert fixed.energy_l_to_r == pytest.approx(cv**2) and fixed.energy_r_to_l == pytest.approx(cv**2)


def test_least_loss_mechanism_oppenheim():
    """Beyond the paper (Bisegna et al. 2023): among all admissible mechanisms opening toward
    -x after M_l closes, the momentum law keeps the most energy with hinges 0e-2i-5e-7i (one
    hinge joint shared with M_l), 0.5567 of it, against 0.4160 for the limit mechanism M_r;
    the mirror impact picks the mirror mechanism."""
    from archrock import geometry
    from archrock.dynamics.impact import least_loss_mechanism
    from archrock.dynamics.response import prepare

    m = prepare(geometry.oppenheim_arch(), "momentum")
    lr = least_loss_mechanism(m.mech_l, m.mech_r)
    assert [(h.joint, h.edge[0]) for h in lr.mechanism.hinges] == [(0, "e"), (2, "i"), (5, "e"), (7, "i")]
    assert lr.energy_ratio == pytest.approx(0.5567, abs=1e-4)
    assert lr.limit_energy_ratio == pytest.approx(m.impact.energy_l_to_r, rel=1e-12)
    assert not lr.is_limit_mechanism and lr.candidates > 50
    rl = least_loss_mechanism(m.mech_r, m.mech_l)
    assert [(h.joint, h.edge[0]) for h in rl.mechanism.hinges] == [(0, "i"), (2, "e"), (5, "i"), (7, "e")]
    assert rl.energy_ratio == pytest.approx(lr.energy_ratio, rel=1e-9)


@pytest.mark.parametrize("seed", [3, 315])
def test_least_loss_never_below_the_limit_mechanism(seed):
    from archrock import geometry
    from archrock.dynamics.impact import least_loss_mechanism
    from archrock.dynamics.response import prepare

    m = prepare(geometry.random_arch(seed=seed), "momentum")
    for old, new in ((m.mech_l, m.mech_r), (m.mech_r, m.mech_l)):
        res = least_loss_mechanism(old, new)
        assert 0 < res.limit_energy_ratio <= res.energy_ratio <= 1.0


# ----------------------------------------------------------------------------- ImpactSpec
def test_impact_spec_round_trips_and_parses_every_spelling():
    from archrock.dynamics.impact import PAPER_PRACTICE, ImpactSpec

    for spec in (ImpactSpec(), PAPER_PRACTICE, ImpactSpec("momentum"), ImpactSpec.fixed(0.8),
                 ImpactSpec.fixed(0.7, literal=True), ImpactSpec("least-loss"),
                 ImpactSpec("momentum", on="nominal", literal=True),
                 ImpactSpec("paper", on="nominal"), ImpactSpec("paper", fallback="momentum"),
                 ImpactSpec("fixed", cv=0.6, note="why")):
        assert ImpactSpec.from_dict(spec.to_dict()) == spec
    assert ImpactSpec.parse(None) == PAPER_PRACTICE
    # 0.1.0's ensemble spelling is the paper model on the nominal arch, written out: no fallback
    assert ImpactSpec.parse("nominal-paper") == ImpactSpec("paper", on="nominal")
    assert ImpactSpec.parse("momentum") == ImpactSpec("momentum", on="arch")
    assert ImpactSpec.parse(0.8) == ImpactSpec.parse("fixed", cv=0.8) == ImpactSpec.parse(None, cv=0.8)
    assert ImpactSpec.parse(0.8, literal=True).literal
    assert ImpactSpec.parse(None, literal=True) == ImpactSpec("paper", literal=True, on="nominal",
                                                              fallback="momentum")


def test_impact_spec_dicts_of_0_4_read_as_before():
    """The default's dict is 0.4's (manifests of default runs resume); the written-out paper
    model on the nominal arch says it has no fallback; a 0.4 dict without one is the default."""
    from archrock.dynamics.impact import PAPER_PRACTICE, ImpactSpec

    old = {"model": "paper", "cv": None, "literal": False, "on": "nominal"}
    assert PAPER_PRACTICE.to_dict() == old
    assert ImpactSpec.from_dict(old) == PAPER_PRACTICE
    assert ImpactSpec("paper", on="nominal").to_dict() == {**old, "fallback": None}
    assert ImpactSpec("paper").to_dict() == {**old, "on": "arch"}
    assert "fallback" in ImpactSpec("paper", fallback="momentum").to_dict()


@pytest.mark.parametrize("kwargs, field", [
    (dict(model="elastic"), "impact model"),
    (dict(model="fixed"), "cv"),
    (dict(model="fixed", cv=1.5), "cv"),
    (dict(model="fixed", cv=float("nan")), "cv"),
    (dict(model="paper", cv=0.5), "cv"),
    (dict(model="least-loss", on="nominal"), "impact on"),
    (dict(model="momentum", literal=True), "literal"),
    (dict(model="paper", on="crown"), "impact on"),
    (dict(model="momentum", fallback="momentum"), "fallback"),
    (dict(model="paper", fallback="least-loss"), "fallback"),
    (dict(model="paper", note="why"), "note"),
])
def test_impact_spec_refuses_bad_fields(kwargs, field):
    from archrock.dynamics.impact import ImpactSpec

    with pytest.raises(ArchInputError, match=f"^{field}:"):
        ImpactSpec(**kwargs)


def test_impact_spec_on_nominal_is_the_papers_practice():
    """on='nominal': the model's c_v on the nominal arch, fixed (energy-consistently) on every
    arch; the nominal arch itself, prepared alone, keeps the model's own law."""
    from archrock.dynamics.impact import PAPER_PRACTICE, ImpactSpec
    from archrock.dynamics.response import prepare

    nominal = geometry.oppenheim_arch()
    ra = geometry.random_arch(seed=315)
    resolved = PAPER_PRACTICE.resolved(nominal)
    # c_v is a computed number (five equations through LAPACK): its last digit follows the
    # numpy/scipy build, so it is compared to 1e-12 (the paper's 0.8754 is good to 5e-5)
    assert resolved.model == "fixed" and resolved.on == "arch" and not resolved.literal
    assert resolved.cv == pytest.approx(0.8753811790524885, rel=1e-12)
    model = prepare(ra, PAPER_PRACTICE, nominal=nominal)
    assert model.impact.model == "fixed"
    assert model.impact.energy_l_to_r == pytest.approx(0.8753811790524885**2, rel=1e-12)
    assert model.impact.energy_r_to_l == pytest.approx(0.8753811790524885**2, rel=1e-12)
    alone = prepare(ra, PAPER_PRACTICE)            # one arch: its own nominal arch
    assert alone.impact == prepare(ra, "paper").impact
    mom = prepare(ra, ImpactSpec("momentum", on="nominal"), nominal=nominal).impact
    assert mom.energy_l_to_r == pytest.approx(prepare(nominal, "momentum").impact.energy_l_to_r)
    assert ImpactSpec.fixed(0.5).resolved(nominal) == ImpactSpec.fixed(0.5)
    with pytest.raises(ArchInputError, match="^impact model"):
        ImpactSpec.parse("bogus")


# ----------------------------------------------------------------------------- the fallback
@pytest.fixture(scope="module")
def semicircle17():
    """A 17-voussoir semicircle (R = 5 m, t = 0.9 m: span 10, rise 5 of the centreline) that
    stands (k = 0.2326) and on which the paper model creates energy (ratio 1.3035 l_to_r)."""
    return geometry.nominal_arch(radius=5.0, embrace_deg=180.0, thickness=0.9, voussoirs=17)


def test_default_falls_back_to_momentum_where_paper_creates_energy(semicircle17):
    from archrock.dynamics.impact import PAPER_PRACTICE, ImpactSpec
    from archrock.dynamics.response import prepare

    law = prepare(semicircle17).impact                 # the default: one arch, its own nominal
    assert law.model == "momentum"
    assert "creates energy" in law.fallback and "kinetic energy ratio 1.3035" in law.fallback
    assert law.fallback.endswith("momentum law used")
    # it is the momentum law of that arch, the same call: bit for bit
    mom = prepare(semicircle17, "momentum").impact
    assert (law.l_to_r, law.r_to_l, law.energy_l_to_r) == (mom.l_to_r, mom.r_to_l,
                                                          mom.energy_l_to_r)
    assert mom.fallback is None and max(law.energy_l_to_r, law.energy_r_to_l) < 1
    assert prepare(semicircle17, PAPER_PRACTICE).impact == law
    assert law.to_dict()["fallback"] == law.fallback


@pytest.mark.parametrize("spec", ["paper", "nominal-paper"])
def test_paper_given_by_name_still_refuses(semicircle17, spec):
    from archrock.dynamics.impact import ImpactSpec
    from archrock.dynamics.response import prepare

    with pytest.raises(EnergyGainError, match="creates energy.*use the momentum law"):
        prepare(semicircle17, spec)                   # the arch alone
    with pytest.raises(EnergyGainError, match="creates energy"):
        # a study around it: the spec resolved on it as the nominal arch
        prepare(semicircle17, ImpactSpec.parse(spec), nominal=semicircle17)


def test_default_on_a_nominal_arch_that_falls_back(semicircle17):
    """Studies: the default fixes the momentum law's c_v of such a nominal arch on every arch,
    and the resolved spec and every arch's law say why."""
    from archrock.dynamics.impact import PAPER_PRACTICE, nominal_cv
    from archrock.dynamics.response import prepare

    resolved = PAPER_PRACTICE.resolved(semicircle17)
    assert resolved.model == "fixed"
    assert resolved.cv == nominal_cv(semicircle17, "momentum")
    assert resolved.note.startswith("on the nominal arch, ") and "creates energy" in resolved.note
    assert resolved.note in resolved.describe() and resolved.to_dict()["note"] == resolved.note
    ra = geometry.random_arch(semicircle17, seed=1)
    law = prepare(ra, PAPER_PRACTICE, nominal=semicircle17).impact
    assert law.model == "fixed" and law.cv == resolved.cv and law.fallback == resolved.note


def test_fallback_leaves_usable_arches_alone(opp):
    """Where the paper model can be used the fallback changes nothing: the same law, bit for
    bit, and no note (Oppenheim's c_v 0.87538, momentum 0.64496)."""
    from archrock.dynamics.impact import PAPER_PRACTICE, nominal_cv
    from archrock.dynamics.response import prepare

    law = impact_law(*opp, "paper", fallback="momentum")
    assert law == impact_law(*opp, "paper") and law.fallback is None
    assert "fallback" not in law.to_dict()
    default = prepare(geometry.oppenheim_arch()).impact
    assert default == law
    # five linear equations through LAPACK: the last digits follow the build, so 1e-12
    assert default.l_to_r == pytest.approx(0.8753811790524912, rel=1e-12)
    assert PAPER_PRACTICE.resolved(geometry.oppenheim_arch()).note is None
    assert nominal_cv(geometry.oppenheim_arch(), "momentum") == pytest.approx(0.64496, abs=5e-6)


def test_fixed_cv_zero_is_a_law_that_stops_the_arch():
    """The momentum law keeps nothing on some arches (R = 10 m, 90 deg, t = 1.5 m: M_l and M_r
    are orthogonal in the mass metric), so the default's nominal c_v there is 0: a fixed c_v
    of 0 is a law (the first impact stops the arch), not an input error; below 0 or above 1 is."""
    from archrock.geometry import nominal_arch
    from archrock.dynamics.impact import PAPER_PRACTICE, ImpactSpec
    from archrock.dynamics.response import prepare, respond
    from archrock.groundmotion import oppenheim_pulse

    flat = nominal_arch(10.0, 90.0, 1.5, 7)
    assert prepare(flat, "momentum").impact.l_to_r == pytest.approx(0.0, abs=1e-12)
    spec = PAPER_PRACTICE.resolved(flat)
    assert spec.model == "fixed" and spec.cv == pytest.approx(0.0, abs=1e-12)
    res = respond(geometry.oppenheim_arch(), oppenheim_pulse(-1.0, 0.2), impact=ImpactSpec.fixed(0.0))
    assert res.status == "rest" and len(res.impacts) == 1
    for bad in (-0.1, 1.1):
        with pytest.raises(ArchInputError, match=r"cv: .*allowed 0 <= cv <= 1"):
            ImpactSpec.fixed(bad)
