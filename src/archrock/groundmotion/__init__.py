"""Ground motions: horizontal ground acceleration histories xg''(t) (docs/method.md, Response).

Conventions: SI units (s, m/s^2); ``accel`` is positive toward +x (to the right), the same x as
the arch geometry.  Amplitudes passed to the pulse constructors are in g (multiples of ``G``) and
may be negative: the paper's forcing is Oppenheim's pulse with a = -1 g, t_p = 0.20 s.

A :class:`GroundMotion` is a piecewise-linear history through its samples.  The idealised
pulses encode a step (a jump in acceleration) by a time twice in a row; the history is
right-continuous there (at the repeated time the later value applies).  A record (a file, an
upload) has strictly increasing times: a repeated time is refused naming its line
(:func:`.records.check_time_order`; a step is written as a short ramp).  Before t = 0 and after
the last sample the acceleration is 0.  So a record whose last sample is nonzero drops to 0 just after its end; the
pulse constructors end their histories with an explicit 0 where the drop matters.

Modules: :mod:`.motion` (the model, :func:`from_samples`), :mod:`.pulses` (idealised pulses),
:mod:`.records` (two-column and PEER NGA ``.AT2`` files), :mod:`.p695` (the FEMA P695
record sets as built-in suites, extra ``records``), :mod:`.spectra` (5%-damped response
spectra), :mod:`.selection` (records chosen and scaled for a target spectrum), :mod:`.synthetic` (seeded
band-limited noise), :mod:`.spec` (serialisable
specifications that rebuild a motion: :class:`PulseSpec`, :class:`RecordSpec`).  Every bad input
raises :class:`archrock.errors.ArchInputError` with a one-line message naming the field; a PGA
above :data:`MAX_PGA_G` or a record sampled more coarsely than :data:`MAX_RECORD_DT_S` cannot be
meant and is refused, above :data:`WARN_PGA_G` / :data:`WARN_RECORD_DT_S` a warning is issued.
"""

from ..units import G  # re-exported: the package's gravity constant [m/s^2]
from .motion import (MAX_PGA_G, MAX_RECORD_DT_S, UNITS, WARN_PGA_G, WARN_RECORD_DT_S,
                     GroundMotion, check_pga, from_samples)
from .pulses import (PULSE_KINDS, half_sine_pulse, one_sine_pulse, oppenheim_pulse, pulse,
                     pulse_kind, rectangular_pulse, ricker_pulse)
from .p695 import SUITES, suite_motion, suite_motions, suite_records
from .records import load_record, read_at2, read_two_column
from .selection import RecordSelection, select_records
from .spectra import response_spectrum
from .spec import PulseSpec, RecordSpec, motion_spec_from_dict
from .synthetic import band_limited_noise

__all__ = [
    "G",
    "UNITS",
    "MAX_PGA_G",
    "WARN_PGA_G",
    "MAX_RECORD_DT_S",
    "WARN_RECORD_DT_S",
    "check_pga",
    "PULSE_KINDS",
    "GroundMotion",
    "oppenheim_pulse",
    "rectangular_pulse",
    "half_sine_pulse",
    "one_sine_pulse",
    "ricker_pulse",
    "pulse",
    "pulse_kind",
    "from_samples",
    "read_two_column",
    "read_at2",
    "load_record",
    "band_limited_noise",
    "SUITES",
    "suite_records",
    "suite_motion",
    "suite_motions",
    "response_spectrum",
    "select_records",
    "RecordSelection",
    "PulseSpec",
    "RecordSpec",
    "motion_spec_from_dict",
]
