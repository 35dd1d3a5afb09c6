"""Files of the vibration-signature study: signals (CSV, WAV), spectra, indicators, plots, report."""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from hubvib.foundation.output import save_figure, write_csv, write_json, write_text
from hubvib.render.captions import figure_lines
from hubvib.render.html import write_html_report

from .indicators import INDICATORS
from .accelerometer import write_signal_csv, write_wav
from .spectral import angle_domain, record_spectrum, spectrogram
from .signature_study import SignalStudy

ZOOM = 10  # planet-pass orders on either side of the mesh order in the zoomed spectrum


def depth_name(depth: float) -> str:
    return f"{1e3 * depth:.3g}mm".replace(".", "p")


def indicator_rows(study: SignalStudy) -> list[dict]:
    rows = []
    for d in study.depths:
        for seed, values in enumerate(d.values):
            rows.append({"depth_mm": 1e3 * d.depth, "seed": seed, **values.to_dict()})
    return rows


def summary_rows(study: SignalStudy) -> list[dict]:
    rows = []
    intact = study.depths[0].summary()
    for d in study.depths:
        row = {"depth_mm": 1e3 * d.depth}
        for name, s in d.summary().items():
            spread = intact[name]["std"]
            row |= {f"{name}_mean": s["mean"], f"{name}_std": s["std"],
                    f"{name}_separation": (s["mean"] - intact[name]["mean"]) / spread
                    if spread else None}
        rows.append(row)
    return rows


def spectrum_rows(study: SignalStudy) -> list[dict]:
    """Per carrier order: frequency, amplitude and phase at every depth (noise-free)."""
    base = study.depths[0].spectrum
    rows = []
    for k in base.orders[1:]:
        row = {"order": int(k), "frequency_hz": float(k * study.carrier_hz)}
        for d in study.depths:
            name = depth_name(d.depth)
            row[f"amplitude_{name}_m_s2"] = float(d.spectrum.amplitude[k])
            row[f"phase_{name}_deg"] = float(math.degrees(d.spectrum.phase[k]))
        rows.append(row)
    return rows


def line_rows(study: SignalStudy) -> list[dict]:
    return [{"depth_mm": 1e3 * d.depth, **line.to_dict(),
             "frequency_hz": line.order * study.carrier_hz}
            for d in study.depths for line in d.lines]


def to_json(study: SignalStudy, files: dict) -> dict:
    """The JSON of ``hubvib signal --json`` and ``results.json`` (paths as given)."""
    summary = {1e3 * d.depth: d.summary() for d in study.depths}
    return {
        "scene": study.scene_name,
        "sample_rate_hz": study.options.sample_rate_hz, "carrier_hz": study.carrier_hz,
        "mesh_hz": study.mesh_hz, "n_planets": study.n_planets,
        "time_step_s": study.step, "steps_per_revolution": study.steps_per_revolution,
        "noise_rms_m_s2": study.noise_rms, "options": study.options.to_dict(),
        "depths": [{"depth_mm": 1e3 * d.depth, "signal_csv": str(files["csv"][i]),
                    "signal_wav": str(files["wav"][i]),
                    "indicators": summary[1e3 * d.depth],
                    "top_harmonics": [line.to_dict() for line in d.lines],
                    "simulation_seconds": d.seconds,
                    "non_multiple_fraction": d.non_multiple_fraction,
                    "contact": d.contact}
                   for i, d in enumerate(study.depths)],
        "non_multiple_fraction": [{"depth_mm": 1e3 * d.depth,
                                   "fraction": d.non_multiple_fraction}
                                  for d in study.depths],
        "load_sharing": study.load_sharing,
        "sensors": study.sensors,
        "roc": study.roc,
        "tacho_csv": "tacho.csv",
        "monotone_indicators": study.monotone(),
        "checks": study.checks,
        "files": [str(p) for p in files["all"]],
    }


def write_signal_study(study: SignalStudy, folder: Path, plots: bool = True) -> dict:
    """Write everything into ``folder``; returns the JSON of ``results.json`` (file paths
    relative to ``folder``)."""
    folder = Path(folder)
    fs = study.options.sample_rate_hz
    csvs, wavs = [], []
    for d in study.depths:
        name = depth_name(d.depth)
        csvs.append(write_signal_csv(folder / f"signal_{name}.csv", d.time, d.record))
        wavs.append(write_wav(folder / f"signal_{name}.wav", d.record, fs))
    files = csvs + wavs + [
        write_csv(folder / "order_spectrum.csv", spectrum_rows(study)),
        write_csv(folder / "harmonics.csv", line_rows(study)),
        write_csv(folder / "indicators.csv", indicator_rows(study)),
        write_csv(folder / "indicators_summary.csv", summary_rows(study)),
        write_csv(folder / "tacho.csv", [{"pulse_time_s": float(t)} for t in study.tacho])]
    pictures = []
    if plots:
        pictures = [save_figure(_spectrum_figure(study), folder / "order_spectrum.png"),
                    save_figure(_spectrogram_figure(study), folder / "spectrogram.png"),
                    save_figure(_indicator_figure(study), folder / "indicators.png"),
                    save_figure(_tsa_figure(study), folder / "tsa.png")]
    files += pictures
    files.append(write_text(folder / "report.md", report(study, [p.name for p in pictures])))
    files.append(write_html_report(folder))
    files.append(folder / "results.json")

    def rel(paths):
        return [p.relative_to(folder).as_posix() for p in paths]

    data = to_json(study, {"csv": rel(csvs), "wav": rel(wavs), "all": rel(files)})
    write_json(folder / "results.json", data)
    return data


def report(study: SignalStudy, pictures: list[str]) -> str:
    o = study.options
    deepest = study.depths[-1]
    monotone = study.monotone()
    lines = [
        f"# hubvib vibration signature: {study.scene_name}", "",
        "## Vibration signature", "",
        f"Sun at {o.sun_speed_rpm:g} min^-1 and {o.sun_torque_N_m:g} N m; carrier "
        f"{study.carrier_hz:.4g} Hz, ring mesh {study.mesh_hz:.4g} Hz (order "
        f"{study.ring_teeth}), {study.n_planets} planets. Sensor on the ring at "
        f"{o.sensor_angle_deg:g} deg, cracked ring tooth {study.crack_tooth}. "
        f"{o.revolutions:g} carrier revolutions at {o.sample_rate_hz:g} Hz, white noise of "
        f"{o.noise_level:g} x the intact RMS ({study.noise_rms:.4g} m/s^2), "
        f"{o.noise_seeds} seeds per depth.", "",
        "Model: the lumped 9 + 3N DOF model with every sun-planet and ring-planet mesh "
        "stiffness varying in time along the FE mesh-cycle curves (intact; the cracked "
        "tooth's curve while a planet meshes it), each mesh placed in its cycle by the gear "
        "geometry (Parker & Lin 2004 phasing), mean curves scaled to the lumped model's c_sp, "
        f"c_rp (`mesh_stiffness = \"{o.mesh_stiffness}\"`); modal damping "
        f"{o.damping_ratio:g}; periodic steady state by the {o.integrator} scheme, "
        f"{study.steps_per_revolution} steps per revolution (h = {study.step:.4g} s). "
        "Sensor: each ring-mesh force through a Hann window of half-width one planet "
        "spacing (McFadden & Smith 1985), divided by the ring mass"
        + (f", plus {o.rigid_path:g} x the ring's radial acceleration" if o.rigid_path else "")
        + ". ASSUMED: the crack changes only the cracked tooth's mesh stiffness (the rim "
        "stiffness c_ru, c_r stays at the preset).", "",
        "### Checks", ""]
    checks = study.checks
    if "cancellation_rule" in checks:
        lines.append(f"- Planet phasing: {checks['cancellation_rule']}. Intact, the largest "
                     f"line at an order that is not a multiple of N is "
                     f"{checks['non_multiple_of_N_relative']:.2g} of the largest line.")
    if "load_sharing_rule" in checks:
        lines.append(f"- Load sharing: {checks['load_sharing_rule']}.")
    halving = checks.get("step_halving")
    if halving:
        lines.append(f"- Halving the time step changes the intact order amplitudes up to order "
                     f"{halving['max_order']} (the analysed mesh harmonics and their sidebands) "
                     f"by at most {halving['relative_change']:.2g} of the largest (tolerance "
                     f"0.02); up to the Nyquist order {halving['full_order']}, where the highest "
                     f"modes ring, by {halving['full_band_relative_change']:.2g}.")
    errors = o.errors
    sharing = ", ".join(f"{v:.4g}" for v in study.load_sharing)
    lines += ["", "### Errors, load sharing, contact", "",
              f"Pin-hole errors: tangential {_metres(o.planet_position_errors_m)}, "
              f"radial {_metres(o.pin_hole_radial_errors_m)}; ring run-out "
              f"{o.ring_runout_m:g} m. Static ring-mesh force of each planet over the mean "
              f"(intact): {sharing}."
              + (" The errors break the phase cancellation: lines at orders that are not "
                 "multiples of N are labelled '(planet error)' / '(planet load)'."
                 if errors.any() else ""), "",
              "| depth [mm] | non-multiple energy share | min total/static mesh force "
              "(linear) | mesh | separated [% of a revolution] |",
              "|---:|---:|---:|---|---:|"]
    for d in study.depths:
        ratios = d.contact["min_force_ratio"]
        worst = min(ratios, key=ratios.get)
        separated = max(d.contact["separated_fraction"].values())
        lines.append(f"| {1e3 * d.depth:.3g} | {d.non_multiple_fraction:.3g} | "
                     f"{ratios[worst]:.3g} | {worst} | {100 * separated:.3g} |")
    lines += ["", "Below 0 the linear mesh spring would pull; the signal then comes from the "
              f"piecewise contact model (`contact = \"{o.contact}\"`: stiffness 0 where a "
              "tooth pair separates)."]
    lines += ["", "### Indicators against crack depth (mean over the noise seeds)", "",
              "| depth [mm] | " + " | ".join(INDICATORS) + " |",
              "|---:|" + "---:|" * len(INDICATORS)]
    for d in study.depths:
        s = d.summary()
        lines.append(f"| {1e3 * d.depth:.3g} | "
                     + " | ".join(f"{s[n]['mean']:.4g} ± {s[n]['std']:.2g}" for n in INDICATORS)
                     + " |")
    for sensor in study.sensors:
        lines += ["", f"Sensor at {sensor['angle_from_crack_deg']:g} deg from the cracked tooth "
                  f"({sensor['angle_deg']:.4g} deg):", "",
                  "| depth [mm] | non-multiple share | " + " | ".join(INDICATORS) + " |",
                  "|---:|---:|" + "---:|" * len(INDICATORS)]
        for row in sensor["depths"]:
            lines.append(f"| {row['depth_mm']:.3g} | {row['non_multiple_fraction']:.3g} | "
                         + " | ".join(f"{row['indicators'][n]['mean']:.4g}"
                                      for n in INDICATORS) + " |")
    if monotone:
        names = ", ".join(f"{m['indicator']} ({m['direction']}, deepest "
                          f"{m['separation_at_deepest']:+.3g} intact standard deviations)"
                          for m in monotone)
        lines += ["", f"Monotone with depth: {names}."]
    else:
        lines += ["", "No indicator is monotone with depth in this scene."]
    if study.roc:
        lines += roc_section(study.roc)
    lines += ["", f"### Largest lines at {1e3 * deepest.depth:.3g} mm (noise-free)", "",
              "| order | frequency [Hz] | amplitude [m/s^2] | label |", "|---:|---:|---:|---|"]
    for line in deepest.lines:
        lines.append(f"| {line.order:g} | {line.order * study.carrier_hz:.1f} | "
                     f"{line.amplitude:.4g} | {line.label} |")
    if pictures:
        lines += ["", "### Plots", ""] + [x for p in pictures for x in figure_lines(p)]
    return "\n".join(lines) + "\n"


def _axes(rows: int = 1, **options):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(rows, 1, figsize=(8, 3.2 * rows), squeeze=False,
                             layout="constrained", **options)
    # panels further apart than a panel's labels from its frame: each label reads as its
    # own panel's
    fig.get_layout_engine().set(h_pad=0.15)
    return fig, axes


def _spectrum_figure(study: SignalStudy):
    """Overview of the carrier orders up to the last analysed mesh harmonic and its
    sidebands, and a zoom around the mesh order; each panel with its own axis labels."""
    fig, axes = _axes(2)
    overview, zoom = axes[:, 0]
    intact, deepest = study.depths[0], study.depths[-1]
    record_intact = record_spectrum(angle_domain(2 * math.pi * study.carrier_hz * intact.time,
                                                 intact.record, study.points_per_revolution))
    top = study.options.mesh_harmonics * study.ring_teeth + ZOOM * study.n_planets
    keep = record_intact.orders <= top
    overview.semilogy(record_intact.orders[keep], record_intact.amplitude[keep], lw=0.5,
                      color="0.6", label="intact record (noise)")
    styles = ((intact, "o-", "tab:blue"), (deepest, "x--", "tab:orange"))
    for d, style, colour in styles:
        k = d.spectrum.orders[1:top + 1]
        overview.semilogy(k, d.spectrum.amplitude[1:top + 1], style[0], ms=3, color=colour,
                          label=f"{1e3 * d.depth:.3g} mm (steady state)")
    low = study.ring_teeth - ZOOM * study.n_planets
    high = study.ring_teeth + ZOOM * study.n_planets
    for d, style, colour in styles:
        zoom.plot(d.spectrum.orders[low:high + 1], d.spectrum.amplitude[low:high + 1],
                  style, ms=4, lw=0.8, color=colour,
                  label=f"{1e3 * d.depth:.3g} mm (steady state)")
    zoom.axvline(study.ring_teeth, color="k", ls=":", lw=0.8,
                 label=f"mesh order z_r = {study.ring_teeth}")
    overview.set_ylim(bottom=1e-5 * max(d.spectrum.amplitude[1:].max() for d in study.depths))
    order = "carrier order (× %.4g Hz)" % study.carrier_hz
    overview.set_title(f"carrier orders 1 to {top}", fontsize=9)
    zoom.set_title(f"zoom: orders {low} to {high} around the mesh order z_r = "
                   f"{study.ring_teeth}", fontsize=9)
    for ax in (overview, zoom):
        ax.set_xlabel(order)
        ax.set_ylabel("amplitude [m/s²]")
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7)
    return fig


def _spectrogram_figure(study: SignalStudy):
    fig, axes = _axes(1)
    d = study.depths[-1]
    fs = study.options.sample_rate_hz
    segment = 2 ** int(round(math.log2(fs / (study.n_planets * study.carrier_hz))))
    s = spectrogram(d.record, fs, min(segment, d.record.size))
    mesh = axes[0, 0].pcolormesh(s.time_s, s.frequency_hz, 20 * np.log10(s.amplitude + 1e-12),
                                 shading="auto")
    fig.colorbar(mesh, ax=axes[0, 0], label="dB re 1 m/s²")
    axes[0, 0].set_xlabel("time [s]")
    axes[0, 0].set_ylabel("frequency [Hz]")
    axes[0, 0].set_title(f"spectrogram, crack {1e3 * d.depth:.3g} mm", fontsize=9)
    return fig


#: one colour and marker per indicator (``INDICATORS`` has 11: the 10 tab colours and black)
INDICATOR_COLOURS = ("tab:blue", "tab:orange", "tab:green", "tab:red", "tab:purple",
                     "tab:brown", "tab:pink", "tab:gray", "tab:olive", "tab:cyan", "black")
INDICATOR_MARKERS = ("o", "s", "^", "v", "D", "P", "X", "*", "<", ">", "h")


def _indicator_figure(study: SignalStudy):
    """One panel per indicator, each on its own scale: the indicators grow from a few per
    cent (RMS) to a thousandfold (M8A), and one common axis flattens all but the largest."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.patches import Patch

    columns = 4
    rows = -(-(len(INDICATORS) + 1) // columns)  # one cell more for the legend
    fig, axes = plt.subplots(rows, columns, figsize=(2.6 * columns, 2.1 * rows + 0.5),
                             sharex=True, squeeze=False, layout="constrained")
    depths = [1e3 * d.depth for d in study.depths]
    summaries = [d.summary() for d in study.depths]
    handles = []
    for ax, name, colour, marker in zip(axes.flat, INDICATORS, INDICATOR_COLOURS,
                                        INDICATOR_MARKERS):
        means = np.array([s[name]["mean"] for s in summaries])
        stds = np.array([s[name]["std"] for s in summaries])
        ref = means[0] if means[0] else 1.0
        ax.axhline(1.0, color="0.5", lw=0.8, ls="--", label="intact mean")
        ax.fill_between(depths, (means - 2 * stds) / ref, (means + 2 * stds) / ref,
                        color=colour, alpha=0.2, lw=0)
        line, = ax.plot(depths, means / ref, color=colour, marker=marker, ms=4, label=name)
        handles.append(line)
        ax.set_title(name, fontsize=9)
        ax.tick_params(labelsize=7)
        ax.grid(True, alpha=0.3)
    for ax in axes.flat[len(INDICATORS):]:
        ax.axis("off")
    reference = axes.flat[0].get_lines()[0]
    band = Patch(color="0.5", alpha=0.3, label="± 2 std over the noise seeds")
    axes.flat[-1].legend(handles=handles + [reference, band], loc="center", fontsize=7,
                         ncol=2, title="mean over the seeds", title_fontsize=7)
    fig.supxlabel("crack depth [mm]", fontsize=9)
    fig.supylabel("indicator / its intact mean", fontsize=9)
    return fig


def _tsa_figure(study: SignalStudy):
    """The intact and the deepest crack's TSA in panels of their own on one scale (overlaid,
    the trace drawn last covers the other), and their difference (the same noise seed:
    the noise cancels)."""
    fig, axes = _axes(3, sharex=True)
    intact, deepest = study.depths[0], study.depths[-1]
    angle = 360 * np.arange(intact.tsa[0].size) / intact.tsa[0].size
    names = [f"{1e3 * d.depth:.3g} mm" for d in (intact, deepest)]
    traces = ((intact.tsa[0], f"{names[0]} (intact)", "tab:blue"),
              (deepest.tsa[0], f"{names[1]} (deepest crack)", "tab:orange"),
              (deepest.tsa[0] - intact.tsa[0], f"{names[1]} − {names[0]}", "black"))
    for ax, (values, label, colour) in zip(axes[:, 0], traces):
        ax.plot(angle, values, lw=0.6, color=colour, label=label)
        ax.set_ylabel("TSA [m/s²]")
        ax.grid(True, alpha=0.3)
    axes[1, 0].sharey(axes[0, 0])
    axes[2, 0].set_ylabel("difference [m/s²]")
    axes[2, 0].set_xlabel("carrier angle [deg]")
    # above the panels, over no trace
    fig.legend(loc="outside upper center", ncol=3, fontsize=8, title_fontsize=9,
               title="time-synchronous average over one carrier revolution (first noise "
                     "seed)")
    return fig


def _metres(values) -> str:
    return f"{list(values)} m" if values else "none"


def _alarm(row: dict) -> str:
    """When an indicator alarms: above its threshold if it grows with the crack, below it
    if it falls (``roc.detection_rates`` orients each by its mean shift at the deepest
    crack)."""
    side = "rises above" if row["direction"] == "increasing" else "falls below"
    return f"{side} {row['threshold']:.4g}"


def roc_section(roc: dict) -> list[str]:
    """The detection-rate table of the report: POD per depth at the family-wise
    false-alarm rate, AUC at the deepest crack, the first depth seen, and for each
    indicator the side of its threshold that alarms (a falling indicator detects by a
    decrease)."""
    depths = roc["depth_mm"]
    lines = ["", "### Detection rates (ROC / POD)", "",
             f"{roc['records_per_depth']} records per depth ({roc['evaluation_noise']}); "
             f"thresholds from {roc['training_records']} intact records with "
             f"{roc['training_noise']} noise at a family-wise false-alarm rate of "
             f"{roc['false_alarm_rate']:g} (max-T, T = {roc['max_z_threshold']:.3g} standard "
             f"deviations); measured "
             f"on the intact evaluation records: {roc['family_false_alarm_measured']:.3g} ± "
             f"{roc['family_false_alarm_standard_error']:.2g}. Robustness (not claimed): the "
             f"same thresholds on intact records with {roc['coloured_noise']} noise give "
             f"{roc['family_false_alarm_coloured']:.3g}, with {roc['heavy_tail_noise']} noise "
             f"{roc['family_false_alarm_heavy_tail']:.3g}: thresholds must be trained on the "
             "machine's own healthy records.", "",
             "| indicator | alarm when it | " + " | ".join(f"POD {d:g} mm" for d in depths)
             + f" | AUC {depths[-1]:g} mm | first depth with POD >= 0.9 [mm] |",
             "|---|---|" + "---:|" * (len(depths) + 2)]
    for name, row in roc["indicators"].items():
        seen = row["first_depth_seen_mm"]
        lines.append(f"| {name} | {_alarm(row)} | " + " | ".join(f"{p:.2f}" for p in row["pod"])
                     + f" | {row['auc'][-1]:.3f} | {'-' if seen is None else f'{seen:g}'} |")
    lines.append("| any | | " + " | ".join(f"{p:.2f}" for p in roc["any_indicator_pod"])
                 + " | | |")
    route = roc.get("frequency_route")
    if route:
        seen = route["first_depth_seen_mm"]
        lines.append("| frequency route (law) | | "
                     + " | ".join(f"{p:.2f}" for p in route["pod"])
                     + f" | | {'-' if seen is None else f'{seen:g}'} |")
    falling = [name for name, row in roc["indicators"].items()
               if row["direction"] != "increasing"]
    if falling:
        one = len(falling) == 1
        lines += ["", f"{', '.join(falling)}: lower at the deepest crack than intact, so "
                  f"{'its' if one else 'their'} alarm is a value below the threshold; a depth "
                  f"in the last column is detected by a decrease from the intact records, not "
                  f"by a value that grows with depth."]
        lines += ["", "Frequency route: natural frequencies identified in this record and an "
                  "intact one (Bayesian FFT), POD from the identification law (Cramer-Rao "
                  f"bound at {route['record_s']:.3g} s, damping {route['damping_ratio']:g}, "
                  f"modal SNR {route['snr']:g}; Bonferroni over the modes at the same "
                  "family-wise false-alarm rate; nominal reducer, no drift), modes "
                  + (", ".join(str(m) for m in route["modes"]) or "none")
                  + " (the others: close modes, band or record too short)."]
    return lines
