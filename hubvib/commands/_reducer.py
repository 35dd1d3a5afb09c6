"""``--preset`` and ``--design``: the options that name a command's reducer (one of them)."""
from __future__ import annotations

from hubvib.design import preset_names

#: the design preset of a command given neither --preset nor --design
DEFAULT_PRESET = "raba118"


def add_reducer_options(p, design_help: str = "a reducer design file (or a preset design's "
                        "name); not with --preset") -> None:
    """``--preset P`` and ``--design F``: one of them names the reducer (``reducer_name``)."""
    p.add_argument("--preset", default=None, choices=sorted(preset_names()),
                   help=f"a registered design preset (hubvib.design.PRESETS); default "
                   f"{DEFAULT_PRESET}; not with --design")
    p.add_argument("--design", metavar="FILE.toml", help=design_help)


def reducer_name(args) -> str:
    """The design file or preset name the options give: ``--design``, else ``--preset``
    (default ``DEFAULT_PRESET``); both given is refused, naming both."""
    if args.design is not None and args.preset is not None:
        raise ValueError(f"--preset {args.preset} and --design {args.design} both name the "
                         "reducer; give one of them")
    return args.design if args.design is not None else args.preset or DEFAULT_PRESET
