"""The torus-screw gear companion analysis (seed paper)."""
