"""Run ``hubvib`` in-process and capture what it prints."""
import contextlib
import io
import json

from hubvib.cli import main


def run_cli(argv):
    """(exit code, stdout parsed as JSON with ``--json`` else the text, stderr text)."""
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        code = main(argv)
    text = out.getvalue()
    return code, (json.loads(text) if "--json" in argv and text.strip() else text), err.getvalue()
