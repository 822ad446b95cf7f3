"""The figures of wsntrack, for scripts and notebooks: the same code as the commands.

  run_plots(RUN_DIR, out=None, image_format="png")      what `wsntrack run` writes into plots/: the
                                                         tracks on the field, cardinality, OSPA, ...
  animation(RUN_DIR, out=None, animate_format="gif")     `wsntrack replay`: one frame per tick
  sweep_plots(SWEEP_DIR, out=None, plot_format="png", x=None)
                                                         a finished sweep's plots drawn again from its
                                                         summary.csv (nothing is run): as PDF for a
                                                         paper, or against another measured x

Each returns the files it wrote; a bad input raises PlotError with the tool's message (also on
stderr) and its exit status."""

import io
import sys
from contextlib import redirect_stderr
from pathlib import Path


class PlotError(RuntimeError):
    """A figure that could not be drawn: `status` is the tool's exit status, str() its message."""

    def __init__(self, status, message):
        super().__init__(message)
        self.status = status


def _run_tool(argv):
    from .plots.cli import main
    captured = io.StringIO()
    with redirect_stderr(captured):
        try:
            status = main(argv)
        except SystemExit as stop:  # argparse's error
            status = stop.code
    sys.stderr.write(captured.getvalue())
    if status:
        raise PlotError(status, captured.getvalue().strip() or f"plot_run.py exited {status}")


def run_plots(run_dir, out=None, image_format="png"):
    """The plots of a finished run (png, svg or pdf) into `out` (default RUN_DIR/plots); their paths."""
    directory = Path(out) if out else Path(run_dir) / "plots"
    _run_tool([str(run_dir), "--format", image_format] + (["--out", str(out)] if out else []))
    return sorted(directory.glob(f"*.{image_format}"))


def animation(run_dir, out=None, animate_format="gif", quiet=True):
    """The replay animation of a run (gif, mp4 or html) at `out` (default RUN_DIR/plots/replay.FORMAT);
    its path."""
    target = Path(out) if out else Path(run_dir) / "plots" / f"replay.{animate_format}"
    _run_tool([str(run_dir), "--animate", "--animate-format", animate_format, "--out", str(target)] +
              (["--quiet"] if quiet else []))
    return target


def sweep_plots(sweep_dir, out=None, plot_format="png", x=None):
    """A finished sweep's plots again (png, svg or pdf), against the measured metric `x` if given
    (one the sweep tabulated); into `out` nothing is deleted, only files of the plots' names written."""
    from .rundir import InputError
    from .sweep.results import redraw_plots
    try:
        return redraw_plots(sweep_dir, out, plot_format, x)
    except (InputError, ValueError) as error:
        raise PlotError(2, str(error)) from None
