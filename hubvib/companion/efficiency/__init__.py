"""Efficiency of the torus-screw / roller reducer (seed companion analysis)."""
