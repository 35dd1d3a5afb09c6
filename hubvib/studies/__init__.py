"""What a scene or a command runs: the lumped sweep (``sweep``), the plane crack study
(``crack_study``), the solid crack growth (``crack_growth``), the FE crack cases they share
(``crack_sweep``), the scene file that selects them (``scene``), and a design's stiffness
table (``stiffness``, what ``hubvib stiffness`` prints)."""
