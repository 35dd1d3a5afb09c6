"""``hubvib`` command line.  ``main(argv)`` returns the exit code (testable in-process)."""
from __future__ import annotations

import argparse
import sys

from hubvib.lumped import ParameterError
from hubvib.meshing.session import MeshingError

from .commands import command_modules


def main(argv: list[str] | None = None) -> int:
    parser = _parser()
    args = parser.parse_args(argv)
    try:
        return args.handler(args)
    except (ParameterError, ValueError, MeshingError) as exc:
        print(f"hubvib: error: {exc}", file=sys.stderr)
        return 2
    except ModuleNotFoundError as exc:
        print(f"hubvib: error: {exc.name} is not installed; this command needs the FE extras: "
              f"pip install \"hubvib[fem]\"", file=sys.stderr)
        return 2


def _parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="hubvib", description=__doc__)
    sub = parser.add_subparsers(dest="command", required=True)
    for module in command_modules():
        module.add_parser(sub)
    return parser


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
