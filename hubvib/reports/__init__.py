"""The study reports apart from their computation: ``report.md`` and its figures, the
results tables (CSV, ``results.json``) and their provenance, assembled once from typed
results and written once (SI inside; millimetres and hertz only in the written text)."""

__all__: list[str] = []
