"""The report's sentence on where the ring's own modes lie reads the list it stands beside
(the validity band's list of coupled modes of the ring's own), not a stock range."""
from __future__ import annotations

import re

import numpy as np

from hubvib.detection.elastic_model import ElasticDetail
from hubvib.detection.pod import family_pod
from hubvib.detection.result import DetectionResult
from hubvib.elastic.validity import PairedMode, RingMode, ValidityBand, validity_lines
from hubvib.reports.elastic_sections import side_by_side


def _result(kinds=("rotational", "ring", "ring")) -> DetectionResult:
    depths = (0.0, 0.003)
    intact = np.array([1000.0, 2270.0, 4700.0])
    record = intact + np.array([[0, 0, 0], [-0.5, -18.0, -26.0]])
    sigma = {10.0: np.array([0.8, 1.1, 1.5])}
    pod = {t: family_pod(record - intact, s, (2, 1), 0.005) for t, s in sigma.items()}
    detail = ElasticDetail(kinds, (0, 3, 4), (0, 0, 1), (0.1, 0.9, 0.8), record.copy(),
                           np.zeros((2, 3), dtype=bool), np.array([0.05, 1.0, 0.6]), 2e9,
                           (7e8, 1.8e6), 38000, np.pi / 2)
    labels = tuple(f"elastic n={n} ({k}, {f:.1f} Hz)" for n, k, f in zip((0, 3, 4), kinds,
                                                                            intact))
    return DetectionResult("elastic", depths, record, labels, sigma, (2, 1), pod, pod, 0.9,
                           0.01, 10.0, 0, detail=detail)


def _band() -> ValidityBand:
    paired = (PairedMode(1, 1010.0, 1000.0, -0.0099, 0.99, 0.1, 0.01, 0),)
    ring_modes = (RingMode(2270.0, 0.8, 0.1, 3), RingMode(1052.0, 0.7, 0.2, 2),
                  RingMode(4700.0, 0.9, 0.1, 4))
    return ValidityBand(paired, ring_modes, 1052.0, "ring mode", 0.01, 1040.0, 2, 10e3,
                        "foundation", (7e8, 1.8e6), 11)


def _from(text: str) -> float:
    return float(re.search(r"lie from (\d+) Hz on", text).group(1))


def test_sentence_reads_the_validity_list_beside_it():
    """The band's list (unsorted in the band: 2270, 1052, 4700 Hz) starts at 1052 Hz as
    printed; the sentence says 1052 Hz and names the list's nodal diameters."""
    band = _band()
    sentence = "\n".join(side_by_side(None, _result(), band))
    listed = "\n".join(validity_lines(band))
    own = re.search(r"Coupled modes of the ring's own [^:]*: (.*)\.", listed).group(1)
    first_listed = min(float(f) for f in re.findall(r"(\d+) Hz \(n", own))
    assert _from(sentence) == first_listed == 1052.0, (sentence, own)
    assert "nodal diameters 2, 3, 4" in sentence and "3 coupled modes" in sentence
    assert "2-5 and breathing" not in sentence


def test_sentence_without_a_band_reads_the_ring_class():
    """No validity band: the modes classed 'ring' (the ring's largest kinetic-energy share)
    in the mode table, here 2270 and 4700 Hz."""
    sentence = "\n".join(side_by_side(None, _result()))
    assert _from(sentence) == 2270.0
    none = "\n".join(side_by_side(None, _result(("rotational",) * 3)))
    assert "no coupled mode of the ring's own" in none
