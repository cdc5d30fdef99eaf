"""Old import paths (archrock 0.5's flat package) still work for one release, warn, and give
the very module at its new place (no second copy of any class)."""

import importlib
import pickle
import subprocess
import sys

import pytest

from archrock import _moved


@pytest.mark.parametrize("old", sorted(_moved.MOVED))
def test_every_old_path_is_the_new_module(old):
    new = importlib.import_module(f"archrock.{_moved.MOVED[old]}")
    sys.modules.pop(f"archrock.{old}", None)
    with pytest.warns(DeprecationWarning, match=f"archrock.{old} moved to archrock."):
        mod = importlib.import_module(f"archrock.{old}")
    assert mod is new
    # the module keeps its own spec: its relative imports still resolve from its new package
    # (an aliased __spec__ made later lazy imports inside it warn, in whatever test ran next)
    assert mod.__spec__.name == f"archrock.{_moved.MOVED[old]}"


def test_submodule_of_a_moved_package_is_not_a_second_copy():
    from archrock.dynamics.impact.laws import ImpactLaw

    sys.modules.pop("archrock.impact", None)
    sys.modules.pop("archrock.impact.laws", None)
    with pytest.warns(DeprecationWarning):
        from archrock.impact.laws import ImpactLaw as Old
    assert Old is ImpactLaw
    assert sys.modules["archrock.impact.laws"] is sys.modules["archrock.dynamics.impact.laws"]


def test_attribute_access_and_pickles_use_the_new_path():
    import archrock
    from archrock.geometry import oppenheim_arch
    from archrock.statics.limit import limit_analysis

    # an earlier import of archrock.limit leaves the attribute on the package: start clean
    vars(archrock).pop("limit", None)
    sys.modules.pop("archrock.limit", None)
    with pytest.warns(DeprecationWarning):
        old = archrock.limit
    assert old.limit_analysis is limit_analysis
    res = limit_analysis(oppenheim_arch())
    blob = pickle.dumps(res.mechanism_l)
    assert b"archrock.statics.hinges" in blob and b"archrock.limit\n" not in blob
    assert pickle.loads(blob) == res.mechanism_l
    # a pickle written before statics/limit.py was split names archrock.statics.limit: the
    # same class objects, re-exported there
    before = pickle.dumps(res.mechanism_l, protocol=2).replace(b"archrock.statics.hinges",
                                                               b"archrock.statics.limit")
    assert b"archrock.statics.hinges" not in before
    assert pickle.loads(before) == res.mechanism_l


def test_fresh_interpreter_old_import_line():
    """The way a 0.5 script starts: a plain import of an old path in a new process."""
    code = ("import warnings; warnings.simplefilter('error', DeprecationWarning)\n"
            "try:\n    from archrock.limit import limit_analysis\n"
            "except DeprecationWarning as w:\n    print('warned:', w)\n"
            "from archrock.statics.limit import limit_analysis\nprint(limit_analysis.__module__)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    assert out.returncode == 0, out.stderr
    assert "warned: archrock.limit moved to archrock.statics.limit" in out.stdout
    assert out.stdout.strip().endswith("archrock.statics.limit")
