"""The README's quick start names what exists, and the Python examples (docs/python.md, the
README's Python section until 0.7) run and print what the page says they print."""

import contextlib
import io
import re
from pathlib import Path

import pytest

README = Path(__file__).resolve().parents[2] / "README.md"
PYTHON = README.parent / "docs" / "python.md"


def _blocks():
    return re.findall(r"```python\n(.*?)```", PYTHON.read_text(encoding="utf-8"), flags=re.S)


def _section(text, title):
    body = text.split(f"\n## {title}\n", 1)[1]
    return body.split("\n## ", 1)[0]


def test_readme_python_blocks_are_all_run():
    # the blocks run below are exactly the code blocks of docs/python.md: a block there fenced
    # other than ```python (or one the pattern misses) would go unchecked, and one left
    # unclosed would swallow the text after it
    text = PYTHON.read_text(encoding="utf-8")
    section = re.findall(r"^```(\w*)\n(.*?)^```$", text, flags=re.S | re.M)
    assert section and all(lang == "python" for lang, _ in section)
    assert _blocks() == [code for _, code in section]
    assert text.count("```python\n") == len(_blocks())


def test_readme_quick_start_commands():
    """The quick start's two commands are exactly these, and what they name exists: the 'all'
    extra (with the test tools), the archrock console script and `paper --out`."""
    import tomllib

    from archrock.cli import build_parser

    quick = _section(README.read_text(encoding="utf-8"), "Quick start")
    install = 'python -m venv .venv && .venv/bin/pip install -q ".[all]"'
    assert re.findall(r"```bash\n(.*?)\n```", quick, flags=re.S) == [
        f"{install} && .venv/bin/archrock paper --out paper-out",
        f"{install} && .venv/bin/python -m pytest",
    ]
    project = tomllib.loads((README.parent / "pyproject.toml").read_text(encoding="utf-8"))
    project = project["project"]
    assert project["scripts"]["archrock"] == "archrock.cli:main"
    extras = project["optional-dependencies"]
    everything = re.search(r"archrock\[(.*)\]", extras["all"][0]).group(1).split(",")
    # every extra but the documentation site's tools (`docs`, installed by CI after `all`)
    assert set(everything) == set(extras) - {"all", "docs"} and "test" in everything
    args = build_parser().parse_args(["paper", "--out", "paper-out"])
    assert (args.command, args.out) == ("paper", "paper-out")


@pytest.mark.parametrize("i", range(len(_blocks())))
def test_readme_python_block_runs(i, tmp_path, monkeypatch):
    pytest.importorskip("matplotlib")
    monkeypatch.chdir(tmp_path)
    code = _blocks()[i]
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        exec(compile(code, f"docs/python.md block {i}", "exec"), {})
    printed = out.getvalue().splitlines()
    # each print() prints one line; the numbers in its '# comment' must match what it printed
    prints = [line for line in code.splitlines() if line.startswith("print(")]
    assert len(printed) == len(prints)
    expected = [(re.findall(r"#\s*(.*)$", line) or [""])[0].strip() for line in prints]
    checked = 0
    for want, got in zip(expected, printed):
        shown = [float(x) for x in re.findall(r"-?\d+\.\d+(?:e-?\d+)?", got)]
        for num in re.findall(r"-?\d+\.\d+", want.split("(")[0]):
            decimals = len(num.split(".")[1])
            # the page shows `decimals` decimals: a printed value within half a unit of the
            # last one (1e-12 more for a computed value right on a rounding boundary)
            assert any(abs(x - float(num)) <= 0.5 * 10.0**-decimals + 1e-12 for x in shown), \
                f"docs/python.md says {want!r}, the code printed {got!r}"
            checked += 1
    assert checked >= 2
