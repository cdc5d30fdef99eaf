"""The one reader of the files a user gives archrock, bounded by size at the door.

Every input file (a geometry or arcade JSON document, a recorded ground motion, a DXF drawing,
a site spectrum) is read through :func:`read_input`, which refuses a file past the limit of its
kind before reading it: a regular file by its size on disk, anything else (a pipe, a device such
as /dev/zero or /dev/urandom, whose size reads as 0) by reading at most limit + 1 bytes.  The
message names the file, its kind and the limit.  Without it /dev/zero ran out of memory and
/dev/urandom ran until killed.
"""

from __future__ import annotations

import os
import stat
from pathlib import Path

from ..errors import ArchInputError

__all__ = ["MAX_INPUT_BYTES", "read_input", "input_limit"]

MB = 1_000_000
#: Largest input file of each kind [bytes].  A geometry of the most voussoirs (2000) as polygons
#: of 40 points a line is about 5 MB of JSON, an arcade of 50 spans under 2 MB; a PEER record of
#: 100,000 samples is about 1.6 MB, so 50 MB is minutes of record at 1,000 Hz; a surveyed DXF
#: of an arch, with its drawing's other layers, is a few MB; a spectrum table is tens of rows.
MAX_INPUT_BYTES = {
    "geometry": 10 * MB,
    "arcade": 10 * MB,
    "record": 50 * MB,
    "DXF": 50 * MB,
    "spectrum": 1 * MB,
}


def input_limit(kind: str) -> int:
    """The size limit [bytes] of an input file of ``kind`` (a key of MAX_INPUT_BYTES)."""
    if kind not in MAX_INPUT_BYTES:
        raise ArchInputError(f"input kind: {kind!r}; allowed {', '.join(MAX_INPUT_BYTES)}")
    return MAX_INPUT_BYTES[kind]


def _too_large(p: Path, kind: str, limit: int, size: str) -> ArchInputError:
    return ArchInputError(f"{p}: {kind} file too large ({size}); allowed at most "
                          f"{limit / MB:g} MB ({limit} bytes)")


def _open(p: Path):
    """``p`` opened for reading in binary.  Opened without blocking, then read blocking: a
    named pipe with no writer gives no bytes at once instead of waiting forever at open."""
    nonblock = getattr(os, "O_NONBLOCK", 0)  # POSIX only
    fd = os.open(p, os.O_RDONLY | nonblock | getattr(os, "O_BINARY", 0))
    if nonblock:
        import fcntl

        fcntl.fcntl(fd, fcntl.F_SETFL, fcntl.fcntl(fd, fcntl.F_GETFL) & ~nonblock)
    return os.fdopen(fd, "rb")


#: Bytes read at a time from a stream (a pipe or a device reports no size).
_CHUNK = 1 << 20


def _read_capped(fh, size: int, limit: int) -> bytes:
    """At most ``limit`` + 1 bytes of ``fh``, whose size is thought to be ``size`` (0 for a
    stream).  The buffer asked for is the size expected, not the limit: ``read(limit + 1)``
    allocated the whole limit (50 MB for a record) for a file of any size."""
    first = fh.read(min(size, limit) + 1)
    if len(first) <= size:
        return first  # the whole file: one byte more was asked for and none came
    chunks, total = [first], len(first)
    # a stream, or a file that grew since fstat: read on, one byte past the limit to tell
    while total <= limit:
        chunk = fh.read(min(_CHUNK, limit + 1 - total))
        if not chunk:
            break
        chunks.append(chunk)
        total += len(chunk)
    return b"".join(chunks)


def read_input(path: str | os.PathLike, kind: str) -> bytes:
    """The bytes of the input file ``path`` of ``kind`` (module docstring), refused with an
    :class:`~archrock.errors.ArchInputError` naming the file when it is missing, a directory,
    unreadable or larger than :data:`MAX_INPUT_BYTES` [kind]."""
    limit = input_limit(kind)
    p = Path(path)
    try:
        with _open(p) as fh:
            st = os.fstat(fh.fileno())
            if stat.S_ISDIR(st.st_mode):
                raise IsADirectoryError
            regular = stat.S_ISREG(st.st_mode)
            if regular and st.st_size > limit:  # refused before a byte is read
                raise _too_large(p, kind, limit, f"{st.st_size} bytes")
            data = _read_capped(fh, st.st_size if regular else 0, limit)
    except FileNotFoundError:
        raise ArchInputError(f"{p}: {kind} file not found") from None
    except IsADirectoryError:
        raise ArchInputError(f"{p}: is a directory, expected a {kind} file") from None
    except OSError as exc:
        raise ArchInputError(f"{p}: cannot read the {kind} file ({exc.strerror or exc})") from None
    if len(data) > limit:  # a stream, or a file that grew since fstat
        how = "read from a stream" if not regular else "it grew while read"
        raise _too_large(p, kind, limit, f"more than {limit} bytes, {how}")
    return data
