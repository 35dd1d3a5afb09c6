"""``hubvib modes``: the coupled spectrum with the ring rigid (the 9 + 3N model, as
``hubvib spectrum``) or elastic (the FE ring coupled to the lumped bodies), or a plain
annulus's in-plane modes against ring theory."""
from __future__ import annotations

import argparse
import math

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
    p.add_argument("--ring", choices=("rigid", "elastic"), default=None,
                   help="rigid: the 9 + 3N model (what 'hubvib spectrum' gives); elastic: "
                   "the FE ring coupled (default)")
    p.add_argument("--crack-depth", type=float, default=None, metavar="D",
                   help="root crack length at tooth 0 [m]; 0 = intact (default).  A crack's "
                   "faces are as the working load leaves them: the record's spectrum over "
                   "the planet pitch, or with --carrier-tooth the spectrum at that position")
    p.add_argument("--closed", action="store_true",
                   help="the crack's faces tied (closed) at every position instead")
    p.add_argument("--open", action="store_true",
                   help="the crack's faces free (open) at every position instead")
    p.add_argument("--torque", type=float, default=None, metavar="N_M",
                   help="sun torque of the loaded crack state [N m] (default: the design's "
                   "load.sun_torque; negative: reversed)")
    p.add_argument("--closure-gap", type=float, default=None, metavar="M",
                   help="the crack's faces part only where their free opening exceeds this "
                   "[m] (roughness, residual compression; default 0)")
    p.add_argument("--mesh", choices=("study", "fine"), default="study",
                   help="the ring mesh: the crack study's (default: the same intact mode "
                   "prints the same frequency as 'hubvib run') or the finer modal mesh")
    p.add_argument("--mounting", choices=("foundation", "clamped", "free"), default="foundation",
                   help="the ring on its support arcs: a foundation sized to the design's "
                   "c_r and c_ru (default), clamped, or free")
    p.add_argument("--carrier-tooth", type=int, default=None, metavar="K",
                   help="ring tooth of planet 1 (default: the cracked tooth 0 for an intact "
                   "or a tied/open crack; a loaded crack: the record over the pitch)")
    p.add_argument("--band", type=float, default=10e3, metavar="HZ",
                   help="report the coupled modes up to this frequency [Hz] (default 10000)")
    p.add_argument("--E", type=float, default=None, help="annulus: Young's modulus [Pa] "
                   "(default 210e9)")
    p.add_argument("--nu", type=float, default=None, help="annulus: Poisson's ratio "
                   "(default 0.3)")
    p.add_argument("--density", type=float, default=None, help="annulus: [kg/m^3] "
                   "(default 7850)")
    p.add_argument("--count", type=int, default=12, help="annulus: elastic modes to report")
    p.add_argument("--out", metavar="DIR",
                   help="elastic ring: write modes.json and, with --render, a PNG per "
                   "coupled mode and coupled_modes.vtu (every mode's ring displacement, for "
                   "ParaView) into DIR")
    p.add_argument("--render", action="store_true",
                   help="with --out: off-screen mode-shape pictures and the VTU")
    p.add_argument("--json", action="store_true", help="machine-readable output")
    p.set_defaults(handler=run)


ANNULUS_MATERIAL = {"E": 210e9, "nu": 0.3, "density": 7850.0}
LOADED_FLAGS = ("torque", "closure_gap")


def _given(args, *names) -> list[str]:
    """The flags among ``names`` given on the command line (``--name`` spelling)."""
    return [f"--{n.replace('_', '-')}" for n in names if getattr(args, n) is not None]


def run(args) -> int:
    _refuse_what_does_not_apply(args)
    if args.annulus is not None:
        return _annulus(args)
    reducer_name(args)  # --preset with --design: refused, naming both
    if args.ring == "rigid":
        return _rigid(args)
    return _elastic(args)


def _refuse_what_does_not_apply(args) -> None:
    """One line, naming the flags, for every flag the asked computation would ignore."""
    material = _given(args, "E", "nu", "density")
    if args.annulus is not None:
        if args.preset is not None or args.design is not None:
            raise ValueError("--annulus and --preset/--design both name what to solve; give "
                             "one of them")
        if args.ring == "rigid":
            raise ValueError("--annulus with --ring rigid: the annulus is an elastic FE body; "
                             "drop --ring rigid")
        extra = _given(args, "crack_depth", "carrier_tooth", *LOADED_FLAGS) + [
            f for f, on in (("--closed", args.closed), ("--open", args.open)) if on]
        if extra:
            raise ValueError(f"{', '.join(extra)}: not with --annulus (a plain annulus has "
                             "no crack, planets or load)")
        return
    if material:
        raise ValueError(f"{', '.join(material)}: the annulus's material only; a reducer's "
                         "material comes from its design (--preset/--design)")
    if args.render and not args.out:
        raise ValueError("--render: needs --out DIR")
    if args.ring == "rigid":
        if args.out or args.render:
            raise ValueError("--out, --render: the elastic ring only (drop --ring rigid)")
        extra = _given(args, "crack_depth", "carrier_tooth", *LOADED_FLAGS) + [
            f for f, on in (("--closed", args.closed), ("--open", args.open),
                            ("--mesh", args.mesh != "study")) if on]
        if extra:
            raise ValueError(f"--ring rigid: the 9 + 3N model has no crack, carrier "
                             f"position, load state or ring mesh; drop {', '.join(extra)}")
        return
    depth = 0.0 if args.crack_depth is None else args.crack_depth
    if not (depth >= 0):
        raise ValueError(f"--crack-depth = {args.crack_depth!r} m, allowed >= 0")
    if args.closed and args.open:
        raise ValueError("--closed and --open: give one of them")
    faces = [f for f, on in (("--closed", args.closed), ("--open", args.open)) if on]
    if faces and depth == 0:
        raise ValueError(f"{faces[0]}: needs a crack (--crack-depth > 0)")
    loaded = _given(args, *LOADED_FLAGS)
    if loaded and depth == 0:
        raise ValueError(f"{', '.join(loaded)}: the load state of a crack; needs "
                         "--crack-depth > 0")
    if loaded and faces:
        raise ValueError(f"{', '.join(loaded)} with {faces[0]}: the faces are fixed "
                         "there; drop one")
    if args.torque is not None and not (math.isfinite(args.torque) and args.torque != 0):
        raise ValueError(f"--torque = {args.torque!r} N m, allowed finite and != 0")
    if args.closure_gap is not None and not (math.isfinite(args.closure_gap)
                                             and 0 <= args.closure_gap <= 1e-3):
        raise ValueError(f"--closure-gap = {args.closure_gap!r} m, allowed 0..1e-3")
    if depth > 0 and not faces and (args.out or args.render):
        raise ValueError("--out, --render: the mode files are written for a ring with its "
                         "faces fixed; add --open or --closed (the loaded crack gives a "
                         "spectrum over the pitch, printed or --json)")
    if depth > 0 and not faces and args.mounting == "free":
        raise ValueError("--mounting free with a loaded crack: a free ring has no static "
                         "state under the working load; add --open or --closed, or mount it")


def _check_carrier_tooth(args, design) -> None:
    """``--carrier-tooth`` within the design's ring teeth, refused by the flag's name."""
    from ._applies import refuse_outside

    teeth = design.ring.teeth
    refuse_outside("--carrier-tooth", args.carrier_tooth, 0, teeth - 1,
                   f"a tooth of the {teeth}-tooth ring of design {design.name!r}")


def _state_row(state) -> dict:
    """One carrier position's crack state for the JSON (SI)."""
    return {"carrier_tooth": state.carrier_tooth, "open_length_m": state.open_length_m,
            "max_gap_m": state.max_gap_m}


def _design(args):
    from .design import design_from_argument

    return design_from_argument(reducer_name(args))


def _rigid(args) -> int:
    from hubvib.detection.mode_names import rigid_label
    from hubvib.lumped import natural_modes
    from hubvib.reducer.stages import lumped_parameters

    from . import spectrum

    design = _design(args)
    spec = natural_modes(lumped_parameters(design))
    differences = _differences(args, design)
    if args.json:
        rows = [row | {"label": rigid_label(row["mode"] - 1, row["kind"], row["frequency_hz"])}
                for row in spec.rows()]
        print(json_text({"ring": "rigid", "design": design.name, "method": spec.method,
                         "n_rigid": spec.n_rigid,
                         "modes": rows, "model_differences": differences.to_dict()}))
        return 0
    print(f"{design.name}: rigid ring (the 9 + 3N model); reports name its mode K 'rigid K' "
          "(the elastic ring numbers its own modes)")
    code = spectrum.run(argparse.Namespace(preset=args.preset, design=args.design,
                                           params=None, set=[], method="jacobi", json=False))
    print("\n".join(differences.lines()))
    return code


def _differences(args, design, er=None):
    """The rigid ring's table against the FE ring on the asked mounting and mesh
    (``hubvib.elastic.differences``); ``er``: the intact elastic ring already built, used
    when its basis serves the band's carrier position."""
    from hubvib.elastic.differences import cached_model_differences, model_differences
    from hubvib.elastic.model import out_of_contact_tooth
    from hubvib.reducer.stages import ring_gear

    options = _options(args)
    away = out_of_contact_tooth(ring_gear(design).teeth, design.n_planets)
    if er is not None and er.crack is None and away in er.carrier_teeth:
        return model_differences(design, options, away, er)
    return cached_model_differences(design, options)


def _options(args):
    """The elastic ring's options: the crack study's mesh (``ElasticScene``) unless
    ``--mesh fine`` (the modal mesh of ``ElasticOptions``)."""
    from dataclasses import replace

    from hubvib.elastic.options import ElasticOptions, ElasticScene

    base = ElasticScene().options if args.mesh == "study" else ElasticOptions()
    return replace(base, mounting=args.mounting, band_hz=args.band)


MESH_NAMES = {"study": "the crack study's ring mesh ([elastic] of 'hubvib run')",
              "fine": "the finer modal mesh (not the crack study's: its frequencies differ "
                      "from the study's by the mesh error)"}


def _elastic(args) -> int:
    from hubvib.elastic.content import elastic_label
    from hubvib.elastic.model import elastic_ring, elastic_spectrum, lowest_ring_mode
    from hubvib.elastic.tracking import track_modes
    from hubvib.meshing.crack import Crack

    design = _design(args)
    _check_carrier_tooth(args, design)
    options = _options(args)
    depth = 0.0 if args.crack_depth is None else args.crack_depth
    crack = Crack(depth=depth) if depth > 0 else None
    if crack is not None and not (args.closed or args.open):
        if args.carrier_tooth is None:
            return _loaded_record(args, design, crack, options)
        return _loaded_position(args, design, crack, options)
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
        row["label"] = elastic_label(spec.content[i], row["frequency_hz"])
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
            "ring_dofs": er.body.ndofs, "mesh": args.mesh}
    lowest = lowest_ring_mode(er)
    head["lowest_ring_mode"] = None if lowest is None else {
        "frequency_hz": lowest[0], "nodal_diameter": lowest[1]}
    differences = _differences(args, design, er)
    head["model_differences"] = differences.to_dict()
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
    print(f"ring mesh: {MESH_NAMES[args.mesh]}")
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
    print(f"{'mode':>4} {'f [Hz]':>10}  {'class':<13} {'n':>2} {'p':>2} {'ring':>5} mult "
          f"{'pair, split [Hz]':<18}{extra}")
    for row in rows:
        p = "-" if row["harmonic_index"] is None else row["harmonic_index"]
        line = (f"{row['mode']:>4} {row['frequency_hz']:>10.1f}  {row['class']:<13} "
                f"{row['nodal_diameter']:>2} {p:>2} {row['ring_share']:>5.2f} "
                f"{row['multiplicity']:>4} {_pair_words(row):<18}")
        if tracked is not None and row["tracks_intact_mode"] is not None:
            line += (f"  {row['intact_frequency_hz']:>11.1f}  mode {row['tracks_intact_mode']}"
                     + (" (split pair)" if row["split_pair"] else ""))
        elif tracked is not None:
            line += f"  {NOT_TRACKED:>11}"
        print(line.rstrip())
    print("n: the ring's dominant nodal diameters; p: harmonic index under the planets' "
          "symmetry; ring: the ring's share of the kinetic energy; class: 'ring' where the "
          "ring holds the largest kinetic-energy share of the bodies, else the mode's type "
          "under the planets' symmetry; mult 2: a pair by that symmetry (found by shape), "
          "with its partner and split; reports name a coupled mode 'elastic n=N (class, "
          "f Hz)', not by its number here (the rigid ring numbers its own modes)")
    print("\n".join(differences.lines()))
    if written:
        pictures = sum(1 for w in written if w.suffix == ".png")
        print(f"written: {written[0]}" + (f", {pictures} PNG files and coupled_modes.vtu in "
                                          f"{written[0].parent}" if pictures else ""))
    return 0


def _pair_words(row) -> str:
    """``with 4, 0.9`` for a mode paired by symmetry, ``-`` otherwise."""
    if row.get("pair_mode") is None:
        return "-"
    return f"with {row['pair_mode']}, {row['pair_split_hz']:.1f}"


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
    E, nu, density = (ANNULUS_MATERIAL[k] if getattr(args, k) is None else getattr(args, k)
                      for k in ("E", "nu", "density"))
    material = Material(E, nu, density)
    modes = annulus_modes(r_in, r_out, width, material, args.count)
    radius, h = 0.5 * (r_in + r_out), r_out - r_in
    rows = []
    for f, n in zip(modes.frequency_hz, modes.nodal_diameter):
        n = int(n)
        thick = thick_ring_hz(n, radius, h, width, E, nu, density)[0] if n != 1 else None
        thin = thin_ring_hz(n, radius, h, width, E, density) if n >= 2 else None
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


def _torque_fraction(args, design) -> tuple[float, float]:
    """(fraction of the design's sun torque, closure gap [m]) the flags ask for."""
    gap = 0.0 if args.closure_gap is None else float(args.closure_gap)
    if args.torque is None:
        if not design.sun_torque > 0:
            raise ValueError(f"design load.sun_torque = {design.sun_torque!r} N m: no working "
                             "load to leave the crack in; give --torque")
        return 1.0, gap
    if not design.sun_torque > 0:
        raise ValueError(f"design load.sun_torque = {design.sun_torque!r} N m: --torque is "
                         "scaled from it; give the design a load.sun_torque > 0")
    return args.torque / design.sun_torque, gap


def _loaded_record(args, design, crack, options) -> int:
    """The record's spectrum over the planet pitch about the loaded crack."""
    from hubvib.elastic.content import elastic_label
    from hubvib.elastic.cases import cached_case, elastic_case
    from hubvib.elastic.loaded import CLOSURE_GAPS, TORQUE_FRACTIONS, record_track
    from hubvib.elastic.options import ElasticScene
    from hubvib.elastic.rest import rest_stiffness

    fraction, gap = _torque_fraction(args, design)
    scene = ElasticScene(ring="elastic", options=options)
    k_rest = rest_stiffness(design, options.rest)
    intact = cached_case(design, None, scene, k_rest)
    stored = gap in CLOSURE_GAPS and (gap == 0 and fraction > 0 or any(
        math.isclose(fraction, f) for f in TORQUE_FRACTIONS))
    case = cached_case(design, crack, scene, k_rest) if stored else elastic_case(
        design, crack, scene, k_rest, (fraction,), (gap,))
    track = record_track(intact, case, fraction, gap)
    away = intact.away
    rows = []
    for i in range(track.reference_hz.size):
        rows.append({"mode": i + 1,
                     "label": (elastic_label(away.content[i], away.frequency_hz[i])
                               if i < away.frequency_hz.size else None),
                     "frequency_hz": track.record_hz[i],
                     "intact_hz": track.intact_record_hz[i],
                     "change_hz": track.change_hz[i],
                     "instantaneous_min_hz": track.instantaneous_min_hz[i],
                     "instantaneous_max_hz": track.instantaneous_max_hz[i],
                     "frequency_slip_hz": track.slip_hz[i], "regime": track.regime[i],
                     "split_hz": list(track.split_hz[i])})
    states = [_state_row(s) for s in track.states]
    head = {"ring": "elastic", "design": design.name, "state": f"{crack.start} crack "
            f"{1e3 * crack.depth:.3g} mm, faces as the working load leaves them",
            "mounting": options.mounting, "mesh": args.mesh, "torque_N_m": track.torque_N_m,
            "closure_gap_m": track.closure_gap_m, "open_share": track.open_share,
            "crack_state": states, "band_hz": options.band_hz, "k_rest_N_m": k_rest}
    if args.json:
        print(json_text(_finite(head | {"modes": rows})))
        return 0
    print(f"ring mesh: {MESH_NAMES[args.mesh]}")
    print(f"{design.name}: elastic ring, {head['state']}; sun torque {track.torque_N_m:g} N m, "
          f"closure gap {1e6 * track.closure_gap_m:g} um; mounting {options.mounting}")
    print(f"faces apart at {100 * track.open_share:.0f} % of the {len(states)} carrier "
          "positions of a planet pitch (planet 1 from the cracked tooth on):")
    print("  tooth " + " ".join(f"{s['carrier_tooth']:>5}" for s in states))
    print("  open [mm] " + " ".join(f"{1e3 * s['open_length_m']:>5.2f}" for s in states))
    print("  gap [um]  " + " ".join(f"{1e6 * s['max_gap_m']:>5.2f}" for s in states))
    print("a record over many carrier revolutions; frequencies [Hz], in the order of the "
          "intact ring's modes half a pitch from the cracked tooth:")
    print(f"{'mode':>4} {'record':>9} {'intact':>9} {'change':>8} {'min':>9} {'max':>9} "
          f"{'sliding':>9}  {'regime':<9} name")
    for r in rows:
        print(f"{r['mode']:>4} {_hz(r['frequency_hz'], 9)} {_hz(r['intact_hz'], 9)} "
              f"{_hz(r['change_hz'], 8, 2)} {_hz(r['instantaneous_min_hz'], 9)} "
              f"{_hz(r['instantaneous_max_hz'], 9)} {_hz(r['frequency_slip_hz'], 9)}  "
              f"{r['regime']:<9} {r['label'] or ''}"
              + (f" {r['split_hz']}" if r["split_hz"] else ""))
    print("record: what a record's identification returns (pressed faces stuck); min/max: "
          "over the positions; sliding: the record with the pressed faces sliding (bound); "
          f"'{NOT_TRACKED}': no mode of that state follows this one by shape; name: the "
          "intact coupled mode as reports name it (nodal diameter, class, its frequency half "
          "a pitch from the cracked tooth)")
    return 0


def _loaded_position(args, design, crack, options) -> int:
    """The spectrum at one carrier position about the crack as the load leaves it there."""
    import numpy as np

    from hubvib.elastic.crack_state import crack_state
    from hubvib.elastic.loaded import loaded_spectrum
    from hubvib.elastic.model import elastic_ring, elastic_spectrum
    from hubvib.elastic.tracking import track_modes
    from hubvib.lumped.elastic_ring import engagement
    from hubvib.reducer.stages import mesh_force

    fraction, gap = _torque_fraction(args, design)
    tooth = args.carrier_tooth
    er = elastic_ring(design, crack, False, options, (tooth,), more_positions=(tooth,),
                      crack_faces=True)
    teeth = engagement(er.params, er.operators, tooth).teeth
    state, solution = crack_state(er.contact, tooth, teeth, fraction * mesh_force(design), gap)
    stick = loaded_spectrum(er, tooth, solution.pressed, True)
    slip = loaded_spectrum(er, tooth, solution.pressed, False)
    intact = elastic_spectrum(elastic_ring(design, None, False, options, (tooth,),
                                           k_rest=er.k_rest), tooth)
    mass = er.body.rigid_mass()[0, 0]
    tracked = track_modes(intact, stick, mass)
    to_stick = track_modes(stick, slip, mass).reference
    slip_of = np.full(stick.frequency_hz.size, np.nan)
    for j, r in enumerate(to_stick):
        if r >= 0:
            slip_of[r] = slip.frequency_hz[j]
    rows = stick.rows()
    for i, row in enumerate(rows):
        ref = tracked.reference[i]
        row["intact_hz"] = float(intact.frequency_hz[ref]) if ref >= 0 else None
        row["tracks_intact_mode"] = ref + 1 if ref >= 0 else None
        row["frequency_slip_hz"] = slip_of[i]
    head = {"ring": "elastic", "design": design.name, "state": f"{crack.start} crack "
            f"{1e3 * crack.depth:.3g} mm, faces as the working load leaves them",
            "mounting": options.mounting, "mesh": args.mesh, "carrier_tooth": tooth,
            "engaged_teeth": list(teeth), "torque_N_m": fraction * design.sun_torque,
            "closure_gap_m": gap,
            "crack_state": [_state_row(state)],
            "open_pairs": int(sum(state.open_pairs)), "pairs": len(state.open_pairs),
            "band_hz": options.band_hz, "k_rest_N_m": er.k_rest}
    if args.json:
        print(json_text(_finite(head | {"modes": rows})))
        return 0
    print(f"ring mesh: {MESH_NAMES[args.mesh]}")
    print(f"{design.name}: elastic ring, {head['state']}; sun torque "
          f"{head['torque_N_m']:g} N m, closure gap {1e6 * gap:g} um")
    print(f"planet 1 on ring tooth {tooth} (teeth {list(teeth)}): faces apart over "
          f"{1e3 * state.open_length_m:.2f} mm of the crack ({head['open_pairs']} of "
          f"{head['pairs']} node pairs), largest gap {1e6 * state.max_gap_m:.2f} um")
    print(f"{'mode':>4} {'f [Hz]':>10} {'sliding':>10} {'intact':>10}  {'class':<13} n")
    for row in rows:
        print(f"{row['mode']:>4} {_hz(row['frequency_hz'], 10)} "
              f"{_hz(row['frequency_slip_hz'], 10)} {_hz(row['intact_hz'], 10)}  "
              f"{row['class']:<13} {row['nodal_diameter']}")
    print("f: pressed faces stuck (small vibrations stick); sliding: pressed faces free to "
          f"slide (the bound); '{NOT_TRACKED}': no mode of that state follows this one by "
          "shape")
    return 0


#: what a table prints where a mode has no counterpart (NaN or None in the data)
NOT_TRACKED = "not tracked"


def _hz(value, width: int, digits: int = 1) -> str:
    """``value`` [Hz] right-aligned in ``width``, or ``NOT_TRACKED`` for None, NaN, inf."""
    if value is None or not math.isfinite(value):
        return f"{NOT_TRACKED:>{width}}"
    return f"{value:>{width}.{digits}f}"


def _finite(data):
    """``data`` for JSON: numbers as floats, NaN and infinities as None."""
    from hubvib.foundation.output import finite_or_none

    if isinstance(data, dict):
        return {k: _finite(v) for k, v in data.items()}
    if isinstance(data, (list, tuple)):
        return [_finite(v) for v in data]
    if isinstance(data, (bool, str)) or data is None:
        return data
    if isinstance(data, int):
        return data
    try:
        return finite_or_none(data)
    except (TypeError, ValueError):
        return data
