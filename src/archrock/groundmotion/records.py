"""Readers of recorded ground motions: two-column text files and PEER NGA ``.AT2`` files.

Every bad file raises :class:`archrock.errors.ArchInputError` with a one-line message naming the
file, the line and what is allowed.
"""

from __future__ import annotations

import hashlib
import io
import itertools
import math
from array import array
from collections.abc import Iterator
import re
import warnings
from pathlib import Path

import numpy as np

from ..errors import ArchInputError
from ..geometry.inputfile import read_input
from ..units import G
from .p695 import is_suite, is_suite_ref, record_sha256, suite_motion
from .motion import (MAX_RECORD_DT_S, WARN_RECORD_DT_S, GroundMotion, _unit_factor,
                     check_pga)

#: A two-column file is a sampled record, checked as a PEER ``.AT2`` file is (time step at most
#: MAX_RECORD_DT_S, warned above WARN_RECORD_DT_S), unless it is a corner list: a
#: piecewise-linear motion given by its corners, where long intervals are meant, declared by a
#: comment line ``# corners``.  Every record, sampled or corners, file or upload, has strictly
#: increasing times (:func:`check_time_order`).
CORNERS_MARK = "corners"
_CORNERS_HINT = f"a piecewise-linear motion given by its corners: put a '# {CORNERS_MARK}' line first"
#: How a step (a jump of the acceleration) is written in a record: a short ramp, not a time twice.
STEP_HINT = "one value per instant; write a step as a short ramp, e.g. '0.2 -1' then '0.2001 0.5'"

__all__ = ["read_two_column", "read_at2", "load_record", "file_sha256", "check_time_order"]


def file_sha256(path) -> str:
    """sha256 of a record file's bytes (hex): the checksum every record spec and suite carries.
    Read through the bounded reader (a stream such as /dev/urandom is refused, not hashed
    forever).  A built-in suite's record (``p695-far-field/1a``) has the sha256 of its samples
    (:func:`archrock.groundmotion.p695.record_sha256`)."""
    if is_suite_ref(path):
        return record_sha256(path.strip())
    return hashlib.sha256(read_input(path, "record")).hexdigest()


def _short(text: str, limit: int = 60) -> str:
    """repr of a text snippet for a one-line message (repr escapes newlines)."""
    text = text.strip()
    if len(text) > limit:
        text = text[:limit] + "..."
    return repr(text)


def _read_lines(path) -> tuple[Path, "Iterator[str]"]:
    """The record's path and an iterator over its lines.  The lines are produced one at a time
    (never a list of them), so the memory a record takes is its bytes, its text and the arrays
    read from it, not a Python object per line (a 20 MB upload peaked at +380 MB before)."""
    if not isinstance(path, (str, Path)) and not hasattr(path, "__fspath__"):
        raise ArchInputError(f"record path: {path!r}; allowed a file path")
    p = Path(path)
    if not p.is_file():
        what = "is not a file" if p.exists() else "file not found"
        raise ArchInputError(f"record {p}: {what}; allowed an existing readable file")
    try:
        data = read_input(p, "record")  # bounded by size (geometry.inputfile)
    except ArchInputError as exc:
        raise ArchInputError(f"record {exc}") from None
    if b"\x00" in data:
        raise ArchInputError(f"record {p}: binary data; allowed a text file")
    try:
        data.decode("utf-8")  # validates; the text is decoded line by line below
        encoding = "utf-8"
    except UnicodeDecodeError:
        encoding = "latin-1"  # old headers may hold accented site names
    if b"\r" in data and b"\n" not in data:
        data = data.replace(b"\r", b"\n")  # a file whose lines end in CR alone
    # BytesIO shares the bytes (no copy) and splits on LF; the CR of PEER's CRLF is stripped
    return p, (raw.decode(encoding).rstrip("\r\n") for raw in io.BytesIO(data))


def check_time_order(what: str, line: int, t: float, prev_line: int, t_prev: float) -> None:
    """The one rule on a record's times: each row's time ``t`` [s] (file line ``line``) is
    strictly after the previous row's ``t_prev`` (line ``prev_line``).  A repeated time (two
    values at one instant) or a decreasing one raises ArchInputError naming ``what`` (the
    record), the line and the time.  Every reader of records applies it: the library's
    :func:`read_two_column` (so :func:`load_record`, RecordSpec, suites), the CLI's
    ``--record``/``--records`` and the app's upload, which all read through it."""
    if t > t_prev:
        return
    if t == t_prev:
        raise ArchInputError(f"{what}: line {line}: time {t:g} s repeats line {prev_line}; "
                             f"allowed strictly increasing times ({STEP_HINT})")
    raise ArchInputError(f"{what}: line {line}: time {t:g} s after {t_prev:g} s (line "
                         f"{prev_line}); allowed strictly increasing times")


def _number(p: Path, lineno: int, token: str) -> float:
    try:
        x = float(token)
    except ValueError:
        raise ArchInputError(f"record {p.name}: line {lineno}: {_short(token)} is not a number") from None
    if not math.isfinite(x):
        raise ArchInputError(f"record {p.name}: line {lineno}: {token!r} is not finite; allowed finite numbers")
    return x


def _units_cause(pga_g: float, units: str) -> str:
    """The likely cause of an implausible PGA read in ``units``, with the remedy: the units in
    which the same numbers would be a plausible PGA (0.005-3 g)."""
    if units != "g":
        return f"units? the values were read as {units}; is the file scaled?"
    value = pga_g  # the largest number in the file
    fits = [u for u, per_g in (("m/s2", G), ("cm/s2", 100 * G)) if 0.005 <= value / per_g <= 3.0]
    if not fits:
        return "units? the values were read as g"
    return (f"units? if the values are in {' or '.join(fits)}, give "
            + " or ".join(f"--units {u}" for u in fits))


def _check_record(p: Path, motion: GroundMotion, units: str, lineno_of=None,
                  corners_hint: bool = False) -> None:
    """Refuse or warn about a record that cannot be meant (PGA, time step; module constants
    of :mod:`.motion`). ``lineno_of(i)``: the file line of sample i, for the message."""
    pga_g = motion.pga / G
    check_pga(pga_g, f"record {p.name}", _units_cause(pga_g, units))
    dt = np.diff(motion.times)
    i = int(np.argmax(dt))
    where = f" (line {lineno_of(i + 1)})" if lineno_of is not None else ""
    cause = ("times in ms or in samples? a sampled accelerogram has a step of 0.005-0.02 s"
             if dt[i] >= 1.0 else "a record this coarse misses the pulses that rock an arch")
    if dt[i] > MAX_RECORD_DT_S:
        hint = f"; {_CORNERS_HINT}" if corners_hint else ""
        raise ArchInputError(f"record {p.name}: time step {dt[i]:g} s{where}; allowed at most "
                             f"{MAX_RECORD_DT_S:g} s ({cause}){hint}")
    if dt[i] > WARN_RECORD_DT_S:
        warnings.warn(f"record {p.name}: time step {dt[i]:g} s{where} is coarser than "
                      f"{WARN_RECORD_DT_S:g} s; {cause}", stacklevel=3)


def _is_number(token: str) -> bool:
    try:
        float(token)
    except ValueError:
        return False
    return True


def read_two_column(path, units: str = "g", name: str | None = None) -> GroundMotion:
    """Read "time accel" rows (whitespace- or comma-separated) into a GroundMotion.

    '#' starts a comment (whole line or trailing); blank lines are skipped; the first non-comment
    line may be a non-numeric header.  Times [s] must be >= 0 and strictly increasing
    (:func:`check_time_order`: a repeated time is refused; a step is a short ramp).  If the first
    time is > 0, a zero sample (0, 0) is prepended, so the record ramps from 0 to its first
    value.  ``units`` in UNITS, converted to m/s^2.

    A sampled record is checked as a PEER ``.AT2`` file is: a time step above MAX_RECORD_DT_S
    (0.1 s) is refused, above WARN_RECORD_DT_S (0.05 s) a warning.  A corner list (a
    ``# corners`` comment line) is a piecewise-linear motion by its corners: any interval.
    """
    factor = _unit_factor(units)
    p, lines = _read_lines(path)
    # typed arrays, 8 bytes a value: a list of Python floats costs four times that
    ts = array("d")
    acs = array("d")
    linenos = array("q")
    seen_first = False
    marked = False
    for lineno, raw in enumerate(lines, start=1):
        line, _, comment = raw.partition("#")
        line = line.strip()
        if not line and comment.strip().lower().startswith(CORNERS_MARK):
            marked = True
        if not line:
            continue
        tokens = line.replace(",", " ").replace(";", " ").split()
        if not seen_first:
            seen_first = True
            if not any(_is_number(tok) for tok in tokens):
                continue  # a header line such as "time, accel" (a line with a number is data)
        if len(tokens) != 2:
            raise ArchInputError(
                f"record {p.name}: line {lineno}: {len(tokens)} columns; allowed 2 (time accel)"
            )
        t = _number(p, lineno, tokens[0])
        a = _number(p, lineno, tokens[1])
        if not ts and t < 0.0:
            raise ArchInputError(f"record {p.name}: line {lineno}: time {t:g} s; allowed >= 0 s")
        if ts:
            check_time_order(f"record {p.name}", lineno, t, linenos[-1], ts[-1])
        ts.append(t)
        acs.append(a)
        linenos.append(lineno)
    if not ts:
        raise ArchInputError(f"record {p.name}: empty record (no 'time accel' rows); allowed >= 2 samples")
    if ts[0] > 0.0:
        ts.insert(0, 0.0)
        acs.insert(0, 0.0)
    if len(ts) < 2:
        raise ArchInputError(f"record {p.name}: 1 sample; allowed >= 2 samples")
    motion = GroundMotion(
        np.frombuffer(ts, dtype=float).copy(), np.frombuffer(acs, dtype=float) * factor, name if name is not None else p.stem,
        f"{p} (two-column, {units})",
    )
    if marked:
        check_pga(motion.pga / G, f"record {p.name}", _units_cause(motion.pga / G, units))
    else:
        off = len(ts) - len(linenos)  # 1 if a zero sample was put in front
        _check_record(p, motion, units, lambda i: linenos[max(i - off, 0)], corners_hint=True)
    return motion


_NGA_HEADER = re.compile(r"NPTS\s*=\s*(\S+?)\s*,?\s*DT\s*=\s*(\S+?)\s*,?\s*(SEC\b.*)?$", re.IGNORECASE)
_OLD_HEADER = re.compile(r"^\s*(\S+)\s+(\S+)\s+NPTS\s*,?\s*DT\b", re.IGNORECASE)


def read_at2(path) -> GroundMotion:
    """Read a PEER NGA ``.AT2`` acceleration file (values in g) into a GroundMotion [m/s^2].

    Four header lines; the 4th is ``NPTS=  5000, DT=   .0100 SEC,`` (NGA-West2; commas and case
    optional) or ``  4000    0.00500    NPTS, DT`` (older files).  Then NPTS values in free format.
    The value count must equal NPTS.  Samples at t = k DT, k = 0..NPTS-1.
    """
    p, line_iter = _read_lines(path)
    lines = list(itertools.islice(line_iter, 4))  # the header; the values are read as they come
    expected = "'NPTS= n, DT= dt SEC' (NGA-West2) or 'n dt NPTS, DT' (older PEER)"
    if len(lines) < 4:
        raise ArchInputError(
            f"record {p.name}: missing header ({len(lines)} lines); allowed 4 header lines, the 4th {expected}"
        )
    kind = lines[2].upper()
    m_units = re.search(r"UNITS\s+OF\s+(\S+)", kind)
    if "VELOCITY" in kind or "DISPLACEMENT" in kind or (
        m_units and m_units.group(1).strip(".,;:") not in ("G", "G'S")
    ):
        raise ArchInputError(f"record {p.name}: line 3: {_short(lines[2])}; allowed an acceleration record in g")
    head = lines[3].strip()
    m = _NGA_HEADER.search(head) or _OLD_HEADER.match(head)
    if m is None:
        raise ArchInputError(f"record {p.name}: line 4: header {_short(head)}; allowed {expected}")
    npts_tok, dt_tok = m.group(1), m.group(2)
    try:
        npts = int(npts_tok)
    except ValueError:
        raise ArchInputError(f"record {p.name}: line 4: NPTS {npts_tok!r}; allowed an integer >= 2") from None
    dt = _number(p, 4, dt_tok)
    if dt <= 0.0:
        raise ArchInputError(f"record {p.name}: line 4: DT {dt:g} s; allowed > 0 s")
    if npts < 2:
        what = "empty record, " if npts <= 0 else ""
        raise ArchInputError(f"record {p.name}: line 4: {what}NPTS {npts}; allowed an integer >= 2")
    values = array("d")
    for lineno, raw in enumerate(line_iter, start=5):
        for tok in raw.split():
            values.append(_number(p, lineno, tok))
    if len(values) != npts:
        few = "fewer" if len(values) < npts else "more"
        raise ArchInputError(
            f"record {p.name}: NPTS: header says {npts} but {len(values)} values found ({few}); "
            "allowed exactly NPTS values"
        )
    t = np.arange(npts) * dt
    acc = np.frombuffer(values, dtype=float) * G
    title = lines[1].strip()
    motion = GroundMotion(t, acc, title or p.stem, f"{p} (PEER AT2, g, NPTS={npts}, DT={dt:g} s)")
    _check_record(p, motion, "g (PEER .AT2)")
    return motion


def load_record(path, units: str | None = None) -> GroundMotion:
    """Read a record by suffix: ``.AT2`` (any case) -> :func:`read_at2` (units must be g or None),
    anything else -> :func:`read_two_column` with ``units`` (default 'g').  A built-in suite's
    record ``SUITE/ID`` (:mod:`.p695`; in g) is read from the suite."""
    if not isinstance(path, (str, Path)) and not hasattr(path, "__fspath__"):
        raise ArchInputError(f"record path: {path!r}; allowed a file path")
    if is_suite_ref(path):
        if units is not None and units != "g":
            raise ArchInputError(f"units: {units!r} for {path.strip()}; allowed 'g' (the FEMA "
                                 f"P695 sets are in g)")
        return suite_motion(path.strip())
    if is_suite(path):
        raise ArchInputError(f"record: {path!r} is a suite of records; allowed one record "
                             f"SUITE/ID such as {path}/1a (a suite goes where records go)")
    p = Path(path)
    if p.suffix.lower() == ".at2":
        if units is not None and units != "g":
            raise ArchInputError(f"units: {units!r} for {p.name}; allowed 'g' (PEER .AT2 values are in g)")
        return read_at2(p)
    return read_two_column(p, units="g" if units is None else units)
