"""Names of the lumped model's fields, shared by a design's ``[design.lumped]`` table and
``hubvib.lumped.PlanetaryParameters`` (one source; SI units: N/m, kg, m)."""

#: springs [N/m]
STIFFNESS_FIELDS = ("c_sp", "c_rp", "c_p", "c_c", "c_r", "c_s", "c_su", "c_cu", "c_ru")
#: masses [kg] and reduced masses J / r_b^2 [kg]
MASS_FIELDS = ("m_s", "m_c", "m_r", "m_p", "mu_s", "mu_c", "mu_r", "mu_p")
#: base diameters and the carrier's planet-centre diameter [m]
DIAMETER_FIELDS = ("d_s", "d_c", "d_r", "d_p")
