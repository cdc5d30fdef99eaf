"""The README's Python examples run, and print what the README says they print."""

import contextlib
import io
import re
from pathlib import Path

import pytest

README = Path(__file__).resolve().parents[1] / "README.md"


def _blocks():
    return re.findall(r"```python\n(.*?)```", README.read_text(encoding="utf-8"), flags=re.S)


def test_readme_has_python_examples():
    assert len(_blocks()) >= 2


@pytest.mark.parametrize("i", range(len(_blocks())))
def test_readme_python_block_runs(i, tmp_path, monkeypatch):
    pytest.importorskip("matplotlib")
    monkeypatch.chdir(tmp_path)
    code = _blocks()[i]
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        exec(compile(code, f"README block {i}", "exec"), {})
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
            # the README shows `decimals` decimals: a printed value within half a unit of the
            # last one (1e-12 more for a computed value right on a rounding boundary)
            assert any(abs(x - float(num)) <= 0.5 * 10.0**-decimals + 1e-12 for x in shown), \
                f"README says {want!r}, the code printed {got!r}"
            checked += 1
    assert checked >= 2
