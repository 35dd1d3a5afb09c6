"""What a scene or a command runs: the study kinds (``study``: what a kind is, the registry
and the scene, a tagged union of the kinds; ``kinds`` registers the shipped ones), the
lumped sweep (``sweep``), the plane crack study (``crack_study``), the solid crack growth
(``crack_growth``), the ``[crack]`` table both crack kinds own (``crack_table``), the FE
crack cases they share (``crack_sweep``), the scene file (``scene``: the common tables),
and a design's stiffness table (``stiffness``, what ``hubvib stiffness`` prints)."""
