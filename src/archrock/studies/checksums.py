"""Checksums of the files a study writes and later reads back (:mod:`archrock.studies.store`).

A stored table (an ensemble's batch, a sweep's chunk) gets a sidecar ``NAME.sha256`` holding
the SHA-256 of its bytes in ``sha256sum`` form (``<hex>  NAME``, so ``sha256sum -c`` checks it
too).  The sidecar is written, atomically, *before* the table is renamed into place: a table
that is present always had its checksum written first, so a missing sidecar means a folder
older than checksums (or a table put there by hand), never a crash of this code.

A manifest carries its checksum inside (key :data:`SEAL`): the SHA-256 of its JSON without
that key, keys sorted, compact separators; a file with a wrong one is damaged.  Every write is
atomic: a temporary ``*.tmp-PID`` written, then renamed.  Manifests are fsync'ed before the
rename (a lost manifest loses the folder); tables and sidecars are not, since their checksums
already catch what a power cut can leave (an empty or torn file is recomputed, never read),
and two fsyncs (about 10 ms) would add some 7% to a 500-arch batch of the paper's case.
"""

from __future__ import annotations

import hashlib
import json
import os
from pathlib import Path

__all__ = ["SEAL", "file_sha256", "write_atomic", "write_sidecar", "sidecar_path",
           "check_sidecar", "seal", "check_seal"]

#: the key of a manifest's own checksum
SEAL = "checksum"
_CHUNK = 1 << 20


def file_sha256(path: Path) -> str:
    """SHA-256 (hex) of a file's bytes, read in 1 MiB pieces."""
    h = hashlib.sha256()
    with open(path, "rb") as fh:
        for piece in iter(lambda: fh.read(_CHUNK), b""):
            h.update(piece)
    return h.hexdigest()


def write_atomic(path: Path, data: bytes, durable: bool = True) -> None:
    """Write ``data`` as ``path``: a ``*.tmp-PID`` file written (``durable``: fsync'ed), then
    renamed, so ``path`` never names half-written bytes of this write."""
    tmp = path.with_name(f"{path.name}.tmp-{os.getpid()}")
    with open(tmp, "wb") as fh:
        fh.write(data)
        if durable:
            fh.flush()
            os.fsync(fh.fileno())
    os.replace(tmp, path)


def sidecar_path(path: Path) -> Path:
    """The checksum file of ``path`` (``batch-00000.parquet`` -> ``batch-00000.parquet.sha256``)."""
    return path.with_name(path.name + ".sha256")


def write_sidecar(path: Path, digest: str, name: str | None = None) -> None:
    """Record ``digest``, the SHA-256 of the file to be named ``name`` (default: ``path``'s)."""
    write_atomic(sidecar_path(path), f"{digest}  {name or path.name}\n".encode("ascii"),
                 durable=False)


def check_sidecar(path: Path) -> str | None:
    """Why the file ``path`` fails its recorded checksum (None: it matches).  Raises
    FileNotFoundError when no checksum is recorded (a folder older than checksums)."""
    side = sidecar_path(path)
    try:
        text = side.read_bytes().decode("ascii")
    except FileNotFoundError:
        raise
    except (OSError, UnicodeDecodeError):
        return f"damaged: its checksum file {side.name} cannot be read"
    fields = text.split()
    if len(fields) != 2 or len(fields[0]) != 64 or fields[1] != path.name:
        return f"damaged: its checksum file {side.name} is not '<sha256>  {path.name}'"
    try:
        actual = file_sha256(path)
    except OSError as exc:
        return f"unreadable ({exc.strerror or type(exc).__name__})"
    if actual != fields[0].lower():
        return (f"damaged: its sha256 ({actual[:12]}...) is not the one recorded in "
                f"{side.name} ({fields[0][:12]}...)")
    return None


def _canonical(obj: dict) -> bytes:
    body = {k: v for k, v in obj.items() if k != SEAL}
    return json.dumps(body, sort_keys=True, separators=(",", ":"), allow_nan=False).encode()


def seal(obj: dict) -> dict:
    """``obj`` with its checksum under :data:`SEAL` (a new dict; the original is not changed)."""
    return {**{k: v for k, v in obj.items() if k != SEAL},
            SEAL: "sha256:" + hashlib.sha256(_canonical(obj)).hexdigest()}


def check_seal(obj) -> str | None:
    """Why a manifest read from JSON is damaged (None: its checksum matches, or it records none:
    a folder older than checksums, which the caller checks otherwise)."""
    if not isinstance(obj, dict):
        return f"holds {type(obj).__name__}, not an object"
    recorded = obj.get(SEAL)
    if recorded is None:
        return None
    try:
        want = "sha256:" + hashlib.sha256(_canonical(obj)).hexdigest()
    except (TypeError, ValueError):
        return "its contents cannot be checked"
    if recorded != want:
        return "its contents do not match the sha256 it records"
    return None
