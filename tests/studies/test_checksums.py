"""Checksums of stored files (archrock.studies.checksums): sidecars and sealed manifests."""

import hashlib
import json

import pytest

from archrock.studies.checksums import (SEAL, check_seal, check_sidecar, file_sha256, seal,
                                        sidecar_path, write_atomic, write_sidecar)


def test_sidecar_is_sha256sum_form_and_catches_a_flipped_byte_and_a_truncation(tmp_path):
    path = tmp_path / "batch-00000.parquet"
    data = bytes(range(256)) * 40
    write_atomic(path, data)
    write_sidecar(path, file_sha256(path))
    want = hashlib.sha256(data).hexdigest()
    assert sidecar_path(path).read_text() == f"{want}  batch-00000.parquet\n"
    assert check_sidecar(path) is None
    flipped = bytearray(data)
    flipped[len(data) // 2] ^= 0x01  # one bit
    path.write_bytes(bytes(flipped))
    assert check_sidecar(path).startswith("damaged: its sha256 (")
    path.write_bytes(data[:-100])
    assert "is not the one recorded in batch-00000.parquet.sha256" in check_sidecar(path)
    assert not list(tmp_path.glob("*.tmp-*"))  # every temporary file was renamed


def test_sidecar_missing_or_damaged(tmp_path):
    path = tmp_path / "chunk-00001.parquet"
    path.write_bytes(b"x")
    with pytest.raises(FileNotFoundError):  # a folder older than checksums
        check_sidecar(path)
    sidecar_path(path).write_text("0123  chunk-00001.parquet\n")
    assert "is not '<sha256>  chunk-00001.parquet'" in check_sidecar(path)
    write_sidecar(path, file_sha256(path), name="chunk-00002.parquet")  # another file's
    assert "is not '<sha256>  chunk-00001.parquet'" in check_sidecar(path)


def test_seal_catches_any_change_of_a_value():
    data = {"format": "archrock-ensemble/4", "config": {"seed": 3, "samples": 2000},
            "runs": [{"wall": 1.25}]}
    sealed = seal(data)
    assert SEAL not in data and sealed[SEAL].startswith("sha256:")
    back = json.loads(json.dumps(sealed, indent=2))  # as written and read back
    assert check_seal(back) is None
    back["config"]["seed"] = 4
    assert check_seal(back) == "its contents do not match the sha256 it records"
    assert check_seal({"format": "old"}) is None  # no checksum: older than checksums
    assert check_seal([1, 2]) == "holds list, not an object"
    assert seal(sealed) == sealed  # sealing again gives the same checksum
