"""The property sweep's arches with no mechanism under Heyman's hypotheses (the static LP is
unbounded: wedged between their springings, they carry any horizontal load) all have a finite
collapse multiplier once the masonry has a finite compressive strength.

tests/data/sweep_no_mechanism.json lists them: the 39 of benchmarks/sweep_limit.py's 400 arches
(seed 0, 3 to 200 voussoirs) found by solving each one's static LP."""

from __future__ import annotations

import json
import math
import sys
from pathlib import Path

import pytest

from archrock.errors import GeometryOutcome
from archrock.statics.limit import limit_analysis

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "benchmarks"))
from sweep_limit import build  # noqa: E402

CASES = json.loads((Path(__file__).resolve().parents[1] / "data" /
                    "sweep_no_mechanism.json").read_text())["cases"]
#: the ones with at most 20 voussoirs run by default; the rest are slow
SMALL = [c for c in CASES if c[1][3] <= 20]


def _check(case, fc):
    arch = build(*case[1])
    with pytest.raises(GeometryOutcome, match="no mechanism"):
        limit_analysis(arch)
    res = limit_analysis(arch.with_fc(fc))
    assert math.isfinite(res.k) and res.k > 0
    for d in "lr":
        lo, hi = getattr(res, f"k_bounds_{d}")
        assert lo <= getattr(res, f"k_{d}") * (1 + 1e-9) and hi - lo <= 1e-6 * abs(hi)
    return res.k


def test_the_list_is_the_sweeps_39():
    assert len(CASES) == 39 and len(SMALL) == 4


@pytest.mark.parametrize("case", SMALL, ids=[str(c[0]) for c in SMALL])
def test_small_sweep_arches_get_a_finite_k(case):
    k5 = _check(case, 5.0)
    # weaker masonry carries less
    assert limit_analysis(build(*case[1]).with_fc(2.0)).k < k5


@pytest.mark.slow
@pytest.mark.parametrize("case", [c for c in CASES if c not in SMALL],
                         ids=[str(c[0]) for c in CASES if c not in SMALL])
def test_every_sweep_arch_gets_a_finite_k(case):
    _check(case, 5.0)
