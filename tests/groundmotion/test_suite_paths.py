"""One reading of a --records list (groundmotion.suite.record_paths) for every command."""

import pytest

from archrock.errors import ArchInputError
from archrock.groundmotion.suite import record_paths


def test_folders_give_their_at2_files_in_name_order_and_files_stay(tmp_path):
    suite = tmp_path / "suite"
    suite.mkdir()
    for name in ("b.AT2", "a.at2", "notes.txt"):
        (suite / name).write_text("x")
    two = tmp_path / "two.txt"
    two.write_text("0 0\n")
    got = record_paths([str(two), str(suite)])
    assert got == (str(two), str(suite / "a.at2"), str(suite / "b.AT2"))
    with pytest.raises(ArchInputError, match="records: .* is neither a file nor a folder"):
        record_paths([str(tmp_path / "missing")])
    empty = tmp_path / "empty"
    empty.mkdir()
    with pytest.raises(ArchInputError, match="no .AT2 file in the folder"):
        record_paths([str(empty)])
