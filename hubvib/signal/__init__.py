"""Vibration signature of a cracked ring gear at a fixed sensor.

FE mesh-cycle stiffness (``mesh_curves``) placed per planet by the gear geometry
(``mesh_phase``) drives the lumped model in time (``dynamics``, ``time_response``,
``simulation``); a ring-mounted sensor (``sensor``) records it; ``spectral``
(shared with the seed-000 harmonics), ``indicators``, ``study`` and ``report``
turn it into spectra and condition indicators against crack depth.  Beside them:
manufacturing errors and load sharing (``errors``), tooth separation (``contact``),
sensors placed from the crack (``sensors``), speed fluctuation, tacho and order
tracking (``speed``), the records pipeline (``records``) and detection rates
(``roc``).  Only numpy and scipy are imported with the package.
"""
from .benchmark import benchmark_signal
from .options import SignalOptions, parse_signal_table

__all__ = ["benchmark_signal", "SignalOptions", "parse_signal_table"]
