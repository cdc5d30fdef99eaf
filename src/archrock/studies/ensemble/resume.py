"""The batches of an ensemble run: each one read back from the output folder (resumed) or
computed, and the per-sample tables joined with the run's timing.

A folder written by other code (another release, another build) is resumed by verification:
the first batch of each such source is recomputed here, and its other batches are kept (and
re-stamped with this code's digest) only if that batch comes out bit for bit the same.
"""

from __future__ import annotations

import time

from ..._progress import Progress
from ..store import (OTHER_CODE, Manifest, batch_path, code_digest, is_damage, read_batch,
                     same_bits, say_damage, write_batch, written_by)
from .compute import run_batches
from .config import EnsembleConfig
from .executors import execute, run_device

__all__ = ["EnsembleBatches"]


class EnsembleBatches:
    """The batches of one run of ``config`` (settings: a RunSettings; impact and nominal: what
    the manifest records; t_start: the run's perf_counter at its start).  :meth:`run` reads or computes them all; :meth:`timing` says how."""

    def __init__(self, config: EnsembleConfig, settings, keep_frame: bool, impact: dict,
                 nominal: dict, t_start: float):
        self.config, self.settings, self.keep_frame = config, settings, keep_frame
        self.out = settings.out
        self.t_start = t_start  # the run's start (perf_counter), the nominal's analysis included
        self.manifest = (Manifest(self.out, config, impact, nominal) if self.out is not None
                         else None)
        self.frames: dict[int, object] = {}
        self.done: set[int] = set()
        self.batch_timings: dict[int, dict] = {}
        self.todo: list[int] = []
        self.recomputed: dict[int, str] = {}
        self.executor = None
        self.device = None  # where the batches computed ran: 'cpu' or 'gpu'
        self.bar = Progress(config.samples, settings.progress)

    # ------------------------------------------------------------------ one batch's fate
    def loaded(self, b: int, df) -> None:
        """Batch b read back from the folder."""
        self.done.add(b)
        if self.keep_frame:
            self.frames[b] = df
        self.manifest.batch_done(b, len(df), {}, computed=False)
        self.bar.update(len(df))

    def recompute(self, b: int, why: str) -> None:
        """Batch b is to be computed again (``why``: what was wrong with its file)."""
        self.todo.append(b)
        self.recomputed[b] = why
        self.manifest.run["recomputed"][str(b)] = why
        line = f"ensemble: recomputing batch {b}: {batch_path(self.out, b).name} {why}"
        if is_damage(why):  # never silent, even without progress output
            say_damage(line, self.bar.note if self.bar.enabled else None)
        else:
            self.bar.note(line)

    def finished(self, b: int, df, timings: dict) -> None:
        """Batch b computed: kept, and written with the manifest when there is a folder."""
        self.done.add(b)
        if self.keep_frame:
            self.frames[b] = df
        self.batch_timings[b] = timings
        if self.out is not None:
            write_batch(self.out, b, df, self.config)
            self.manifest.batch_done(b, len(df), timings, computed=True)
            self.manifest.save()
        self.bar.update(len(df))

    # ------------------------------------------------------------------ the run
    def run(self) -> None:
        """Read what the folder holds, verify other code's batches, compute the rest."""
        try:
            foreign = self._sort_batches()
            for digest, bs in foreign.items():
                self._verify_foreign(digest, bs)
            self.todo.sort()
            self.device = run_device(self.config, self.todo, self.settings)
            gpu = None
            if self.device == "gpu" and self.todo:  # which GPU, for the log and provenance
                from ..._device import gpu_note

                gpu = gpu_note()
                self.bar.note(f"ensemble: batch kernels on the GPU: {gpu}")
            if self.manifest is not None:
                self.manifest.run["device"] = self.device  # a run setting: not in the config
                if gpu is not None:
                    self.manifest.run["gpu"] = gpu
                self.manifest.save()
            self.executor, _ = execute(self.config, self.todo, self.finished, self.settings,
                                       self.device)
        finally:
            self.bar.close()
            if self.manifest is not None:
                self.manifest.finish(complete=len(self.done) == self.config.n_batches)

    def _sort_batches(self) -> dict[str, list[int]]:
        """Each batch loaded, to recompute or to compute; returns the batches written by other
        sources, by their digest."""
        out, config = self.out, self.config
        foreign: dict[str, list[int]] = {}
        mine = code_digest() if out is not None else None
        for b in range(config.n_batches):
            df, why = read_batch(out, b, config, any_code=True) if out is not None else (None, None)
            writer = written_by(out, b) if df is not None else mine
            if writer != mine:
                foreign.setdefault(writer, []).append(b)
            elif df is not None:
                self.loaded(b, df)
            elif why is not None:
                self.recompute(b, why)
            else:
                self.todo.append(b)
            del df
        return foreign

    def _verify_foreign(self, digest: str, bs: list[int]) -> None:
        """Resume by verification (module doc): batches ``bs`` of the source ``digest``."""
        out, config = self.out, self.config
        old, _ = read_batch(out, bs[0], config, any_code=True)
        self.recomputed[bs[0]] = self.manifest.run["recomputed"][str(bs[0])] = (
            f"{OTHER_CODE} ({str(digest)[:12]}): recomputed to verify its other batches")
        (_, new, timings), = run_batches(config, [bs[0]], self.settings.executor == "in-process",
                                         self._verifying_device(bs[0]))
        self.finished(bs[0], new, timings)
        differs = same_bits(old, read_batch(out, bs[0], config)[0])
        del old, new
        if differs is not None:
            for b in bs[1:]:
                self.recompute(b, f"{OTHER_CODE}, whose batch {bs[0]} this code recomputes "
                                  f"differently ({differs})")
            return
        self.bar.note(f"ensemble: batch {bs[0]}, {OTHER_CODE} ({str(digest)[:12]}), recomputed "
                      f"bit for bit the same: its {len(bs) - 1} other batch(es) kept")
        self.manifest.run.setdefault("verified", {})[str(digest)] = {
            "recomputed_batch": bs[0], "kept": bs[1:]}
        for b in bs[1:]:
            df, _ = read_batch(out, b, config, any_code=True)
            write_batch(out, b, df, config)
            self.loaded(b, df)
            del df

    def _verifying_device(self, b: int) -> str:
        """The device that recomputes the other code's batch b: the one that wrote it (the
        manifest says; 'cpu' before 0.8), where this run may use it.  The GPU's last bits
        differ from the CPU's (docs/gpu.md): compared across devices, a batch would differ
        and every other batch of that code be recomputed for nothing."""
        from ..._device import gpu_present

        wrote = self.manifest.data["batches"].get(str(b), {}).get("device", "cpu")
        mine = self.settings.run_device
        if wrote != "gpu" or mine == "cpu":
            return "cpu"
        return "gpu" if mine == "gpu" or gpu_present() else "cpu"

    # ------------------------------------------------------------------ what came of it
    def frame(self):
        """The per-sample table in sample order (None without ``keep_frame``)."""
        import pandas as pd

        if not self.keep_frame:
            return None
        return pd.concat([self.frames[b] for b in sorted(self.frames)], ignore_index=True)

    def timing(self, workers: int) -> dict:
        """Wall time, executor, and which batches were computed, loaded or recomputed."""
        wall = time.perf_counter() - self.t_start
        computed = sorted(self.batch_timings)
        n_computed = int(sum(self.config.batch_range(b)[1] for b in computed))
        spent = self.batch_timings.values()
        return {"wall_s": wall, "executor": self.executor, "workers": workers,
                "device": self.device,
                "computed_batches": computed,
                "loaded_batches": sorted(self.done - set(computed)),
                "recomputed_batches": {str(b): why for b, why in sorted(self.recomputed.items())},
                "computed_samples": n_computed,
                "samples_per_s": n_computed / wall if n_computed and wall > 0 else None,
                "prepare_s": float(sum(t["prepare_s"] for t in spent)),
                "response_s": float(sum(t["response_s"] for t in spent))}
