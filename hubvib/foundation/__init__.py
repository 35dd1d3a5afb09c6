"""Shared leaves below every layer: atomic output (``output``), BLAS thread limits
(``blas``), the base of input errors (``errors``).  Standard library and numpy only; it
imports nothing else of hubvib."""
