"""Lumped vibration model of a planetary gear stage (sun, carrier, ring, N planets).

Only numpy and scipy are imported here; nothing of the FE stages.  The parameters of a
registered design preset are built one layer up, from its design:
``hubvib.reducer.lumped_preset("raba118")``.
"""
from .eigensolve import METHODS, IndefiniteStiffnessError
from .energy import ModalEnergy, modal_energy
from .network import dof_names, mass_matrix, spring_network, stiffness_matrix
from .parameters import ParameterError, PlanetaryParameters, equally_spaced_angles, field_names
from .printed import printed_stiffness_matrix
from .sensitivity import Sensitivity, frequency_sensitivity
from .shift import FrequencyShift, frequency_shift
from .spectrum import Spectrum, natural_modes, printed_modes
from .sweep import Sweep, sweep

__all__ = [
    "METHODS", "IndefiniteStiffnessError", "ModalEnergy", "modal_energy", "dof_names",
    "mass_matrix", "spring_network", "stiffness_matrix", "ParameterError",
    "PlanetaryParameters", "equally_spaced_angles", "field_names", "printed_stiffness_matrix", "Sensitivity", "frequency_sensitivity",
    "FrequencyShift", "frequency_shift", "Spectrum", "natural_modes", "printed_modes",
    "Sweep", "sweep",
]
