"""matplotlib as the tools draw with it: the Agg backend without pyplot (its import and figure
manager are a third of the start-up and not needed to save a figure), and figures whose margins are
set in inches."""


def load_matplotlib(dpi, warm_up=False):
    """(matplotlib, None), or (None, the ImportError) when it cannot be imported. PNGs are saved at
    `dpi`, SVGs keep their text as text. `warm_up` loads the fonts and the renderer at once, while
    there is time to spare (plot_run.py --wait)."""
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.figure
        from matplotlib.backends.backend_agg import FigureCanvasAgg
    except ImportError as error:
        return None, error
    matplotlib.rcParams.update({"savefig.dpi": dpi, "svg.fonttype": "none", "font.size": 10})
    if warm_up:
        fig = matplotlib.figure.Figure(figsize=(1, 1))
        fig.add_subplot().set_title("warm-up")
        FigureCanvasAgg(fig).draw()
    return matplotlib, None


#: Set by plot_run.py --allow-incomplete to the reason a run is incomplete: every figure made while it is
#: set carries "INCOMPLETE RUN" across it and the reason at its foot, so that no copy of a plot of a
#: failed run can pass for a plot of a complete one.
INCOMPLETE_STAMP = {"reason": None}


def stamp_if_incomplete(fig):
    """Writes the INCOMPLETE RUN stamp on `fig` when a run incomplete is being drawn; returns fig."""
    reason = INCOMPLETE_STAMP["reason"]
    if reason:
        fig.text(0.5, 0.5, "INCOMPLETE RUN", ha="center", va="center", rotation=20, fontsize=40,
                 fontweight="bold", color="#c00000", alpha=0.35, zorder=1000)
        fig.text(0.5, 0.005, reason, ha="center", va="bottom", fontsize=8, color="#c00000",
                 wrap=True, zorder=1000)
    return fig


def new_figure(mpl, width, height, left, right, bottom, top):
    """A figure of width x height inches whose axes leave the given margins (inches). Margins are
    set by hand: bbox_inches="tight" would draw every figure twice, doubling the plotting time."""
    fig = stamp_if_incomplete(mpl.figure.Figure(figsize=(width, height)))
    ax = fig.add_axes([left / width, bottom / height, 1 - (left + right) / width, 1 - (bottom + top) / height])
    return fig, ax
