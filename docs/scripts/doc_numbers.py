"""The numbers README.md and docs/*.md quote from a command, each checked against what the
command prints today.

    python docs/scripts/doc_numbers.py              # the fast entries: a line per drifted number
    python docs/scripts/doc_numbers.py --slow       # also the long commands (minutes)
    python docs/scripts/doc_numbers.py --update     # rewrite drifted numbers in the docs, list them
    python docs/scripts/doc_numbers.py --only TEXT  # the entries whose command contains TEXT

The registry (:data:`ENTRIES`, in docs/scripts/doc_numbers_registry.py) holds no number: each entry
is a quote of the doc with ``{}`` where the number stands, the command, and a regular expression
that reads the number from the command's output (one group per ``{}``).  The doc is the only
place a number is written, so ``--update`` edits the docs alone, and a changed result fails
tests/test_docs_numbers.py until the docs change with it.  A quoted number matches when it
equals the command's value at the precision it is quoted at (its decimals, half a unit of the
last digit).  :func:`unregistered` finds numbers in command-output code blocks and beside
``print(...)`` calls in Python blocks that no entry covers (and that are not listed as
machine-dependent), so a new quoted number cannot slip in unchecked, and
:func:`read_before_written` finds an example that reads a file above the one that writes it.

Run from anywhere with ``PYTHONPATH=src`` (the checkout's package); commands run in this
process, in a temporary folder (paths under tests/ and docs/ are made absolute).
"""

from __future__ import annotations

import argparse
import contextlib
import io
import os
import re
import sys
import tempfile
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
if str(Path(__file__).resolve().parent) not in sys.path:   # the registry beside this file
    sys.path.insert(0, str(Path(__file__).resolve().parent))

#: A quoted number: optional sign, digits with optional thousands commas, optional decimals.
NUMBER = r"[-+]?(?:\d{1,3}(?:,\d{3})+|\d+)(?:\.\d+)?(?:e[-+]?\d+)?"


@dataclass(frozen=True)
class Entry:
    """One quote of a doc and the command whose output it quotes.

    ``quote``: the doc's text with ``{}`` for each number (whitespace matches any whitespace,
    so a quote may cross a line break); ``cmd``: archrock's argv, or ``"py:NAME"`` for the
    function ``NAME`` of doc_numbers_registry.py that returns the text to read; ``read``: a regular
    expression over that text with one group per ``{}``, in the same order, or ``"json:"`` and
    the comma-separated paths of the values in the JSON document it prints; ``scale``: what
    multiplies the command's value before comparing (100 for a fraction quoted in %);
    ``slow``: the command takes more than a few seconds (the ``-m slow`` set); ``status``: the
    exit status the command must end with (3: an outcome quoted from its message); ``order``:
    which of ``read``'s groups each ``{}`` takes, where the output prints them in another order
    (default: the groups in turn); ``skip``: the ``{}`` (by position) read but not compared,
    because the command does not print them reproducibly (say why beside the entry);
    ``at_least``: each quoted number is a floor, not a value: the command's value must reach it
    (speed ratios, which vary from run to run with the machine's load), and ``--update`` leaves
    it alone (a value below its floor is a slowdown to look into, not a number to rewrite)."""

    doc: str
    quote: str
    cmd: tuple | str
    read: str
    scale: float | tuple = 1.0
    slow: bool = False
    status: int = 0
    order: tuple = ()
    skip: tuple = ()
    at_least: bool = False

    @property
    def count(self) -> int:
        """How many of the quote's numbers are compared."""
        return self.quote.count("{}") - len(self.skip)

    def pattern(self) -> re.Pattern:
        """The quote as a regular expression: the numbers as groups, whitespace as ``\\s+``."""
        parts = []
        for i, lit in enumerate(self.quote.split("{}")):
            words = lit.split()
            text = r"\s+".join(re.escape(w) for w in words)
            if not words and lit:
                text = r"\s+"
            else:
                if lit[:1].isspace() and i > 0:
                    text = r"\s+" + text
                if lit[-1:].isspace() and i < self.quote.count("{}"):
                    text = text + r"\s+"
            parts.append(text)
        return re.compile(f"({NUMBER})".join(parts))

    def key(self) -> str:
        return self.cmd if isinstance(self.cmd, str) else "archrock " + " ".join(self.cmd)


@dataclass(frozen=True)
class Unchecked:
    """A quoted number that is not a result to check: a timing, a count of the machine's work,
    an input echoed back.  ``quote`` as in :class:`Entry`; ``why`` says why it is left out."""

    doc: str
    quote: str
    why: str

    def pattern(self) -> re.Pattern:
        return Entry(self.doc, self.quote, (), "").pattern()


def decimals(text: str) -> int:
    """Digits after the decimal point of a quoted number (0 for an integer)."""
    mantissa = text.lower().split("e")[0]
    return len(mantissa.split(".")[1]) if "." in mantissa else 0


def parse(text: str) -> float:
    return float(text.replace(",", ""))


def unit(text: str) -> float:
    """One unit of the last digit of a printed number (1e-4 for 0.3700, 1e-16 for 7.77e-16)."""
    mantissa, _, exponent = text.lower().partition("e")
    return 10.0 ** (int(exponent or 0) - decimals(mantissa))


def agrees(quoted: str, value: float, printed: float = 0.0) -> bool:
    """``quoted`` is ``value`` at the precision it is quoted at: within half a unit of its last
    digit, plus half of ``printed``, the unit the command printed ``value`` at (two roundings of
    one number: 0.7535 printed 0.753 and quoted 75.4%)."""
    q = parse(quoted)
    return abs(value - q) <= 0.5 * (unit(quoted) + printed) * (1 + 1e-9) + 1e-12 * abs(q)


def reaches(quoted: str, value: float, printed: float = 0.0) -> bool:
    """``value`` is at least the floor ``quoted`` (a speed ratio quoted as "at least 200x")."""
    return value >= parse(quoted)


def formatted(quoted: str, value: float) -> str:
    """``value`` written as ``quoted`` is: same decimals, thousands commas, explicit sign."""
    d = decimals(quoted)
    text = f"{value:,.{d}f}" if "," in quoted else f"{value:.{d}f}"
    if quoted.startswith("+") and value >= 0:
        text = "+" + text
    return text


def _absolute(arg: str) -> str:
    """Paths of the repository (tests/data/..., docs/...) made absolute, so that commands can run
    in a temporary folder."""
    head = arg.split("/")[0]
    if head in ("tests", "docs") and (ROOT / arg).exists():
        return str(ROOT / arg)
    return arg


def run_archrock(argv, expect: int = 0) -> str:
    """archrock's stdout and stderr for ``argv``, run in this process in a temporary folder."""
    from archrock.cli import main

    out, err = io.StringIO(), io.StringIO()
    here = os.getcwd()
    with tempfile.TemporaryDirectory() as tmp:
        os.chdir(tmp)
        try:
            with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
                try:
                    status = main([_absolute(a) for a in argv])
                except SystemExit as exc:
                    status = exc.code
        finally:
            os.chdir(here)
    text = out.getvalue() + "\n" + err.getvalue()
    if (status or 0) != expect:
        raise RuntimeError(f"archrock {' '.join(argv)} exited {status}:\n{err.getvalue()}")
    return text


_OUTPUTS: dict[str, str] = {}


def output(entry: Entry) -> str:
    """The text ``entry`` reads its numbers from (each command run once per process)."""
    key = entry.key()
    if key not in _OUTPUTS:
        if isinstance(entry.cmd, str):
            from doc_numbers_registry import FUNCTIONS
            _OUTPUTS[key] = FUNCTIONS[entry.cmd.removeprefix("py:")]()
        else:
            _OUTPUTS[key] = run_archrock(entry.cmd, entry.status)
    return _OUTPUTS[key]


@dataclass
class Finding:
    entry: Entry
    line: int                  # 1-based line of the doc where the quote starts
    quoted: list[str]
    values: list[float]
    problem: str = ""          # "" when every number agrees
    printed: list[float] = ()  # the unit each value was printed at, scaled as the value

    @property
    def drifted(self) -> list[int]:
        ok = reaches if self.entry.at_least else agrees
        return [i for i, (q, v, p) in enumerate(zip(self.quoted, self.values, self.printed))
                if i not in self.entry.skip and not ok(q, v, p)]


def json_values(text: str, paths: str) -> list[str] | None:
    """The values at ``paths`` (comma-separated, keys joined by dots: ``p_collapse.low``) of the
    JSON document that ``text`` starts with, as text (full precision)."""
    import json
    try:
        doc, _ = json.JSONDecoder().raw_decode(text[text.index("{"):])
        values = []
        for path in paths.split(","):
            v = doc
            for key in path.strip().split("."):
                v = v[key]
            values.append(repr(float(v)))
        return values
    except (ValueError, KeyError, TypeError):
        return None


def locate(entry: Entry, text: str | None = None) -> list[re.Match]:
    """Where the entry's quote stands in its doc."""
    if text is None:
        text = (ROOT / entry.doc).read_text()
    return list(entry.pattern().finditer(text))


def check(entry: Entry) -> Finding:
    """Compare the entry's quoted numbers with what its command prints."""
    text = (ROOT / entry.doc).read_text()
    found = locate(entry, text)
    if len(found) != 1:
        return Finding(entry, 0, [], [], f"quote found {len(found)} times in {entry.doc} "
                                         f"(must be once): {entry.quote!r}")
    m = found[0]
    line = text.count("\n", 0, m.start()) + 1
    quoted = list(m.groups())
    if entry.read.startswith("json:"):
        groups = json_values(output(entry), entry.read.removeprefix("json:"))
        if groups is None:
            return Finding(entry, line, quoted, [], f"{entry.key()}: no {entry.read!r} in its JSON")
    else:
        got = re.search(entry.read, output(entry), re.S)
        if got is None:
            return Finding(entry, line, quoted, [], f"{entry.key()}: output no longer matches "
                                                    f"{entry.read!r}")
        groups = list(got.groups())
    if entry.order:
        groups = [groups[i] for i in entry.order]
    if len(groups) != entry.quote.count("{}"):
        return Finding(entry, line, quoted, [], "read has a group count unlike the quote's")
    scales = (entry.scale if isinstance(entry.scale, tuple) else
              (entry.scale,) * entry.quote.count("{}"))
    values = [parse(g) * s for g, s in zip(groups, scales)]
    printed = [unit(g) * abs(s) for g, s in zip(groups, scales)]
    return Finding(entry, line, quoted, values, printed=printed)


def update(findings: list[Finding]) -> list[str]:
    """Rewrite the drifted numbers in their docs; one line per change."""
    changes, by_doc = [], {}
    for f in findings:
        if not f.problem and f.drifted and not f.entry.at_least:
            by_doc.setdefault(f.entry.doc, []).append(f)
    for doc, fs in by_doc.items():
        path = ROOT / doc
        text = path.read_text()
        for f in fs:
            m = locate(f.entry, text)[0]
            pieces, last = [], m.start()
            for i, (q, v) in enumerate(zip(f.quoted, f.values)):
                new = formatted(q, v)
                pieces += [text[last:m.start(i + 1)], new]
                last = m.end(i + 1)
                if i in f.drifted:
                    changes.append(f"{doc}:{f.line}: {q} -> {new}   ({f.entry.key()})")
            text = text[:m.start()] + "".join(pieces) + text[last:]
        path.write_text(text)
    return changes


# ---------------------------------------------------------------------------------------------
# the guard: quoted numbers no entry covers

def doc_files() -> list[str]:
    return ["README.md"] + sorted(f"docs/{p.name}" for p in (ROOT / "docs").glob("*.md"))


_COMMAND = re.compile(r"^\s*(\$ )?archrock\b")


def quoted_outputs(doc: str, text: str) -> list[tuple[int, int, str]]:
    """(start, end, why) of every stretch of ``text`` whose numbers are quoted results: the
    output lines of a code block that shows an ``archrock`` command with what it prints, and the
    comment of a ``print(...)`` line in a Python block."""
    spans, pos, inside, lang, body = [], 0, False, "", []
    for line in text.splitlines(keepends=True):
        start, pos = pos, pos + len(line)
        if line.startswith("```"):
            if not inside:
                inside, lang, body = True, line[3:].strip(), []
                continue
            inside = False
            if lang == "python":
                for s, ln in body:
                    if "print(" in ln and "#" in ln:
                        spans.append((s + ln.index("#"), s + len(ln), "print comment"))
            elif any(_COMMAND.match(ln) for _, ln in body):
                continued = False
                for s, ln in body:
                    stripped = ln.strip()
                    if _COMMAND.match(ln) or continued or not stripped or \
                            stripped.startswith(("#", "python ", "pip ")):
                        continued = stripped.endswith("\\")
                        continue
                    spans.append((s, s + len(ln), "command output"))
            continue
        if inside:
            body.append((start, line))
    return spans


def unregistered(entries=None, unchecked=None) -> list[str]:
    """Numbers in command outputs and print comments of the docs that no entry and no
    :class:`Unchecked` item covers: ``doc:line: number in 'line'``."""
    from doc_numbers_registry import ENTRIES, UNCHECKED
    entries = ENTRIES if entries is None else entries
    unchecked = UNCHECKED if unchecked is None else unchecked
    missing = []
    for doc in doc_files():
        text = (ROOT / doc).read_text()
        covered = []
        for item in [e for e in entries if e.doc == doc] + [u for u in unchecked if u.doc == doc]:
            # a registered quote covers its literal numbers too (labels and inputs it echoes)
            covered += [(m.start(), m.end()) for m in item.pattern().finditer(text)]
        for start, end, why in quoted_outputs(doc, text):
            for m in re.finditer(NUMBER, text[start:end]):
                a, b = start + m.start(), start + m.end()
                # digits inside words and labels (M_l, 2i-5e, RSN6, x2) are not quoted numbers
                if a > 0 and (text[a - 1].isalnum() or text[a - 1] in "_."):
                    continue
                if b < len(text) and (text[b].isalpha() or text[b] == "_"):
                    continue
                if not any(s <= a and b <= e for s, e in covered):
                    line = text.count("\n", 0, a) + 1
                    missing.append(f"{doc}:{line}: {m.group()} ({why}) in "
                                   f"{text[start:end].strip()[:90]!r}")
    return missing


_READS = re.compile(r"--(?:geometry|records?|arcade)\s+((?:[\w./-]+\.(?:json|AT2|txt)\s*)+)"
                    r"|read_arch\(\"([^\"]+)\"")
_WRITES = re.compile(r"(?:--out|--write)\s+([\w./-]+\.(?:json|AT2|txt))"
                     r"|write_arch\([^,]+,\s*\"([^\"]+)\"")


def read_before_written() -> list[str]:
    """Examples that read a file (``--geometry F``, ``read_arch("F")``) above the example of the
    same page that writes it (``--out F``, ``write_arch(..., "F")``): ``doc:line: F ...``."""
    found = []
    for doc in doc_files():
        reads, writes = {}, {}
        for n, line in enumerate((ROOT / doc).read_text().splitlines(), 1):
            for m in _READS.finditer(line):
                for name in (m.group(1) or m.group(2)).split():
                    reads.setdefault(name, n)
            for m in _WRITES.finditer(line):
                writes.setdefault(m.group(1) or m.group(2), n)
        found += [f"{doc}:{n}: reads {name}, written below at line {writes[name]}"
                  for name, n in reads.items() if writes.get(name, 0) > n]
    return found


def main(argv=None) -> int:
    from doc_numbers_registry import ENTRIES

    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--update", action="store_true", help="rewrite drifted numbers in the docs")
    p.add_argument("--slow", action="store_true", help="include the long commands")
    p.add_argument("--only", metavar="TEXT", help="entries whose command contains TEXT")
    args = p.parse_args(argv)
    chosen = [e for e in ENTRIES if (args.slow or not e.slow)
              and (args.only is None or args.only in e.key())]
    findings = []
    for e in chosen:
        findings.append(check(e))
        f = findings[-1]
        if f.problem:
            print(f"ERROR {e.doc}: {f.problem}", flush=True)
        for i in f.drifted:
            print(f"{'BELOW FLOOR' if e.at_least else 'DRIFT'} {e.doc}:{f.line}: quoted "
                  f"{f.quoted[i]}, {e.key()} gives "
                  f"{formatted(f.quoted[i], f.values[i])} ({f.values[i]:.6g})", flush=True)
    missing = unregistered() + read_before_written()
    for m in missing:
        print(f"UNREGISTERED {m}" if " reads " not in m else f"ORDER {m}")
    numbers = sum(e.count for e in chosen)
    drifted = sum(len(f.drifted) for f in findings)
    errors = sum(bool(f.problem) for f in findings)
    print(f"{numbers} numbers in {len(chosen)} quotes checked against "
          f"{len({e.key() for e in chosen})} commands: {drifted} drifted, {errors} errors, "
          f"{len(missing)} unregistered or out of order" + ("" if args.slow else
                                           f" ({sum(e.count for e in ENTRIES if e.slow)} "
                                           "more with --slow)"))
    if args.update:
        for line in update(findings):
            print("updated", line)
        return 1 if errors or missing else 0
    return 1 if drifted or errors or missing else 0


if __name__ == "__main__":
    sys.exit(main())
