"""Statistics of fragility: lognormal fragility functions fitted to collapse data (docs/method.md, Ensembles).

Model (Baker 2015, Earthquake Spectra 31): P(collapse | IM = x) = Phi(ln(x / theta) / beta), with
``theta`` the median collapse capacity (same units as the intensity measure: a scale factor, PGA
in g, ...) and ``beta`` the standard deviation of ln(capacity) (dimensionless).

Two estimators, as in Baker (2015):

* :func:`fit_ida_moments` -- incremental dynamic analysis (IDA): one first-collapse intensity per
  record; method of moments on the logs (``ln theta = mean``, ``beta = std(ddof=1)``).  Records that
  never collapsed are rejected by default (``censored="error"``); ``censored="mle"`` fits them as
  right-censored observations instead.
* :func:`fit_stripes_mle` -- multiple-stripe analysis: ``trials[j]`` analyses at intensity
  ``intensities[j]`` of which ``collapses[j]`` collapsed; maximum likelihood on the product of
  binomial probabilities (Baker eq. 11).

Rocking collapse is not monotonic in the scale factor (an arch can collapse, survive and collapse
again as the record is scaled up a few per cent), so :func:`first_collapse` reports the first
collapse *and* the survivals above it, and the fragility is a statement over records.

:func:`bootstrap_fit` adds percentile confidence intervals; :func:`collapse_probability` gives the
binomial interval of a single stripe.  Pure numpy/scipy; bad input raises
:class:`~archrock.errors.ArchInputError` whose message starts with the offending field; data from
which no fragility can be identified raises :class:`~archrock.errors.FitError`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np
from scipy.special import gammaln, ndtr, ndtri
from scipy.stats import binomtest

from ..errors import ArchInputError, FitError
# the likelihoods and the plateau test (private helpers, their own module for size)
from .likelihood import (_LOG_SQRT_2PI, _censored_negll, _check_plateau, _ida_plateau_negll,
                         _minimise, _stripes_negll, _stripes_plateau_negll, _with_plateau)

__all__ = [
    "FragilityFit",
    "fit_ida_moments",
    "fit_stripes_mle",
    "bootstrap_fit",
    "collapse_probability",
    "first_collapse",
    "FIT_CHOICES",
]

#: Values of :attr:`FragilityFit.method`.
FIT_CHOICES = ("moments", "mle", "censored_mle")



# --------------------------------------------------------------------------- validation helpers

def _array1d(name: str, values) -> np.ndarray:
    try:
        arr = np.asarray(values, dtype=float)
    except (TypeError, ValueError):
        raise ArchInputError(f"{name}: expected a 1-d list of numbers, got {values!r}") from None
    if arr.ndim != 1 or arr.size == 0:
        raise ArchInputError(f"{name}: expected a non-empty 1-d list of numbers, got shape {arr.shape}")
    return arr


def _positive(name: str, values) -> np.ndarray:
    arr = _array1d(name, values)
    if not np.all(np.isfinite(arr) & (arr > 0)):
        raise ArchInputError(f"{name}: must be > 0 and finite")
    return arr


def _integers(name: str, values, lo: int, what: str) -> np.ndarray:
    arr = _array1d(name, values)
    if not np.all(np.isfinite(arr)) or np.any(arr != np.round(arr)) or np.any(arr < lo):
        raise ArchInputError(f"{name}: must be integers {what}")
    return arr.astype(np.int64)


def _confidence(value) -> float:
    try:
        c = float(value)
    except (TypeError, ValueError):
        raise ArchInputError(f"confidence: must be a number between 0 and 1 (exclusive), got {value!r}") from None
    if not (0.0 < c < 1.0):
        raise ArchInputError(f"confidence: must be between 0 and 1 (exclusive), got {value!r}")
    return c


def _count(name: str, value, lo: int, what: str) -> int:
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ArchInputError(f"{name}: must be an integer {what}, got {value!r}") from None
    if not math.isfinite(v) or v != round(v) or v < lo:
        raise ArchInputError(f"{name}: must be an integer {what}, got {value!r}")
    return int(v)


# --------------------------------------------------------------------------- result

@dataclass(frozen=True)
class FragilityFit:
    """A fitted lognormal fragility function P(C | IM = x) = Phi(ln(x/theta)/beta).

    theta: median collapse capacity, same units as the intensities that were fitted.
    beta: lognormal standard deviation (dimensionless).
    method: "moments" (IDA, method of moments), "mle" (multiple stripes, binomial likelihood) or
        "censored_mle" (IDA with right-censored records that never collapsed).
    n_records: records (IDA) or individual analyses (stripes, = sum of trials) used.
    log_likelihood: maximised (mle) or evaluated (moments) log-likelihood at (theta, beta).
        Stripes: sum of ln binomial pmf, binomial coefficients included.  IDA: sum of the normal
        log-density of ln(x) (density of the log-intensity, so it does not depend on units),
        plus ln(1 - Phi) for censored records.
    theta_ci, beta_ci, confidence: two-sided percentile bootstrap intervals and their level
        (None unless produced by :func:`bootstrap_fit`).
    n_boot, n_boot_failed: bootstrap resamples requested, and those excluded because the
        resampled data could not identify a fit (None without bootstrap).
    ci_note: why an interval asked for is None (it cannot be estimated: the resamples cannot
        vary), or what it covers; None otherwise.
    p_max: upper asymptote of the curve, P = p_max * Phi(ln(x/theta)/beta): 1 for the plain
        lognormal; below 1 where the data level off (some records never collapse the arch
        whatever the scale tried) and a likelihood ratio test prefers the plateau
        (:func:`level_off`).  theta, beta are then those of the records that do collapse.
    level_off: the test that chose between the two (a dict: statistic, p-value, the plain
        lognormal's theta, beta and log-likelihood, and a sentence), None where not tested.
    """

    theta: float
    beta: float
    method: str
    n_records: int
    log_likelihood: float | None = None
    theta_ci: tuple[float, float] | None = None
    beta_ci: tuple[float, float] | None = None
    confidence: float | None = None
    n_boot: int | None = None
    n_boot_failed: int | None = None
    ci_note: str | None = None
    p_max: float = 1.0
    level_off: dict | None = None

    def __post_init__(self):
        if not (0.0 < self.p_max <= 1.0):
            raise ArchInputError(f"p_max: must be in (0, 1], got {self.p_max!r}")
        if not (math.isfinite(self.theta) and self.theta > 0):
            raise ArchInputError(f"theta: must be > 0 and finite, got {self.theta!r}")
        if not (math.isfinite(self.beta) and self.beta > 0):
            raise ArchInputError(f"beta: must be > 0 and finite, got {self.beta!r}")
        if self.method not in FIT_CHOICES:
            raise ArchInputError(f"method: must be one of {FIT_CHOICES}, got {self.method!r}")

    def probability(self, x) -> np.ndarray:
        """P(collapse | IM = x) for intensities x >= 0 (same units as theta); x = 0 gives 0."""
        arr = np.asarray(x, dtype=float)
        if np.any(np.isnan(arr)) or np.any(arr < 0):
            raise ArchInputError("x: intensities must be >= 0 (not NaN)")
        with np.errstate(divide="ignore"):  # ln 0 = -inf -> Phi(-inf) = 0, which is right
            return self.p_max * ndtr(np.log(arr / self.theta) / self.beta)

    def quantile(self, p) -> np.ndarray:
        """Intensity at which the collapse probability is p (0 <= p <= 1):
        theta*exp(beta*Phi^-1(p / p_max)); inf for p >= p_max < 1 (never reached)."""
        arr = np.asarray(p, dtype=float)
        if np.any(np.isnan(arr)) or np.any((arr < 0) | (arr > 1)):
            raise ArchInputError("p: probabilities must be between 0 and 1")
        return self.theta * np.exp(self.beta * ndtri(np.minimum(arr / self.p_max, 1.0)))

    def to_dict(self) -> dict:
        """Plain-Python dict (JSON-serialisable: tuples become lists under json.dumps)."""
        def opt(v, f):
            return None if v is None else f(v)
        return {
            "theta": float(self.theta),
            "beta": float(self.beta),
            "method": self.method,
            "n_records": int(self.n_records),
            "log_likelihood": opt(self.log_likelihood, float),
            "theta_ci": opt(self.theta_ci, lambda t: (float(t[0]), float(t[1]))),
            "beta_ci": opt(self.beta_ci, lambda t: (float(t[0]), float(t[1]))),
            "confidence": opt(self.confidence, float),
            "n_boot": opt(self.n_boot, int),
            "n_boot_failed": opt(self.n_boot_failed, int),
            "ci_note": self.ci_note,
            "p_max": float(self.p_max),
            "level_off": self.level_off,
        }


# --------------------------------------------------------------------------- IDA

def fit_ida_moments(collapse_intensities, *, censored: str = "error",
                    max_intensity=None, plateau=False) -> FragilityFit:
    """Fragility from IDA first-collapse intensities (one per record, > 0, units of the IM).

    censored="error" (default): method of moments, ln theta = mean(ln x), beta = std(ln x, ddof=1)
    (Baker 2015 eq. 3-4).  A record that never collapsed (np.inf or nan) raises FitError:
    dropping it would bias theta low, so the choice is left to the caller.

    censored="mle": maximum likelihood with right-censoring; a record that never collapsed up to
    its highest analysed intensity m contributes 1 - Phi(ln(m/theta)/beta).  ``max_intensity``
    (scalar, or one value per record, ignored for records that collapsed) gives m and is required
    when any record survived.  This is an MLE, so with no survivors beta = std(ln x, ddof=0).

    plateau (censored="mle" with survivors): False (default) the plain lognormal; True the
    curve P = p_max Phi(ln(x/theta)/beta) whose 1 - p_max never collapse; "auto" the plateau
    where a likelihood ratio test says the data level off below P = 1 (``level_off`` of the
    result records the test and the plain fit beside it).
    """
    _check_plateau(plateau)
    if censored not in ("error", "mle"):
        raise ArchInputError(f"censored: must be 'error' or 'mle', got {censored!r}")
    x = _array1d("collapse_intensities", collapse_intensities)
    survived = np.isnan(x) | (x == np.inf)
    xc = x[~survived]
    if np.any(~np.isfinite(xc) | (xc <= 0)):
        raise ArchInputError("collapse_intensities: must be > 0 (np.inf or nan for records that never collapsed)")
    if censored == "error":
        if np.any(survived):
            raise FitError(
                f"collapse_intensities: {int(survived.sum())} of {x.size} records never collapsed (inf/nan); "
                "use censored='mle' with max_intensity, or analyse them to higher intensity")
        return _moments_fit(np.log(x))
    return _censored_fit(np.log(xc), max_intensity, survived, plateau)


def _moments_fit(lnx) -> FragilityFit:
    """The method of moments on the log first-collapse intensities (every record collapsed)."""
    n = lnx.size
    if n < 2:
        raise FitError("collapse_intensities: one value (one record): beta cannot be "
                       "estimated; need at least 2 distinct values")
    if np.ptp(lnx) == 0:
        raise FitError("collapse_intensities: need at least 2 distinct values to estimate beta")
    lt, b = float(np.mean(lnx)), float(np.std(lnx, ddof=1))
    ll = float(np.sum(-math.log(b) - _LOG_SQRT_2PI - 0.5 * ((lnx - lt) / b) ** 2))
    return FragilityFit(theta=math.exp(lt), beta=b, method="moments", n_records=n, log_likelihood=ll)


def _censored_at(max_intensity, survived) -> np.ndarray:
    """ln of the highest analysed intensity of each record that never collapsed (``survived``:
    one flag per record); empty when every record collapsed."""
    n = survived.size
    if not np.any(survived):
        return np.empty(0)
    if max_intensity is None:
        raise ArchInputError("max_intensity: required (> 0) when some records never collapsed")
    m = np.asarray(max_intensity, dtype=float)
    if m.ndim == 0:
        m = np.full(n, float(m))
    if m.shape != (n,):
        raise ArchInputError(f"max_intensity: must be a scalar or one value per record ({n}), got shape {m.shape}")
    m = m[survived]
    if not np.all(np.isfinite(m) & (m > 0)):
        raise ArchInputError("max_intensity: must be > 0 and finite")
    return np.log(m)


def _censored_fit(lnx, max_intensity, survived, plateau) -> FragilityFit:
    """Maximum likelihood with right-censoring: ``lnx`` the log collapse intensities, the
    records flagged ``survived`` censored at their ``max_intensity``."""
    if lnx.size < 2 or np.ptp(lnx) == 0:
        # with fewer than two distinct collapses the likelihood is unbounded as beta -> 0
        raise FitError("collapse_intensities: need at least 2 distinct finite collapse intensities")
    lnm, n = _censored_at(max_intensity, survived), survived.size
    x0 = np.array([np.mean(lnx), math.log(max(np.std(lnx, ddof=1), 1e-3))])
    lt, lb = _minimise(_censored_negll, x0, (lnx, lnm, float(n)))
    ll = -_censored_negll(np.array([lt, lb]), lnx, lnm, 1.0)[0]
    fit = FragilityFit(theta=math.exp(lt), beta=math.exp(lb), method="censored_mle",
                       n_records=n, log_likelihood=float(ll))
    if lnm.size == 0:  # every record collapsed: nothing levels off
        return fit
    return _with_plateau(fit, plateau, _ida_plateau_negll, (lnx, lnm), np.r_[lnx, lnm],
                         float(n), lnx.size / n, lnx)


# --------------------------------------------------------------------------- multiple stripes

def _stripes_data(intensities, trials, collapses):
    x = _positive("intensities", intensities)
    n = _integers("trials", trials, 1, ">= 1")
    z = _integers("collapses", collapses, 0, "between 0 and trials")
    if not (x.size == n.size == z.size):
        raise ArchInputError(
            f"trials: intensities, trials and collapses must have the same length "
            f"({x.size}, {n.size}, {z.size})")
    if np.any(z > n):
        raise ArchInputError("collapses: must be between 0 and trials")
    return x, n, z


def _check_identifiable(x, n, z) -> None:
    """Raise unless the binomial MLE is finite with beta in (0, inf).

    Probit likelihood facts (Albert & Anderson 1984, with ln x as the only covariate): the MLE
    exists iff there is no (quasi-)separation, i.e. some collapse occurs below some survival
    (else beta -> 0) and some survival below some collapse (else the trend is reversed).  The
    likelihood is concave in (a, b) = (-ln theta/beta, 1/beta), so the fitted slope is positive
    iff the score at b = 0 is, i.e. iff collapsed analyses have a larger mean ln x than all.
    """
    total, zc = int(n.sum()), int(z.sum())
    if zc == 0:
        raise FitError("collapses: no collapse at any intensity; the fragility cannot be identified "
                             "(analyse higher intensities)")
    if zc == total:
        raise FitError("collapses: every trial collapsed at every intensity; the fragility cannot be "
                             "identified (analyse lower intensities)")
    if np.unique(x).size < 2:
        raise FitError("intensities: need at least 2 distinct intensity levels")
    lo_collapse = x[z > 0].min()
    hi_survival = x[z < n].max()
    if not lo_collapse < hi_survival:
        raise FitError(
            f"collapses: stripes are separated (no survival above the lowest collapse at {lo_collapse:g}), "
            "beta -> 0; add stripes between the last all-survive and first all-collapse levels")
    lnx = np.log(x)
    if not np.sum(z * lnx) / zc > np.sum(n * lnx) / total + 1e-12 * (1 + abs(lnx).max()):
        raise FitError("collapses: collapse fraction does not increase with intensity; "
                             "a lognormal fragility cannot be fitted")


def fit_stripes_mle(intensities, trials, collapses, *, plateau=False) -> FragilityFit:
    """Multiple-stripe maximum likelihood fit (Baker 2015 eq. 11).

    intensities: IM level of each stripe (> 0, any units; theta comes out in the same units).
    trials: analyses at each level (integers >= 1); collapses: how many collapsed (0..trials).
    Stripes with 0 or all collapses are used as they are (they carry information through
    ln(1 - Phi) and ln Phi).  Raises ArchInputError when the data cannot identify a fit: no
    collapse, no survival, a single level, separated stripes (beta -> 0) or a decreasing trend.
    plateau: as :func:`fit_ida_moments` (False, True or "auto": the stripes level off below 1).
    """
    _check_plateau(plateau)
    x, n, z = _stripes_data(intensities, trials, collapses)
    _check_identifiable(x, n, z)
    lnx = np.log(x)
    nf, zf = n.astype(float), z.astype(float)
    # Start: weighted least squares on probits of the (continuity-corrected) fractions.
    p = (zf + 0.5) / (nf + 1.0)
    y = ndtri(p)
    w = nf
    xm, ym = np.average(lnx, weights=w), np.average(y, weights=w)
    sxx = np.average((lnx - xm) ** 2, weights=w)
    slope = np.average((lnx - xm) * (y - ym), weights=w) / sxx if sxx > 0 else 0.0
    if slope > 0:
        x0 = np.array([xm - ym / slope, -math.log(slope)])
    else:  # cannot happen after the identifiability check except by the correction; stay sane
        x0 = np.array([xm, math.log(max(math.sqrt(sxx), 0.1))])
    x0[1] = np.clip(x0[1], math.log(1e-3), math.log(10.0))
    lt, lb = _minimise(_stripes_negll, x0, (lnx, nf, zf, float(n.sum())))
    const = np.sum(gammaln(nf + 1) - gammaln(zf + 1) - gammaln(nf - zf + 1))
    ll = -_stripes_negll(np.array([lt, lb]), lnx, nf, zf, 1.0)[0] + const
    fit = FragilityFit(theta=math.exp(lt), beta=math.exp(lb), method="mle",
                       n_records=int(n.sum()), log_likelihood=float(ll))
    top = int(np.argmax(x))
    # the constant is added back so both log-likelihoods compare (it cancels in the test)
    fit = replace(fit, log_likelihood=float(ll - const))
    fit = _with_plateau(fit, plateau, _stripes_plateau_negll, (lnx, nf, zf), lnx,
                        float(n.sum()), zf[top] / nf[top], lnx, weights=zf + 1e-12)
    if fit.level_off is not None:  # the plain fit's log-likelihood with its constant too
        fit.level_off["lognormal"]["log_likelihood"] += float(const)
    return replace(fit, log_likelihood=float(fit.log_likelihood + const))


# --------------------------------------------------------------------------- bootstrap

def bootstrap_fit(fit_function, *data, n_boot: int = 200, confidence: float = 0.9,
                  seed=0, **fit_kwargs) -> FragilityFit:
    """Fit, then add percentile bootstrap confidence intervals for theta and beta.

    ``bootstrap_fit(fit_ida_moments, x, censored=..., max_intensity=...)`` resamples records with
    replacement (a survivor keeps its own max_intensity).
    ``bootstrap_fit(fit_stripes_mle, intensities, trials, collapses)`` resamples the individual
    analyses with replacement within each stripe, which is exactly collapses*_j ~
    Binomial(trials_j, collapses_j/trials_j): the stripe design is kept, the outcomes vary.

    The point estimate is the fit of the original data.  Resamples that cannot identify a fit
    (e.g. all stripes resampled to 0/1) are excluded and counted in ``n_boot_failed``; more than
    half failing raises FitError.  An interval that cannot be estimated is None, with the reason
    in ``ci_note``: stripes that are each all-collapse or all-survive (e.g. one analysis per
    stripe) cannot vary under resampling, and a percentile interval of zero width means the
    resamples did not vary.  ``seed`` (int or numpy SeedSequence) makes the result
    reproducible; ``confidence`` is the two-sided level (0.9 -> 5th and 95th percentiles).
    """
    n_boot = _count("n_boot", n_boot, 2, ">= 2")
    conf = _confidence(confidence)
    if fit_function is fit_ida_moments:
        base, resample = _ida_resampler(data, fit_kwargs)
    elif fit_function is fit_stripes_mle:
        base, resample = _stripes_resampler(data, fit_kwargs)
        if isinstance(resample, str):  # Binomial(n, 0 or 1) resamples are the data itself
            return replace(base, confidence=conf, n_boot=n_boot, n_boot_failed=0,
                           ci_note=f"not estimated: {resample}, so resampling within "
                                   f"stripes cannot vary")
    else:
        raise ArchInputError("fit_function: must be fit_ida_moments or fit_stripes_mle")
    return _percentile_band(base, resample, n_boot, conf, seed)


def _ida_resampler(data, fit_kwargs):
    """The point fit of the IDA data and a function of a generator that fits one resample of
    the records (a survivor keeps its own max_intensity)."""
    if len(data) != 1:
        raise ArchInputError("data: fit_ida_moments takes one array (collapse_intensities)")
    x = _array1d("collapse_intensities", data[0])
    fit_kwargs = dict(fit_kwargs)
    m = fit_kwargs.pop("max_intensity", None)
    if m is not None and np.ndim(m) == 0:
        m = np.full(x.size, float(m))
    if m is not None:
        m = np.asarray(m, dtype=float)
    base = fit_ida_moments(x, max_intensity=m, **fit_kwargs)
    # the resamples fit the model the data chose (a test per resample would mix models)
    kw = {**fit_kwargs, **({"plateau": base.p_max < 1.0} if "plateau" in fit_kwargs else {})}

    def resample(rng):
        idx = rng.integers(0, x.size, x.size)
        return fit_ida_moments(x[idx], max_intensity=None if m is None else m[idx], **kw)
    return base, resample


def _stripes_resampler(data, fit_kwargs):
    """The point fit of the stripes and a function of a generator that fits one resample of
    the analyses within each stripe; (fit, the reason in words) where the stripes cannot vary
    under resampling."""
    if len(data) != 3 or set(fit_kwargs) - {"plateau"}:
        raise ArchInputError("data: fit_stripes_mle takes (intensities, trials, collapses) "
                             "and the option plateau only")
    x, n, z = _stripes_data(*data)
    base = fit_stripes_mle(x, n, z, **fit_kwargs)
    plat = base.p_max < 1.0 if fit_kwargs else False
    if np.all((z == 0) | (z == n)):
        why = ("one analysis per stripe (one record on one arch)" if np.all(n == 1)
               else "every stripe is all-collapse or all-survive")
        return base, why

    def resample(rng):
        return fit_stripes_mle(x, n, rng.binomial(n, z / n), plateau=plat)
    return base, resample


def _percentile_band(base, resample, n_boot: int, conf: float, seed) -> FragilityFit:
    """``base`` with the percentile intervals of theta and beta over ``n_boot`` resamples
    (as :func:`bootstrap_fit` says: failures counted, zero widths said)."""
    rng = np.random.default_rng(seed)
    thetas, betas, failed = [], [], 0
    for _ in range(n_boot):
        try:
            f = resample(rng)
        except FitError:  # unidentifiable resample; counted, reported
            failed += 1
            continue
        thetas.append(f.theta)
        betas.append(f.beta)
    if failed > n_boot // 2:
        raise FitError(f"data: {failed} of {n_boot} bootstrap resamples cannot identify a fit; "
                             "too few records or collapses for a confidence interval")
    q = [(1.0 - conf) / 2.0, (1.0 + conf) / 2.0]
    tci = tuple(float(v) for v in np.quantile(thetas, q))
    bci = tuple(float(v) for v in np.quantile(betas, q))
    # a zero-width percentile interval says the resamples did not vary, not that theta is known
    flat = [name for name, ci in (("theta", tci), ("beta", bci)) if ci[0] == ci[1]]
    note = (f"{' and '.join(flat)} interval not estimated: the bootstrap resamples do not vary"
            if flat else None)
    return replace(base, theta_ci=None if "theta" in flat else tci,
                   beta_ci=None if "beta" in flat else bci, confidence=conf, n_boot=n_boot,
                   n_boot_failed=failed, ci_note=note)


# --------------------------------------------------------------------------- single stripe

def collapse_probability(collapses: int, trials: int, confidence: float = 0.95,
                         method: str = "wilson") -> tuple[float, float, float]:
    """(p_hat, low, high): collapse fraction at one intensity and its two-sided interval.

    method="wilson" (default): Wilson score interval (without continuity correction), close
    to nominal coverage and never degenerate: scipy.stats.binomtest(k, n).proportion_ci(
    confidence, method="wilson").
    method="clopper-pearson": exact interval, coverage >= nominal (conservative):
    binomtest(k, n).proportion_ci(confidence, method="exact").
    No trials raise ArchInputError: there is no probability to estimate (callers report None).
    """
    if not isinstance(trials, bool) and trials == 0:
        raise ArchInputError("trials: 0; a collapse probability cannot be estimated from no "
                             "trials (allowed an integer >= 1)")
    n = _count("trials", trials, 1, ">= 1")
    k = _count("collapses", collapses, 0, "between 0 and trials")
    if k > n:
        raise ArchInputError(f"collapses: must be between 0 and trials ({n}), got {k}")
    conf = _confidence(confidence)
    p = k / n
    scipy_method = {"wilson": "wilson", "clopper-pearson": "exact"}.get(method)
    if scipy_method is None:
        raise ArchInputError(f"method: must be 'wilson' or 'clopper-pearson', got {method!r}")
    ci = binomtest(k, n).proportion_ci(confidence_level=conf, method=scipy_method)
    lo, hi = float(ci.low), float(ci.high)
    # exact ends at 0/n (the formulas give them up to rounding)
    lo = 0.0 if k == 0 else min(max(lo, 0.0), 1.0)
    hi = 1.0 if k == n else min(max(hi, 0.0), 1.0)
    return p, lo, hi


# --------------------------------------------------------------------------- IDA helper

def first_collapse(scales, collapsed) -> dict:
    """Summarise one IDA curve: scale factors (strictly increasing, > 0) and collapse flags.

    Returns {"first_collapse": smallest scale that collapsed, or None,
             "survivals_above": scales above it that survived (list, increasing),
             "resurrections": number of collapse -> survival switches as the scale grows}.
    Rocking collapse is not monotonic in intensity; Baker's moments fit uses first_collapse,
    and survivals_above / resurrections say how far the curve is from monotonic.
    """
    s = _positive("scales", scales)
    if np.any(np.diff(s) <= 0):
        raise ArchInputError("scales: must be strictly increasing, > 0 and finite")
    c = np.asarray(collapsed)
    if c.shape != s.shape:
        raise ArchInputError(f"collapsed: must have one flag per scale ({s.size}), got shape {c.shape}")
    if c.dtype != bool:
        try:
            cf = c.astype(float)
        except (TypeError, ValueError):
            raise ArchInputError("collapsed: must be booleans (or 0/1)") from None
        if not np.all((cf == 0) | (cf == 1)):
            raise ArchInputError("collapsed: must be booleans (or 0/1)")
        c = cf == 1
    hits = np.flatnonzero(c)
    if hits.size == 0:
        return {"first_collapse": None, "survivals_above": [], "resurrections": 0}
    i0 = int(hits[0])
    after = c[i0:]
    return {
        "first_collapse": float(s[i0]),
        "survivals_above": [float(v) for v in s[i0:][~after]],
        "resurrections": int(np.sum(after[:-1] & ~after[1:])),
    }
