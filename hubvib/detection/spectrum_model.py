"""What detection and diagnosis need of a spectrum model, and the rigid-ring lumped model's
implementation (SI).

A spectrum model gives, for the crack depths of its sweep, the natural frequencies a record
sees [Hz]: the nominal reducer's and those of reducers drawn from its uncertainty model,
the modes in one fixed order (mode ``i`` is the same mode at every depth).  The rigid-ring
lumped model (:class:`RigidSpectrum`, a wrapper of ``CrackModel`` and
:mod:`.uncertainty`) and the elastic ring
(:class:`hubvib.detection.elastic_model.ElasticSpectrum`) implement it, with one
argument order: ``(options, timing, ...)``.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol, runtime_checkable

import numpy as np

from .budget import chunked_frequencies
from .drift import Drift, drift_model
from .model import CrackModel
from .uncertainty import draw, nominal, observed_frequencies

__all__ = ["SpectrumModel", "RigidSpectrum", "as_spectrum_model"]


@runtime_checkable
class SpectrumModel(Protocol):
    """A crack model as detection and diagnosis use it.

    ``depths``: the sweep's crack depths [m], the first 0; ``ring``: ``"rigid"`` or
    ``"elastic"``.
    """

    depths: tuple
    ring: str

    def nominal_hz(self, options, timing, long_record: bool | None = None) -> np.ndarray:
        """Observed frequencies of the nominal reducer [Hz], (depths, modes).
        ``long_record``: the record spans more than one engagement of the cracked tooth
        (default: from ``options.record_length``)."""

    def sampled_hz(self, options, timing, samples: int, rng, workers: int = 1,
                   depth_index=None, long_record: bool | None = None) -> np.ndarray:
        """Observed frequencies of ``samples`` reducers drawn from the uncertainty model
        with ``rng`` [Hz], (samples, depths, modes); with ``depth_index`` (one index per
        sample) depth 0 and that depth only: (samples, 2, modes)."""

    def mode_labels(self) -> tuple:
        """One short name per mode (its order in the arrays)."""

    def drift(self, intact_hz, options) -> Drift:
        """Drift between two records (temperature, load) of modes whose intact
        frequencies are ``intact_hz`` [Hz]."""

    def mesh_stiffness(self) -> dict:
        """Provenance of the ring-planet mesh stiffness, as the JSON outputs give it."""

    def at_depths(self, depths) -> "SpectrumModel":
        """The same model at other depths [m] (the first 0, within the sweep)."""

    @property
    def tracked(self):
        """(depths, modes) of bool: whether the nominal continuation of each mode is
        tracked (a sampled change of an untracked one counts as none); None: all are."""


@dataclass(frozen=True)
class RigidSpectrum:
    """The rigid-ring lumped model (``CrackModel``) through :mod:`.uncertainty`: the same
    numbers as calling its functions directly."""

    crack: CrackModel
    ring: str = "rigid"

    @property
    def depths(self) -> tuple:
        return self.crack.depths

    def _long(self, timing, options, long_record):
        return timing.long_record(options.record_length) if long_record is None else long_record

    def nominal_hz(self, options, timing, long_record: bool | None = None) -> np.ndarray:
        return observed_frequencies(self.crack, nominal(self.crack), timing.engaged_fraction,
                                    self._long(timing, options, long_record))[0]

    def sampled_hz(self, options, timing, samples: int, rng, workers: int = 1,
                   depth_index=None, long_record: bool | None = None) -> np.ndarray:
        drawn = draw(self.crack, options, samples, rng)
        fraction, long = timing.engaged_fraction, self._long(timing, options, long_record)
        if depth_index is None:
            return chunked_frequencies(self.crack, drawn, fraction, long, workers)
        return observed_frequencies(self.crack, drawn, fraction, long, workers,
                                    depth_index=depth_index)

    def mounting(self):
        """How this model's mounting is scaled (:class:`.mounting_map.RigidMounting`: the
        torsional and radial mounting stiffness in series with the FE ring body)."""
        from .mounting_map import RigidMounting

        return RigidMounting(self.crack)

    def mode_labels(self) -> tuple:
        """``rigid 13 (rotational, 4548.5 Hz)`` per mode (:func:`.result.rigid_label`)."""
        from hubvib.lumped import natural_modes

        from .mode_names import rigid_label

        spectrum = natural_modes(self.crack.parameters(0), self.crack.method)
        f = spectrum.omega / (2 * np.pi)
        return tuple(rigid_label(i, kind, f[i]) for i, kind in enumerate(spectrum.kind))

    @property
    def tracked(self):
        """Every mode of the lumped model is tracked at every depth (None: no mask)."""
        return None

    def drift(self, intact_hz, options) -> Drift:
        return drift_model(self.crack.parameters(0), intact_hz, options, self.crack.method)

    def mesh_stiffness(self) -> dict:
        return self.crack.mesh_stiffness()

    def at_depths(self, depths) -> "RigidSpectrum":
        return RigidSpectrum(self.crack.at_depths(depths))


def as_spectrum_model(model) -> SpectrumModel:
    """``model`` as a SpectrumModel: a ``CrackModel`` is wrapped in :class:`RigidSpectrum`,
    anything else is taken to implement the protocol."""
    if isinstance(model, CrackModel):
        return RigidSpectrum(model)
    if not isinstance(model, SpectrumModel):
        raise TypeError(f"{type(model).__name__} is neither a CrackModel nor a "
                        f"SpectrumModel")
    return model
