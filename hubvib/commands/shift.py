"""``hubvib shift --to KEY VALUE``: per-mode frequency shift when one parameter changes."""
from __future__ import annotations

import re

from hubvib.lumped import ParameterError
from hubvib.lumped.parameters import scalar_field_names
from hubvib.foundation.output import json_text
from hubvib.runtime.params_input import parse_number

from ._parameters import PARAMETER_HELP, add_parameter_options, parameters

#: what the command line of ``shift`` reads as a negative number rather than an option
NEGATIVE_NUMBER = re.compile(r"^-(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$|^-(inf|infinity|nan)$",
                             re.IGNORECASE)


def add_parser(sub) -> None:
    p = sub.add_parser("shift", help="per-mode frequency shift when one parameter changes",
                       epilog=PARAMETER_HELP)
    add_parameter_options(p)
    p.add_argument("--to", nargs=2, required=True, metavar=("KEY", "VALUE"),
                   help="the modified parameter (one number, SI) and its new value, e.g. "
                   "--to c_ru 1e5")
    # a VALUE such as -1e5 or -inf is a value, not an option (argparse takes only -1 and
    # -1.5 for numbers), so that the parameter's own check names its allowed range; no
    # option of this command looks like a number
    p._negative_number_matcher = NEGATIVE_NUMBER
    p.set_defaults(handler=run)


def run(args) -> int:
    from hubvib.lumped import frequency_shift

    key, value = target(*args.to)
    params = parameters(args)
    try:
        shift = frequency_shift(params, key, value, method=args.method)
    except ParameterError as exc:  # the new value out of its range: name the flag too
        raise ParameterError(f"--to {key} {args.to[1]}: {exc}") from None
    if args.json:
        print(json_text({"parameter": key, "base": shift.base_value, "modified": value,
                         "modes": shift.rows()}))
        return 0
    print(f"{key}: {shift.base_value:.6g} -> {value:.6g}")
    print(f"{'mode':>4} {'type':<13} {'base [rad/s]':>13} {'new [rad/s]':>12} "
          f"{'d [rad/s]':>10} {'d [Hz]':>9} {'d [%]':>8}")
    for r in shift.rows():
        print(f"{r['mode']:>4} {r['kind']:<13} {r['omega_base_rad_s']:>13.3f} "
              f"{r['omega_modified_rad_s']:>12.3f} {r['delta_rad_s']:>10.3f} "
              f"{r['delta_hz']:>9.3f} {r['percent']:>8.3f}")
    return 0


def target(key: str, text: str) -> tuple[str, float]:
    """``--to KEY VALUE`` checked: KEY a one-number parameter, VALUE a number."""
    allowed = scalar_field_names()
    if key not in allowed:
        why = _NOT_SHIFTABLE.get(key, "is not a parameter")
        raise ParameterError(f"--to {key!r} {why}; allowed: {', '.join(allowed)}")
    return key, parse_number(f"--to {key}", text)


_NOT_SHIFTABLE = {
    "theta": "holds one value per planet",
    "theta_deg": "holds one value per planet",
    "c_rp_factors": "holds one value per planet",
    "n_planets": "changes the model's size, so no mode can be followed",
    "alpha_w_deg": "sets alpha_s and alpha_r together; shift one of them [rad]",
}
