"""scikit-fem stiffness extraction (stage 2 of the chain)."""
