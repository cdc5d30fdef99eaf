"""Work bounds of the studies: estimate a study's computing time before starting it, refuse it
beyond :data:`MAX_WORK_S` (:class:`~archrock.errors.LimitExceededError`, saying how to proceed)
and warn above :data:`WARN_WORK_S`.

The costs are rough (within a factor of a few): measured on the 2-core development machine
with numba; without numba the kernels run about :data:`NO_NUMBA_FACTOR` times slower.
"""

from __future__ import annotations

import os
import warnings

from .._jit import HAVE_NUMBA
from ..errors import LimitExceededError

__all__ = ["MAX_WORK_S", "WARN_WORK_S", "PROGRESS_S", "response_cost_s", "check_work",
           "format_duration"]

#: Seconds of one outcome-only response to a pulse (collapse_amplitude on Oppenheim's arch:
#: 168 responses in 0.062 s).
PULSE_RESPONSE_S = 4e-4
#: Extra seconds per second of a record (a 20 s record: about 3 ms a response).
RECORD_RESPONSE_S_PER_S = 1.5e-4
#: One random arch of an ensemble: limit analysis alone (bench_limit: ~1e5 arches/s) ...
SAMPLE_LIMIT_S = 2e-5
#: ... and with its response to a pulse (bench_ensemble: 10,000 arches in 5.6 s on one core).
SAMPLE_RESPONSE_S = 6e-4
#: One random arch of finite compressive strength prepared (the crushing statics and the four-link
#: models, one arch at a time in Python: 40 arches of 7 and of 15 voussoirs in 0.10-0.16 s each on
#: the loaded 2-core development machine).
SAMPLE_FINITE_S = 0.15
#: One bootstrap fit: moments (~70 us) or the stripes' maximum likelihood (~2 ms).
FIT_MOMENTS_S, FIT_MLE_S = 7e-5, 2e-3
#: Slow-down of the pure-Python kernels (ARCHROCK_NO_NUMBA=1 or numba missing).
NO_NUMBA_FACTOR = 50.0

#: Above this estimate [s] a study is refused: a day of this machine is beyond what a command
#: should start unasked (a typo such as --samples 10**12 or --scales 0.1:3:1000000). Set the
#: environment variable ARCHROCK_MAX_WORK_S to allow more.
MAX_WORK_S = 24 * 3600.0
#: Above this estimate [s] a warning says how long the study will take.
WARN_WORK_S = 60.0
#: Above this estimate [s] a study shows its progress on stderr (when asked to).
PROGRESS_S = 2.0


def response_cost_s(duration: float | None = None) -> float:
    """Seconds of one response to a pulse (``duration`` None) or to a record of ``duration`` s,
    with numba (:func:`check_work` scales it without)."""
    return PULSE_RESPONSE_S + (0.0 if duration is None else RECORD_RESPONSE_S_PER_S * duration)


def format_duration(s: float) -> str:
    for unit, size in (("days", 86400.0), ("h", 3600.0), ("min", 60.0)):
        if s >= size:
            return f"{s / size:.3g} {unit}"
    return f"{s:.2g} s"


def _max_work_s() -> float:
    try:
        return float(os.environ.get("ARCHROCK_MAX_WORK_S", MAX_WORK_S))
    except ValueError:
        return MAX_WORK_S


def check_work(what: str, units: float, unit: str, seconds_each: float, advice: str,
               workers: int = 1, kernel: bool = True) -> float:
    """Estimated seconds of ``units`` pieces of work of ``seconds_each`` (measured with numba;
    ``kernel``: slower without it) on ``workers`` cores; LimitExceededError above
    :data:`MAX_WORK_S` (with ``advice``: how to proceed), a warning above
    :data:`WARN_WORK_S`. Returns the estimate."""
    each = seconds_each * (NO_NUMBA_FACTOR if kernel and not HAVE_NUMBA else 1.0)
    est = float(units) * each / max(1, min(workers, os.cpu_count() or 1))
    limit = _max_work_s()
    said = f"{what}: about {units:.3g} {unit}, estimated {format_duration(est)} on this machine"
    if est > limit:
        raise LimitExceededError(f"{said}; allowed up to {format_duration(limit)} "
                                 f"(ARCHROCK_MAX_WORK_S); {advice}")
    if est > WARN_WORK_S:
        warnings.warn(said, stacklevel=3)
    return est

