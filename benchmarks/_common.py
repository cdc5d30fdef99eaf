"""What the benchmarks share: their command line's start and end, and the record of a timed
ensemble.  Each benchmark runs as a script (``python benchmarks/bench_x.py``), so this folder is
on its import path."""

from __future__ import annotations

import argparse
import json


def parser(doc: str, samples: int | None = None) -> argparse.ArgumentParser:
    """A benchmark's command line, described by the first line of its docstring ``doc``, with
    ``--json FILE`` and, when ``samples`` is given, ``--samples N`` (default ``samples``)."""
    ap = argparse.ArgumentParser(description=doc.split("\n")[0])
    if samples is not None:
        ap.add_argument("--samples", type=int, default=samples)
    ap.add_argument("--json", help="also write the figures to this JSON file")
    return ap


def speed_record(samples: int, wall: float, prepare_s: float, response_s: float,
                 **extra) -> dict:
    """The speed of ``samples`` arches in ``wall`` [s], ``prepare_s`` and ``response_s`` [s] of
    it, and the ``extra`` figures."""
    return {"samples": samples, "wall_s": wall, "arches_per_s": samples / wall,
            "prepare_s": prepare_s, "response_s": response_s, **extra}


def ensemble_record(res, samples: int, wall: float) -> dict:
    """Speed and outcomes of a timed ensemble ``res`` of ``samples`` arches in ``wall`` [s]."""
    f = res.frame
    return speed_record(samples, wall, res.timing["prepare_s"], res.timing["response_s"],
                        collapsed=int(f["collapsed"].sum()),
                        left_out=int((f["error"] != "").sum()))


def finish(out: dict, path: str | None) -> dict:
    """Write the figures ``out`` to the JSON file ``path`` when given; returns ``out``."""
    if path:
        with open(path, "w", encoding="utf-8") as fh:
            json.dump(out, fh, indent=2)
    return out
