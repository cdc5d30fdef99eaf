"""f_c as a factor of the Sobol indices (studies.sensitivity): one more input, ``fc``, that
sets each arch's strength; a nominal of finite strength without a strength spread keeps its
f_c on every arch; an infinite strength leaves the map as it was."""

import numpy as np
import pytest

from archrock.errors import ArchInputError
from archrock.geometry import Arch, oppenheim_arch
from archrock.geometry.sampling import Spreads
from archrock.studies.sensitivity import arches_from_inputs, input_layout


def test_fc_is_one_input_and_sets_each_arch_strength():
    nominal = oppenheim_arch().with_fc(4.0)
    spreads = Spreads(0.1, 0.1, 0.05, fc=0.5)
    layout = input_layout(nominal, spreads)
    assert layout[-1] == ("fc", "fc", 0, -1, -1) and len(layout) == 3 * nominal.n + 1
    x = np.zeros((3, len(layout)))
    x[:, -1] = [-1.0, 0.0, 0.5]
    arches = arches_from_inputs(nominal, spreads, x)
    assert all(isinstance(a, Arch) for a in arches)
    assert np.allclose([a.fc for a in arches], [2.0, 4.0, 5.0], rtol=1e-15, atol=0)
    # the voussoir inputs at 0: the nominal's blocks, whatever the strength input
    assert all(np.allclose(a.joint_points, nominal.joint_points, rtol=0, atol=1e-12)
               for a in arches)


def test_a_fixed_strength_is_kept_and_infinite_strength_is_unchanged():
    spreads = Spreads(0.1, 0.1, 0.05)
    x = np.random.default_rng(0).uniform(-1, 1, (4, 3 * 7))
    plain = arches_from_inputs(oppenheim_arch(), spreads, x)
    strong = arches_from_inputs(oppenheim_arch().with_fc(3.0), spreads, x)
    assert isinstance(plain, tuple)  # circular arrays, as before
    for b, a in enumerate(strong):
        assert a.fc == pytest.approx(3.0, rel=0, abs=0)
        assert np.array_equal(a.spans, plain[0][b]) and np.array_equal(a.thicknesses, plain[1][b])


def test_strength_spread_without_strength_is_refused():
    with pytest.raises(ArchInputError, match=r"^spread fc: 0\.3 .*allowed 0"):
        input_layout(oppenheim_arch(), Spreads(fc=0.3))


@pytest.mark.slow  # 96 arches through the finite-strength statics: about 13 s
def test_sobol_indices_with_fc_as_a_factor():
    pytest.importorskip("SALib")
    from archrock.studies.sensitivity import sobol_indices

    res = sobol_indices(oppenheim_arch().with_fc(2.0), Spreads(0.0, 0.0, 0.0, fc=0.5),
                        samples=16, motion=None, num_resamples=20)
    assert res.groups[-1] == "fc" and res.unusable == 0
    # only the strength is spread: all of k's variance is the fc input's
    k = res.outputs.index("k")
    assert res.variance[k] > 0
    assert res.index("k", "fc", "ST") == pytest.approx(1.0, abs=0.1)
    assert res.index("k", "span", "ST") == pytest.approx(0.0, abs=1e-9)
