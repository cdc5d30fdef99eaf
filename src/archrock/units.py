"""Physical constants shared by the whole package (SI units)."""

#: Gravity acceleration [m/s^2]: weights, multipliers in g and accelerations in g use this value.
G = 9.81
