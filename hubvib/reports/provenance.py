"""What every results file carries: standard JSON numbers and the run's provenance."""
from __future__ import annotations

import datetime
import math
from importlib import metadata

__all__ = ["json_safe", "provenance"]


def json_safe(value):
    """JSON-safe: NaN and infinity become None (standard JSON)."""
    if isinstance(value, dict):
        return {k: json_safe(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [json_safe(v) for v in value]
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value


def provenance() -> dict:
    """hubvib version and the date of the run (UTC)."""
    try:
        version = metadata.version("hubvib")
    except metadata.PackageNotFoundError:
        from hubvib import __version__ as version
    return {"hubvib_version": version,
            "date": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")}

