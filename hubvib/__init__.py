"""hubvib: crack-induced natural-frequency shifts of planetary hub reducers."""
__version__ = "0.1.0"
