"""The fragility figure of ``archrock fragility``, four-link or engine: drawn after the results
are written, so that a failure to draw is one warning line, never the end of the run."""

from __future__ import annotations

import sys


def fragility_figure(res_ida, res_msa, plot) -> bool:
    """Draw the fragility figure; where drawing fails, one warning line on stderr (the results
    are already written) and False, never a traceback that ends the run."""
    from ..reports.plots import plot_fragility

    try:
        fit = res_msa.fit if res_msa is not None and res_msa.fit is not None else res_ida.fit
        plot_fragility(fit, res_msa, plot, ida=res_ida)
    except Exception as exc:  # noqa: BLE001 -- any failure of a figure is a warning, by design
        why = " ".join(str(exc).split()) or type(exc).__name__
        print(f"archrock: warning: figure {plot} not written ({type(exc).__name__}: {why}); "
              f"the results above are complete", file=sys.stderr)
        return False
    return True
