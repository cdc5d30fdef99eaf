"""The documentation site's configuration (mkdocs.yml) against the pages on disk: the nav names
only files that exist and every page of docs/ is in the nav, so none is orphaned.  Read as text,
without mkdocs or a YAML library (the `docs` extra is not needed to run the tests)."""

import re
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
DOCS = REPO / "docs"


def _config() -> str:
    return (REPO / "mkdocs.yml").read_text(encoding="utf-8")


def _nav(text: str) -> list[str]:
    """The targets of the nav, in order: `- Title: target` and `- target` lines of the block
    under `nav:`, up to the next top-level key."""
    block = text.split("\nnav:\n", 1)[1]
    block = re.split(r"\n(?=\S)", block, maxsplit=1)[0]
    targets = []
    for line in block.splitlines():
        m = re.match(r"\s*-\s+(?:[^:]+:\s+)?(\S+)\s*$", line)
        if m and not line.rstrip().endswith(":"):
            targets.append(m.group(1))
    return targets


def _gallery_dirs(text: str) -> tuple[str, str]:
    """(examples_dirs, gallery_dirs) of the gallery plugin, relative to the repository."""
    ex = re.search(r"^\s+examples_dirs:\s+(\S+)\s*$", text, flags=re.M).group(1)
    gal = re.search(r"^\s+gallery_dirs:\s+(\S+)\s*$", text, flags=re.M).group(1)
    return ex, gal


def _pages() -> set[str]:
    """Every Markdown page of docs/, relative to it, but the generated gallery, the gallery's
    sources and the scripts (excluded from the site in mkdocs.yml)."""
    ex, gal = _gallery_dirs(_config())
    skip = [REPO / ex, REPO / gal, DOCS / "scripts"]
    return {p.relative_to(DOCS).as_posix() for p in DOCS.rglob("*.md")
            if not any(p.is_relative_to(s) for s in skip)}


def test_the_nav_is_read():
    nav = _nav(_config())
    assert nav[0] == "index.md" and "api/geometry.md" in nav and "method.md" in nav
    assert len(nav) == len(set(nav)), "a page twice in the nav"


def test_the_nav_names_only_existing_pages():
    text = _config()
    _, gal = _gallery_dirs(text)
    missing = []
    for target in _nav(text):
        if target.endswith(".md"):
            if not (DOCS / target).is_file():
                missing.append(target)
        elif (DOCS / target).resolve() != (REPO / gal).resolve():
            # the one nav entry that is not a page: the gallery, generated at build
            missing.append(f"{target} (neither a page nor the gallery {gal})")
    assert not missing, f"mkdocs.yml's nav names what is not there: {missing}"


def test_every_docs_page_is_in_the_nav():
    orphans = sorted(_pages() - set(_nav(_config())))
    assert not orphans, f"pages of docs/ that the site's nav does not reach: {orphans}"


def test_an_orphan_page_and_a_missing_one_are_found(tmp_path, monkeypatch):
    """The checks themselves, on a small site: a page without a nav entry, a nav entry
    without a page."""
    import sys

    (tmp_path / "docs" / "api").mkdir(parents=True)
    for page in ("index.md", "lost.md", "api/geometry.md"):
        (tmp_path / "docs" / page).write_text("# a page\n")
    (tmp_path / "mkdocs.yml").write_text(
        "plugins:\n  - gallery:\n      examples_dirs: docs/examples\n"
        "      gallery_dirs: docs/generated/gallery\nnav:\n  - Home: index.md\n"
        "  - API:\n      - Geometry: api/geometry.md\n  - Gone: gone.md\n"
        "  - Gallery: generated/gallery\nextra: {}\n")
    here = sys.modules[__name__]
    monkeypatch.setattr(here, "REPO", tmp_path)
    monkeypatch.setattr(here, "DOCS", tmp_path / "docs")
    nav = _nav(_config())
    assert nav == ["index.md", "api/geometry.md", "gone.md", "generated/gallery"]
    assert _pages() - set(nav) == {"lost.md"}
    assert [t for t in nav if t.endswith(".md") and not (tmp_path / "docs" / t).is_file()] \
        == ["gone.md"]


def test_the_gallery_has_its_examples():
    ex, _ = _gallery_dirs(_config())
    examples = sorted((REPO / ex).glob("plot_*.py"))
    assert (REPO / ex / "README.md").is_file() and len(examples) >= 4
    for path in examples:   # each parses, and opens with its title as the gallery shows it
        source = path.read_text(encoding="utf-8")
        compile(source, str(path), "exec")
        assert re.match(r'"""\n# \S', source), f"{path.name}: no '# Title' docstring"


def test_the_api_reference_has_a_page_per_layer():
    layers = ["geometry", "statics", "groundmotion", "dynamics", "contact", "studies",
              "reports", "options", "app"]
    nav = _nav(_config())
    for layer in layers:
        assert f"api/{layer}.md" in nav
        assert f"::: archrock.{layer}\n" in (DOCS / "api" / f"{layer}.md").read_text()
