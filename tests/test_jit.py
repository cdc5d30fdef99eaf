"""The package digest that stamps numba caches and ensemble batch files."""

from __future__ import annotations

import shutil
from pathlib import Path

import archrock
from archrock._jit import _package_digest


def _copy(tmp_path) -> Path:
    root = tmp_path / "archrock"
    shutil.copytree(Path(archrock.__file__).parent, root,
                    ignore=shutil.ignore_patterns("__pycache__", "*.pyc"))
    return root


def test_digest_covers_subpackages(tmp_path):
    root = _copy(tmp_path)
    assert _package_digest(root) == _package_digest()
    # a change in a subpackage's module (not only in a top-level one) changes it
    spec = root / "groundmotion" / "spec.py"
    spec.write_text(spec.read_text() + "\n# changed\n")
    changed = _package_digest(root)
    assert changed != _package_digest()
    # so does a new module deeper down, and a rename
    deep = root / "groundmotion" / "extra"
    deep.mkdir()
    (deep / "__init__.py").write_text("")
    added = _package_digest(root)
    assert added != changed
    (deep / "__init__.py").rename(deep / "other.py")
    assert _package_digest(root) not in (added, changed)


def test_digest_ignores_non_sources(tmp_path):
    root = _copy(tmp_path)
    (root / "notes.txt").write_text("not a source")
    (root / "groundmotion" / "__pycache__").mkdir(exist_ok=True)
    (root / "groundmotion" / "__pycache__" / "spec.cpython-311.pyc").write_bytes(b"\0")
    assert _package_digest(root) == _package_digest()
