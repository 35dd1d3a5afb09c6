"""Report sections of the detection study (markdown), generated from its results."""
from __future__ import annotations

import math

import numpy as np

from hubvib.detection.mode_names import mode_names
from hubvib.detection.mode_names import rigid_label
from hubvib.detection.resolution import bracket
from hubvib.detection.numbers import depth_mm, number, percent, shift_hz
from hubvib.detection.series import DIRECT, RATIO


def mounting_sentence(model, sources: dict | None = None) -> str:
    """How the ring support enters the lumped model, and what share the mounting holds.

    ``sources`` names where the lumped c_ru and c_r come from (``{"c_ru": "design 'x''s
    lumped table", ...}``, ``Scene.lumped_source``); without it they are the reducer's."""
    params = model.params
    sources = sources or {}
    origin = {n: f" ({sources[n]})" if n in sources else "" for n in ("c_ru", "c_r")}
    if model.apply == RATIO:
        return (f"`apply = \"ratio\"`: the reducer's c_ru{origin['c_ru']} and "
                f"c_r{origin['c_r']} scaled by FE(depth)/FE(intact). "
                "This is the paper's hypothesis that the whole support compliance is the ring "
                "body: an upper bound of the effect, not a mounting anyone measured.")
    if model.apply == DIRECT:
        return ("`apply = \"direct\"`: c_ru and c_r are the FE ring body itself (a rigid "
                "mounting): the largest effect a real mounting can leave.")
    identified = []
    for name, given in (("c_ru", params.c_ru), ("c_r", params.c_r)):
        total = float(getattr(model, name)[0])
        if math.isclose(total, given, rel_tol=1e-9):
            identified.append(f"{name} = {given:.4g} N/m{origin[name]}")
    how = (f"identified so that the intact totals equal the reducer's "
           f"{' and '.join(identified)}" if identified else "given in the scene")
    share = [f"{100 * float(getattr(model, n)[0]) / getattr(model, f'{n}_mount'):.4g} % of the "
             f"ring's {what} compliance" for n, what in (("c_ru", "torsional"),
                                                          ("c_r", "radial"))]
    return (f"`apply = \"series\"`: the mounting in series with the FE ring body, c_ru mounting "
            f"{model.c_ru_mount:.6g} N/m and c_r mounting {model.c_r_mount:.6g} N/m ({how}). "
            f"The mounting holds {share[0]} and {share[1]}: that share of a body softening "
            f"never reaches the spectrum, so through c_ru and c_r the mounting decides what a "
            f"crack can show.")


def _support_sentence(pod) -> str:
    """Which stiffness carries the detectable signals at the scene's mounting."""
    depth = pod.detectable_depth()
    carriers = {}
    for i in np.flatnonzero(~np.isnan(depth)):
        k = int(np.searchsorted(pod.depths, depth[i]))
        carriers.setdefault(str(pod.nominal.carried_by[k, i]), []).append(float(depth[i]))
    through_support = [d for c in ("c_ru", "c_r") for d in carriers.get(c, [])]
    if through_support:
        return (f"Through the ring support (c_ru, c_r) a crack is detectable from "
                f"{depth_mm(min(through_support))} mm under this mounting.")
    text = ("Through the ring support (c_ru, c_r) no crack of the sweep is detectable under "
            "this mounting (the map below shows how stiff it must be).")
    if "c_rp" in carriers:
        text += (" What remains is the cracked tooth's own mesh stiffness (c_rp), which no "
                 "mounting filters.")
    return text


def _sigma_range(pod, watched) -> str:
    """The identification scatter of the watched modes, as text."""
    sigma = pod.sigma_hz[watched]
    return (f"{sigma.min():.3g} Hz" if np.isclose(sigma.min(), sigma.max(), rtol=5e-3)
            else f"{sigma.min():.3g}-{sigma.max():.3g} Hz")


def _crossing(pod, T, which: str = "") -> str:
    """Where the family POD with records of ``T`` [s] crosses the required probability
    (``which``: ``""``, ``"drift"``, ``"compensated"``), as :mod:`hubvib.detection.resolution`
    words it: ``below 3 mm`` means at or below the shallowest crack computed."""
    table = getattr(pod, f"family_pod_{which}" if which else "family_pod")
    return bracket(pod.depths, table[T], pod.detection_probability).words()


def _family_sentence(pod, bold: bool = True) -> str:
    """The rigid ring's answer: where the watched family's POD crosses the required
    probability per record length (``bold``: the short answer's lead)."""
    parts = [f"{T:g} s: {_crossing(pod, T)}" for T in sorted(pod.family_pod)]
    f0 = pod.nominal.frequency_hz[0]
    modes = ", ".join(rigid_label(i, pod.kind[i], f0[i]) for i in pod.watched)
    mark = "**" if bold else ""
    return (f"{mark}Watching modes {modes} together (alarm when any of them drops below its "
            f"threshold; family-wise false-alarm rate {pod.false_alarm_rate:g}), the depth "
            f"from which a crack is detected with POD >= {pod.detection_probability:g} is, "
            "with records of " + "; ".join(parts) + f".{mark} Records of the same reducer "
            "intact and now, identified by the same method, without drift between them; with "
            "the scene's temperature and load drift: " + "; ".join(
                f"{T:g} s: {_crossing(pod, T, 'drift')}" for T in sorted(pod.family_pod_drift))
            + " (compensated by reference modes: " + "; ".join(
                f"{T:g} s: {_crossing(pod, T, 'compensated')}"
                for T in sorted(pod.family_pod_compensated)) + ").")


def drift_lines(pod, options) -> list[str]:
    """What temperature and load drift between the records do, and what compensation buys."""
    drift = pod.drift
    if drift is None or not pod.family_pod_drift:
        return []
    w = pod.watched
    f0 = pod.nominal.frequency_hz[0]
    per_k = ", ".join(f"rigid {i + 1} {drift.per_kelvin_hz[i]:+.3g} Hz" for i in w)
    per_load = ", ".join(f"rigid {i + 1} {1e-3 * drift.per_load_hz[i]:+.3g} Hz" for i in w)
    refs = ", ".join(f"rigid {i + 1} by {rigid_label(r, pod.kind[r], f0[r])}" if r >= 0
                     else f"rigid {i + 1}: none"
                     for i, r in zip(w, pod.references))
    lengths = sorted(pod.family_pod_drift)

    def depth(T, which):
        d = pod.family_detectable_depth(T, which)
        return "none" if math.isnan(d) else f"{depth_mm(d)} mm"

    lines = [
        f"- Drift between the two records (`hubvib.detection.drift`): a uniform "
        f"temperature change (modulus {options.modulus_per_K:g}/K, expansion "
        f"{options.expansion_per_K:g}/K: {per_k} per K; standard deviation "
        f"{options.temperature_std:g} K) and a common change of every mesh stiffness from "
        f"the load ({per_load} per 0.1 %; standard deviation "
        f"{100 * options.mesh_load_std:g} %). Compensation: each watched mode minus "
        f"f_i / f_r times an unmoved, well-separated reference mode ({refs}) removes the "
        "uniform part exactly. Smallest depth with family POD >= "
        f"{pod.detection_probability:g}: "
        + "; ".join(f"{T:g} s: {depth(T, '')} without drift, {depth(T, 'drift')} with it, "
                    f"{depth(T, 'compensated')} compensated" for T in lengths) + ".",
        "- Family POD with the drift, uncompensated / compensated [-]:", "",
        "| depth [mm] | " + " | ".join(f"{T:g} s" for T in lengths) + " |",
        "|---:|" + "---:|" * len(lengths)]
    for k, d in enumerate(pod.depths):
        lines.append(f"| {depth_mm(d)} | " + " | ".join(
            f"{pod.family_pod_drift[T][k]:.3f} / {pod.family_pod_compensated[T][k]:.3f}"
            for T in lengths) + " |")
    return lines + [""]


def _modulation_sentence(study, watched) -> str:
    """Where the passes modulate a watched mode by more than 1 rad."""
    index = study.carrier.modulation_index
    split = [(i, int(np.argmax(index[:, i] > 1))) for i in watched if (index[:, i] > 1).any()]
    if not split:
        return ""
    parts = ", ".join(f"rigid {i + 1} from {depth_mm(study.pod.depths[k])} mm" for i, k in split)
    return (f" Caution: each pass of a planet over the cracked tooth modulates the phase of "
            f"{parts} by more than 1 rad (see Carrier position): there the crack shows as "
            f"sidebands {study.timing.pass_frequency:.3g} Hz apart as much as a shifted line.")


def short_answer(name: str, model, study, sources: dict | None = None,
                 lead: list[str] = ()) -> list[str]:
    """The report's opening: ``lead`` (the answer of the model that holds,
    :mod:`hubvib.reports.answer`), then the rigid ring's modes to watch, shift per depth,
    detectable depth, mounting."""
    pod, options = study.pod, study.options
    watched = study.watched_modes()
    depth = pod.detectable_depth()
    f0 = pod.nominal.frequency_hz[0]
    rule = (f"POD >= {options.detection_probability:g} at a family-wise false-alarm rate of "
            f"{options.false_alarm_rate:g} over the {len(watched)} watched modes; records of "
            f"{options.record_length:g} s, modal damping {100 * options.damping_ratio:g} % "
            f"(ASSUMED unless the scene sets it), modal SNR {options.snr:g}, so one identified "
            f"frequency scatters by {_sigma_range(pod, watched)}; compared with the same "
            "reducer's intact spectrum")
    modes = ", ".join(f"{rigid_label(i, pod.kind[i], f0[i])} (signal in "
                      f"{pod.nominal.carried_by[-1, i]})" for i in watched)
    found = ~np.isnan(depth[watched])
    lines = ["## Short answer", "", *lead, mounting_sentence(model, sources), "",
             _family_sentence(pod, bold=not lead), ""]
    if found.any():
        first = np.nanmin(depth[watched])
        shallowest = pod.depths[1]
        note = " (the shallowest crack computed)" if math.isclose(first, shallowest) else ""
        lines.append(f"**Watch modes {modes}. On one mode alone a crack is detectable from "
                     f"{depth_mm(first)} mm{note}** under this mounting ({rule}). "
                     f"{_support_sentence(pod)}"
                     f"{_modulation_sentence(study, watched)}")
    else:
        lines.append(f"**Watch modes {modes}: on one mode alone no crack of the sweep is "
                     f"detectable under this mounting** ({rule}); these move most against "
                     f"their identification scatter. {_support_sentence(pod)}")
    lines += ["", "Time-averaged shift a record sees [Hz] and the mode's POD per depth (nr: "
              "smaller than the FE error of the stiffness carrying it, not resolved):", ""]
    names = mode_names(f0)
    head = "| depth [mm] | " + " | ".join(f"rigid mode {names[i]} [Hz] | [%] | POD"
                                         for i in watched)
    lines += [head + " |", "|---:|" + "---:|---:|---:|" * len(watched)]
    for k, d in enumerate(pod.depths):
        cells = []
        for i in watched:
            s = pod.nominal.shift_hz[k, i]
            flag = "" if k == 0 or pod.resolved[k, i] else " nr"
            cells += [shift_hz(s, f0[i]) + flag, percent(100 * s / f0[i]),
                      f"{pod.pod[k, i]:.2f}"]
        lines.append(f"| {depth_mm(d)} | " + " | ".join(cells) + " |")
    model_depth = pod.detectable_depth(model_baseline=True)
    if pod.pod_model is not None:
        best = np.nanmin(model_depth) if not np.isnan(model_depth).all() else None
        lines += ["", "Compared with the model's intact spectrum instead (no measured baseline), "
                  f"the parameter scatter (masses {100 * options.scatter_masses:g} %, springs "
                  f"{100 * options.scatter_stiffnesses:g} %, mounting "
                  f"{100 * options.scatter_mounting:g} %) "
                  + ("hides every crack of the sweep." if best is None else
                     f"leaves a crack detectable from {depth_mm(best)} mm.")]
    lines += ["", *map_summary(study.map), ""]
    return lines


def map_summary(dmap) -> list[str]:
    """One sentence per mounting swept and stiffness carrying the signal
    (:func:`.mounting_map_sections.map_summary`)."""
    from hubvib.reports.mounting_map_sections import map_summary as summary

    return summary(dmap)


def map_table(dmap) -> list[str]:
    """The rigid map's table (:func:`.mounting_map_sections.map_table`)."""
    from hubvib.reports.mounting_map_sections import map_table as table

    return table(dmap)


def pod_section(study) -> list[str]:
    """How the threshold follows from the physics, and the POD per watched mode."""
    pod, options, timing = study.pod, study.options, study.timing
    long = timing.long_record(options.record_length)
    return [
        "## Detection threshold and probability of detection", "",
        f"- Measurement: a frequency identified from one {options.record_length:g} s record "
        f"scatters normally by the Cramer-Rao bound of the Bayesian-FFT identification "
        f"(Au's law sqrt(zeta f / (2 pi T)) in the limit of a wide band and high SNR): with "
        f"{100 * options.damping_ratio:g} % damping and modal SNR {options.snr:g}, "
        f"{_sigma_range(pod, pod.watched)} for the watched modes. Against the reducer's own "
        f"intact measurement mode i alarms on a drop below -z sqrt(2) sigma_i with the "
        f"per-mode rate {pod.per_mode_rate:.3g}, so that the {len(pod.watched)} watched modes "
        f"together raise a false alarm with probability {options.false_alarm_rate:g} (Sidak; "
        "independent identification errors). Frequencies can only drop: a crack softens "
        "springs (Courant-Fischer), so the test is one-sided.",
        *drift_lines(pod, options),
        "- Family POD (any watched mode alarms) per depth and record length [-]:", "",
        "| depth [mm] | " + " | ".join(f"{T:g} s" for T in sorted(pod.family_pod)) + " |",
        "|---:|" + "---:|" * len(pod.family_pod),
        *[f"| {depth_mm(d)} | " + " | ".join(f"{pod.family_pod[T][k]:.3f}"
                                               for T in sorted(pod.family_pod)) + " |"
          for k, d in enumerate(pod.depths)], "",
        f"- Scatter (log-normal, relative standard deviation): masses "
        f"{100 * options.scatter_masses:g} %, springs {100 * options.scatter_stiffnesses:g} %, "
        f"ring mounting {100 * options.scatter_mounting:g} %; FE error estimates (three mesh "
        "levels: Richardson with the observed order in 0.5..4, else the larger difference) as the standard deviation of a discretisation error common "
        f"to all depths. {pod.samples} Monte Carlo samples per depth (batched lumped solves).",
        "- Record against mesh timing: "
        + (f"a record longer than one engagement ({1e3 * timing.pass_seconds:.3g} ms) sees the "
           f"time-averaged stiffness (the cracked tooth is in mesh "
           f"{100 * timing.engaged_fraction:.3g} % of the time), so the c_rp effect enters "
           "diluted by that fraction." if long else
           "the record fits inside one engagement and sees the in-mesh spectrum."),
        "- A shift smaller than the change the FE error of its own stiffness would cause is "
        "flagged *not resolved* and never counts as detectable.", ""]


def carrier_section(study) -> list[str]:
    """Fraction of time in mesh and the spectra in and out of engagement."""
    carrier, timing = study.carrier, study.timing
    out, inside = carrier.omega_out[-1], carrier.omega_in[-1]
    relative = inside / out - 1
    moving = np.flatnonzero(np.abs(relative) > 1e-8)
    lines = [
        "## Carrier position", "",
        f"The ring is held; the carrier turns at {timing.carrier_speed * 60 / (2 * math.pi):.4g} "
        f"rpm (ASSUMED). The cracked tooth (z_r = {timing.ring_teeth}, contact ratio "
        f"{timing.contact_ratio:.3f}) is in mesh with one of the {timing.n_planets} planets "
        f"{100 * timing.engaged_fraction:.3g} % of the time, in passes of "
        f"{1e3 * timing.pass_seconds:.3g} ms (one per planet and carrier revolution). Within a "
        f"pass the frequency resolution cannot be finer than {1 / timing.pass_seconds:.3g} Hz.",
        f"Each pass puts sidebands at multiples of {timing.pass_frequency:.3g} Hz around every "
        "mode; the record sees the central line at the time-averaged frequency. The "
        "modulation index (phase a mode loses during one pass) tells how strong the "
        "sidebands are: above 1 rad the mode's peak splits and a single shifted line is no "
        "longer what a peak picker finds.", "",
        "Spectrum at the deepest crack in and out of engagement (modes that differ):", "",
        "| rigid mode | out of engagement [Hz] | planet 1 on the crack [Hz] | difference [%] "
        "| long record [Hz] | modulation index [rad] |",
        "|---:|---:|---:|---:|---:|---:|"]
    observed = carrier.omega_observed[-1]
    index = carrier.modulation_index[-1]
    names = mode_names(carrier.omega_out[0])
    for i in moving:
        lines.append(f"| {names[i]} | {out[i] / (2 * math.pi):.3f} | "
                     f"{inside[i] / (2 * math.pi):.3f} | {percent(100 * relative[i])} | "
                     f"{observed[i] / (2 * math.pi):.3f} | {number(index[i], 2)}"
                     f"{' (peak splits)' if index[i] > 1 else ''} |")
    if moving.size == 0:
        lines.append("| - | | | no mode differs | | |")
    return lines + [""]
