"""``hubvib spectrum``: natural frequencies, mode types and multiplicities."""
from __future__ import annotations

from hubvib.foundation.output import json_text

from ._parameters import PARAMETER_HELP, add_parameter_options, parameters, stiffness_methods


def add_parser(sub) -> None:
    p = sub.add_parser("spectrum", help="natural frequencies, mode types and multiplicities",
                       epilog=PARAMETER_HELP)
    add_parameter_options(p)
    p.set_defaults(handler=run)


def run(args) -> int:
    from hubvib.lumped import natural_modes

    params = parameters(args)
    spectrum = natural_modes(params, args.method)
    springs = {key: {"value_N_m": float(getattr(params, key)), "method": method}
               for key, method in stiffness_methods(args).items()}
    if args.json:
        print(json_text({"method": spectrum.method, "n_rigid": spectrum.n_rigid,
                         "modes": spectrum.rows(), "stiffness": springs}))
        return 0
    print(f"{'mode':>4} {'omega [rad/s]':>14} {'f [Hz]':>11}  {'type':<13} mult")
    for r in spectrum.rows():
        print(f"{r['mode']:>4} {r['omega_rad_s']:>14.3f} {r['frequency_hz']:>11.3f}  "
              f"{r['kind']:<13} {r['multiplicity']}")
    if spectrum.n_rigid:
        print(f"{spectrum.n_rigid} rigid-body mode(s): the supports and springs leave the "
              "system free to move without strain; their frequency is exactly 0.")
    print("springs [N/m]: " + ", ".join(f"{key} {row['value_N_m']:.6g} ({row['method']})"
                                         for key, row in springs.items()))
    return 0
