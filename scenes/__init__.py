"""Scene files shipped with hubvib: ``hubvib scenes`` lists them, ``hubvib run NAME`` runs one."""
