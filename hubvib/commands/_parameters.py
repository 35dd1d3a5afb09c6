"""Options shared by the commands that take lumped parameters."""
from __future__ import annotations

from pathlib import Path

from hubvib.design import preset_names
from hubvib.lumped import METHODS, field_names
from hubvib.runtime.params_input import CONVENIENCE_KEYS, load_parameters, parse_set

PARAMETER_HELP = (
    "Parameter keys (SI: kg, m, N/m, rad): " + ", ".join(field_names())
    + "; edge conveniences: " + ", ".join(CONVENIENCE_KEYS)
    + ". m_* masses, mu_* reduced masses J/r_b^2, d_* base diameters, c_sp/c_rp mesh, "
    "c_p/c_c/c_r/c_s bearings, c_su/c_cu/c_ru reduced torsional stiffness, alpha_s/alpha_r "
    "working pressure angles, theta planet angles."
)


def add_parameter_options(p) -> None:
    p.add_argument("--preset", default="raba118", choices=sorted(preset_names()),
                   help="a registered design preset (hubvib.design.PRESETS)")
    p.add_argument("--design", metavar="FILE.toml",
                   help="a reducer design file (or a preset design's name): its lumped model")
    p.add_argument("--params", type=Path, metavar="FILE.toml",
                   help="TOML file of parameter keys (may name its own preset)")
    p.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                   help=PARAMETER_HELP)
    p.add_argument("--method", default="jacobi", choices=METHODS)
    p.add_argument("--json", action="store_true", help="machine-readable output")


def parameters(args):
    """The lumped parameters the options describe (``--design`` replaces ``--preset``)."""
    if args.design is None:
        return load_parameters(args.preset, args.params, parse_set(args.set))
    from hubvib.build.stages import lumped_parameters
    from hubvib.runtime.params_input import apply_overrides

    from .design import design_from_argument

    if args.params is not None:
        raise ValueError("--design and --params both give the reducer; use one")
    return apply_overrides(lumped_parameters(design_from_argument(args.design)),
                           parse_set(args.set))
