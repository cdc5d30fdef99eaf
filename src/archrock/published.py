"""Figures published in the paper (EURODYN 2017) and the default spreads, in one place.

These are the values archrock is checked against (docs/verification.md); the random arches'
geometries were not published, so RA-1 and RA-2 are plausibility figures for the Monte Carlo.
"""

#: Collapse multiplier of Oppenheim's arch (R = 10 m, 157.5 deg, t = 1.5 m, 7 voussoirs).
K_OPPENHEIM = 0.3700
#: Coefficient of restitution of Oppenheim's arch (De Lorenzis et al.'s impact model).
CV_OPPENHEIM = 0.8754
#: (k_l, k_r) of the paper's random arches: RA-1 recovers, RA-2 fails after an impact.
RANDOM_ARCHES = {"RA-1": (0.4111, 0.3104), "RA-2": (0.3946, 0.3501)}
#: Uniform spreads of span, thickness and radius that give multipliers spread like RA-1/RA-2.
DEFAULT_SPREADS = {"spread_span": 0.1, "spread_thickness": 0.1, "spread_radius": 0.05}
