"""Reading and writing arch geometry files (JSON).

Two formats (docs/geometry.md), voussoirs ordered from the left springing, lengths in metres,
density in kg/m^3 (optional), loads optional in both ([kg per metre of depth] at [x, y])::

    {"voussoirs": [{"span_deg": 22.5, "radius": 10.0, "thickness": 1.5}, ...],
     "density": 2000, "loads": [{"voussoir": 3, "mass": 8000.0, "at": [0.0, 11.0]}]}

a circular :class:`~archrock.geometry.Arch` (spans in degrees), or::

    {"voussoirs": [{"intrados": [[x, y], ...], "extrados": [[x, y], ...]}, ...],
     "density": 2000, "loads": [{"voussoir": 5, "mass": 8000.0, "at": [6.0, 9.0]}]}

a :class:`~archrock.geometry.PolygonArch` (each line from left to right).  A polygon block may
carry ``"kind": "pier" | "buttress" | "voussoir"`` (an arch on piers, docs/piers.md): the file is
then read as an :class:`~archrock.geometry.ArchOnPiers`, and a kind not in that list is refused.

A third kind of document, ``{"kind": "arcade", "blocks": [...], "contacts": [...]}``, holds an
arcade (several arches on shared piers: blocks with their contacts, docs/arcades.md):
:func:`read_arcade` / :func:`write_arcade` (:meth:`archrock.geometry.arcade.Arcade.to_dict`).
:func:`read_arch` refuses it by name.

Every error is an :class:`~archrock.errors.ArchInputError` whose one-line message names the
file and the offending field.
"""

from __future__ import annotations

import json
import os
from pathlib import Path

from ..errors import ArchInputError
from . import VoussoirArch, arch_from_dict
from .inputfile import read_input

__all__ = ["read_arch", "write_arch", "read_arcade", "write_arcade"]


def read_arch(path: str | os.PathLike) -> VoussoirArch:
    """Read an arch from a JSON geometry file of either format (module docstring); name = file
    stem."""
    p = Path(path)
    data = _read_json(p, "geometry")
    if isinstance(data, dict) and data.get("kind") == "arcade":
        raise ArchInputError(f"{p}: an arcade document (several spans); allowed an arch here "
                             f"(read it with `archrock arcade --geometry`)")
    try:
        return arch_from_dict(data, name=p.stem)
    except ArchInputError as exc:
        raise ArchInputError(f"{p}: {exc}") from None


def read_arcade(path: str | os.PathLike, on_size=None):
    """Read an arcade document (module docstring) as an :class:`~archrock.geometry.arcade.
    Arcade`; name = file stem.  ``on_size``: called with the number of blocks the document
    lists before they are checked (a work bound can refuse it first)."""
    from .arcade import Arcade

    p = Path(path)
    data = _read_json(p, "arcade")
    if on_size is not None and isinstance(data, dict) and isinstance(data.get("blocks"), list):
        on_size(len(data["blocks"]))
    try:
        return Arcade.from_dict(data, name=p.stem)
    except ArchInputError as exc:
        raise ArchInputError(f"{p}: {exc}") from None


def write_arcade(arcade, path: str | os.PathLike, metadata: dict | None = None) -> Path:
    """Write an :class:`~archrock.geometry.arcade.Arcade` as its JSON document (repr-precision
    floats: :func:`read_arcade` gives it back to the bit). Returns the path."""
    from .arcade import Arcade

    if not isinstance(arcade, Arcade):
        raise ArchInputError(f"arcade: expected an Arcade, got {type(arcade).__name__}")
    data = arcade.to_dict()
    if metadata:
        data["metadata"] = metadata
    return _write_json(data, Path(path))


def _read_json(p: Path, kind: str):
    """The JSON document of file ``p`` of ``kind`` ('geometry' or 'arcade'), bounded by size
    (:mod:`.inputfile`)."""
    try:
        text = read_input(p, kind).decode("utf-8")
    except UnicodeDecodeError as exc:
        raise ArchInputError(f"{p}: not a text file (UTF-8 decoding failed at byte {exc.start})") from None
    try:
        # NaN/Infinity tokens (not JSON, but Python writes them) are parsed here and refused
        # by the arch's from_dict, whose message names the voussoir and field that hold them.
        data = json.loads(text)
    except json.JSONDecodeError as exc:
        raise ArchInputError(
            f"{p}: invalid JSON at line {exc.lineno}, column {exc.colno}: {exc.msg}") from None
    except RecursionError:
        raise ArchInputError(f"{p}: invalid JSON: nested too deeply") from None
    except ValueError:  # an integer of over 4300 digits (Python's int-from-text limit)
        raise ArchInputError(f"{p}: invalid JSON: a number of more than 4300 digits; allowed "
                             f"numbers within double precision") from None
    return data


def write_arch(arch: VoussoirArch, path: str | os.PathLike, metadata: dict | None = None) -> Path:
    """Write ``arch`` (circular or polygon) as a JSON geometry file; ``metadata`` (JSON-serialisable) is stored
    under the key ``"metadata"`` and ignored by :func:`read_arch`. Returns the path."""
    if not isinstance(arch, VoussoirArch):
        raise ArchInputError(f"arch: expected an arch (Arch or PolygonArch), got "
                             f"{type(arch).__name__}")
    p = Path(path)
    data = arch.to_dict()
    if metadata:
        data["metadata"] = metadata
    return _write_json(data, p)


def _write_json(data: dict, p: Path) -> Path:
    # repr-precision floats: read_arch(write_arch(a)) reproduces the arch to the last bit of
    # radius/thickness and of polygon points (spans go through degrees, exact to ~1e-16 rad).
    text = json.dumps(data, indent=2, allow_nan=False) + "\n"
    try:
        p.write_text(text, encoding="utf-8")
    except OSError as exc:
        raise ArchInputError(f"{p}: cannot write the geometry file ({exc.strerror or exc})") from None
    return p
