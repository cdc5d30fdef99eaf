"""JSON keys are field names: every configuration (a frozen dataclass with to_dict/from_dict)
serialises under its fields' own names and reads its dict back equal, through JSON; the old
keys of archrock <= 0.6 are read as aliases; the ensemble's configuration hash keeps 0.4's form."""

import dataclasses
import hashlib
import json
from pathlib import Path

import pytest

import archrock
from archrock.contact.settings import EngineSettings
from archrock.dynamics.impact import PAPER_PRACTICE, ImpactSpec
from archrock.errors import ArchInputError
from archrock.geometry import nominal_arch
from archrock.geometry.base import Load
from archrock.geometry.defect import Defect
from archrock.geometry.displaced import SupportMovement
from archrock.geometry.sampling import LEGACY_KEYS, Spreads
from archrock.groundmotion import PulseSpec, RecordSpec
from archrock.studies.assessment import AssessConfig
from archrock.studies.codecheck import CodeCheckConfig, SiteSpectrum
from archrock.studies.ensemble import EnsembleConfig
from archrock.studies.enginestudy import EngineRun
from archrock.studies.runner import RunSettings
from archrock.studies.selection import SelectionConfig

DATA = Path(__file__).parent / "data"

#: Keys beside the fields: a tag naming the class, or derived figures not read back.
EXTRA_KEYS = {PulseSpec: {"type"}, RecordSpec: {"type"}, SiteSpectrum: {"parameters", "pga_g"}}
#: Fields left out of the dict where they hold the value the others imply (read back so).
IMPLIED = {ImpactSpec: {"fallback", "note"},
           # zero turn written by omission, so that the hash of a 0.6 ensemble on moved
           # supports keeps its form
           SupportMovement: {"rotation", "pivot_depth"},
           # the piers' spreads and f_c's (0.8) likewise: a configuration without them hashes
           # as before
           Spreads: {"pier_lean", "pier_width", "pier_height", "pier_course", "fc"}}
#: Geometry files have their own documented format (docs/geometry.md), not a config's.
FILE_FORMATS = {"Arch", "PolygonArch", "FamilyArch", "ArchOnPiers", "Arcade"}


@pytest.fixture(scope="module")
def record(tmp_path_factory):
    path = tmp_path_factory.mktemp("rec") / "two-column.txt"
    path.write_text("".join(f"{0.01 * i:.2f} {0.1 * (i % 7 - 3):.3f}\n" for i in range(200)))
    return RecordSpec.from_file(path, "m/s2", -1.5)


@pytest.fixture(scope="module")
def configs(record):
    table = SiteSpectrum("table", periods=(0.0, 0.5, 2.0), values=(0.3, 0.6, 0.1))
    return [
        Spreads(0.2, 0.15, 0.05, 3.0), Spreads(),
        Spreads(pier_lean=1.0, pier_width=0.1, pier_height=0.05, pier_course=0.2),
        PulseSpec("ricker", 0.5, 0.4), record,
        PAPER_PRACTICE, ImpactSpec.fixed(0.8, literal=True), ImpactSpec.parse("least-loss"),
        Defect.parse("3:thickness=0.5,side=extrados"), Defect.parse("2:tilt=-5"),
        SupportMovement(0.01, 0.002, "both"), SupportMovement(0.0, 0.0, "left", 0.02, 1.5), Load(2, 150.0, (0.5, 9.0)),
        EngineSettings(), EngineRun(t_free=20.0, collapse_drop=0.3),
        RunSettings(workers=2, out="runs/a", progress=True), RunSettings(), CodeCheckConfig(fc=1.2, control=3, spectrum=table),
        SiteSpectrum("ntc", ag=0.2, f0=2.4, tc_star=0.3), table,
        AssessConfig(samples=3, spreads=Spreads(0.05, 0.05, 0.02), records=("a.AT2",)),
        EnsembleConfig.from_arch(nominal_arch(), samples=30, seed=4, batch_size=7,
                                 spreads=Spreads(0.05, 0.1, 0.02), motion=record,
                                 impact=ImpactSpec.fixed(0.7), early_stop=True,
                                 support=SupportMovement(0.05), support_draw="uniform"),
        EnsembleConfig.from_arch(nominal_arch(), samples=10),
        SelectionConfig(), SelectionConfig(count=9, period_range=(0.2, 1.5), lower=0.95,
                                           scale_bounds=(0.25, 5.0), one_per_station=False),
    ]


def _config_classes() -> set[str]:
    """Every class of the package that defines both to_dict and from_dict (read from the
    sources, app and cli excluded)."""
    import ast

    root = Path(archrock.__file__).parent
    found = set()
    for path in root.rglob("*.py"):
        if path.relative_to(root).parts[0] in ("app", "cli"):
            continue
        text = path.read_text(encoding="utf-8")
        if "def from_dict" not in text:
            continue
        for node in ast.parse(text).body:
            if isinstance(node, ast.ClassDef):
                names = {f.name for f in node.body if isinstance(f, ast.FunctionDef)}
                if {"to_dict", "from_dict"} <= names:
                    found.add(node.name)
    return found


def test_every_configuration_class_is_checked_here(configs):
    checked = {type(c) for c in configs}
    missing = _config_classes() - {c.__name__ for c in checked} - FILE_FORMATS
    assert not missing, sorted(missing)
    assert {EnsembleConfig, Spreads, PulseSpec, RecordSpec, ImpactSpec, Defect} <= checked


def test_keys_are_the_field_names_and_json_reads_back_equal(configs):
    for c in configs:
        cls = type(c)
        d = json.loads(json.dumps(c.to_dict()))
        fields = {f.name for f in dataclasses.fields(c)}
        keys = set(d) - EXTRA_KEYS.get(cls, set())
        assert keys <= fields, (cls.__name__, sorted(keys - fields))
        assert fields - keys <= IMPLIED.get(cls, set()), (cls.__name__, sorted(fields - keys))
        back = cls.from_dict(d)
        assert back == c, cls.__name__
        assert back.to_dict() == c.to_dict()


def test_spreads_read_the_old_keys_as_aliases():
    old = {"spread_span": 0.2, "spread_thickness": 0.15, "spread_radius": 0.05,
           "spread_tilt_deg": 3.0}
    assert Spreads.from_dict(old) == Spreads(0.2, 0.15, 0.05, 3.0)
    assert Spreads.from_dict({"spread_span": 0.3, "tilt": 1.0}) == Spreads(span=0.3, tilt=1.0)
    # every field of 0.6 has its old key; the piers' spreads (0.7) and f_c's (0.8) never had
    # another
    assert set(LEGACY_KEYS.values()) == {f.name for f in dataclasses.fields(Spreads)
                                         if not f.name.startswith("pier_") and f.name != "fc"}
    assert Spreads(0.2, 0.15, 0.05, 3.0).legacy_dict() == old
    assert "spread_tilt_deg" not in Spreads().legacy_dict()  # 0.1.0's dict without a tilt
    with pytest.raises(ArchInputError, match="span given twice"):
        Spreads.from_dict({"span": 0.1, "spread_span": 0.2})
    with pytest.raises(ArchInputError, match=r"unknown key\(s\) \['tilt_deg'\]"):
        Spreads.from_dict({"tilt_deg": 1.0})


def test_the_0_4_0_manifest_reads_and_hashes_as_it_was_written():
    """tests/data/ensemble-0.4.0's manifest holds 0.4's keys: it reads as the configuration of
    its command, its dict upgrades to this release's keys, and the configuration hash (of the
    legacy form, computed explicitly) is the sha256 of the very dict 0.4.0 wrote."""
    manifest = json.loads((DATA / "ensemble-0.4.0" / "manifest.json").read_text())
    old = manifest["config"]
    assert "spread_span" in old["spreads"] and "early_stop" not in old
    cfg = EnsembleConfig.from_dict(old)
    assert cfg == EnsembleConfig.from_arch(
        nominal_arch(), samples=48, batch_size=16, seed=7,
        motion=PulseSpec("oppenheim", -1.0, 0.2))
    assert cfg.legacy_dict() == old
    assert cfg.config_hash() == hashlib.sha256(json.dumps(old, sort_keys=True).encode()).hexdigest()
    assert EnsembleConfig.upgrade_dict(old) == cfg.to_dict()
    assert cfg.to_dict()["spreads"] == {"span": 0.1, "thickness": 0.1, "radius": 0.05, "tilt": 0.0}
    pq = pytest.importorskip("pyarrow.parquet")
    meta = pq.read_schema(DATA / "ensemble-0.4.0" / "batches" / "batch-00000.parquet").metadata
    assert json.loads(meta[b"archrock.ensemble"])["config_sha256"] == cfg.config_hash()


def test_the_hash_depends_on_what_changes_results_only():
    a = EnsembleConfig.from_arch(nominal_arch(), samples=10)
    assert a.config_hash() == EnsembleConfig.from_dict(json.loads(a.to_json())).config_hash()
    assert a.config_hash() == EnsembleConfig.from_dict(a.legacy_dict()).config_hash()
    b = EnsembleConfig.from_arch(nominal_arch(), samples=10, spreads=Spreads(tilt=0.0, span=0.11))
    assert a.config_hash() != b.config_hash()
    assert EnsembleConfig.upgrade_dict(a.legacy_dict()) == a.to_dict()
