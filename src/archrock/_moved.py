"""Old import paths of archrock 0.5 (a flat package) kept working for one release.

0.6 put every module in the folder of its layer (docs/architecture.md).  ``import
archrock.limit`` and ``from archrock.impact.laws import ...`` still work but warn
(DeprecationWarning) and give the module at its new place: the same module object, so classes,
``isinstance`` checks and pickles are those of the new path, never a second copy.  Removed in 0.7.
"""

from __future__ import annotations

import importlib
import importlib.abc
import importlib.util
import sys
import warnings

#: old name (under ``archrock.``) -> new name; a package's submodules follow it
MOVED = {
    "sampling": "geometry.sampling", "files": "geometry.files", "dxf": "geometry.dxf",
    "limit": "statics.limit", "friction": "statics.friction", "thrust": "statics.thrust",
    "mechanism": "dynamics.fourlink", "impact": "dynamics.impact", "kernel": "dynamics.kernel",
    "response": "dynamics.response", "batch": "dynamics.batch",
    "population": "dynamics.population", "sweep": "dynamics.sweep",
    "ensemble": "studies.ensemble", "curves": "studies.curves", "fragility": "studies.fragility",
    "ida": "studies.ida", "sensitivity": "studies.sensitivity", "defectmap": "studies.defectmap",
    "codecheck": "studies.codecheck", "verification": "studies.verification",
    "assessment": "studies.assessment", "work": "studies.work", "studyrun": "studies.runner",
    "study": "studies.paper",
    "plots": "reports.plots", "animate": "reports.animate",
    "contactplots": "reports.contactplots",
}


def new_name(name: str) -> str | None:
    """The current full name of an old full module name, or None when it did not move."""
    parts = name.split(".")
    if len(parts) < 2 or parts[0] != "archrock" or parts[1] not in MOVED:
        return None
    return ".".join(["archrock", MOVED[parts[1]], *parts[2:]])


def warn(old: str, new: str, stacklevel: int = 3) -> None:
    warnings.warn(f"{old} moved to {new} in archrock 0.6; the old path goes in 0.7",
                  DeprecationWarning, stacklevel=stacklevel)


class _Alias(importlib.abc.MetaPathFinder, importlib.abc.Loader):
    """Resolves an old name to the module at its new name (imported once, under that name)."""

    def find_spec(self, fullname, path=None, target=None):
        new = new_name(fullname)
        if new is None:
            return None
        return importlib.util.spec_from_loader(fullname, self, is_package=False)

    def create_module(self, spec):
        new = new_name(spec.name)
        warn(spec.name, new, stacklevel=8)
        module = importlib.import_module(new)
        # its own spec, kept the first time (by the new name: aliases may nest)
        _REAL_SPECS.setdefault(new, module.__spec__)
        return module

    def exec_module(self, module):
        # the module at its new name is already executed; the import system has just set its
        # __spec__ to the old name's, which would make the module's own relative imports
        # resolve against the old package: give it back its own
        module.__spec__ = _REAL_SPECS[module.__name__]


#: new full name -> the module's own spec (restored after each alias import)
_REAL_SPECS: dict = {}


def install() -> None:
    # first on the path: otherwise the path finder would load a second copy of a moved
    # package's submodule through the package's own __path__
    if not any(isinstance(f, _Alias) for f in sys.meta_path):
        sys.meta_path.insert(0, _Alias())
