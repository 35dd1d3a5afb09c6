"""Checks of what a picture claims: every series named, colours told apart, series not
hidden, no text clipped or overlapping, labels on their own axes (matplotlib), and the
colour bar of a pyvista render readable against what lies behind it.

Each check returns what it found wrong (an empty list when the picture is right), so a
failing test names the offending text, series or colour.
"""
from __future__ import annotations

import weakref
from contextlib import contextmanager

import numpy as np

#: WCAG 2 minimum contrast ratio of normal text against its background
READABLE = 4.5


# --- matplotlib ----------------------------------------------------------------------------

#: figure -> (text, window extent) of every text its one checked drawing drew
_SETTLED = weakref.WeakKeyDictionary()


@contextmanager
def _recording_texts():
    """Collect every Text artist that draws something while the block runs."""
    from matplotlib.text import Text

    drawn, original = [], Text.draw

    def draw(self, renderer):
        if self.get_visible() and self.get_text().strip():
            drawn.append(self)
        return original(self, renderer)

    Text.draw = draw
    try:
        yield drawn
    finally:
        Text.draw = original


def settle(fig):
    """Draw ``fig`` once, note every text it draws and keep its layout from then on (the
    checks draw it again without laying it out anew each time); returns its renderer."""
    if fig not in _SETTLED:
        with _recording_texts() as drawn:
            fig.canvas.draw()
        fig.set_layout_engine("none")
        renderer = fig.canvas.get_renderer()
        _SETTLED[fig] = [(t, t.get_window_extent(renderer)) for t in dict.fromkeys(drawn)]
    return fig.canvas.get_renderer()


def drawn_texts(fig) -> list:
    """(text, window extent) of every non-empty text the figure draws (tick labels
    outside the view and empty labels are not drawn and so not listed)."""
    settle(fig)
    return _SETTLED[fig]


def clipped_texts(fig, tolerance: float = 0.5) -> list[str]:
    """Texts reaching outside the figure (in pixels; saving with a tight bounding box
    would hide this by growing the picture around them)."""
    box = fig.bbox
    return [repr(t.get_text()) for t, e in drawn_texts(fig)
            if e.x0 < box.x0 - tolerance or e.y0 < box.y0 - tolerance
            or e.x1 > box.x1 + tolerance or e.y1 > box.y1 + tolerance]


def overlapping_texts(fig, shrink: float = 1.0) -> list[tuple[str, str]]:
    """Pairs of drawn texts whose extents (each shrunk by ``shrink`` px) overlap."""
    texts = drawn_texts(fig)
    found = []
    for i, (a, ea) in enumerate(texts):
        for b, eb in texts[i + 1:]:
            if (min(ea.x1, eb.x1) - max(ea.x0, eb.x0) > 2 * shrink
                    and min(ea.y1, eb.y1) - max(ea.y0, eb.y0) > 2 * shrink):
                found.append((a.get_text(), b.get_text()))
    return found


def data_axes(fig) -> list:
    """The axes that draw data (lines, collections or patches besides their frame)."""
    return [ax for ax in fig.axes if ax.axison and (ax.lines or ax.collections)]


def misplaced_axis_labels(fig) -> list[str]:
    """Axes that draw data without an x or y label of their own (a shared label of the
    figure, ``supxlabel``/``supylabel``, counts), and titles or axis labels lying
    nearer to another data axes than to their own."""
    renderer = settle(fig)
    panels = data_axes(fig)
    shared = {"x": fig.get_supxlabel().strip(), "y": fig.get_supylabel().strip()}
    wrong = []

    def gap(extent, box):
        dx = max(box.x0 - extent.x1, extent.x0 - box.x1, 0.0)
        dy = max(box.y0 - extent.y1, extent.y0 - box.y1, 0.0)
        return float(np.hypot(dx, dy))

    for ax in panels:
        siblings = {"x": ax.get_shared_x_axes().get_siblings(ax),
                    "y": ax.get_shared_y_axes().get_siblings(ax)}
        for which in ("x", "y"):
            # a panel stacked on others sharing its axis may leave the label to them
            labelled = any(getattr(other, f"get_{which}label")().strip()
                           for other in siblings[which])
            if not labelled and not shared[which]:
                wrong.append(f"panel {ax.get_title()!r}: no {which} label")
        for text in (ax.title, ax.xaxis.label, ax.yaxis.label):
            if not text.get_text().strip():
                continue
            extent = text.get_window_extent(renderer)
            mine = gap(extent, ax.get_window_extent(renderer))
            for other in panels:
                if other is not ax and gap(extent, other.get_window_extent(renderer)) < mine:
                    wrong.append(f"{text.get_text()!r} lies nearer to the panel "
                                 f"{other.get_title()!r} than to its own")
    return wrong


def _legend_texts(fig) -> set[str]:
    legends = list(fig.legends) + [ax.get_legend() for ax in fig.axes]
    return {t.get_text() for legend in legends if legend is not None
            for t in legend.get_texts()}


def series(fig) -> list:
    """The data series of the figure: every visible line of a data axes."""
    return [line for ax in data_axes(fig) for line in ax.get_lines() if line.get_visible()]


def unnamed_series(fig) -> list[str]:
    """Series without an entry in a legend of the figure (auto labels ``_child3`` and
    labels no legend shows)."""
    named = _legend_texts(fig)
    return [f"{line.get_label()!r} in panel {line.axes.get_title()!r}"
            for line in series(fig) if line.get_label() not in named]


def covered_by_legends(fig) -> list[str]:
    """Series with data points under a legend box (a legend drawn over the data)."""
    renderer = settle(fig)
    boxes = [legend.get_window_extent(renderer) for legend in
             list(fig.legends) + [ax.get_legend() for ax in fig.axes] if legend is not None]
    covered = []
    for line in series(fig):
        points = line.get_transform().transform(line.get_xydata())
        points = points[np.all(np.isfinite(points), axis=1)]
        inside = line.axes.get_window_extent(renderer)
        points = points[(points[:, 0] >= inside.x0) & (points[:, 0] <= inside.x1)
                        & (points[:, 1] >= inside.y0) & (points[:, 1] <= inside.y1)]
        for box in boxes:
            under = ((points[:, 0] > box.x0 + 1) & (points[:, 0] < box.x1 - 1)
                     & (points[:, 1] > box.y0 + 1) & (points[:, 1] < box.y1 - 1))
            if under.any():
                covered.append(f"{line.get_label()!r}: {int(under.sum())} point(s) under a "
                               "legend")
    return covered


def shared_colours(lines) -> list[tuple[str, str]]:
    """Pairs of ``lines`` with different labels drawn in the same colour."""
    from matplotlib.colors import to_rgba

    first = {}
    clashes = []
    for line in lines:
        colour = to_rgba(line.get_color())
        label = line.get_label()
        if colour in first and first[colour] != label:
            clashes.append((first[colour], label))
        first.setdefault(colour, label)
    return clashes


def squashed_series(fig, lines, fraction: float = 0.05) -> list[str]:
    """Of ``lines``, those whose values vary but span less than ``fraction`` of their
    panel's height (drawn on a scale set by a much larger series)."""
    settle(fig)
    squashed = []
    for line in lines:
        ax = line.axes
        y = np.asarray(line.get_ydata(), dtype=float)
        y = y[np.isfinite(y)]
        if y.size < 2 or np.ptp(y) <= 1e-12 * np.abs(y).max():
            continue
        x = np.full(y.size, np.mean(ax.get_xlim()))
        shown = ax.transData.transform(np.column_stack([x, y]))[:, 1]
        height = ax.get_window_extent().height
        if np.ptp(shown) < fraction * height:
            squashed.append(f"{line.get_label()!r}: {np.ptp(shown) / height:.1%} of its "
                            "panel's height")
    return squashed


def _pixels(ax) -> np.ndarray:
    """The canvas with only ``ax`` drawn (RGB)."""
    renderer = ax.figure.canvas.get_renderer()
    renderer.clear()
    ax.draw(renderer)
    return np.asarray(renderer.buffer_rgba())[..., :3].astype(np.int16)


def hidden_series(fig, visible: float = 0.6, change: int = 48) -> list[str]:
    """Series of which less than ``visible`` of the pixels they draw alone stay visible
    with everything else of their panel drawn (covered by what is drawn over them): a
    pixel shows the series where removing it changes a colour channel by more than
    ``change`` of 255 (anti-aliased edges peeking out from under another line do not
    count).  Each panel is drawn on its own (legends over data: ``covered_by_legends``)."""
    settle(fig)
    hidden = []
    lines = series(fig)
    for ax in dict.fromkeys(line.axes for line in lines):
        everything = _pixels(ax)
        drawn = [a for a in (*ax.lines, *ax.collections, *ax.patches, *ax.texts)
                 if a.get_visible()]
        for artist in drawn:
            artist.set_visible(False)
        blank = _pixels(ax)  # the panel without any of them
        for line in (line for line in lines if line.axes is ax):
            line.set_visible(True)
            alone = _pixels(ax)
            line.set_visible(False)
            for artist in drawn:
                artist.set_visible(artist is not line)
            without = _pixels(ax)
            for artist in drawn:
                artist.set_visible(False)
            own = (np.abs(alone - blank).max(axis=2) > change).sum()
            shown = (np.abs(everything - without).max(axis=2) > change).sum()
            if own and shown < visible * own:
                hidden.append(f"{line.get_label()!r}: {shown / own:.0%} visible")
        for artist in drawn:
            artist.set_visible(True)
    return hidden


# --- pyvista ------------------------------------------------------------------------------

def relative_luminance(rgb) -> np.ndarray:
    """WCAG 2 relative luminance of sRGB colours in 0..1 (last axis: r, g, b)."""
    c = np.asarray(rgb, dtype=float)
    linear = np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)
    return linear @ np.array([0.2126, 0.7152, 0.0722])


def contrast_ratio(a, b) -> np.ndarray:
    """WCAG 2 contrast ratio of colours ``a`` and ``b`` (sRGB in 0..1), 1..21."""
    la, lb = relative_luminance(a), relative_luminance(b)
    return (np.maximum(la, lb) + 0.05) / (np.minimum(la, lb) + 0.05)


def _screenshot(plotter) -> np.ndarray:
    plotter.render()
    return plotter.screenshot(None, return_img=True)[..., :3].astype(int)


def scalar_bar_texts(plotter) -> list[dict]:
    """Per colour bar of ``plotter`` (drawn, not yet saved): the pixels of its title and
    of its tick labels (where the picture changes when the text is made transparent),
    the picture without either text, and both text colours.  The layout does not move:
    only the texts' opacity changes, and it is restored."""
    plotter.suppress_rendering = False
    found = []
    for name, bar in plotter.scalar_bars.items():
        title, labels = bar.GetTitleTextProperty(), bar.GetLabelTextProperty()
        opacity = title.GetOpacity(), labels.GetOpacity()
        shots = {}
        for key, (t, s) in {"both": (1, 1), "labels": (0, 1), "title": (1, 0),
                            "none": (0, 0)}.items():
            title.SetOpacity(t * opacity[0])
            labels.SetOpacity(s * opacity[1])
            shots[key] = _screenshot(plotter)
        title.SetOpacity(opacity[0])
        labels.SetOpacity(opacity[1])
        found.append({"name": name,
                      "title": np.any(shots["both"] != shots["labels"], axis=2),
                      "labels": np.any(shots["both"] != shots["title"], axis=2),
                      "background": shots["none"] / 255.0,
                      "title_colour": np.array(title.GetColor()),
                      "label_colour": np.array(labels.GetColor())})
    return found


def _grown(mask: np.ndarray, pixels: int = 1) -> np.ndarray:
    out = mask.copy()
    for _ in range(pixels):
        out[1:] |= out[:-1].copy()
        out[:-1] |= out[1:].copy()
        out[:, 1:] |= out[:, :-1].copy()
        out[:, :-1] |= out[:, 1:].copy()
    return out


def unreadable_bar_text(bars, ratio: float = READABLE) -> list[str]:
    """Of ``bars`` (:func:`scalar_bar_texts`), the texts whose colour has less than
    ``ratio`` contrast against the picture behind them (every pixel under a glyph and
    one pixel around it)."""
    wrong = []
    for bar in bars:
        for part in ("title", "labels"):
            mask = bar[part]
            if not mask.any():
                wrong.append(f"{bar['name']!r}: no {part} drawn")
                continue
            colour = bar["title_colour" if part == "title" else "label_colour"]
            behind = bar["background"][_grown(mask)]
            worst = float(contrast_ratio(colour, behind).min())
            if worst < ratio:
                wrong.append(f"{bar['name']!r} {part}: contrast {worst:.2f} < {ratio}")
    return wrong


def bar_title_over_labels(bars) -> list[str]:
    """Of ``bars`` (:func:`scalar_bar_texts`), those whose title's bounding box holds
    pixels of a tick label."""
    wrong = []
    for bar in bars:
        rows, cols = np.nonzero(bar["title"])
        if rows.size == 0:
            continue
        box = bar["labels"][rows.min():rows.max() + 1, cols.min():cols.max() + 1]
        if box.any():
            wrong.append(f"{bar['name']!r}: {int(box.sum())} tick-label pixels inside the "
                         "title's box")
    return wrong
