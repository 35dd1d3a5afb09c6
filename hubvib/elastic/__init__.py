"""The elastic-ring planetary model from a reducer design (SI inside).

The ring is the project's plane FE body (any design, intact, cracked with open or closed
faces), reduced to its own modes plus the residual flexibility of the planets' contacts
(``hubvib.fem.ring_basis``) and coupled to the lumped sun, carrier and planets
(``hubvib.lumped.elastic_ring``).  One concept per module: ``options`` (mesh, mounting,
cut-off), ``rest`` (the ring-planet spring without the ring body), ``model`` (a design's
coupled model and its spectrum at a carrier position), ``content`` (nodal diameters,
harmonic index, mode class, multiplicity), ``tracking`` (modes followed over crack depth),
``crack_state`` (the crack's faces in contact under the working load), ``loaded`` (the
coupled modes about that state over a planet pitch), ``record_spectrum`` (what a
record of a mode whose frequency varies over the pitch shows)
and ``annulus`` (a plain annulus, for checks against ring theory).  Every name below is
imported on first use (PEP 562).
"""
from typing import TYPE_CHECKING

from hubvib.foundation.lazy import lazy_face

if TYPE_CHECKING:
    from .annulus import annulus_modes
    from .content import ModeContent, mode_content
    from .crack_state import CrackState, crack_state
    from .loaded import LoadedSpectra, RecordTrack, record_track
    from .model import ElasticRing, ElasticSpectrum, elastic_ring, elastic_spectrum
    from .options import ElasticOptions
    from .record_spectrum import RecordSpectrum, record_spectrum
    from .rest import rest_stiffness
    from .tracking import track_modes

__all__ = [
    "ElasticOptions", "ElasticRing", "ElasticSpectrum", "elastic_ring", "elastic_spectrum",
    "ModeContent", "mode_content", "rest_stiffness", "track_modes", "annulus_modes",
    "CrackState", "crack_state", "LoadedSpectra", "RecordTrack", "record_track",
    "RecordSpectrum", "record_spectrum",
]
__getattr__, __dir__ = lazy_face(__name__, __file__, __all__)
