"""``hubvib`` command line.  ``main(argv)`` returns the exit code (testable in-process).

Exit codes: 0 done; 1 a check failed (``validate``, ``stability``); 2 bad input, or
output that cannot be written (one line ``hubvib: error: ...`` naming the flag,
key or file); 130 interrupted (Ctrl-C: one line ``hubvib: interrupted``); 141
standard output closed early (``hubvib spectrum | head -1``, ``--help`` too) or
from the start (``>&-``): quiet, like a program stopped by SIGPIPE; 143 terminated
(SIGTERM: one line ``hubvib: terminated``).  No traceback for any of these.  A signal
that comes before the interpreter has started ``hubvib`` ends it by its default action
(nothing was started that needs cleaning up; a shell reports 143 or 130 the same).

Run as the program, SIGTERM unwinds like Ctrl-C (``Terminated``), so that every
``finally`` runs: the output stage folders, the output lock, the worker pool and the
temporary files and folders in the cache are removed on the way out (what ``kill -9``
leaves, the next run removes: ``hubvib.runtime.cache_check.sweep_cache``).  A SIGTERM or
SIGINT repeated within ``REPEAT_SECONDS`` of the first is the same request and changes
nothing (``timeout`` sends SIGTERM to the command and then to its whole process group,
and a terminal's Ctrl-C is often pressed twice: a repeat that ended the process at once
left the lock, the stage and the pool's semaphores behind); one that comes later, while
the clean-up still runs, ends the process at once.  Once the outcome is decided and its
line printed, SIGTERM and SIGINT are ignored while the interpreter exits.
"""
from __future__ import annotations

import argparse
import ctypes
import errno
import json
import os
import signal
import sys
import time

EXIT_ERROR = 2
EXIT_INTERRUPTED = 130
EXIT_BROKEN_PIPE = 141  # 128 + SIGPIPE, what a shell reports for `yes | head -1`
EXIT_TERMINATED = 143  # 128 + SIGTERM


#: a SIGTERM or SIGINT this soon after the first is the same request [s]
REPEAT_SECONDS = 2.0


class Terminated(KeyboardInterrupt):
    """SIGTERM, raised in the main thread (see the module docstring); a KeyboardInterrupt,
    so that whatever stops cleanly on Ctrl-C (worker pools, locks, stages) does so here."""


class _Stop:
    """When the first SIGTERM or SIGINT came (``time.monotonic``), and which it was."""

    first: float | None = None
    signum: int | None = None


def _on_stop_signal(signum, frame):
    """The first SIGTERM raises ``Terminated``, the first SIGINT ``KeyboardInterrupt``;
    a repeat within ``REPEAT_SECONDS`` is ignored; a later one ends the process at once
    (the signal's default action)."""
    now = time.monotonic()
    if _Stop.first is None:
        _Stop.first, _Stop.signum = now, signum
        raise Terminated if signum == signal.SIGTERM else KeyboardInterrupt
    if now - _Stop.first < REPEAT_SECONDS:
        return
    signal.signal(signum, signal.SIG_DFL)
    os.kill(os.getpid(), signum)


def _terminate_by_exception() -> None:
    """SIGTERM raises ``Terminated`` and SIGINT ``KeyboardInterrupt`` in this process, once
    (main thread only; see the module docstring)."""
    _Stop.first = _Stop.signum = None
    try:
        signal.signal(signal.SIGTERM, _on_stop_signal)
        if signal.getsignal(signal.SIGINT) is signal.default_int_handler:
            signal.signal(signal.SIGINT, _on_stop_signal)
    except ValueError:  # not the main thread: the defaults stay
        pass


def main(argv: list[str] | None = None) -> int:
    """Run the command line ``argv`` (default ``sys.argv[1:]``); return the exit code.

    Called as the program (``argv`` None), a Ctrl-C after the last point where Python
    could still turn it into ``KeyboardInterrupt`` here is ignored: it used to escape
    ``main`` (1 run in 25 killed by the signal instead of exit 130).
    """
    _Stop.first = _Stop.signum = None  # this call's stop only
    if argv is None:
        _terminate_by_exception()
    try:
        try:
            return _main(argv)
        finally:
            if argv is None:
                _ignore_interrupts()
    except Terminated:
        _say("hubvib: terminated")
        return EXIT_TERMINATED
    except KeyboardInterrupt:  # came while main was returning: still one line, exit 130
        if argv is None:
            _ignore_interrupts()
        _say("hubvib: interrupted")
        return EXIT_INTERRUPTED
    except Exception:
        if _Stop.signum is None:
            raise
        return _stopped()


def _stopped() -> int:
    """The one line and the exit code of the stop signal this process received: the
    failure it caused (an extension module's import turns the exception raised inside it
    into an ``ImportError`` that no longer names it) is its consequence, not the outcome."""
    if _Stop.signum == signal.SIGTERM:
        _say("hubvib: terminated")
        return EXIT_TERMINATED
    _say("hubvib: interrupted")
    return EXIT_INTERRUPTED


def _ignore_interrupts() -> None:
    """From here on SIGINT and SIGTERM change nothing (the process is about to exit).

    Also clears CPython's "unhandled KeyboardInterrupt" flag: a Ctrl-C that ran through
    code an extension module runs with ``PyRun_*`` while being imported (then caught
    here) leaves it set, and ``python -m hubvib.cli`` then died by SIGINT after exit 130
    was chosen (13 of 40 interrupts in the first second); an empty ``PyRun_*`` resets it.
    """
    try:
        signal.signal(signal.SIGINT, signal.SIG_IGN)
        # the outcome is decided (done, failed or stopped) and its line printed: a SIGTERM
        # now changes nothing either (the interpreter's last teardown puts the default
        # action back in place of a Python handler, not of this)
        signal.signal(signal.SIGTERM, signal.SIG_IGN)
    except ValueError:  # not the main thread: nothing to do
        return
    try:
        ctypes.pythonapi.PyRun_SimpleString(b"")
    except (AttributeError, OSError):  # not CPython
        pass


def _main(argv: list[str] | None) -> int:
    # everything, imports included, inside the try: Ctrl-C at any moment is one line
    as_json = False  # with --json an error is also a JSON object on stdout
    try:
        from hubvib.meshing.session import MeshingError

        try:
            args = _parse(sys.argv[1:] if argv is None else list(argv))
        except SystemExit as stop:
            # argparse exits: 0 after --help, printed on stdout (on stderr when there is
            # none), 2 after a usage error, printed on stderr; a closed pipe shows here
            if stop.code == 0 and sys.stdout is not None:
                sys.stdout.flush()
            raise
        as_json = bool(getattr(args, "json", False))
        try:
            code = args.handler(args)
            _flush_stdout()
            return code
        except (ValueError, MeshingError) as exc:  # ParameterError, SceneError, CacheError...
            return _error(exc, as_json)
        except ModuleNotFoundError as exc:
            return _error(f"{exc.name} is not installed; this command needs the FE extras: "
                          "pip install \"hubvib[fem]\"", as_json)
    except Terminated:
        _say("hubvib: terminated")
        return EXIT_TERMINATED
    except KeyboardInterrupt:
        _say("hubvib: interrupted")
        return EXIT_INTERRUPTED
    except BrokenPipeError:
        _silence_stdout()
        return EXIT_BROKEN_PIPE
    except OSError as exc:  # hubvib.foundation.output.OutputError names the file; others say what failed
        if type(exc).__str__ is not OSError.__str__:
            return _error(exc, as_json)
        where = f"{exc.filename!r}: " if exc.filename else ""
        return _error(f"{where}{exc.strerror or exc}", as_json)


def _flush_stdout() -> None:
    """Flush what the command printed: a closed pipe shows here (``BrokenPipeError``), not
    in the interpreter's exit.  No standard output at all (started with it closed, ``>&-``:
    Python's ``sys.stdout`` is None and every print was dropped) counts as one."""
    if sys.stdout is None:
        raise BrokenPipeError(errno.EPIPE, "standard output is closed")
    sys.stdout.flush()


def _error(message, as_json: bool = False) -> int:
    """One line ``hubvib: error: ...`` on stderr; with ``--json`` also
    ``{"error": ..., "exit_code": 2}`` on stdout (a script reading stdout sees why).
    After a stop signal the error is its consequence: the stop's line instead."""
    if _Stop.signum is not None:
        return _stopped()
    _say(f"hubvib: error: {message}")
    if as_json:
        try:
            print(json.dumps({"error": str(message), "exit_code": EXIT_ERROR}), flush=True)
        except (OSError, ValueError):
            _silence_stdout()  # stdout itself is gone: the interpreter's last flush would fail
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


class _Retry(Exception):
    """A usage error met by the one-command parser: parse again with every command."""


class _Parser(argparse.ArgumentParser):
    """argparse with a usage error on one line, ``hubvib CMD: error: ...`` naming the flag
    (argparse's own text: the flag, the value, the choices), exit 2; the usage is
    ``hubvib CMD --help``."""

    def error(self, message):
        self.exit(2, f"{self.prog}: error: {message} ({self.prog} --help lists the flags)\n")


class _OneCommandParser(_Parser):
    """The parser of a command line that names its command: that command's module only
    (the others' imports cost a second or more).  Its usage errors are raised as
    :class:`_Retry` while it parses, so that the whole parser reports them with the
    same text as before; its help is the command's own, unchanged."""

    parsing = False

    def error(self, message):
        if _OneCommandParser.parsing:
            raise _Retry(message)
        super().error(message)


def _parse(argv: list[str]) -> argparse.Namespace:
    """``argv`` parsed with its command's module only when its first word names one, else
    (and on any usage error) with every command."""
    if argv and not argv[0].startswith("-"):
        _OneCommandParser.parsing = True
        try:
            return _parser(argv[0]).parse_args(argv)
        except _Retry:
            pass
        finally:
            _OneCommandParser.parsing = False
    return _parser().parse_args(argv)


def _parser(command: str | None = None) -> argparse.ArgumentParser:
    """The parser of every command, or of ``command`` only (a :class:`_OneCommandParser`;
    every command when no module is named so)."""
    from .commands import command_modules

    parser = (_OneCommandParser if command else _Parser)(
        prog="hubvib", description="Natural-frequency shifts of planetary hub reducers with a "
        "cracked ring gear.", epilog="exit codes: 0 done, 1 a check failed (validate, "
        "stability), 2 bad input or output that cannot be written, 130 interrupted, 141 "
        "standard output closed early, 143 terminated")
    sub = parser.add_subparsers(dest="command", required=True)
    for module in command_modules(command):
        module.add_parser(sub)
    return parser


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
