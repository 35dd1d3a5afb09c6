"""Scripted checks of hubvib against published data, exact and high-precision references."""
