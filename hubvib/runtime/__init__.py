"""How the app runs work: engines (local processes or Dask), the worker pool, progress
lines, the FE case cache and its check, and the lumped parameter input."""
