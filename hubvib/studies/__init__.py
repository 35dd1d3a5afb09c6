"""What a scene runs: the lumped sweep (``sweep``), the plane crack study
(``crack_study``), the solid crack growth (``crack_growth``), the FE crack cases they share
(``crack_sweep``), and the scene file that selects them (``scene``)."""
