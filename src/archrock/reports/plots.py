"""Figures (matplotlib, imported lazily: the core modules never import this one), by concept:

* :mod:`.drawing`: the colours, an arch's voussoirs, joints and hinges (:func:`draw_arch`,
  :func:`draw_hinges`), and the figure files (:func:`new_figure`, :func:`save_figure`: the Agg
  canvas directly, so scripts and the CLI never depend on an interactive backend);
* :mod:`.limitplots`: limit analysis (:func:`plot_limit`, the paper's Fig. 3 for any arch;
  :func:`save_limit_figure`; k against the piers' height);
* :mod:`.responseplots`: ground motions, responses (the paper's Fig. 4) and displaced arches;
* :mod:`.studyplots`: collapse and fragility curves, an ensemble's histograms, defect maps.

This module gives every public name of the four in one place, as before the split.
"""

from __future__ import annotations

from .drawing import (MAX_FIGURE_PIXELS, MIN_DPI, STYLE, block_faces, clip_thrust_polyline,
                      draw_arch, draw_hinges, figure_path, label_joint, new_figure, output_file,
                      save_figure, springing_level, voussoir_bounds, voussoir_outline)
from .limitplots import plot_k_against_pier_height, plot_limit, save_limit_figure
from .responseplots import (FIGURE_TAIL_S, displaced_hinges, displaced_outlines, draw_displaced,
                            figure_t_end, plot_ground_motion, plot_response,
                            save_response_figure)
from .studyplots import (DEFECT_CMAP, defect_norm, plot_collapse_curve, plot_defect_map,
                         plot_fragility, plot_multiplier_histograms)

__all__ = [
    "voussoir_outline", "voussoir_bounds", "label_joint", "draw_arch", "draw_hinges",
    "plot_limit", "save_limit_figure", "new_figure", "save_figure", "figure_t_end",
    "figure_path", "MAX_FIGURE_PIXELS", "plot_ground_motion", "plot_response",
    "save_response_figure", "PAPER_FIGURES", "draw_displaced", "displaced_outlines",
    "displaced_hinges", "plot_defect_map", "defect_norm", "plot_k_against_pier_height",
    "block_faces",
    # public here before the split too
    "STYLE", "MIN_DPI", "output_file", "springing_level", "clip_thrust_polyline",
    "FIGURE_TAIL_S", "plot_collapse_curve", "plot_fragility", "plot_multiplier_histograms",
    "DEFECT_CMAP",
]

#: the figures of the paper's study (:func:`archrock.studies.paper.run_paper_study`)
PAPER_FIGURES = {"fig3": save_limit_figure, "fig4": save_response_figure}
