"""The lumped model's standing against the published Raba 118/76 spectrum, as the study
reports state it: the sentence and its numbers come from the same comparison
``hubvib validate raba118`` prints (:meth:`hubvib.validation.raba118.RabaValidation.claim`)."""
from __future__ import annotations

from functools import lru_cache


@lru_cache(maxsize=1)
def raba_claim() -> str:
    """What the comparison with the published Raba 118/76 spectrum shows, with its numbers
    (computed now from the preset)."""
    from hubvib.reducer import lumped_preset
    from hubvib.validation.raba118 import validate

    return validate(lumped_preset("raba118")).claim()


def lumped_model_status() -> str:
    """The report's validation-status sentence on the lumped model's spectrum."""
    claim = raba_claim()
    return claim[0].upper() + claim[1:]
