"""Options shared by the commands that take lumped parameters."""
from __future__ import annotations

from pathlib import Path

from hubvib.lumped import METHODS, field_names
from hubvib.runtime.params_input import (CONVENIENCE_KEYS, load_parameters, parse_set,
                                         read_toml_file)

from ._reducer import DEFAULT_PRESET, add_reducer_options, reducer_name

PARAMETER_HELP = (
    "Parameter keys (SI: kg, m, N/m, rad): " + ", ".join(field_names())
    + "; edge conveniences: " + ", ".join(CONVENIENCE_KEYS)
    + ". m_* masses, mu_* reduced masses J/r_b^2, d_* base diameters, c_sp/c_rp mesh, "
    "c_p/c_c/c_r/c_s bearings, c_su/c_cu/c_ru reduced torsional stiffness, alpha_s/alpha_r "
    "working pressure angles, theta planet angles."
)


def add_parameter_options(p) -> None:
    add_reducer_options(p, "a reducer design file (or a preset design's name): its lumped "
                        "model; not with --preset")
    p.add_argument("--params", type=Path, metavar="FILE.toml",
                   help="TOML file of parameter keys (may name its own preset)")
    p.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                   help=PARAMETER_HELP)
    p.add_argument("--method", default="jacobi", choices=METHODS)
    p.add_argument("--json", action="store_true", help="machine-readable output")


def parameters(args):
    """The lumped parameters the options describe (``--design`` or ``--preset``)."""
    reducer_name(args)
    if args.design is None:
        if args.preset is not None and args.params is not None:
            named = read_toml_file(args.params).get("preset", args.preset)
            if named != args.preset:
                raise ValueError(f"--preset {args.preset} and --params {args.params} (preset = "
                                 f"{named!r}) name different presets; give one of them")
        return load_parameters(args.preset or DEFAULT_PRESET, args.params, parse_set(args.set))
    from hubvib.reducer.consistency import check_consistent
    from hubvib.reducer.stages import lumped_parameters
    from hubvib.runtime.params_input import apply_overrides

    from .design import design_from_argument

    if args.params is not None:
        raise ValueError("--design and --params both give the reducer; use one")
    design = design_from_argument(args.design)
    params = apply_overrides(lumped_parameters(design), parse_set(args.set))
    check_consistent(design, params, "--set", ValueError)
    return params


def stiffness_methods(args) -> dict[str, str]:
    """How each stiffness of ``parameters(args)`` is obtained, named as ``hubvib design
    check`` names it: the design's method (geometry, ISO 6336-1, bearings) or
    ``design.lumped``, then ``--params FILE`` and ``--set`` where they replace it.  A
    ``--params`` file that names its own preset takes that preset's design."""
    from hubvib.reducer.stages import DESIGN_TABLE, derived_field_methods
    from hubvib.design.fields import STIFFNESS_FIELDS
    from .design import design_from_argument

    file_values = {} if args.params is None else read_toml_file(args.params)
    name = file_values.pop("preset", None) or reducer_name(args)
    design = design_from_argument(name)
    methods = derived_field_methods(design) | dict.fromkeys(design.lumped_fields, DESIGN_TABLE)
    methods.update(dict.fromkeys(file_values, "--params"))
    methods.update(dict.fromkeys(parse_set(args.set), "--set"))
    return {k: methods.get(k, "model default") for k in STIFFNESS_FIELDS}
