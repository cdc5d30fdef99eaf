"""The likelihoods behind the fragility fits of :mod:`archrock.studies.fragility` and their
maximisation: the binomial likelihood of multiple stripes, the censored likelihood of IDA
first-collapse intensities, both over (ln theta, ln beta); and the plateau (an upper asymptote
p_max < 1 of P(collapse)) with the likelihood ratio test that decides whether the data level
off.  Private to the fragility fits; pure numpy/scipy.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
from scipy.optimize import minimize
from scipy.special import log_ndtr

from ..errors import ArchInputError, FitError

_LOG_SQRT_2PI = 0.5 * math.log(2.0 * math.pi)


# --------------------------------------------------------------------------- optimisation core

def _minimise(fun, x0, args) -> np.ndarray:
    """Minimise a smooth objective (value, gradient) over (ln theta, ln beta).

    Working in logs keeps theta, beta > 0 without bounds.  BFGS with the analytic gradient is
    fast; Nelder-Mead from its end point is the fallback when line searches stall (flat tails).
    Both bounded in iterations (BFGS 400, SciPy's default for two unknowns, made explicit;
    Nelder-Mead 4000); where neither converges the data identify no fit: FitError (a study
    reports it as "no fit", it does not stop).
    """
    res = minimize(fun, x0, args=args, jac=True, method="BFGS",
                   options={"gtol": 1e-9, "maxiter": _BFGS_MAXITER})
    if res.success or np.max(np.abs(res.jac)) < 1e-6:
        return res.x
    res2 = minimize(lambda p, *a: fun(p, *a)[0], res.x, args=args, method="Nelder-Mead",
                    options={"xatol": 1e-10, "fatol": 1e-14, "maxiter": _NM_MAXITER})
    if res2.success and np.all(np.isfinite(res2.x)):
        return res2.x
    raise FitError(f"data: the likelihood maximisation did not converge in {_BFGS_MAXITER} BFGS "
                   f"and {_NM_MAXITER} Nelder-Mead iterations ({res.message}); no fit")


#: iteration bounds of :func:`_minimise`
_BFGS_MAXITER, _NM_MAXITER = 400, 4000


def _stripes_negll(params, lnx, n, z, scale):
    """Negative binomial log-likelihood (without the constant) / scale, and its gradient."""
    lt, lb = params
    b = math.exp(lb)
    u = (lnx - lt) / b
    lc, ls = log_ndtr(u), log_ndtr(-u)  # ln Phi(u), ln(1 - Phi(u)) without cancellation
    ll = np.sum(z * lc + (n - z) * ls)
    logphi = -0.5 * u * u - _LOG_SQRT_2PI
    # d ll / du; the Mills ratios phi/Phi stay finite in the tails (~|u|), no overflow.
    dll = z * np.exp(logphi - lc) - (n - z) * np.exp(logphi - ls)
    grad = np.array([np.sum(dll) / -b, -np.sum(dll * u)])
    return -ll / scale, -grad / scale


def _censored_negll(params, lnx, lnm, scale):
    """Negative log-likelihood of log-normal data lnx with survivors censored at lnm (/scale)."""
    lt, lb = params
    b = math.exp(lb)
    u = (lnx - lt) / b
    v = (lnm - lt) / b
    ls = log_ndtr(-v)
    ll = np.sum(-lb - _LOG_SQRT_2PI - 0.5 * u * u) + np.sum(ls)
    # d/dlt: sum(u)/b + sum(h(v))/b ; d/dlb: sum(u^2 - 1) + sum(h(v) v), with h = phi/(1-Phi)
    h = np.exp(-0.5 * v * v - _LOG_SQRT_2PI - ls)
    g_lt = (np.sum(u) + np.sum(h)) / b
    g_lb = np.sum(u * u - 1.0) + np.sum(h * v)
    return -ll / scale, -np.array([g_lt, g_lb]) / scale


# --------------------------------------------------------------------------- plateau

#: level of the likelihood ratio test that decides whether the data level off (:func:`_level_off`)
LEVEL_OFF_ALPHA = 0.05
#: the least gap 1 - p_max that counts as levelling off: with hundreds of runs a stripe a
#: percent or two under the lognormal is significant yet changes no decision, and the plain
#: curve stays the governing fit there (a 600-run suite tested p = 7e-10 at p_max = 0.980)
LEVEL_OFF_MIN_GAP = 0.05
#: bounds of the plateau fit: theta within e^3 (x20) of the intensities analysed, beta, p_max
_LT_MARGIN, _LB_BOUNDS, _P_BOUNDS = 3.0, (math.log(1e-3), math.log(10.0)), (1e-6, 1.0)


def _log1m_pphi(lp, l1p, ls):
    """ln(1 - p Phi(u)) = ln((1 - p) + p (1 - Phi(u))), from ln p, ln(1 - p) and ln(1 - Phi(u)):
    no cancellation where p = 1 and Phi(u) is near 1."""
    return np.logaddexp(l1p, lp + ls)


def _p_logs(p):
    return math.log(p), (math.log1p(-p) if p < 1.0 else -math.inf)


def _ida_plateau_negll(params, lnx, lnm, scale):
    """-log-likelihood / scale of collapses lnx (density p phi) and survivors censored at lnm
    (1 - p Phi), under P(x) = p Phi(ln(x/theta)/beta): a fraction 1 - p never collapses."""
    lt, lb, p = params
    b = math.exp(lb)
    lp, l1p = _p_logs(p)
    u = (lnx - lt) / b
    ll = np.sum(lp - lb - _LOG_SQRT_2PI - 0.5 * u * u)
    if lnm.size:
        ll += np.sum(_log1m_pphi(lp, l1p, log_ndtr(-(lnm - lt) / b)))
    return -ll / scale


def _stripes_plateau_negll(params, lnx, n, z, scale):
    """-binomial log-likelihood / scale (without the constant) of P(x) = p Phi(ln(x/theta)/beta)."""
    lt, lb, p = params
    u = (lnx - lt) / math.exp(lb)
    lp, l1p = _p_logs(p)
    ll = np.sum(z * (lp + log_ndtr(u)) + (n - z) * _log1m_pphi(lp, l1p, log_ndtr(-u)))
    return -ll / scale


def _fit_plateau(negll, starts, args, lnx_all, scale) -> tuple[np.ndarray, float]:
    """(ln theta, ln beta, p_max) maximising the plateau likelihood, and that log-likelihood
    (the objective is divided by ``scale``, the number of observations); L-BFGS-B inside bounds relative to the intensities analysed
    (theta within x20 of them, 1e-3 <= beta <= 10, 1e-6 <= p_max <= 1), from each start."""
    bounds = [(float(lnx_all.min()) - _LT_MARGIN, float(lnx_all.max()) + _LT_MARGIN),
              _LB_BOUNDS, _P_BOUNDS]
    best = None
    for x0 in starts:
        x0 = np.clip(np.asarray(x0, float), [b[0] for b in bounds], [b[1] for b in bounds])
        res = minimize(negll, x0, args=(*args, scale), method="L-BFGS-B", bounds=bounds,
                       options={"maxiter": _BFGS_MAXITER, "ftol": 1e-13, "gtol": 1e-9})
        if np.all(np.isfinite(res.x)) and np.isfinite(res.fun) and (best is None or res.fun < best.fun):
            best = res
    if best is None:
        raise FitError("data: the plateau likelihood could not be maximised; no fit")
    return best.x, -float(best.fun) * scale


def _level_off(fit0, params, ll1: float):
    """Choose between the plain lognormal ``fit0`` and the plateau fit (``params``, its
    log-likelihood ``ll1``): likelihood ratio D = 2 (ll1 - ll0); p_max = 1 lies on
    the boundary, so D follows 1/2 chi2_0 + 1/2 chi2_1 under the plain model (Self & Liang 1987):
    p-value = chi2.sf(D, 1) / 2.  The plateau governs where p < LEVEL_OFF_ALPHA and p_max is at
    least LEVEL_OFF_MIN_GAP below 1."""
    from scipy.stats import chi2

    lt, lb, p = (float(v) for v in params)
    ll0 = float(fit0.log_likelihood)
    ll1 = max(ll1, ll0)  # the plateau model contains the plain one (p_max = 1)
    d = 2.0 * (ll1 - ll0)
    pval = 0.5 * float(chi2.sf(d, 1)) if d > 0 else 1.0
    levels = bool(pval < LEVEL_OFF_ALPHA and p <= 1.0 - LEVEL_OFF_MIN_GAP)
    if levels:
        note = (f"the data level off below P = 1: fitted with an upper asymptote p_max = {p:.3f} "
                f"(likelihood ratio {d:.1f}, p = {pval:.2g}); the plain lognormal (theta "
                f"{fit0.theta:.4g}, beta {fit0.beta:.3f}) would run to P = 1 where the data do not")
    elif pval < LEVEL_OFF_ALPHA and p < 1.0:
        note = (f"the plateau p_max = {p:.3f} is within {LEVEL_OFF_MIN_GAP:g} of P = 1 "
                f"(likelihood ratio {d:.1f}, p = {pval:.2g}): the plain lognormal is kept")
    else:
        note = (f"no levelling off below P = 1 detected (likelihood ratio {d:.2f}, p = "
                f"{pval:.2g}): the plain lognormal")
    info = {"test": "likelihood ratio, p_max < 1 against p_max = 1 (1/2 chi2_0 + 1/2 chi2_1)",
            "statistic": d, "p_value": pval, "alpha": LEVEL_OFF_ALPHA,
            "min_gap": LEVEL_OFF_MIN_GAP, "levels_off": levels,
            "p_max": p if levels else 1.0,
            "lognormal": {"theta": fit0.theta, "beta": fit0.beta, "log_likelihood": ll0},
            "note": note}
    if not levels:
        return replace(fit0, level_off=info)
    return replace(fit0, theta=math.exp(lt), beta=math.exp(lb), p_max=p,
                   log_likelihood=ll1, level_off=info)


def _check_plateau(plateau):
    if plateau not in (False, True, "auto"):
        raise ArchInputError(f"plateau: {plateau!r}; allowed False (plain lognormal), True (fit "
                             f"an upper asymptote p_max) or 'auto' (where a test says the data "
                             f"level off)")
    return plateau


def _with_plateau(fit0, plateau, negll, args, lnx_all, scale, p0, lnc, weights=None):
    """fit0 as it is (plateau False), the plateau fit (True), or the one the test chooses
    ('auto').  Starts: the plain fit with p_max = 1 and p0 (the fraction that collapsed at the
    top of the range), and the collapses' own log mean and spread (``lnc``, ``weights``)."""
    if plateau is False:
        return fit0
    lt0, lb0 = math.log(fit0.theta), math.log(fit0.beta)
    mc = float(np.average(lnc, weights=weights))
    sc = math.sqrt(max(float(np.average((lnc - mc) ** 2, weights=weights)), 1e-6))
    p0 = min(max(p0, 0.05), 1.0)
    try:
        params, ll1 = _fit_plateau(negll, [(lt0, lb0, 1.0), (lt0, lb0, p0),
                                           (mc, math.log(sc), p0)], args, lnx_all, scale)
    except FitError as exc:
        if plateau is True:
            raise
        # the plain fit stands; say the alternative could not be tried
        return replace(fit0, level_off={"levels_off": False, "p_max": 1.0,
                                        "note": f"plateau not tested: {exc}"})
    if plateau is True:
        lt, lb, p = (float(v) for v in params)
        return replace(fit0, theta=math.exp(lt), beta=math.exp(lb), p_max=p,
                       log_likelihood=ll1, level_off=None)
    return _level_off(fit0, params, ll1)
