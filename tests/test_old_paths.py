"""archrock 0.5's flat module paths (aliased with a warning in 0.6) are gone in 0.7: importing one
fails plainly, and no finder of archrock's is left on the import path to revive them."""

import importlib
import pickle
import subprocess
import sys

import pytest

#: the 0.5 names (under ``archrock.``) that 0.6 moved into the folder of their layer
OLD = ("sampling", "files", "dxf", "limit", "friction", "thrust", "mechanism", "impact", "kernel",
       "response", "batch", "population", "sweep", "ensemble", "curves", "fragility", "ida",
       "sensitivity", "defectmap", "codecheck", "verification", "assessment", "work",
       "studyrun", "study", "plots", "animate", "contactplots")


@pytest.mark.parametrize("old", OLD)
def test_old_path_is_not_importable(old):
    sys.modules.pop(f"archrock.{old}", None)
    with pytest.raises(ModuleNotFoundError, match=f"archrock.{old}"):
        importlib.import_module(f"archrock.{old}")


def test_old_submodule_and_attribute_are_gone():
    import archrock

    with pytest.raises(ModuleNotFoundError, match="archrock.impact"):
        importlib.import_module("archrock.impact.laws")
    with pytest.raises(AttributeError, match="'limit'"):
        archrock.limit  # noqa: B018
    # the new paths are where the names live
    from archrock.dynamics.impact.laws import ImpactLaw
    from archrock.statics.limit import limit_analysis

    assert ImpactLaw.__module__ == "archrock.dynamics.impact.laws"
    assert limit_analysis.__module__ == "archrock.statics.limit"


def test_no_alias_finder_on_the_import_path():
    importlib.import_module("archrock")
    assert not [f for f in sys.meta_path if type(f).__module__.startswith("archrock")]


def test_fresh_interpreter_old_import_line_fails():
    """The way a 0.5 script starts: a plain import of an old path in a new process."""
    code = ("try:\n    from archrock.limit import limit_analysis\n"
            "except ModuleNotFoundError as e:\n    print('missing:', e.name)\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == "missing: archrock.limit"


def test_pickles_name_the_current_paths():
    """Result objects pickle under their current modules, and a pickle written before
    statics/limit.py was split (naming archrock.statics.limit) still loads."""
    from archrock.geometry import oppenheim_arch
    from archrock.statics.limit import limit_analysis

    res = limit_analysis(oppenheim_arch())
    blob = pickle.dumps(res.mechanism_l)
    assert b"archrock.statics.hinges" in blob
    assert pickle.loads(blob) == res.mechanism_l
    before = pickle.dumps(res.mechanism_l, protocol=2).replace(b"archrock.statics.hinges",
                                                               b"archrock.statics.limit")
    assert b"archrock.statics.hinges" not in before
    assert pickle.loads(before) == res.mechanism_l
