"""Off-screen pictures: mode shapes of the lumped model (``modes``), FE fields of the
ring (``fe``), and the render cache (``cache``).  pyvista is imported where it is used."""
