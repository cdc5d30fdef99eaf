"""Strict JSON at the edge: what the command line prints and the app answers."""

from __future__ import annotations

import math


def json_safe(obj):
    """``obj`` with every non-finite float (NaN, inf; numpy's too) replaced by None, so that
    it is strict JSON: an undefined statistic (the std of one sample, a fit with no collapse)
    reads null rather than breaking the output."""
    if isinstance(obj, dict):
        return {k: json_safe(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [json_safe(v) for v in obj]
    if hasattr(obj, "tolist") and hasattr(obj, "dtype"):  # numpy scalar or array
        return json_safe(obj.tolist())
    if isinstance(obj, float) and not math.isfinite(obj):
        return None
    return obj
