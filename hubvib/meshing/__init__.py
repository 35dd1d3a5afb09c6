"""Gmsh meshes of the ring gear and external gears (stage 1 of the chain)."""
