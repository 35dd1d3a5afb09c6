"""The report's words for the elastic-ring answer: both models side by side, then the
elastic ring's watched modes and their changes (Markdown lines)."""
from __future__ import annotations

import math

import numpy as np

from hubvib.detection.elastic_model import bilinear_hz
from hubvib.detection.result import DetectionResult


def _answer(result: DetectionResult | None, length: float) -> str:
    """The crossing of one record length in words, ``-`` without that model or length."""
    if result is None or length not in result.pod:
        return "-"
    return result.answer(length)


def side_by_side(rigid: DetectionResult | None, elastic: DetectionResult,
                 validity=None) -> list[str]:
    """Both models' POD crossing per record length (:mod:`hubvib.detection.resolution`),
    and why they differ; ``validity``: the rigid-ring model's band
    (``hubvib.elastic.validity.ValidityBand``) whose list of the ring's own modes the
    report prints, read here for where those modes lie."""
    lengths = sorted(t for t in elastic.pod if rigid is None or t in rigid.pod)
    rows = ["| record | rigid ring (9 + 3N) | elastic ring |", "|---:|---|---|"]
    for t in lengths:
        rows.append(f"| {t:g} s | {_answer(rigid, t)} | {_answer(elastic, t)} |")
    watched = elastic.watched
    if watched:
        i = watched[0]
        best = (f"its best mode, {elastic.labels[i]}, moves "
                f"{_shift(np.nanmin(elastic.shift_hz[:, i]))} at most over the sweep against an "
                f"identification scatter of {elastic.sigma_hz[elastic.record_length][i]:.2f} Hz")
    else:
        best = "the sensor sees none of the modes the crack moves"
    added = ("" if not elastic.added_depths else
             " The elastic ring's depths " + ", ".join(f"{1e3 * d:.3g}" for d in
                                                       elastic.added_depths)
             + f" mm were added to resolve the crossing ({elastic.refinement}); the rigid "
             "ring's depths are the scene's FE cases (each added depth would cost FE runs), "
             "so its crossing is resolved only as finely as the sweep.")
    return [
        "**Both ring models**: where the family POD crosses "
        f"{elastic.detection_probability:g} ({_scatter_words(elastic)}):", "", *rows, "",
        "They differ because the rigid-ring model has no mode of the ring's own: there the "
        "crack acts only through the ring body's c_ru, c_r in series with a soft mounting "
        "and through one tooth pair's c_rp, which hardly move the lumped modes. "
        + ring_modes_sentence(elastic, validity)
        + f" The crack, cutting the rim they bend, moves them: {best}.{added}", ""]


def ring_modes_sentence(elastic: DetectionResult, validity=None) -> str:
    """Where the elastic ring's modes of the ring's own lie, read from the list the report
    prints: the validity band's ring modes (``validity.ring_modes``), or without a band
    the modes classed 'ring' (the ring holds the largest kinetic-energy share)."""
    if validity is not None:
        found = sorted((m.frequency_hz, m.nodal_diameter) for m in validity.ring_modes)
        where = "listed with the validity band below"
    else:
        found = sorted((f, n) for f, n, kind in zip(elastic.intact_hz,
                                                   elastic.detail.nodal_diameter,
                                                   elastic.detail.kind) if kind == "ring")
        where = "class 'ring' in the mode table"
    if not found:
        return ("The elastic ring has no coupled mode of the ring's own in its band "
                f"({where}).")
    diameters = sorted({int(n) for _, n in found})
    return (f"The elastic ring's {len(found)} coupled modes of the ring's own ({where}; "
            f"nodal diameters {', '.join(str(n) for n in diameters)}) lie from "
            f"{found[0][0]:.0f} Hz on.")


def _scatter_words(elastic: DetectionResult) -> str:
    """How the elastic ring's POD was obtained, for the side-by-side caption."""
    if not elastic.samples:
        return ("the elastic ring for the nominal reducer with identification noise only, "
                "the rigid ring with parameter scatter and FE error as above")
    masses, springs, mounting, fe = elastic.detail.scatter
    return (f"both with parameter scatter and FE error: the elastic ring over "
            f"{elastic.samples} Monte Carlo reducers, masses and the ring's mass "
            f"{100 * masses:g} %, springs and the ring-planet spring {100 * springs:g} %, "
            f"the ring's foundation {100 * mounting:g} %, the ring's FE error "
            f"{100 * fe:g} % of each crack change")


def _shift(value: float) -> str:
    return "(not tracked)" if not np.isfinite(value) else f"{value:+.1f} Hz"


def _pod_words(elastic: DetectionResult) -> str:
    if not elastic.samples:
        return ("The family POD is the nominal reducer's (identification noise only).")
    return ("The family POD is the mean over " f"{elastic.samples} Monte Carlo reducers "
            "(lumped masses and the ring's mass, springs and the ring-planet spring, the "
            "foundation scattered log-normal, and the ring's FE error on each crack change), "
            "the identification noise integrated exactly, each against its own intact record; "
            "the nominal reducer's is in results.json (`family_pod_nominal`).")


def elastic_section(elastic: DetectionResult, validity=None) -> list[str]:
    """The elastic ring's model, watched modes and their changes per depth."""
    detail = elastic.detail
    f = detail.foundation
    mount = ("clamped on the support arcs" if f is None else
             f"on a Winkler foundation over the support arcs (k_n {f[0]:.4g}, k_t {f[1]:.4g} "
             "N/m^2), sized so that its rigid-ring totals equal the design's lumped c_r and "
             "c_ru")
    lines = [
        "## Elastic ring", "",
        f"The ring as the design's plane FE ring ({detail.ring_dofs} DOFs, P2, plane "
        f"stress) {mount}, reduced to its own modes and the planets' contact flexibility and "
        "coupled to the lumped sun, carrier and planets; the ring-planet spring without the "
        f"ring body {detail.k_rest:.4g} N/m (planet tooth and contact; the ring tooth is in "
        "the FE ring). " + _load_words(elastic) + " Watched: the modes the sensor at "
        f"{math.degrees(detail.sensor_angle):g} deg from the cracked tooth sees (radial "
        "ring motion there at least 10 % of the largest), ranked by change against "
        "scatter. " + _pod_words(elastic)
        + " docs/elastic_ring.md has the model, its checks and the ring's modes.", ""]
    if validity is not None:
        from hubvib.elastic.validity import validity_lines

        lines += validity_lines(validity)
    elif detail.lowest_ring_mode is not None:
        f, n = detail.lowest_ring_mode
        lines += [f"The mounted ring's lowest elastic mode of its own is {f:.1f} Hz "
                  f"(n = {n}); the rigid-ring model has no such mode.", ""]
    watched = list(elastic.watched)
    if not watched:
        return lines + ["The sensor sees none of the modes the crack moves.", ""]
    loaded = detail.open_hz is not None and any(t is not None for t in detail.tracks)
    second = "open" if loaded else "bilinear"
    head = "| depth [mm] | " + " | ".join(
        f"{elastic.labels[i]} record / {second} [Hz]" for i in watched) + " | family POD |"
    lines += [head, "|---:|" + "---|" * len(watched) + "---:|"]
    pod = elastic.pod[elastic.record_length]
    other = (detail.open_hz - detail.open_hz[0]) if loaded else (
        bilinear_hz(elastic) - bilinear_hz(elastic)[0])
    for k, d in enumerate(elastic.depths):
        cells = []
        for i in watched:
            o = elastic.shift_hz[k, i]
            b = other[k, i]
            split = " (split pair)" if detail.split_pair[k, i] else ""
            cells.append(" / ".join("-" if not np.isfinite(x) else f"{x:+.1f}"
                                    for x in (o, b)) + split)
        added = " (added)" if d in elastic.added_depths else ""
        lines.append(f"| {1e3 * d:.3g}{added} | " + " | ".join(cells) + f" | {pod[k]:.2f} |")
    if loaded:
        lines += ["", "Record: the change a record identifies with the crack under the "
                  "working load (the intact ring treated the same way); open: the faces "
                  "held open with planet 1 half a planet pitch away (an upper bound: the "
                  "crack open at every moment of the record)."]
        lines += crack_state_lines(elastic)
    if elastic.left_out:
        lines += ["", "Left out of this table: " + "; ".join(
            f"{1e3 * d:.3g} mm ({why})" for d, why in elastic.left_out) + "."]
    lines += ["", f"Records of {elastic.record_length:g} s; identification scatter of the "
              "watched modes " + ", ".join(
                  f"{elastic.sigma_hz[elastic.record_length][i]:.2f}" for i in watched)
              + " Hz; '-': no mode of the cracked ring continues it with a subspace match of 0.5 "
              "or more (modes mix as the crack grows; a crack through the rim opens the ring). `elastic_ring.csv` has every coupled mode below the band's "
              "top, with the change when planet 1 is on the cracked tooth (`in_contact_hz`, "
              "against the intact ring at that carrier position).", ""]
    return lines


def _load_words(elastic: DetectionResult) -> str:
    """What the statistic is: the loaded crack over a planet pitch, or the open crack."""
    detail = elastic.detail
    track = next((t for t in detail.tracks if t is not None), None)
    if track is None:
        return ("The crack is in the ring, so it acts at every carrier position: the change "
                "with planet 1 half a planet pitch away, faces open (an upper bound), is the "
                "statistic; tied faces give the intact ring, so the breathing crack's "
                "bilinear estimate is 2 f_open f_intact / (f_open + f_intact).")
    gap = "" if not track.closure_gap_m else f", closure gap {1e6 * track.closure_gap_m:g} um"
    return (
        f"The crack is loaded by the working torque ({track.torque_N_m:g} N m at the sun, "
        "the design's `load.sun_torque`, the same quantity as a `[signal]` table's "
        f"`sun_torque_N_m`{gap}): at each carrier position of one planet pitch the faces are "
        "apart or pressed (frictionless Signorini contact on the FE ring), small vibrations "
        "about each state see the pressed faces stuck (their sliding is the bound in "
        "`elastic_ring.csv`, `slip_hz`), and a record spanning many planet passes sees the "
        "mixture of the states' responses weighted by their dwell (`hubvib.elastic."
        "record_spectrum`: the time average where a mode's swing stays inside its "
        "half-power band, else the mixture's highest peak). That record frequency, against "
        "the intact ring's treated the same way, is the statistic.")


def crack_state_lines(elastic: DetectionResult) -> list[str]:
    """The crack's state over the pitch per depth: share of positions with the faces
    apart, largest open length and gap."""
    rows = ["", "The crack's state over one planet pitch under the working load:", "",
            "| depth [mm] | positions with faces apart | largest open length [mm] | "
            "largest gap [um] |", "|---:|---:|---:|---:|"]
    for d, track in zip(elastic.depths, elastic.detail.tracks):
        states = getattr(track, "states", ()) if track is not None else ()
        if not states:
            continue
        length = max(s.open_length_m for s in states)
        gap = max(s.max_gap_m for s in states)
        rows.append(f"| {1e3 * d:.3g} | {100 * track.open_share:.0f} % | "
                    f"{1e3 * length:.2f} | {1e6 * gap:.2f} |")
    return rows + [""]


def load_sensitivity_lines(variants, record_length: float) -> list[str]:
    """The smallest detectable depth per closure gap and torque (nominal POD)."""
    if not variants:
        return []
    lengths = sorted({t for v in variants for t in v.answer})
    rows = ["## What the answer rests on: closure gap and load", "",
            "The crack's state depends on a closure gap (roughness, the residual compression "
            "of a case-hardened root: the faces separate only where the free opening exceeds "
            "it) and, with a gap, on the torque. Where the family POD of the nominal reducer "
            "(identification noise only) crosses the required probability, on the same "
            "depths:", "",
            "| closure gap [um] | torque | " + " | ".join(f"{t:g} s records" for t in lengths)
            + " |", "|---:|---:|" + "---|" * len(lengths)]
    for v in variants:
        torque = "any" if v.gap == 0 else f"{100 * v.torque_fraction:g} %"
        rows.append(f"| {1e6 * v.gap:g} | {torque} | "
                    + " | ".join(v.answer.get(t, "-") for t in lengths) + " |")
    return rows + ["", "With no gap the state does not depend on the torque's size (the "
                   "contact problem is linear in the load); `results.json` "
                   "(`load_sensitivity`) has each variant's open share per depth.", ""]
