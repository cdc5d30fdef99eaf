"""A record suite: a folder of accelerograms read once, each with its file's sha256.

A suite is a folder of ``.AT2`` files or one of the built-in FEMA P695 sets (:mod:`.p695`,
extra ``records``).  A fragility study runs every record of a suite on every arch at many scale factors.  The suite is
read here once (:func:`read_suite`); the study packs the records end to end
(:class:`archrock.dynamics.sweep.SweepMotions`) and hands them to every worker once, and the results name
each record with the sha256 of its file, so a result can be traced to the exact files.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from ..errors import ArchInputError
from .motion import GroundMotion
from .p695 import SUITES, is_suite, is_suite_ref, suite_refs
from .records import file_sha256, load_record

__all__ = ["RecordSuite", "read_suite", "read_records", "record_paths", "suite_files",
           "file_sha256"]

#: suffixes of the record files a suite folder holds (any case)
SUITE_SUFFIXES = (".at2",)


@dataclass(frozen=True, eq=False)
class RecordSuite:
    """Records read from files: ``records[i]`` from ``files[i]`` with ``sha256[i]``."""

    records: tuple
    files: tuple
    sha256: tuple

    def __len__(self) -> int:
        return len(self.records)

    def __iter__(self):
        return iter(self.records)

    def to_dict(self) -> list:
        return [{"name": r.name, "file": f, "sha256": h, "pga_g": r.pga_g,
                 "duration": float(r.times[-1])}
                for r, f, h in zip(self.records, self.files, self.sha256)]


def suite_files(folder) -> list[Path]:
    """The record files of a suite folder: its PEER ``.AT2`` files (not its subfolders'), in
    file-name order; ArchInputError when it is no folder or holds none."""
    p = Path(folder)
    if not p.is_dir():
        raise ArchInputError(f"records: {str(folder)!r} is not a folder; allowed a folder of "
                             f"PEER .AT2 files")
    files = sorted(f for f in p.iterdir() if f.is_file() and f.suffix.lower() in SUITE_SUFFIXES)
    if not files:
        raise ArchInputError(f"records: no .AT2 file in the folder {str(folder)!r}; allowed a "
                             f"folder holding PEER .AT2 files")
    return files


def record_paths(items) -> tuple:
    """Record files, folders and built-in suites, in the order given, as the records they name
    (a folder stands for :func:`suite_files`, a suite such as ``p695-far-field`` for its
    records ``SUITE/ID``): the one reading of a ``--records`` list in every command."""
    out = []
    for item in items or ():
        if is_suite(item):  # a built-in suite stands for its records, SUITE/ID each
            out += list(suite_refs(item))
            continue
        if is_suite_ref(item):
            out.append(item.strip())
            continue
        p = Path(item)
        if p.is_dir():
            out += [str(f) for f in suite_files(p)]
        elif p.is_file():
            out.append(str(p))
        else:
            raise ArchInputError(f"records: {str(item)!r} is neither a file nor a folder; "
                                 f"allowed record files (PEER .AT2 or two-column text), "
                                 f"folders of .AT2 files and the suites {', '.join(SUITES)}")
    return tuple(out)


def read_suite(folder, units: str | None = None) -> RecordSuite:
    """Every PEER ``.AT2`` file of ``folder`` (not its subfolders), in file-name order."""
    return read_records(suite_files(folder), units)


def read_records(paths, units: str | None = None) -> RecordSuite:
    """Record files and folders (a folder stands for its :func:`read_suite`), in the order given,
    each read once; two paths naming the same file are refused."""
    files = record_paths(paths)
    records = [load_record(p, units=units) for p in files]
    shas = [file_sha256(p) for p in files]
    seen = {}
    for f, h in zip(files, shas):
        key = f if is_suite_ref(f) else str(Path(f).resolve())
        if key in seen:
            raise ArchInputError(f"records: {f!r} is given twice; allowed each record once")
        seen[key] = h
    if not records or not all(isinstance(r, GroundMotion) for r in records):
        raise ArchInputError("records: allowed at least one record file or folder")
    return RecordSuite(tuple(records), tuple(str(f) for f in files), tuple(shas))
