"""The package's structure in figures: what docs/architecture.md and the 0.7 notes quote.

Usage: python docs/scripts/structure.py [--src DIR]

Prints the places of the import graph (each layer's folder is one place, each top-level module
one), its edges and levels, any import that runs up a layer, any circle of imports between the
modules of one folder (module-level and function-level imports alike), the largest module and the
longest function, and the functions of ``studies/`` over 60 lines.  Reads the code as text (ast);
runs nothing of it.
"""

from __future__ import annotations

import argparse
import ast
import sys
from pathlib import Path

#: the layers of docs/architecture.md (tests/test_architecture.py holds the same table)
LAYER = {
    "errors": 0, "units": 0, "published": 0, "_jit": 0, "_records": 0, "_progress": 0,
    "_pairwise": 0, "leftout": 0,
    "geometry": 1, "statics": 2, "groundmotion": 3, "dynamics": 4, "contact": 5, "studies": 6,
    "reports": 7, "options": 7, "app": 8, "cli": 9, "__main__": 9,
}


def _module_name(root: Path, path: Path) -> tuple[str, ...]:
    rel = path.relative_to(root).with_suffix("")
    parts = rel.parts
    return parts[:-1] if parts[-1] == "__init__" else parts


def _imports(root: Path, path: Path) -> set[tuple[str, ...]]:
    """Full archrock module names (as tuples below the package) imported anywhere in path."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    package = path.relative_to(root).parts[:-1]
    out: set[tuple[str, ...]] = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom):
            if node.level == 0:
                if node.module and node.module.split(".")[0] == "archrock":
                    base = tuple(node.module.split(".")[1:])
                else:
                    continue
            else:
                keep = len(package) - (node.level - 1)
                base = tuple(package[:keep]) + (tuple(node.module.split(".")) if node.module else ())
            if node.module is None or (root.joinpath(*base, "__init__.py").is_file()):
                # "from . import x" / "from .pkg import x": x may be a module of the package
                for a in node.names:
                    if root.joinpath(*base, a.name + ".py").is_file() or \
                            root.joinpath(*base, a.name, "__init__.py").is_file():
                        out.add(base + (a.name,))
                    elif base:
                        out.add(base)
            elif base:
                out.add(base)
        elif isinstance(node, ast.Import):
            for a in node.names:
                parts = a.name.split(".")
                if parts[0] == "archrock" and len(parts) > 1:
                    out.add(tuple(parts[1:]))
    return out


def module_graph(root: Path) -> dict[tuple[str, ...], set[tuple[str, ...]]]:
    return {_module_name(root, p): _imports(root, p) for p in sorted(root.rglob("*.py"))}


def place_graph(graph) -> dict[str, set[str]]:
    places: dict[str, set[str]] = {}
    for mod, targets in graph.items():
        if not mod:
            continue  # the package's lazy namespace re-exports every layer
        own = mod[0]
        places.setdefault(own, set()).update(t[0] for t in targets if t and t[0] != own)
    return places


def levels(places: dict[str, set[str]]) -> int:
    memo: dict[str, int] = {}

    def depth(p: str, seen=()) -> int:
        if p in seen:
            return 0
        if p not in memo:
            memo[p] = 1 + max((depth(q, seen + (p,)) for q in places.get(p, ())), default=0)
        return memo[p]
    return max(depth(p) for p in places)


def folder_cycles(graph) -> list[list[str]]:
    """Circles of imports between the modules of one folder (a package's __init__ left out:
    it re-exports its modules by design)."""
    found = []
    folders = {m[:-1] for m in graph if len(m) > 1}
    for folder in sorted(folders):
        mods = {m for m in graph if m[:-1] == folder and m != folder}
        edges = {m: {t for t in graph[m] if t in mods and t != m} for m in mods}
        for cycle in _cycles(edges):
            found.append([".".join(m) for m in cycle])
    return found


def _cycles(edges) -> list[list]:
    """One circle per strongly connected component of more than one node (Tarjan)."""
    index, low, stack, on, comps, counter = {}, {}, [], set(), [], [0]

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in edges[v]:
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                comps.append(sorted(comp))
    for v in sorted(edges):
        if v not in index:
            visit(v)
    return comps


def functions(root: Path):
    for path in sorted(root.rglob("*.py")):
        tree = ast.parse(path.read_text(encoding="utf-8"))
        for node in ast.walk(tree):
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                yield node.end_lineno - node.lineno + 1, path.relative_to(root), node.name


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--src", default=str(Path(__file__).resolve().parents[2] / "src" / "archrock"))
    root = Path(ap.parse_args(argv).src)
    graph = module_graph(root)
    places = place_graph(graph)
    edges = sum(len(v) for v in places.values())
    up = [f"{a} -> {b}" for a, out in places.items() for b in out
          if LAYER.get(b, 99) > LAYER.get(a, 99) or {a, b} == {"reports", "options"}]
    print(f"places {len(places)}, edges {edges}, levels {levels(places)}, "
          f"imports running up {len(up)}")
    for line in up:
        print(f"  up: {line}")
    cycles = folder_cycles(graph)
    print(f"circles inside a folder: {len(cycles)}")
    for c in cycles:
        print("  circle: " + " <-> ".join(c))
    sizes = sorted(((len(p.read_text(encoding='utf-8').splitlines()), p.relative_to(root))
                    for p in root.rglob("*.py")), reverse=True)
    over = [s for s in sizes if s[0] > 700]
    print(f"modules {len(sizes)}, largest {sizes[0][1]} {sizes[0][0]} lines, over 700 lines: "
          f"{len(over)}" + "".join(f"\n  {n} {p}" for n, p in over))
    funcs = sorted(functions(root), reverse=True)
    print(f"longest function {funcs[0][1]}:{funcs[0][2]} {funcs[0][0]} lines")
    study = [f for f in funcs if f[1].parts[0] == "studies" and f[0] > 60]
    print(f"functions of studies/ over 60 lines: {len(study)}"
          + "".join(f"\n  {n} {p}:{name}" for n, p, name in study))
    return 0


if __name__ == "__main__":
    sys.exit(main())
