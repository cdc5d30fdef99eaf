"""The run options of the study commands: ``--workers``, ``--scheduler``, ``--out``,
``--device`` and ``--no-progress`` turned into one :class:`~archrock.studies.runner.RunSettings`, and the
renderer of the progress protocol (:mod:`archrock._progress`) on stderr."""

from __future__ import annotations

import sys

__all__ = ["run_settings", "StderrProgress", "STDERR_PROGRESS"]


def _terminal() -> bool:
    """stderr is a terminal (where a bar redraws in place); in a log file or a pipe every redraw
    of a bar would be one more line."""
    try:
        return bool(sys.stderr.isatty())
    except (AttributeError, ValueError):
        return False


class _Bar:
    """A tqdm bar on stderr, redrawn at most once a second."""

    def __init__(self, tqdm_bar):
        self.tqdm = tqdm_bar

    def update(self, n: int):
        self.tqdm.update(n)

    def write(self, text: str):
        self.tqdm.write(text, file=sys.stderr)

    def close(self):
        self.tqdm.close()


class StderrProgress:
    """The CLI's progress renderer: each line on stderr; on a terminal a study's count is a
    tqdm bar instead (when tqdm is installed)."""

    def __call__(self, line: str) -> None:
        print(line, file=sys.stderr, flush=True)

    def bar(self, total: int, desc: str, unit: str):
        """A bar for ``total`` units, or None (plain, throttled lines) off a terminal."""
        if not _terminal():
            return None
        try:
            from tqdm import tqdm
        except ImportError:
            return None
        from .._progress import Progress

        return _Bar(tqdm(total=total, unit=unit, desc=desc, file=sys.stderr,
                         dynamic_ncols=True, mininterval=Progress.MIN_INTERVAL_S))


STDERR_PROGRESS = StderrProgress()


def run_settings(args, *, out=None, workers=True, scheduler=True, progress=True,
                 sink=STDERR_PROGRESS):
    """The :class:`RunSettings` of a study command's flags: ``--workers`` (1: in-process),
    ``--scheduler``, ``out`` (the checked ``--out`` folder, or None) and ``--no-progress``
    (progress to ``sink``, stderr by default, unless given) and ``--device`` (cpu where the
    command has none).  workers/scheduler/progress False: the command has no such flag (or
    does not run on it), the field stays at its default."""
    from ..studies.runner import RunSettings

    w = getattr(args, "workers", None) if workers else None
    return RunSettings(
        workers=None if w is None or w == 1 else w,
        scheduler=getattr(args, "scheduler", None) if scheduler else None,
        out=out,
        progress=(sink if progress and not getattr(args, "no_progress", False) else None),
        device=getattr(args, "device", None) or "cpu")


def cpu_only(args, command: str) -> None:
    """Refuse ``--device gpu`` before any work where ``command``'s kernels run on the CPU only
    (its sweeps, or the contact engine); ``auto`` is then the CPU."""
    if getattr(args, "device", "cpu") == "gpu":
        from ..studies.runner import RunSettings

        RunSettings(device="gpu").on_cpu(command)


def gpu_ready(args) -> None:
    """With ``--device gpu``, refuse before any work where no GPU (nor numba's simulator) is
    usable here: the one line of :func:`archrock._device.resolve_device`."""
    if getattr(args, "device", "cpu") == "gpu":
        from .._device import resolve_device

        resolve_device("gpu")
