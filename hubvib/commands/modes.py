"""``hubvib modes``: the coupled spectrum with the ring rigid (the 9 + 3N model, as
``hubvib spectrum``) or elastic (the FE ring coupled to the lumped bodies), or a plain
annulus's in-plane modes against ring theory."""
from __future__ import annotations

import argparse

from hubvib.foundation.output import json_text

from ._reducer import add_reducer_options, reducer_name


def add_parser(sub) -> None:
    p = sub.add_parser(
        "modes", help="coupled modes with a rigid or an elastic ring (nodal diameters, "
        "harmonic index, class), or a plain annulus against ring theory",
        description="The elastic ring is the design's plane FE ring (P2, plane stress) on "
        "its mounting, reduced to its own modes and the planets' contact flexibility, coupled "
        "to the lumped sun, carrier and planets; every compliance is counted once (the "
        "ring-planet spring holds the planet tooth and the contact only).")
    add_reducer_options(p)
    p.add_argument("--annulus", nargs=3, type=float, metavar=("R_IN", "R_OUT", "WIDTH"),
                   help="a free plain annulus [m] instead of a reducer (not with --preset or "
                   "--design)")
    p.add_argument("--ring", choices=("rigid", "elastic"), default="elastic",
                   help="rigid: the 9 + 3N model (what 'hubvib spectrum' gives); elastic: "
                   "the FE ring coupled (default)")
    p.add_argument("--crack-depth", type=float, default=0.0, metavar="D",
                   help="root crack length at tooth 0 [m]; 0 = intact")
    p.add_argument("--closed", action="store_true",
                   help="the crack's faces tied (closed) instead of open")
    p.add_argument("--mounting", choices=("foundation", "clamped", "free"), default="foundation",
                   help="the ring on its support arcs: a foundation sized to the design's "
                   "c_r and c_ru (default), clamped, or free")
    p.add_argument("--carrier-tooth", type=int, default=None, metavar="K",
                   help="ring tooth of planet 1 (default: the cracked tooth 0)")
    p.add_argument("--band", type=float, default=10e3, metavar="HZ",
                   help="report the coupled modes up to this frequency [Hz] (default 10000)")
    p.add_argument("--E", type=float, default=210e9, help="annulus: Young's modulus [Pa]")
    p.add_argument("--nu", type=float, default=0.3, help="annulus: Poisson's ratio")
    p.add_argument("--density", type=float, default=7850.0, help="annulus: [kg/m^3]")
    p.add_argument("--count", type=int, default=12, help="annulus: elastic modes to report")
    p.add_argument("--out", metavar="DIR",
                   help="elastic ring: write modes.json and, with --render, a PNG per "
                   "coupled mode and coupled_modes.vtu (every mode's ring displacement, for "
                   "ParaView) into DIR")
    p.add_argument("--render", action="store_true",
                   help="with --out: off-screen mode-shape pictures and the VTU")
    p.add_argument("--json", action="store_true", help="machine-readable output")
    p.set_defaults(handler=run)


def run(args) -> int:
    if args.annulus is not None:
        if args.preset is not None or args.design is not None:
            raise ValueError("--annulus and --preset/--design both name what to solve; give "
                             "one of them")
        return _annulus(args)
    reducer_name(args)  # --preset with --design: refused, naming both
    if args.render and not args.out:
        raise ValueError("--render: needs --out DIR")
    if args.ring == "rigid":
        if args.out or args.render:
            raise ValueError("--out, --render: the elastic ring only (drop --ring rigid)")
        if args.crack_depth or args.closed or args.carrier_tooth is not None:
            raise ValueError("--ring rigid: the 9 + 3N model has no crack or carrier position; "
                             "drop --crack-depth, --closed and --carrier-tooth")
        return _rigid(args)
    return _elastic(args)


def _design(args):
    from .design import design_from_argument

    return design_from_argument(reducer_name(args))


def _rigid(args) -> int:
    from hubvib.reducer.stages import lumped_parameters
    from hubvib.lumped import natural_modes

    from . import spectrum

    spec = natural_modes(lumped_parameters(_design(args)))
    if args.json:
        print(json_text({"ring": "rigid", "method": spec.method, "n_rigid": spec.n_rigid,
                         "modes": spec.rows()}))
        return 0
    return spectrum.run(argparse.Namespace(preset=args.preset, design=args.design,
                                           params=None, set=[], method="jacobi", json=False))


def _elastic(args) -> int:
    from hubvib.elastic.model import elastic_ring, elastic_spectrum, lowest_ring_mode
    from hubvib.elastic.options import ElasticOptions
    from hubvib.elastic.tracking import track_modes
    from hubvib.meshing.crack import Crack

    if not (args.crack_depth >= 0):
        raise ValueError(f"--crack-depth = {args.crack_depth!r} m, allowed >= 0")
    if args.closed and args.crack_depth == 0:
        raise ValueError("--closed: needs a crack (--crack-depth > 0)")
    design = _design(args)
    options = ElasticOptions(mounting=args.mounting, band_hz=args.band)
    crack = Crack(depth=args.crack_depth) if args.crack_depth > 0 else None
    positions = None if args.carrier_tooth is None else (args.carrier_tooth,)
    er = elastic_ring(design, crack, args.closed, options, positions)
    spec = elastic_spectrum(er)
    tracked = None
    if crack is not None:
        intact = elastic_spectrum(elastic_ring(design, None, False, options, er.carrier_teeth),
                                  spec.carrier_tooth)
        tracked = track_modes(intact, spec, er.body.rigid_mass()[0, 0])
    rows = spec.rows()
    for i, row in enumerate(rows):
        if tracked is not None:
            ref = tracked.reference[i]
            row["tracks_intact_mode"] = ref + 1 if ref >= 0 else None
            row["intact_frequency_hz"] = (float(intact.frequency_hz[ref]) if ref >= 0 else None)
            row["tracking_match"] = tracked.match[i]
            row["split_pair"] = tracked.split_pair[i]
    head = {"ring": "elastic", "design": design.name, "state": er.label,
            "mounting": er.body.mounting, "carrier_tooth": spec.carrier_tooth,
            "engaged_teeth": list(spec.modes.engagement.teeth),
            "foundation_N_m2": None if er.foundation is None else
            {"normal": er.foundation.k_n, "tangential": er.foundation.k_t},
            "k_rest_N_m": er.k_rest, "band_hz": options.band_hz,
            "ring_modes_kept": int(er.basis.mode_hz.size), "cutoff_hz": options.cutoff_hz,
            "ring_dofs": er.body.ndofs}
    lowest = lowest_ring_mode(er)
    head["lowest_ring_mode"] = None if lowest is None else {
        "frequency_hz": lowest[0], "nodal_diameter": lowest[1]}
    written = []
    if args.out:
        from pathlib import Path

        from hubvib.foundation.output import write_text

        folder = Path(args.out)
        written.append(write_text(folder / "modes.json", json_text(head | {"modes": rows})))
        if args.render:
            from hubvib.render.coupled import render_coupled_modes

            written += render_coupled_modes(er, spec, folder)
    if args.json:
        print(json_text(head | {"modes": rows}))
        return 0
    print(f"{design.name}: elastic ring, {er.label}, mounting {er.body.mounting}"
          + ("" if er.foundation is None else
             f" (foundation k_n {er.foundation.k_n:.4g}, k_t {er.foundation.k_t:.4g} N/m^2, "
             "sized to the design's c_r and c_ru)"))
    print(f"planet 1 on ring tooth {spec.carrier_tooth} (teeth {list(spec.modes.engagement.teeth)}); "
          f"ring-planet spring without the ring body {er.k_rest:.4g} N/m; ring {er.body.ndofs} "
          f"DOFs reduced to {er.basis.size} ({er.basis.mode_hz.size} own modes up to "
          f"{options.cutoff_hz:.0f} Hz)")
    if lowest is not None:
        print(f"the mounted ring's lowest elastic mode of its own: {lowest[0]:.1f} Hz (n = "
              f"{lowest[1]}); the rigid-ring model (hubvib spectrum) holds only well below it")
    extra = "  intact [Hz]  tracks" if tracked is not None else ""
    print(f"{'mode':>4} {'f [Hz]':>10}  {'class':<13} {'n':>2} {'p':>2} {'ring':>5} mult{extra}")
    for row in rows:
        p = "-" if row["harmonic_index"] is None else row["harmonic_index"]
        line = (f"{row['mode']:>4} {row['frequency_hz']:>10.1f}  {row['class']:<13} "
                f"{row['nodal_diameter']:>2} {p:>2} {row['ring_share']:>5.2f} "
                f"{row['multiplicity']:>4}")
        if tracked is not None and row["tracks_intact_mode"] is not None:
            line += (f"  {row['intact_frequency_hz']:>11.1f}  mode {row['tracks_intact_mode']}"
                     + (" (split pair)" if row["split_pair"] else ""))
        print(line)
    print("n: the ring's dominant nodal diameters; p: harmonic index under the planets' "
          "symmetry; ring: the ring's share of the kinetic energy")
    if written:
        pictures = sum(1 for w in written if w.suffix == ".png")
        print(f"written: {written[0]}" + (f", {pictures} PNG files and coupled_modes.vtu in "
                                          f"{written[0].parent}" if pictures else ""))
    return 0


def _annulus(args) -> int:
    from hubvib.elastic.annulus import annulus_modes
    from hubvib.fem.material import Material
    from hubvib.validation.ring_theory import thick_ring_hz, thin_ring_hz

    r_in, r_out, width = args.annulus
    if not (0 < r_in < r_out) or not width > 0:
        raise ValueError(f"--annulus {r_in!r} {r_out!r} {width!r}: allowed 0 < R_IN < R_OUT "
                         "and WIDTH > 0 [m]")
    if not 1 <= args.count <= 60:
        raise ValueError(f"--count = {args.count!r}, allowed 1..60")
    material = Material(args.E, args.nu, args.density)
    modes = annulus_modes(r_in, r_out, width, material, args.count)
    radius, h = 0.5 * (r_in + r_out), r_out - r_in
    rows = []
    for f, n in zip(modes.frequency_hz, modes.nodal_diameter):
        n = int(n)
        thick = thick_ring_hz(n, radius, h, width, args.E, args.nu, args.density)[0] if n != 1 else None
        thin = thin_ring_hz(n, radius, h, width, args.E, args.density) if n >= 2 else None
        rows.append({"frequency_hz": float(f), "nodal_diameter": n,
                     "curved_beam_hz": None if thick is None else float(thick),
                     "thin_ring_hz": thin})
    if args.json:
        print(json_text({"annulus": {"inner_radius_m": r_in, "outer_radius_m": r_out,
                                     "width_m": width}, "dofs": modes.dofs, "modes": rows}))
        return 0
    print(f"free annulus {r_in:g}..{r_out:g} m, width {width:g} m (plane stress, P2, "
          f"{modes.dofs} DOFs); curved beam: extension, shear and rotary inertia")
    print(f"{'FE [Hz]':>11} {'n':>2} {'curved beam [Hz]':>17} {'thin ring [Hz]':>15}")
    for r in rows:
        beam = "" if r["curved_beam_hz"] is None else f"{r['curved_beam_hz']:.1f}"
        thin = "" if r["thin_ring_hz"] is None else f"{r['thin_ring_hz']:.1f}"
        print(f"{r['frequency_hz']:>11.1f} {r['nodal_diameter']:>2} {beam:>17} {thin:>15}")
    return 0
