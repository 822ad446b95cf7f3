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


def new_figure(mpl, width, height, left, right, bottom, top):
    """A figure of width x height inches whose axes leave the given margins (inches). Margins are
    set by hand: bbox_inches="tight" would draw every figure twice, doubling the plotting time."""
    fig = mpl.figure.Figure(figsize=(width, height))
    ax = fig.add_axes([left / width, bottom / height, 1 - (left + right) / width, 1 - (bottom + top) / height])
    return fig, ax
