"""Companion analyses of neighbouring planetary transmissions (the seed papers)."""
