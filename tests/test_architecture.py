"""The layers of docs/architecture.md: no module imports from a layer above its own."""

import ast
from pathlib import Path

import archrock

ROOT = Path(archrock.__file__).parent

#: top-level module or folder -> layer (docs/architecture.md): one folder, one layer
LAYER = {
    "errors": 0, "units": 0, "published": 0, "_jit": 0, "_records": 0, "_progress": 0,
    "_pairwise": 0, "leftout": 0, "_device": 0,
    "geometry": 1,
    "statics": 2,
    "groundmotion": 3,
    "dynamics": 4,
    "contact": 5,
    "studies": 6,
    "reports": 7, "options": 7,
    "app": 8,
    "cli": 9, "__main__": 9,
}
#: same layer, kept apart: neither may import the other
APART: set = {("reports", "options"), ("options", "reports")}


def _top(module_path: Path) -> str:
    rel = module_path.relative_to(ROOT)
    return rel.parts[0].removesuffix(".py")


def _imported_tops(path: Path) -> set[str]:
    """Top-level archrock modules imported anywhere in ``path`` (also inside functions)."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    package = path.relative_to(ROOT).parts[:-1]  # subpackage of this file, () at the top
    out = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom):
            if node.level == 0:
                if node.module and node.module.split(".")[0] == "archrock":
                    parts = node.module.split(".")[1:]
                    out.add(parts[0] if parts else None)
                continue
            base = package[:len(package) - (node.level - 1)] if node.level > 1 else package
            parts = list(base) + (node.module.split(".") if node.module else [])
            if parts:
                out.add(parts[0])
            else:  # "from . import x": x are top-level modules
                out.update(a.name for a in node.names)
        elif isinstance(node, ast.Import):
            for a in node.names:
                if a.name.split(".")[0] == "archrock" and "." in a.name:
                    out.add(a.name.split(".")[1])
    out.discard(None)
    return out


def test_every_module_has_a_layer():
    tops = {_top(p) for p in ROOT.rglob("*.py") if p.name != "__init__.py" or p.parent != ROOT}
    assert tops <= set(LAYER), sorted(tops - set(LAYER))


def test_no_import_runs_back_up():
    bad = []
    for path in sorted(ROOT.rglob("*.py")):
        if path == ROOT / "__init__.py":
            continue  # the lazy namespace re-exports every layer by name
        own = _top(path)
        for other in _imported_tops(path):
            if other == own:
                continue
            if LAYER[other] > LAYER[own] or (own, other) in APART:
                bad.append(f"{path.relative_to(ROOT)} (layer {LAYER[own]}) imports {other} "
                           f"(layer {LAYER[other]})")
    assert not bad, "\n".join(bad)


def import_graph() -> dict[str, set[str]]:
    """Place -> the places it imports (a folder is one place, each top-level module one)."""
    graph: dict[str, set[str]] = {}
    for path in ROOT.rglob("*.py"):
        if path == ROOT / "__init__.py":
            continue
        own = _top(path)
        graph.setdefault(own, set()).update(_imported_tops(path) - {own})
    return graph


def levels(graph: dict[str, set[str]]) -> int:
    """Places on the longest chain of imports (the graph has no cycle: see below)."""
    memo: dict[str, int] = {}

    def depth(p: str) -> int:
        if p not in memo:
            memo[p] = 1 + max((depth(q) for q in graph.get(p, ())), default=0)
        return memo[p]
    return max(depth(p) for p in graph)


def test_no_two_places_import_each_other():
    graph = import_graph()
    pairs = sorted((a, b) for a, out in graph.items() for b in out if a in graph.get(b, ()))
    assert not pairs, pairs
    assert levels({"a": {"b"}, "b": {"c"}, "c": set()}) == 3  # the counter itself


def _folder_edges(folder: Path, root: Path = ROOT) -> dict[str, set[str]]:
    """Within one package folder under ``root`` (the archrock package): each child (module, or
    subfolder as one node; the folder's own ``__init__`` as ``"__init__"``) -> the children it
    imports, at module level or inside a function, through relative or absolute imports."""
    pkg = (root.name,) + folder.relative_to(root).parts
    children = {p.stem for p in folder.glob("*.py")} | {
        p.parent.name for p in folder.glob("*/__init__.py")}

    def node(parts: tuple) -> str | None:
        """The child of ``folder`` that holds the dotted module ``parts``, if any."""
        if parts[:len(pkg)] != pkg:
            return None
        rest = parts[len(pkg):]
        return rest[0] if rest else "__init__"

    graph: dict[str, set[str]] = {}
    for path in folder.rglob("*.py"):
        rel = path.relative_to(root.parent).with_suffix("").parts
        own_pkg = rel[:-1]  # the package this file's relative imports start from
        own = node(rel[:-1] if path.name == "__init__.py" else rel)
        for n in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(n, ast.ImportFrom):
                base = (own_pkg[:len(own_pkg) - (n.level - 1)] if n.level else ()) + tuple(
                    n.module.split(".") if n.module else ())
                targets = [base + (a.name,) if base == pkg and a.name in children else base
                           for a in n.names]
            elif isinstance(n, ast.Import):
                targets = [tuple(a.name.split(".")) for a in n.names]
            else:
                continue
            for t in targets:
                other = node(t)
                if other is not None and other != own:
                    graph.setdefault(own, set()).add(other)
    return graph


def find_cycle(graph: dict[str, set[str]]) -> list[str]:
    """One cycle of ``graph`` as [a, b, ..., a], or [] when it has none."""
    state: dict[str, int] = {}  # 1 on the current path, 2 done
    path: list[str] = []

    def visit(p: str) -> list[str]:
        state[p] = 1
        path.append(p)
        for q in sorted(graph.get(p, ())):
            if state.get(q) == 1:
                return path[path.index(q):] + [q]
            if q not in state and (found := visit(q)):
                return found
        state[p] = 2
        path.pop()
        return []
    for p in sorted(graph):
        if p not in state and (found := visit(p)):
            return found
    return []


def folder_cycles() -> dict[str, list[str]]:
    """Package folder ("archrock/geometry") -> one import cycle among its modules, for each
    folder that has one."""
    out = {}
    for init in sorted(ROOT.rglob("__init__.py")):
        if cycle := find_cycle(_folder_edges(init.parent)):
            out[init.parent.relative_to(ROOT.parent).as_posix()] = cycle
    return out


def test_no_folder_imports_itself_in_a_circle():
    """Bottom to top inside each folder: no module reaches itself again through the modules it
    imports, lazy (function-level) imports included."""
    cycles = folder_cycles()
    assert not cycles, "\n".join(f"{f}: {' -> '.join(c)}" for f, c in cycles.items())


def test_the_circle_finder_finds_circles(tmp_path):
    """The checker itself: a circle through a lazy import and a subfolder is found and named."""
    assert find_cycle({"a": {"b", "c"}, "b": {"c"}, "c": set()}) == []
    pkg = tmp_path / "archrock" / "layer"
    (pkg / "sub").mkdir(parents=True)
    files = {"__init__.py": "from .a import f\n", "a.py": "def f():\n    from .b import g\n",
             "b.py": "import numpy\nfrom archrock.layer.sub import c\n",
             "sub/__init__.py": "", "sub/c.py": "from ..a import f\nfrom ...errors import E\n"}
    for name, text in files.items():
        (pkg / name).write_text(text, encoding="utf-8")
    edges = _folder_edges(pkg, tmp_path / "archrock")
    assert edges == {"__init__": {"a"}, "a": {"b"}, "b": {"sub"}, "sub": {"a"}}
    assert find_cycle(edges) == ["a", "b", "sub", "a"]
    real = _folder_edges(ROOT / "geometry")
    assert "base" in real["circular"] and "batchdraw" in real["sampling"]  # the latter lazy


def test_app_and_cli_share_the_options_not_each_other():
    """The option builders live below both front ends: the app imports ``archrock.options``, never
    the command line, and the command line only launches the app (one edge, cli -> app)."""
    app = set().union(*(_imported_tops(p) for p in (ROOT / "app").rglob("*.py")))
    cli = set().union(*(_imported_tops(p) for p in (ROOT / "cli").rglob("*.py")))
    assert "options" in app and "options" in cli
    assert "cli" not in app
    assert "app" in cli  # `archrock app`
    launchers = [p.name for p in (ROOT / "cli").rglob("*.py") if "app" in _imported_tops(p)]
    assert launchers == ["app.py"]


def test_the_check_sees_relative_and_nested_imports(tmp_path):
    """The checker itself: a function-level relative import from a subpackage is seen."""
    p = ROOT / "studies" / "ensemble" / "run.py"
    assert {"geometry", "studies", "dynamics"} <= _imported_tops(p)
    assert {"statics", "geometry"} <= _imported_tops(ROOT / "dynamics" / "batch.py")


def test_code_and_docs_cite_only_what_users_have():
    """The package and its docs cite docs/*.md, never the project's private METHOD.md, and every
    'docs/method.md, <Section>' cited names a section that exists there."""
    import re

    # the checkout's docs and README (the package itself may be installed elsewhere, as in CI)
    repo = Path(__file__).resolve().parents[1]
    assert (repo / "docs" / "method.md").is_file() and (repo / "README.md").is_file()
    texts = {p: p.read_text(encoding="utf-8") for p in
             [*ROOT.rglob("*.py"), *(repo / "docs").glob("*.md"), repo / "README.md"]}
    sections = set(re.findall(r"^## (\w[\w -]*?)(?: \(|$)", (repo / "docs" / "method.md").read_text(
        encoding="utf-8"), flags=re.M))
    bad = []
    for path, text in texts.items():
        if re.search(r"\bMETHOD\b", text):
            bad.append(f"{path.name}: cites METHOD")
        for m in re.finditer(r"docs/method\.md, ", text):
            cited = text[m.end():m.end() + 40]
            if not any(cited.startswith(sec) for sec in sections):
                bad.append(f"{path.name}: docs/method.md has no section {cited!r}")
    assert not bad, "\n".join(bad)


def test_tests_read_nothing_outside_the_repository():
    """A fresh clone runs every test: no test reads the shared folder beside the checkout, an
    absolute path of the development machine or a folder above the checkout (cases live in
    tests/data, read through conftest's fixtures)."""
    import re

    tests = Path(__file__).resolve().parent
    outside = re.compile(r"parents\[[3-9]\]|[\"']/work/|\.\./shared|[\"']shared[\"']\s*/")
    bad = [f"{p.relative_to(tests)}:{i}: {line.strip()}"
           for p in sorted(tests.rglob("*.py"))
           for i, line in enumerate(p.read_text(encoding="utf-8").splitlines(), 1)
           if outside.search(line) and "outside = re.compile" not in line]
    assert not bad, "\n".join(bad)


if __name__ == "__main__":  # the figures of docs/architecture.md
    g = import_graph()
    print(f"{len(g)} places, {sum(map(len, g.values()))} edges, {levels(g)} levels")
    for folder, cycle in folder_cycles().items():
        print(f"cycle in {folder}: {' -> '.join(cycle)}")
