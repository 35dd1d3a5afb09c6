"""One caption per figure a report shows: what it shows, its colours and magnification.

Reports embed figures with :func:`figure_lines`, which adds the caption line under the
image; a figure without a caption here is a ``KeyError`` (tests render every report
and so find a new figure that nobody described).  Keys are file names without folders;
mode renders are matched by their pattern (``mode_NN``, ``fe_ring_mode_NN``).
"""
from __future__ import annotations

import re
from pathlib import PurePosixPath

from hubvib.render.mode_figure import ARROW
from hubvib.render.modes import AMPLITUDE

#: the FE renders' magnification (``hubvib.render.fe.MAGNIFIED``, which imports the FE
#: stage: a test keeps the two equal)
FE_MAGNIFIED = 0.03

CAPTIONS = {
    "frequency_vs_parameter.png": "Natural frequency [rad/s] of every mode against the swept "
                                  "parameter, both axes logarithmic; one line per mode.",
    "shift_percent.png": "Frequency shift [%] of every mode against the swept parameter (log "
                         "axis); the dotted line is the detection threshold.",
    "frequency_vs_depth.png": "Size of the relative frequency shift [%] of each mode that "
                              "moves against crack depth [mm] (log axis: the modes move by "
                              "parts per million to per cent), planet 1 on the cracked "
                              "tooth; at most eight modes per panel, each panel's legend "
                              "below it.",
    "shift_vs_depth.png": "Frequency drop a record sees [Hz] of each mode against crack depth "
                          "[mm] (log axis); the grey band spans the alarm thresholds of the "
                          "watched modes, from the lowest to the highest.",
    "pod.png": "Probability of detection against crack depth [mm]: left the watched modes "
               "together per record length (linear axis), right each watched mode alone on a "
               "log axis (its POD lies near the false-alarm rate); dashed grey: the required "
               "POD, dotted grey: the false-alarm rate, left the family's, right each mode "
               "alone's (where its curve starts); the legend below the panels.",
    "detectability_map.png": "Smallest detectable crack depth [mm] against the mounting "
                             "stiffness swept [N/m] (log axis): black line over all modes, a "
                             "large marker where a mode sets it, its colour and shape naming "
                             "the stiffness carrying the signal; shaded: mountings where no "
                             "crack of the sweep is detectable.",
    "elastic_map.png": "Elastic ring: smallest detectable crack depth [mm] against the "
                       "foundation scale s (log axis; the watched family and each followed "
                       "mode alone), and beside it the intact frequencies [Hz] of the followed "
                       "modes and the ring's lowest mode of its own.",
    "carrier_position.png": "Size of the frequency change [%] of each mode that moves while "
                            "planet 1 meshes the cracked tooth (deepest crack), one row per "
                            "mode on a log axis: dot at the FE mean mesh ratio over the "
                            "engagement, open circle at its minimum. Right: the mode that "
                            "moves most over one passage against the carrier angle, solid at "
                            "the mean ratio, dashed at the minimum; the shaded band is the "
                            "time the cracked tooth is in mesh.",
    "frequency_both_models.png": "The watched modes' frequency change from the intact "
                                 "ring [Hz] against crack depth [mm]: left the rigid ring "
                                 "(9 + 3N model), right the elastic ring (FE ring coupled), "
                                 "each on a scale of its own and titled with what its change "
                                 "is (a record's under the working load, the elastic ring's "
                                 "the table's 'record' column; or the crack held open where "
                                 "the load cycle was not computed); one colour, marker and "
                                 "line style per mode.",
    "elastic_states.png": "Elastic ring: each watched mode's frequency [Hz] against crack "
                          "depth [mm], one panel per mode on a scale of its own: red solid "
                          "the crack open (faces free), blue dashed record-averaged over a "
                          "carrier revolution (where computed), black dotted closed (faces "
                          "tied: the intact ring).",
    "crack_state.png": "Elastic ring: length of the crack that is open [mm] against the "
                       "carrier position (planet 1's ring tooth, tooth 0 cracked) over a "
                       "revolution, one curve per crack depth.",
    "c_ru_change.png": "Change of c_ru and c_r against the intact ring [%] over the crack "
                       "depth at its deepest point [mm]: one line per half-length "
                       "(semi-elliptic), and the plane crack through the face width.",
    "fe_ring_loaded.png": "The FE ring under the planets' mesh forces: colour is von Mises "
                          "stress [MPa] (scale at the right), grey the undeformed outline, "
                          "deformation magnified as stated in the picture.",
    "fe_crack_tip.png": "Close-up of the crack tip with the mesh: colour is von Mises stress "
                        "[MPa], the bar at the lower left gives the length scale, "
                        "deformation magnified as stated in the picture.",
    "order_spectrum.png": "Amplitude [m/s²] of the sensor signal against carrier order: the "
                          "orders up to the last analysed mesh harmonic and its sidebands "
                          "(log axis), then a zoom around the mesh order z_r (dotted).",
    "spectrogram.png": "Spectrogram of the sensor signal of the deepest crack: frequency "
                       "[Hz] against time [s].",
    "indicators.png": "Condition indicators against crack depth [mm], one panel per "
                      "indicator on a scale of its own, each divided by its intact mean: "
                      "line the mean over the noise seeds, band ± 2 standard deviations "
                      "over them, dashed the intact level 1.",
    "tsa.png": "Time-synchronous average of the sensor signal [m/s²] over one carrier "
               "revolution against the carrier angle [deg]: intact and deepest crack in "
               "panels of their own on one scale, then their difference (the same noise "
               "seed, so the noise cancels).",
}
#: a render's mounting (the last part of its file name) in words
MOUNTED = {"foundation": "on the elastic ring's Winkler foundation over the support arcs "
                         "(its stiffness in the picture; unless the scene gives it, sized so "
                         "that its rigid-ring totals are the design's c_r and c_ru)",
           "clamped": "clamped on the support arcs", "free": "free (no mounting)",
           None: "clamped on the support arcs"}
_PATTERNS = (
    (re.compile(r"fe_ring_mode_(\d+)(?:_(?P<mounting>foundation|clamped|free))?\.png"),
     "FE ring mode {n}, the ring's own (its rigid motions on the mounting left out), "
     "{mounting}: colour is the displacement magnitude relative to its largest value (scale "
     "at the right), grey the undeformed outline; the largest displacement is drawn as "
     f"{100 * FE_MAGNIFIED:g} % of the outer radius; the picture names its frequency and "
     "nodal diameters."),
    (re.compile(r"elastic_mode_(\d+)_([a-z]+)_n(\d+)_(\d+)Hz_(?P<mounting>foundation|clamped|free)"
                r"\.png"),
     "Elastic ring, the watched coupled mode ranked {n} (best first): elastic "
     "n={diameters}, a {kind} mode at {hz} Hz, the intact ring {mounting}, planet 1 half a "
     "planet pitch from the cracked tooth. The ring's deformed FE mesh coloured by its "
     "displacement magnitude relative to its largest value (scale at the right), the sun "
     "orange, planets green, carrier grey moved by the same mode, grey outline at rest; "
     f"largest displacement drawn as {100 * AMPLITUDE:g} % of the ring radius."),
    (re.compile(r"mode_(\d+)\.png"),
     "Rigid mode {n} (the 9 + 3N lumped model): sun orange, planets green, ring purple, "
     "carrier grey; "
     "dashed outlines: the bodies at rest, filled: moved by the mode (largest displacement "
     f"drawn as {100 * AMPLITUDE:g} % of the ring radius); arrows, each in a dark shade "
     f"of its body's colour: the body's translation from its centre and its turn as a "
     f"curved arrow around it (largest "
     f"{100 * ARROW:g} % of the ring radius)."),
    (re.compile(r"mode_(\d+)\.gif"),
     "Mode {n} of the lumped model, animated: sun orange, planets green, ring purple, "
     f"carrier grey, moved by the mode (largest displacement drawn as {100 * AMPLITUDE:g} % "
     "of the ring radius); the grey outlines are the bodies at rest."),
    (re.compile(r"convergence_(\w+)\.png"),
     "Relative error of {n} against DOFs on log-log axes."),
)


def caption(name: str) -> str:
    """The caption of the figure file ``name`` (a path or a file name)."""
    base = PurePosixPath(str(name)).name
    if base in CAPTIONS:
        return CAPTIONS[base]
    for pattern, text in _PATTERNS:
        found = pattern.fullmatch(base)
        if found:
            number = found.group(1)
            words = {"n": int(number) if number.isdigit() else number}
            if "{kind}" in text:
                words |= {"kind": found.group(2), "diameters": int(found.group(3)),
                          "hz": int(found.group(4))}
            if "{mounting}" in text:
                words["mounting"] = MOUNTED[found.group("mounting")]
            return text.format(**words)
    raise KeyError(f"figure {base!r} has no caption in hubvib.render.captions")


def figure_lines(path: str) -> list[str]:
    """Markdown lines showing the figure ``path`` with its caption, then a blank line."""
    return [f"![{PurePosixPath(str(path)).name}]({path})", "", f"*{caption(path)}*", ""]
