"""Off-screen pictures: mode shapes of the lumped model (``modes``, the still picture
``mode_figure``), FE fields of the ring (``fe``), the elastic ring's coupled modes
(``coupled``) and its figures beside the rigid ring (``elastic_figures``), the crack path
(``crack_path``), figure captions (``captions``), the HTML report (``html``) and the render
cache (``cache``).  pyvista is imported where it is
used; every name below is imported on first use (PEP 562)."""
from typing import TYPE_CHECKING

from hubvib.foundation.lazy import lazy_face

if TYPE_CHECKING:
    from .cache import cached_render
    from .captions import caption
    from .path_figure import render_path
    from .fe import RingFields, render_fe, ring_fields
    from .html import write_html_report
    from .modes import render_mode, render_modes
    from .coupled import render_coupled_modes, render_watched_modes
    from .elastic_figures import both_models_figure, crack_states_figure, open_length_figure

__all__ = [
    "render_mode", "render_modes", "RingFields", "ring_fields", "render_fe", "render_path",
    "caption", "write_html_report", "cached_render", "render_coupled_modes",
    "render_watched_modes", "both_models_figure", "crack_states_figure", "open_length_figure",
]
__getattr__, __dir__ = lazy_face(__name__, __file__, __all__)
