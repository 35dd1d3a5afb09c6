"""Helpers the tests share: synthetic FE rows, the demo design, crack scenes, the
independent energy reference, picture checks and the named-paths scanner."""
