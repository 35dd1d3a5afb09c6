"""``hubvib`` command line.  ``main(argv)`` returns the exit code (testable in-process).

Exit codes: 0 done; 1 a check failed (``validate``, ``stability``); 2 bad input, or
output that cannot be written (one line ``hubvib: error: ...`` naming the flag,
key or file); 130 interrupted (Ctrl-C: one line ``hubvib: interrupted``); 141
standard output closed early (``hubvib spectrum | head -1``: quiet, like a
program stopped by SIGPIPE).  No traceback for any of these.
"""
from __future__ import annotations

import argparse
import os
import sys

EXIT_ERROR = 2
EXIT_INTERRUPTED = 130
EXIT_BROKEN_PIPE = 141  # 128 + SIGPIPE, what a shell reports for `yes | head -1`


def main(argv: list[str] | None = None) -> int:
    # everything, imports included, inside the try: Ctrl-C at any moment is one line
    try:
        from hubvib.meshing.session import MeshingError

        args = _parser().parse_args(argv)
        try:
            code = args.handler(args)
            sys.stdout.flush()  # a closed pipe shows here, not in the interpreter's exit
            return code
        except (ValueError, MeshingError) as exc:  # ParameterError, SceneError, CacheError...
            return _error(exc)
        except ModuleNotFoundError as exc:
            return _error(f"{exc.name} is not installed; this command needs the FE extras: "
                          "pip install \"hubvib[fem]\"")
    except KeyboardInterrupt:
        _say("hubvib: interrupted")
        return EXIT_INTERRUPTED
    except BrokenPipeError:
        _silence_stdout()
        return EXIT_BROKEN_PIPE
    except OSError as exc:  # hubvib.foundation.output.OutputError names the file; others say what failed
        if type(exc).__str__ is not OSError.__str__:
            return _error(exc)
        where = f"{exc.filename!r}: " if exc.filename else ""
        return _error(f"{where}{exc.strerror or exc}")


def _error(message) -> int:
    _say(f"hubvib: error: {message}")
    return EXIT_ERROR


def _say(line: str) -> None:
    try:
        print(line, file=sys.stderr, flush=True)
    except (OSError, ValueError):
        pass  # stderr itself is gone


def _silence_stdout() -> None:
    """Point stdout at /dev/null so that the interpreter's final flush cannot fail (the
    recipe of the Python docs, ``signal`` module, "Note on SIGPIPE")."""
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        os.close(devnull)
    except (OSError, ValueError, AttributeError):
        pass  # not a real file (captured in-process): nothing to flush later


def _parser() -> argparse.ArgumentParser:
    from .commands import command_modules

    parser = argparse.ArgumentParser(
        prog="hubvib", description="Natural-frequency shifts of planetary hub reducers with a "
        "cracked ring gear.", epilog="exit codes: 0 done, 1 a check failed (validate, "
        "stability), 2 bad input or output that cannot be written, 130 interrupted, 141 "
        "standard output closed early")
    sub = parser.add_subparsers(dest="command", required=True)
    for module in command_modules():
        module.add_parser(sub)
    return parser


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
