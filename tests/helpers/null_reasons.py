"""Every null a results file writes says why (the rule of ``results.json``): a null value
has a string ``<key>_reason`` beside it; a list holding nulls has one string
``<key>_reason`` beside it; a null in a mapping ``<key>`` (by record length, say) has its
string in the mapping ``<key>_reason`` beside it under the same key."""
from __future__ import annotations


def unexplained_nulls(payload, path: str = "", reasons: dict | None = None) -> list[str]:
    """The paths of the nulls in ``payload`` (parsed JSON) that the rule leaves unexplained;
    ``reasons``: the mapping of reasons that stands beside ``payload`` in its parent."""
    if isinstance(payload, list):
        return [p for i, item in enumerate(payload)
                for p in unexplained_nulls(item, f"{path}[{i}]")]
    if not isinstance(payload, dict):
        return []
    found = []
    for key, value in payload.items():
        if key.endswith("_reason"):
            continue
        reason = payload.get(f"{key}_reason", (reasons or {}).get(key))
        where = f"{path}/{key}"
        if value is None and not isinstance(reason, str):
            found.append(where)
        elif isinstance(value, list):
            if any(v is None for v in value) and not isinstance(reason, str):
                found.append(where + "[]")
            found += unexplained_nulls(value, where)
        elif isinstance(value, dict):
            found += unexplained_nulls(value, where, reason if isinstance(reason, dict) else None)
    return found


def stray_reasons(payload, path: str = "") -> list[str]:
    """The paths of the ``<key>_reason`` strings in ``payload`` (parsed JSON) standing beside
    a ``<key>`` that holds a value (no null to explain) or beside no ``<key>`` at all."""
    if isinstance(payload, list):
        return [p for i, item in enumerate(payload) for p in stray_reasons(item, f"{path}[{i}]")]
    if not isinstance(payload, dict):
        return []
    found = []
    for key, value in payload.items():
        if key.endswith("_reason") and isinstance(value, str):
            base = key[:-len("_reason")]
            held = payload.get(base, 0)
            if base not in payload or not (held is None or (
                    isinstance(held, list) and any(v is None for v in held))):
                found.append(f"{path}/{key}")
        elif isinstance(value, (dict, list)):
            found += stray_reasons(value, f"{path}/{key}")
    return found
