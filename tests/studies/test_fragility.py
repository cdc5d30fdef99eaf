"""Fragility statistics: estimators against known values and independent computations."""

import json
import math

import numpy as np
import pytest
from hypothesis import assume, given, settings, strategies as st
from scipy.optimize import minimize
from scipy.stats import beta as beta_dist, binom, binomtest, norm

from archrock.errors import ArchInputError, ArchrockError, FitError

#: malformed data is an input error; data from which no fit can be identified a FitError
BAD_OR_UNIDENTIFIABLE = (ArchInputError, FitError)
from archrock.studies.fragility import (FragilityFit, bootstrap_fit, collapse_probability,
                                        fit_ida_moments, fit_stripes_mle, first_collapse)

THETA, BETA = 0.4, 0.3


def synthetic_stripes(theta=THETA, beta=BETA, trials=2000, levels=10, seed=1):
    rng = np.random.default_rng(seed)
    x = np.geomspace(0.15, 1.0, levels)
    n = np.full(levels, trials)
    z = rng.binomial(n, norm.cdf(np.log(x / theta) / beta))
    return x, n, z


# ----------------------------------------------------------------------------- FragilityFit

def test_probability_and_quantile_are_inverse():
    f = FragilityFit(theta=0.4, beta=0.3, method="mle", n_records=10)
    assert f.probability(0.4) == pytest.approx(0.5, abs=1e-15)
    assert f.quantile(0.5) == pytest.approx(0.4, rel=1e-15)
    # one beta above the median is Phi(1)
    assert f.probability(0.4 * math.exp(0.3)) == pytest.approx(norm.cdf(1.0), rel=1e-14)
    p = np.array([0.01, 0.16, 0.5, 0.84, 0.99])
    np.testing.assert_allclose(f.probability(f.quantile(p)), p, rtol=1e-12)
    assert f.probability([0.0, np.inf]).tolist() == [0.0, 1.0]
    assert f.quantile([0.0, 1.0]).tolist() == [0.0, np.inf]


@settings(max_examples=40, deadline=None)
@given(theta=st.floats(1e-3, 1e3), beta=st.floats(0.01, 2.0), x=st.floats(1e-4, 1e4))
def test_quantile_inverts_probability_property(theta, beta, x):
    f = FragilityFit(theta=theta, beta=beta, method="moments", n_records=2)
    p = float(f.probability(x))
    # away from saturation the inverse is well conditioned: near p = 1 the spacing of doubles
    # (1e-16) is a relative error of 1e-16 / (1 - p) on the tail that the quantile inherits.
    # assume, not if: a saturated draw is discarded and another drawn, so every one of the
    # examples checks the inverse (hypothesis fails the test if too few are left)
    assume(1e-9 < p < 1 - 1e-9)
    assert float(f.quantile(p)) == pytest.approx(x, rel=1e-6)


def test_to_dict_is_json_serialisable():
    f = FragilityFit(0.4, 0.3, "mle", 20, -3.0, (0.35, 0.45), (0.2, 0.4), 0.9, 100, 1)
    d = f.to_dict()
    assert d["theta"] == 0.4 and d["method"] == "mle" and d["theta_ci"] == (0.35, 0.45)
    assert json.loads(json.dumps(d))["beta_ci"] == [0.2, 0.4]
    with pytest.raises(Exception):
        f.theta = 1.0  # frozen


@pytest.mark.parametrize("kwargs, field", [
    (dict(theta=0.0, beta=0.3, method="mle"), "theta"),
    (dict(theta=0.4, beta=-0.1, method="mle"), "beta"),
    (dict(theta=0.4, beta=float("nan"), method="mle"), "beta"),
    (dict(theta=0.4, beta=0.3, method="least_squares"), "method"),
])
def test_fit_rejects_bad_parameters(kwargs, field):
    with pytest.raises(ArchInputError, match=rf"^{field}:"):
        FragilityFit(n_records=1, **kwargs)


def test_probability_quantile_reject_bad_arguments():
    f = FragilityFit(0.4, 0.3, "mle", 10)
    with pytest.raises(ArchInputError, match=r"^x:"):
        f.probability([-0.1, 0.2])
    with pytest.raises(ArchInputError, match=r"^x:"):
        f.probability(np.nan)
    with pytest.raises(ArchInputError, match=r"^p:"):
        f.quantile(1.5)


# ----------------------------------------------------------------------------- IDA moments

def test_moments_on_hand_made_sample():
    x = [0.2, 0.3, 0.45, 0.5, 0.8]
    f = fit_ida_moments(x)
    lnx = np.log(x)
    # mean of logs and ddof=1 std computed by hand
    m = sum(lnx) / 5
    s = math.sqrt(sum((v - m) ** 2 for v in lnx) / 4)
    assert f.theta == pytest.approx(math.exp(m), rel=1e-14)
    assert f.theta == pytest.approx((0.2 * 0.3 * 0.45 * 0.5 * 0.8) ** 0.2, rel=1e-14)  # geometric mean
    assert f.beta == pytest.approx(s, rel=1e-14)
    assert f.method == "moments" and f.n_records == 5 and f.theta_ci is None
    assert f.log_likelihood == pytest.approx(np.sum(norm.logpdf(lnx, m, s)), rel=1e-12)


def test_ida_survivors_raise_by_default():
    with pytest.raises(FitError, match=r"^collapse_intensities: 1 of 4 records never collapsed"):
        fit_ida_moments([0.3, 0.4, np.inf, 0.5])
    with pytest.raises(FitError, match=r"^collapse_intensities:"):
        fit_ida_moments([0.3, np.nan, 0.5])


def test_censored_mle_without_survivors_is_normal_mle():
    x = np.array([0.2, 0.3, 0.45, 0.5, 0.8])
    f = fit_ida_moments(x, censored="mle")
    lnx = np.log(x)
    assert f.method == "censored_mle"
    assert f.theta == pytest.approx(math.exp(lnx.mean()), rel=1e-7)
    assert f.beta == pytest.approx(lnx.std(ddof=0), rel=1e-7)


def test_censored_mle_recovers_truth_and_matches_direct_optimisation():
    rng = np.random.default_rng(3)
    x = np.exp(rng.normal(math.log(0.5), 0.4, 2000))
    x_max = 0.8
    x[x > x_max] = np.inf  # ~12 % of the records never collapsed up to the largest scale analysed
    f = fit_ida_moments(x, censored="mle", max_intensity=x_max)
    assert f.theta == pytest.approx(0.5, rel=0.03)
    assert f.beta == pytest.approx(0.4, rel=0.05)
    # naive moments on the collapsed records alone are biased low -- the reason for censoring
    assert math.exp(np.log(x[np.isfinite(x)]).mean()) < 0.95 * f.theta

    fin = np.log(x[np.isfinite(x)])
    ns = int(np.sum(~np.isfinite(x)))

    def nll(p):
        return -(norm.logpdf(fin, p[0], p[1]).sum() + ns * norm.logsf(math.log(x_max), p[0], p[1]))
    ref = minimize(nll, [0.0, 1.0], method="Nelder-Mead", options={"xatol": 1e-10, "fatol": 1e-10})
    assert math.log(f.theta) == pytest.approx(ref.x[0], abs=1e-6)
    assert f.beta == pytest.approx(ref.x[1], rel=1e-6)
    assert f.log_likelihood == pytest.approx(-ref.fun, rel=1e-9)


def test_censored_mle_per_record_max_intensity():
    x = [0.3, 0.4, 0.5, np.inf, 0.6, np.inf]
    m = [1, 1, 1, 0.9, 1, 1.2]
    f = fit_ida_moments(x, censored="mle", max_intensity=m)
    g = fit_ida_moments(x, censored="mle", max_intensity=1.2)
    assert f.theta < g.theta  # a survivor with a lower censoring point is weaker evidence


@pytest.mark.parametrize("x, kwargs, field", [
    ([0.3, -0.4, 0.5], {}, "collapse_intensities"),
    ([0.3, 0.0, 0.5], {}, "collapse_intensities"),
    ([0.3, -np.inf, 0.5], {}, "collapse_intensities"),
    ([0.3], {}, "collapse_intensities"),
    ([0.3, 0.3, 0.3], {}, "collapse_intensities"),
    ([], {}, "collapse_intensities"),
    ([[0.3, 0.4]], {}, "collapse_intensities"),
    (["a", "b"], {}, "collapse_intensities"),
    ([0.3, 0.4], dict(censored="drop"), "censored"),
    ([0.3, 0.4, np.inf], dict(censored="mle"), "max_intensity"),
    ([0.3, 0.4, np.inf], dict(censored="mle", max_intensity=[1, 2]), "max_intensity"),
    ([0.3, 0.4, np.inf], dict(censored="mle", max_intensity=-1), "max_intensity"),
    ([0.3, np.inf, np.inf], dict(censored="mle", max_intensity=1), "collapse_intensities"),
])
def test_ida_bad_input(x, kwargs, field):
    with pytest.raises(BAD_OR_UNIDENTIFIABLE, match=rf"^{field}:"):
        fit_ida_moments(x, **kwargs)


# ----------------------------------------------------------------------------- stripes MLE

def test_stripes_mle_recovers_known_parameters():
    x, n, z = synthetic_stripes()
    f = fit_stripes_mle(x, n, z)
    assert f.method == "mle" and f.n_records == 20000
    assert f.theta == pytest.approx(THETA, rel=0.02)
    assert f.beta == pytest.approx(BETA, rel=0.03)
    # the reported log-likelihood is Baker's sum of ln binomial pmf, constants included
    p = f.probability(x)
    assert f.log_likelihood == pytest.approx(binom.logpmf(z, n, p).sum(), rel=1e-10)


def test_stripes_mle_matches_independent_probit_fit():
    # small design with all-0 and all-1 stripes; independent fit in (a, b) = (-ln theta/beta, 1/beta)
    x = np.array([0.1, 0.2, 0.3, 0.4, 0.6, 0.9])
    n = np.array([10, 12, 10, 8, 10, 5])
    z = np.array([0, 1, 4, 5, 9, 5])
    f = fit_stripes_mle(x, n, z)

    def nll(ab):
        return -binom.logpmf(z, n, norm.cdf(ab[0] + ab[1] * np.log(x))).sum()
    ref = minimize(nll, [1.0, 1.0], method="Nelder-Mead", options={"xatol": 1e-10, "fatol": 1e-12})
    assert f.beta == pytest.approx(1 / ref.x[1], rel=1e-5)
    assert f.theta == pytest.approx(math.exp(-ref.x[0] / ref.x[1]), rel=1e-5)
    assert f.log_likelihood == pytest.approx(-ref.fun, abs=1e-8)
    # and it is a maximum: moving theta or beta lowers the likelihood
    for t, b in [(1.02, 1), (0.98, 1), (1, 1.02), (1, 0.98)]:
        p = norm.cdf(np.log(x / (f.theta * t)) / (f.beta * b))
        assert binom.logpmf(z, n, p).sum() < f.log_likelihood


def test_stripes_pooled_duplicate_levels_give_same_fit():
    x, n, z = np.array([0.2, 0.3, 0.5]), np.array([10, 10, 10]), np.array([1, 5, 8])
    f = fit_stripes_mle(x, n, z)
    g = fit_stripes_mle([0.2, 0.3, 0.3, 0.5], [10, 4, 6, 10], [1, 2, 3, 8])
    assert g.theta == pytest.approx(f.theta, rel=1e-7) and g.beta == pytest.approx(f.beta, rel=1e-6)


@pytest.mark.parametrize("x, n, z, field, text", [
    ([0.2, 0.4], [10, 10], [0, 0], "collapses", "no collapse"),
    ([0.2, 0.4], [10, 10], [10, 10], "collapses", "every trial collapsed"),
    ([0.3, 0.3], [10, 10], [4, 6], "intensities", "2 distinct"),
    ([0.2, 0.3, 0.4], [10, 10, 10], [0, 4, 10], "collapses", "separated"),
    ([0.2, 0.4], [10, 10], [0, 10], "collapses", "separated"),
    ([0.2, 0.4], [10, 10], [7, 3], "collapses", "does not increase"),
    ([0.2, 0.3, 0.4], [10, 10, 10], [5, 5, 5], "collapses", "does not increase"),
    ([0.2, -0.4], [10, 10], [1, 5], "intensities", "> 0 and finite"),
    ([0.2, np.nan], [10, 10], [1, 5], "intensities", "> 0 and finite"),
    ([0.2, np.inf], [10, 10], [1, 5], "intensities", "> 0 and finite"),
    ([0.2, 0.4], [10, 0], [1, 0], "trials", ">= 1"),
    ([0.2, 0.4], [10, 9.5], [1, 5], "trials", ">= 1"),
    ([0.2, 0.4], [10, 10], [1, 11], "collapses", "between 0 and trials"),
    ([0.2, 0.4], [10, 10], [-1, 5], "collapses", "between 0 and trials"),
    ([0.2, 0.4], [10, 10], [1.5, 5], "collapses", "between 0 and trials"),
    ([0.2, 0.4, 0.5], [10, 10], [1, 5], "trials", "same length"),
    ([], [], [], "intensities", "non-empty"),
])
def test_stripes_bad_or_unidentifiable_input(x, n, z, field, text):
    with pytest.raises(BAD_OR_UNIDENTIFIABLE, match=rf"^{field}:.*{text}"):
        fit_stripes_mle(x, n, z)


# ----------------------------------------------------------------------------- bootstrap

def test_bootstrap_ida_contains_truth_and_is_reproducible():
    rng = np.random.default_rng(1)
    x = np.exp(rng.normal(math.log(0.5), 0.4, 40))
    f = bootstrap_fit(fit_ida_moments, x, n_boot=300, confidence=0.9, seed=11)
    assert f.theta_ci[0] < 0.5 < f.theta_ci[1]
    assert f.beta_ci[0] < 0.4 < f.beta_ci[1]
    assert f.theta_ci[0] < f.theta < f.theta_ci[1]
    assert (f.confidence, f.n_boot, f.n_boot_failed) == (0.9, 300, 0)
    # point estimate is the fit of the original data
    base = fit_ida_moments(x)
    assert (f.theta, f.beta) == (base.theta, base.beta)
    assert bootstrap_fit(fit_ida_moments, x, n_boot=300, confidence=0.9, seed=11) == f
    other = bootstrap_fit(fit_ida_moments, x, n_boot=300, confidence=0.9, seed=12)
    assert other.theta_ci != f.theta_ci
    # CI width ~ 2 * 1.645 * beta/sqrt(n) in ln theta
    width = math.log(f.theta_ci[1] / f.theta_ci[0])
    assert width == pytest.approx(2 * 1.645 * base.beta / math.sqrt(40), rel=0.25)


def test_bootstrap_ida_coverage_is_near_nominal():
    # a 90 % interval must miss the truth about 1 time in 10 over repeated samples (n = 40);
    # the percentile bootstrap under-covers slightly at this size
    covered = 0
    for s in range(60):
        x = np.exp(np.random.default_rng(100 + s).normal(math.log(0.5), 0.4, 40))
        f = bootstrap_fit(fit_ida_moments, x, n_boot=100, confidence=0.9, seed=s)
        covered += f.theta_ci[0] < 0.5 < f.theta_ci[1]
    assert 45 <= covered <= 59


def test_bootstrap_stripes_contains_truth_and_is_reproducible():
    x, n, z = synthetic_stripes(trials=50, seed=5)
    f = bootstrap_fit(fit_stripes_mle, x, n, z, n_boot=60, seed=0)
    assert f.theta_ci[0] < THETA < f.theta_ci[1]
    assert f.beta_ci[0] < BETA < f.beta_ci[1]
    assert f.method == "mle" and f.confidence == 0.9
    assert bootstrap_fit(fit_stripes_mle, x, n, z, n_boot=60, seed=0) == f
    seq = np.random.SeedSequence(0)
    assert bootstrap_fit(fit_stripes_mle, x, n, z, n_boot=60, seed=seq).theta_ci == f.theta_ci


def test_bootstrap_censored_ida_keeps_each_records_max_intensity():
    x = [0.3, 0.35, 0.4, np.inf, 0.5, 0.55, np.inf, 0.45]
    m = [1.0, 1.0, 1.0, 0.7, 1.0, 1.0, 0.9, 1.0]
    f = bootstrap_fit(fit_ida_moments, x, censored="mle", max_intensity=m, n_boot=50, seed=1)
    assert f.method == "censored_mle" and f.theta_ci[0] < f.theta < f.theta_ci[1]


def test_bootstrap_reports_and_rejects_unidentifiable_resamples():
    # 2 collapses in 9 analyses: some resamples are separated or have no collapse -> counted
    f = bootstrap_fit(fit_stripes_mle, [0.2, 0.3, 0.4], [3, 3, 3], [0, 1, 1], n_boot=50, seed=0)
    assert 0 < f.n_boot_failed < 25 and f.n_boot == 50
    # 1 of 30 vs 2 of 30: most resamples lose the lower collapse or the trend -> refuse
    with pytest.raises(FitError, match=r"^data: \d+ of 50 bootstrap resamples"):
        bootstrap_fit(fit_stripes_mle, [0.2, 0.3], [30, 30], [1, 2], n_boot=50, seed=0)


@pytest.mark.parametrize("args, kwargs, field", [
    ((np.mean, [0.1, 0.2]), {}, "fit_function"),
    ((fit_ida_moments, [0.1, 0.2, 0.3]), dict(n_boot=1), "n_boot"),
    ((fit_ida_moments, [0.1, 0.2, 0.3]), dict(n_boot=10.5), "n_boot"),
    ((fit_ida_moments, [0.1, 0.2, 0.3]), dict(confidence=1.0), "confidence"),
    ((fit_ida_moments, [0.1, 0.2, 0.3]), dict(confidence=0), "confidence"),
    ((fit_ida_moments, [0.1, np.inf, 0.3]), {}, "collapse_intensities"),
    ((fit_stripes_mle, [0.2, 0.4], [10, 10]), {}, "data"),
])
def test_bootstrap_bad_input(args, kwargs, field):
    with pytest.raises(BAD_OR_UNIDENTIFIABLE, match=rf"^{field}:"):
        bootstrap_fit(*args, **kwargs)


# ----------------------------------------------------------------------------- one stripe

@pytest.mark.parametrize("k, n", [(0, 10), (5, 10), (10, 10), (1, 7), (37, 100)])
@pytest.mark.parametrize("conf", [0.9, 0.95])
def test_collapse_probability_matches_scipy(k, n, conf):
    p, lo, hi = collapse_probability(k, n, conf)
    ci = binomtest(k, n).proportion_ci(conf, method="wilson")
    assert p == k / n
    assert (lo, hi) == pytest.approx((ci.low, ci.high), abs=1e-12)
    p, lo, hi = collapse_probability(k, n, conf, method="clopper-pearson")
    ci = binomtest(k, n).proportion_ci(conf, method="exact")
    assert (lo, hi) == pytest.approx((ci.low, ci.high), abs=1e-9)


@pytest.mark.parametrize("k, n", [(0, 10), (5, 10), (10, 10), (1, 7), (37, 100), (2, 17),
                                  (333, 1000), (9999, 10000)])
@pytest.mark.parametrize("conf", [0.5, 0.9, 0.95, 0.99])
def test_collapse_probability_matches_closed_forms(k, n, conf):
    # the intervals come from scipy; this holds them against formulas written out here, so
    # that a change of variant (e.g. Wilson with continuity correction) is caught
    z = norm.ppf(0.5 + conf / 2)
    p = k / n
    d = 1 + z * z / n
    centre = (p + z * z / (2 * n)) / d
    half = z / d * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n))
    _, lo, hi = collapse_probability(k, n, conf)
    # scipy's Wilson arithmetic differs from this one in the last bit (seen: 2.2e-16)
    assert (lo, hi) == pytest.approx((max(centre - half, 0.0), min(centre + half, 1.0)),
                                     abs=1e-12)
    a = 1 - conf
    cp_lo = beta_dist.ppf(a / 2, k, n - k + 1) if k > 0 else 0.0
    cp_hi = beta_dist.ppf(1 - a / 2, k + 1, n - k) if k < n else 1.0
    _, lo, hi = collapse_probability(k, n, conf, method="clopper-pearson")
    # scipy finds the exact ends by root-finding (brentq, xtol 2e-12), not from beta
    # quantiles: they agree to about 5e-13
    assert (lo, hi) == pytest.approx((cp_lo, cp_hi), abs=2e-12)


def test_collapse_probability_known_values():
    # 0 of 10, Wilson 95 %: upper = z^2/n / (1 + z^2/n) = 0.27753...
    z2 = norm.ppf(0.975) ** 2
    assert collapse_probability(0, 10) == (0.0, 0.0, pytest.approx((z2 / 10) / (1 + z2 / 10), rel=1e-12))
    # 0 of 10 exact: upper = 1 - 0.025^(1/10)
    assert collapse_probability(0, 10, method="clopper-pearson")[2] == pytest.approx(1 - 0.025 ** 0.1, rel=1e-10)
    p, lo, hi = collapse_probability(5, 10)
    # symmetric about 1/2; 1e-12 rather than 1e-15: the ends are scipy's arithmetic
    # (binomtest.proportion_ci), whose rounding this test does not control
    assert p == 0.5 and lo == pytest.approx(1 - hi, abs=1e-12)
    # Wilson without continuity correction (scipy's "wilsoncc" is wider)
    assert collapse_probability(3, 10)[1:] == pytest.approx((0.10779126740630, 0.60322185253885),
                                                            abs=1e-12)


@pytest.mark.parametrize("args, kwargs, field", [
    ((11, 10), {}, "collapses"),
    ((-1, 10), {}, "collapses"),
    ((1.5, 10), {}, "collapses"),
    ((0, 0), {}, "trials"),
    ((1, 10), dict(confidence=1.5), "confidence"),
    ((1, 10), dict(method="wald"), "method"),
])
def test_collapse_probability_bad_input(args, kwargs, field):
    with pytest.raises(ArchInputError, match=rf"^{field}:"):
        collapse_probability(*args, **kwargs)


# ----------------------------------------------------------------------------- first collapse

def test_first_collapse_non_monotonic():
    # collapse at 1.1, survives at 1.2 and 1.4, collapses again: two resurrections
    r = first_collapse([1.0, 1.1, 1.2, 1.3, 1.4, 1.5, 1.6], [0, 1, 0, 1, 0, 1, 1])
    assert r == {"first_collapse": 1.1, "survivals_above": [1.2, 1.4], "resurrections": 2}
    # ends on a survival: still counted
    r = first_collapse([0.5, 1.0, 1.5], [False, True, False])
    assert r == {"first_collapse": 1.0, "survivals_above": [1.5], "resurrections": 1}


def test_first_collapse_monotonic_and_never():
    assert first_collapse([0.5, 1.0, 1.5], [False, True, True]) == {
        "first_collapse": 1.0, "survivals_above": [], "resurrections": 0}
    assert first_collapse([0.5, 1.0], [False, False]) == {
        "first_collapse": None, "survivals_above": [], "resurrections": 0}


@pytest.mark.parametrize("scales, collapsed, field", [
    ([1.0, 0.9, 1.2], [0, 1, 1], "scales"),
    ([1.0, 1.0], [0, 1], "scales"),
    ([0.0, 1.0], [0, 1], "scales"),
    ([], [], "scales"),
    ([1.0, 2.0], [0, 1, 1], "collapsed"),
    ([1.0, 2.0], [0, 2], "collapsed"),
    ([1.0, 2.0], ["no", "yes"], "collapsed"),
])
def test_first_collapse_bad_input(scales, collapsed, field):
    with pytest.raises(ArchInputError, match=rf"^{field}:"):
        first_collapse(scales, collapsed)


@pytest.mark.parametrize("fit, args, cls", [
    (fit_ida_moments, ([0.3, -0.4, 0.5],), ArchInputError),
    (fit_ida_moments, ([0.3, 0.3, 0.3],), FitError),
    (fit_stripes_mle, ([0.2, 0.4], [10, 10], [1, 11]), ArchInputError),
    (fit_stripes_mle, ([0.2, 0.4], [10, 10], [0, 10]), FitError),
    (fit_stripes_mle, ([0.2, 0.3, 0.4], [10, 10, 10], [0, 0, 0]), FitError),
])
def test_input_errors_and_fit_errors_are_told_apart(fit, args, cls):
    """Callers (IDA, bootstrap) skip unidentifiable data but must not hide malformed input."""
    with pytest.raises(ArchrockError) as info:
        fit(*args)
    assert type(info.value) is cls


def test_bootstrap_of_stripes_that_cannot_vary_gives_no_interval():
    # one analysis per stripe, not separated (rocking is not monotonic): a fit exists, but
    # Binomial(1, 0 or 1) resamples are the data itself; a zero-width interval would be false
    x, n, z = [0.5, 0.7, 0.9, 1.0, 1.2, 1.4], [1] * 6, [0, 0, 1, 1, 0, 1]
    f = bootstrap_fit(fit_stripes_mle, x, n, z, n_boot=50, seed=0)
    assert f.theta == fit_stripes_mle(x, n, z).theta
    assert f.theta_ci is None and f.beta_ci is None and "one analysis per stripe" in f.ci_note
    assert f.to_dict()["theta_ci"] is None and f.to_dict()["ci_note"] == f.ci_note
    # several analyses per stripe, each stripe all-or-nothing: no interval either
    f = bootstrap_fit(fit_stripes_mle, x, [4] * 6, [0, 0, 4, 4, 0, 4], n_boot=50, seed=0)
    assert f.theta_ci is None and "all-collapse or all-survive" in f.ci_note
    # a stripe that can vary: an interval of positive width, no note
    f = bootstrap_fit(fit_stripes_mle, x, [4] * 6, [0, 1, 2, 2, 3, 4], n_boot=50, seed=0)
    assert f.theta_ci[0] < f.theta_ci[1] and f.ci_note is None


def test_one_record_cannot_give_a_fragility():
    with pytest.raises(FitError, match="one value"):
        fit_ida_moments([0.4])
    with pytest.raises(FitError, match="one value"):
        bootstrap_fit(fit_ida_moments, [0.4], n_boot=10)


def test_collapse_probability_of_no_trials_says_it_cannot_be_estimated():
    with pytest.raises(ArchInputError, match="trials: 0; a collapse probability cannot be estimated"):
        collapse_probability(0, 0)


# ----------------------------------------------------------------------------- progress output

def test_progress_lines_are_throttled(capsys, monkeypatch):
    """`fragility --samples 200` wrote 1,205 progress lines (a tqdm redraw ten times a second
    into a log). Off a terminal the lines now come once per 1% and 1 s, or once a minute, and
    the last: 10,000 updates over 500 s give at most 100 + 500 / 60 + 1 lines."""
    import archrock._progress as progress
    from archrock.cli.runsettings import STDERR_PROGRESS  # the CLI renders; the library never prints

    clock = [1000.0]
    monkeypatch.setattr(progress.time, "monotonic", lambda: clock[0])
    bar = progress.Progress(10_000, STDERR_PROGRESS, desc="ida", unit="response")
    assert bar.bar is None  # captured stderr is no terminal: plain lines, no tqdm redraws
    for _ in range(10_000):
        clock[0] += 0.05
        bar.update(1)
    bar.close()
    lines = capsys.readouterr().err.splitlines()
    assert 90 <= len(lines) <= 110
    assert lines[-1] == "ida: 10000/10000 responses (100%)"
    # slow progress: a line a minute at most, whatever is done
    bar = progress.Progress(10**9, STDERR_PROGRESS, desc="ida", unit="response")
    for _ in range(1000):
        clock[0] += 1.0
        bar.update(1)
    assert len(capsys.readouterr().err.splitlines()) == 16  # 1000 s / 60 s
    # disabled: nothing
    bar = progress.Progress(10, False)
    bar.update(10)
    assert capsys.readouterr().err == ""


def test_progress_callable_gets_the_lines_and_nothing_is_printed(capsys, monkeypatch, caplog):
    """The one progress protocol: a callable receives the same throttled lines (and notes)
    that the CLI prints on stderr; the library prints nothing; True hands them to the
    'archrock.progress' logger; anything else is refused."""
    import archrock._progress as progress

    clock = [0.0]
    monkeypatch.setattr(progress.time, "monotonic", lambda: clock[0])
    got = []
    bar = progress.Progress(200, got.append, desc="curves", unit="arch")
    bar.note("curves: starting")
    for _ in range(200):
        clock[0] += 2.0
        bar.update(1)
    bar.close()
    assert capsys.readouterr().err == ""
    assert got[0] == "curves: starting" and got[-1] == "curves: 200/200 arches (100%)"
    assert len(got) == 101  # 1% of 200 is two arches: a line every other update, and the note
    with pytest.raises(ArchInputError, match="progress: 'yes'; allowed None, True"):
        progress.Progress(10, "yes")
    import logging

    with caplog.at_level(logging.INFO, logger="archrock.progress"):
        bar = progress.Progress(3, True, desc="msa", unit="analysis")
        bar.update(3)
    assert capsys.readouterr().err == ""
    assert [r.getMessage() for r in caplog.records] == ["msa: 3/3 analyses (100%)"]


def test_cli_one_scale_without_collapse_names_scales(capsys, tmp_path):
    """`fragility --scales 2` on a record that never collapses the arch: the message names
    --scales (the option given), not --levels."""
    from archrock.cli import main

    t = np.arange(0, 3.0, 0.01)
    rec = tmp_path / "r.txt"
    np.savetxt(rec, np.column_stack([t, 0.3 * np.sin(2 * np.pi * 1.5 * t)
                                     * np.sin(np.pi * t / 3.0) ** 2]))
    code = main(["fragility", "--records", str(rec), "--scales", "2", "--bootstrap", "0",
                 "--no-progress"])
    err = capsys.readouterr().err
    assert code == 2
    assert err.startswith("archrock: error: scales: 2: no record collapsed") and "0.6" in err


def test_likelihood_maximisation_is_bounded_and_says_no_fit(monkeypatch):
    """Both optimisers run with an explicit iteration bound; where neither converges the
    answer is FitError (a study reports 'no fit'), not a RuntimeError that stops it."""
    import archrock.studies.likelihood as lk  # the fits' maximisation lives there

    seen = []
    real = lk.minimize

    def stalled(fun, x0, args=(), method=None, options=None, **kw):
        seen.append((method, options["maxiter"]))
        res = real(fun, x0, args=args, method=method, options={**options, "maxiter": 1}, **kw)
        res.success = False
        if method == "BFGS":
            res.jac = np.array([1.0, 1.0])
        return res

    monkeypatch.setattr(lk, "minimize", stalled)
    x, n, z = synthetic_stripes(trials=50)
    with pytest.raises(FitError, match="did not converge in 400 BFGS and 4000 Nelder-Mead"):
        fit_stripes_mle(x, n, z)
    assert seen == [("BFGS", 400), ("Nelder-Mead", 4000)]


# ----------------------------------------------------------------------------- censoring, plateau

def plateau_ida(n=1200, theta=0.3, beta=0.3, never=0.48, top=1.0, seed=5):
    """IDA first collapses where a fraction ``never`` of the records never collapse whatever
    the scale (capacity infinite), the others lognormal; censored at ``top``."""
    rng = np.random.default_rng(seed)
    x = np.exp(rng.normal(math.log(theta), beta, n))
    x[rng.random(n) < never] = np.inf
    x[x > top] = np.inf
    return x


def test_half_censored_lognormal_recovers_theta_and_beta_and_no_plateau():
    """Lognormal capacities censored at their median (half the records never collapse up to
    the top of the range): the censored MLE recovers theta and beta; the test finds no
    levelling off (the data do not level off), so the plain curve is kept."""
    rng = np.random.default_rng(5)
    x = np.exp(rng.normal(math.log(0.5), 0.4, 1200))
    x[x > 0.5] = np.inf
    assert 0.45 < np.mean(np.isinf(x)) < 0.55
    f = fit_ida_moments(x, censored="mle", max_intensity=0.5, plateau="auto")
    assert f.theta == pytest.approx(0.5, rel=0.03) and f.beta == pytest.approx(0.4, rel=0.07)
    assert f.p_max == 1.0 and f.level_off["levels_off"] is False
    assert f.level_off["p_value"] > 0.05
    plain = fit_ida_moments(x, censored="mle", max_intensity=0.5)
    assert (f.theta, f.beta, f.log_likelihood) == (plain.theta, plain.beta, plain.log_likelihood)


def test_ida_that_levels_off_gets_a_plateau_that_follows_the_data():
    """48% of the records never collapse: the plain lognormal runs on towards P = 1 (0.56 at
    the top of the range where 0.505 of the curves collapsed, the 0.6 failure mode), the plateau
    fit recovers theta, beta and p_max and reads the empirical fraction at the top."""
    x = plateau_ida()
    emp = np.mean(np.isfinite(x))
    plain = fit_ida_moments(x, censored="mle", max_intensity=1.0)
    f = fit_ida_moments(x, censored="mle", max_intensity=1.0, plateau="auto")
    assert plain.probability(1.0) > emp + 0.05 and plain.probability(3.0) > 0.75
    assert f.level_off["levels_off"] and f.level_off["p_value"] < 1e-10
    assert f.theta == pytest.approx(0.3, rel=0.05) and f.beta == pytest.approx(0.3, rel=0.1)
    assert f.p_max == pytest.approx(1 - 0.48, abs=0.04)
    assert f.probability(1.0) == pytest.approx(emp, abs=0.01)
    assert f.probability(100.0) == pytest.approx(f.p_max, rel=1e-9)  # never beyond the plateau
    assert math.isinf(f.quantile(0.9)) and f.quantile(0.25) < 1.0
    assert f.level_off["lognormal"]["theta"] == pytest.approx(plain.theta, rel=1e-9)
    d = json.loads(json.dumps(f.to_dict()))
    assert d["p_max"] == pytest.approx(f.p_max) and d["level_off"]["levels_off"] is True


def test_stripes_that_level_off_get_a_plateau_through_the_stripes():
    """MSA (binomial likelihood, Baker 2015) where the stripes level off at ~0.52: the plateau
    fit passes through the top stripes, the plain one overshoots them (0.755 read, 0.87 fitted
    in the issue)."""
    rng = np.random.default_rng(11)
    lv = np.geomspace(0.1, 1.0, 8)
    n = np.full(8, 150)
    z = rng.binomial(n, 0.52 * norm.cdf(np.log(lv / 0.3) / 0.3))
    plain = fit_stripes_mle(lv, n, z)
    f = fit_stripes_mle(lv, n, z, plateau="auto")
    top = z[-3:].sum() / n[-3:].sum()
    assert plain.probability(lv[-1]) > top + 0.08
    assert f.level_off["levels_off"] and f.p_max == pytest.approx(0.52, abs=0.06)
    assert f.probability(lv[-1]) == pytest.approx(top, abs=0.05)
    assert f.theta == pytest.approx(0.3, rel=0.1)
    # the log-likelihood is the binomial one with its constant, as the plain fit's
    p = f.probability(lv)
    assert f.log_likelihood == pytest.approx(np.sum(binom.logpmf(z, n, p)), rel=1e-9)
    assert f.level_off["lognormal"]["log_likelihood"] == pytest.approx(plain.log_likelihood, rel=1e-12)
    # a plain lognormal suite: the test keeps the plain fit
    z2 = synthetic_stripes(trials=150, levels=8)[2]
    g = fit_stripes_mle(np.geomspace(0.15, 1.0, 8), np.full(8, 150), z2, plateau="auto")
    assert g.p_max == 1.0 and not g.level_off["levels_off"]


def test_a_plateau_within_the_minimum_gap_of_one_keeps_the_plain_fit():
    """Stripes of 2,000 runs that level off at 0.98: the likelihood ratio prefers the plateau,
    but a ceiling within LEVEL_OFF_MIN_GAP of 1 changes no decision and the plain curve governs
    (the note says why)."""
    lv = np.geomspace(0.1, 1.0, 8)
    n = np.full(8, 2000)
    z = np.round(n * 0.98 * norm.cdf(np.log(lv / 0.3) / 0.3)).astype(int)
    f = fit_stripes_mle(lv, n, z, plateau="auto")
    assert f.level_off["p_value"] < 0.05
    assert not f.level_off["levels_off"] and f.p_max == 1.0
    assert "within 0.05 of P = 1" in f.level_off["note"]


def test_bootstrap_keeps_the_plateau_the_data_chose():
    x = plateau_ida(n=300)
    f = bootstrap_fit(fit_ida_moments, x, censored="mle", max_intensity=1.0, plateau="auto",
                      n_boot=30, seed=2)
    assert f.p_max < 1.0 and f.theta_ci[0] < f.theta < f.theta_ci[1]
    with pytest.raises(ArchInputError, match="plateau: 'yes'"):
        fit_stripes_mle([0.1, 0.2], [5, 5], [1, 3], plateau="yes")


def test_progress_finishes_at_100_percent_where_the_total_was_an_estimate():
    """curves and fragility counted their bisections from above and stopped at ~80%: finish()
    ends the count at 100% (lines: done/done; a bar: filled)."""
    from archrock._progress import Progress

    got = []
    bar = Progress(1000, got.append, desc="curves", unit="response")
    bar.update(800)
    bar.finish()
    bar.close()
    assert got[-1] == "curves: 800/800 responses (100%)"

    class Sink:
        def __init__(self):
            self.n = 0

        def __call__(self, line):
            pass

        def bar(self, total, desc, unit):
            sink = self

            class B:
                def update(self, n):
                    sink.n += n

                def close(self):
                    pass
            self.total = total
            return B()

    s = Sink()
    bar = Progress(1000, s, desc="ida", unit="response")
    bar.update(640)
    bar.finish()
    assert s.n == s.total == 1000


def test_ida_and_msa_progress_end_at_100_percent(monkeypatch):
    """The studies' bars: the IDA's total counts every bisection step of every curve, the last
    line still reads 100% (it stopped at 80% in 0.6)."""
    import archrock.studies.ida as ida_mod
    from archrock.geometry import oppenheim_arch
    from archrock.groundmotion import GroundMotion
    from archrock.studies.runner import RunSettings

    monkeypatch.setattr(ida_mod, "PROGRESS_S", -1.0)  # always show progress
    t = np.arange(0, 2.0, 0.01)
    rec = GroundMotion(t, 3.0 * np.sin(2 * np.pi * 2.0 * t) * np.sin(np.pi * t / 2.0) ** 2, "r")
    got = []
    res = ida_mod.ida([rec], oppenheim_arch(), [0.5, 1.0, 2.0], tol=0.05,
                      settings=RunSettings(progress=got.append))
    lines = [x for x in got if x.startswith("ida: ")]
    assert lines[-1].endswith("(100%)"), got
    done = int(lines[-1].split()[1].split("/")[0])
    assert done < 1 * (3 + 2 + math.ceil(math.log2(1 / 0.05)))  # fewer than the estimate
    got.clear()
    ida_mod.msa([rec], oppenheim_arch(), [0.1, 0.2], settings=RunSettings(progress=got.append))
    assert got[-1] == "msa: 2/2 analyses (100%)"
    assert res.curves[0].first_im is None or res.curves[0].first_im > 0
