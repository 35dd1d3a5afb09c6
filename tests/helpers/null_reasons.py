"""Every null a results file writes says why (the rule of ``results.json``): a null value
has a string ``<key>_reason`` beside it; a list holding nulls has one string
``<key>_reason`` beside it; a null in a mapping ``<key>`` (by record length, say) has its
string in the mapping ``<key>_reason`` beside it under the same key."""
from __future__ import annotations


def unexplained_nulls(payload, path: str = "") -> list[str]:
    """The paths of the nulls in ``payload`` (parsed JSON) that the rule leaves unexplained."""
    found = []
    if isinstance(payload, list):
        for i, item in enumerate(payload):
            found += unexplained_nulls(item, f"{path}[{i}]")
        return found
    if not isinstance(payload, dict):
        return found
    for key, value in payload.items():
        if key.endswith("_reason"):
            continue
        reason = payload.get(f"{key}_reason")
        where = f"{path}/{key}"
        if value is None:
            if not isinstance(reason, str):
                found.append(where)
        elif isinstance(value, list):
            if any(v is None for v in value) and not isinstance(reason, str):
                found.append(where + "[]")
            found += [p for i, v in enumerate(value) if isinstance(v, (dict, list))
                      for p in unexplained_nulls(v, f"{where}[{i}]")]
        elif isinstance(value, dict):
            reasons = reason if isinstance(reason, dict) else {}
            for k, v in value.items():
                if v is None and not k.endswith("_reason") and not isinstance(
                        value.get(f"{k}_reason"), str) and not isinstance(reasons.get(k), str):
                    found.append(f"{where}/{k}")
            found += [p for k, v in value.items() if isinstance(v, (dict, list))
                      for p in unexplained_nulls({k: v, f"{k}_reason": value.get(f"{k}_reason")},
                                                 where)]
    return found
