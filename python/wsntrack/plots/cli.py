"""plot_run.py's command line: the plots of a run directory (what 'wsntrack run' draws after every
run), or with --animate its replay animation (wsntrack.plots.replay)."""

import argparse
import sys
import time
from pathlib import Path

from ..figures import INCOMPLETE_STAMP, load_matplotlib
from ..rundir import InputError, ToolMissing, incomplete_reason, read_metrics_summary, read_per_tick, read_scenario, read_tracks, read_truth
from .charts import plot_cardinality, plot_detections, plot_ospa
from .inputs import few_observations, read_detections, read_sensors
from .replay import ANIMATION_DEFAULTS, ANIMATION_FORMATS, EXIT_BAD_INPUT, EXIT_TOOL_MISSING, animate_main
from .tracks_map import plot_tracks

DESCRIPTION = """\
Draws the plots of a wsntrack run directory (what 'wsntrack run' does after every run unless
--no-plot is given):

  tracks.FORMAT       the estimated global tracks (tracks.csv) against the true target paths
                      (truth.csv) on the sensor field: sensors, supernodes and their tracking
                      groups (the Voronoi cells of the supernodes: every sensor reports to its
                      nearest supernode), like Oh et al. Fig. 9 (right). One colour per
                      track, unless the tracks carry class evidence (some non-empty 'class'
                      cell in tracks.csv): then, as the ONERA paper draws them, a colour per
                      declared class, tick by tick (the segment between two ticks takes the
                      class of the later one), with a legend entry per class present:
                        wheeled_light  light blue     human   vermillion
                        wheeled_heavy  dark blue      group   orange
                        tracked        green          aerial  purple
                        no class yet (an empty cell): dark grey, dotted
                      Each track's id is then written at its last point (up to 30 tracks), and
                      the targets' labels give their true class (truth.csv's 'class').
                      (--animate keeps one colour per track.)
                      Typed sensors (a 'sensors.layout: list' whose entries set 'type', with
                      sensor_model kind field_sensors, ONERA Table I) are drawn with a marker
                      and colour per type, over their coverage: a faint sector of the sensor's
                      range and field of view centred on its heading (degrees counter-clockwise
                      from +x; a disc for a 360-degree field of view), the entry's 'range' and
                      'fov' else (left out or 0) sensor_model.<type>'s 'range' and 'fov_deg',
                      clipped to the region, beneath the paths and tracks; a legend entry per
                      type present gives its number of sensors, e.g. "camera (10)":
                        radar             wine, diamond      pir       rose, triangle down
                        acoustic_antenna  teal, triangle up  camera    indigo, plus
                        acoustic_beacon   olive, circle      magnetic  dark grey, square
                      A list entry without a type stays a plain grey dot, and any other layout
                      or sensor model draws its sensors as grey dots. (--animate draws every
                      sensor as a grey dot.)
  cardinality.FORMAT  K, the number of tracks, and K*, the number of targets, at every tick
                      (the terms of eps_K, Oh eq. 9)
  ospa.FORMAT         OSPA at every tick, with its cut-off c
  detections.FORMAT   (ADMAN sensors only) the number of targets the sensors detect at every
                      tick, inside r0 and in between, against the true number (the ADMAN
                      paper's Fig. 9), and the reports' localisation error (observations.csv)

With --animate it writes instead an animation of the run, one frame per tick (what 'wsntrack
replay RUN_DIR [OPTION]...' does): the sensor field with the supernodes and their tracking groups,
the reports delivered to the supernodes at the tick (observations.csv; late ones and false alarms
marked), the true targets with fading trails, the global tracks with their ids (S:N) and 2-sigma
position ellipses, and beside them the legend, K and K* and OSPA up to the tick. As
replay.FORMAT in RUN_DIR/plots unless --out names a file or another directory: a GIF (default),
an MP4 (H.264; needs ffmpeg) or an HTML page holding every frame and a player (no network needed).

Lengths are in the scenario's units (sensor separations when the grid spacing is 1), times in
ticks. Reads scenario.yaml, truth.csv, tracks.csv (columns found by name: runs from before the
label, covariance and class columns read too, and draw as they always did), observations.csv
(--animate), metrics_per_tick.csv (else metrics.json's metrics.ospa_per_tick) and sensors.csv when
present (else the sensor grid is computed from scenario.yaml). A 'class' cell that is not a class
name above (truth.csv: or 'unknown'), or a 'class_probability' outside [0, 1] or set without a
class, is malformed input; so is, for typed sensors, a type not listed above, a position or heading
that is not a number, a heading outside [-360, 360], an entry's 'range' outside [0, 1e6] or 'fov'
outside [0, 360], or a type's 'range' outside (0, 1e6] or 'fov_deg' outside (0, 360].

Only a complete run is drawn: one whose run.json says "status": "complete" (the launcher writes it
once every process exited 0 and every output exists). A failed, interrupted or still running run,
or one whose run.json has no status (wsntrack before 0.1.0's run status), is refused as malformed
input ("RUN_DIR: incomplete run (status failed: REASON)"); --allow-incomplete draws it anyway with
"INCOMPLETE RUN" and the reason written across every figure (and every frame of --animate).

Exit status: 0 on success; 1 when the video encoder (ffmpeg) fails; 2 for a bad command line, a
missing or malformed input file (reported as FILE:LINE: what was expected) or an output that cannot
be written; 3 when a tool is missing: PyYAML or matplotlib (or numpy or Pillow for --animate) for
this python, or ffmpeg on PATH for an MP4.
"""


def _parser():
    parser = argparse.ArgumentParser(prog="plot_run.py", description=DESCRIPTION,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("run_dir", metavar="RUN_DIR", help="a run directory written by 'wsntrack run'")
    parser.add_argument("--format", choices=("png", "svg", "pdf"), help="image format of the plots (default png)")
    parser.add_argument("--out", metavar="PATH",
                        help="where the plots go (a directory, default RUN_DIR/plots); with --animate a file "
                             "ending in .gif, .mp4 or .html, or a directory for replay.FORMAT (default "
                             "RUN_DIR/plots/replay.FORMAT)")
    parser.add_argument("--dpi", type=int, help="resolution of PNG files (default 150)")
    parser.add_argument("--allow-incomplete", action="store_true",
                        help="draw a run that is not complete (failed, interrupted, still running, or without a "
                             "status in run.json) anyway, every figure stamped INCOMPLETE RUN with the reason")
    parser.add_argument("--wait", action="store_true",
                        help="load matplotlib first, then wait for a line 'go' on stdin before reading RUN_DIR "
                             "(any other line, or the end of stdin: exit 0 without plotting). 'wsntrack run' "
                             "starts the script this way with the cluster, so that loading overlaps the run")
    group = parser.add_argument_group("animation ('wsntrack replay RUN_DIR [OPTION]...' runs plot_run.py "
                                      "--animate RUN_DIR [OPTION]...)")
    group.add_argument("--animate", action="store_true",
                       help="write an animation of the run instead of the plots: one frame per tick")
    group.add_argument("--animate-format", choices=ANIMATION_FORMATS,
                       help="gif (Pillow), mp4 (H.264, needs ffmpeg) or html (one self-contained page with a "
                            "player); default: the suffix of --out, else gif")
    group.add_argument("--fps", type=float, help=f"frames (ticks) per second (default {ANIMATION_DEFAULTS['fps']})")
    group.add_argument("--size", metavar="WxH",
                       help=f"frame size in pixels, rounded down to even numbers (default {ANIMATION_DEFAULTS['size']})")
    group.add_argument("--first", type=int, metavar="TICK", help="first tick drawn (default 1)")
    group.add_argument("--last", type=int, metavar="TICK", help="last tick drawn (default the run's last, T)")
    group.add_argument("--trail", type=int, metavar="TICKS",
                       help=f"length of the fading trails of targets and tracks (default {ANIMATION_DEFAULTS['trail']})")
    group.add_argument("--hold", type=float, metavar="SECONDS",
                       help=f"how long GIF and MP4 show the last frame before they end or loop "
                            f"(default {ANIMATION_DEFAULTS['hold']:g})")
    group.add_argument("--quiet", action="store_true", help="no progress on stderr")
    return parser


def main(argv):
    """plot_run.py ARGV: returns the exit status (0, 1 for a failed encoder, 2 for bad input or
    output, 3 for a missing tool)."""
    parser = _parser()
    args = parser.parse_args(argv)
    animation_options = ("animate_format", "fps", "size", "first", "last", "trail", "hold")
    if args.animate:
        for name, instead in (("format", "--animate-format"), ("dpi", "--size"), ("wait", None)):
            if getattr(args, name):
                parser.error(f"--{name} draws the still plots, not --animate"
                             + (f": use {instead}" if instead else ""))
        return _refuse_incomplete(args) or animate_main(parser, args)
    for name in animation_options + ("quiet",):
        if getattr(args, name) not in (None, False):
            parser.error(f"--{name.replace('_', '-')} needs --animate")
    args.format = args.format or "png"
    args.dpi = 150 if args.dpi is None else args.dpi
    if not 20 <= args.dpi <= 1200:
        parser.error("--dpi must be in [20, 1200]")
    loaded = None
    if args.wait:
        loaded = load_matplotlib(args.dpi, warm_up=True)
        if sys.stdin.readline().strip() != "go":
            return 0
    return _refuse_incomplete(args) or _draw_stills(args, loaded)


def _refuse_incomplete(args):
    """EXIT_BAD_INPUT (after saying why) for a run that is not complete, unless --allow-incomplete,
    which stamps every figure instead; None to go on. Checked after --wait's word to go: the launcher
    marks its run complete just before it gives it. A RUN_DIR that is no directory is left to the
    readers, which say so."""
    run_dir = Path(args.run_dir)
    if not run_dir.is_dir():
        return None
    why = incomplete_reason(run_dir)
    if why and not args.allow_incomplete:
        print(f"plot_run.py: {run_dir}: {why} (--allow-incomplete draws it anyway, stamped INCOMPLETE RUN)",
              file=sys.stderr)
        return EXIT_BAD_INPUT
    if why:
        print(f"plot_run.py: warning: {run_dir}: {why}; every figure is stamped INCOMPLETE RUN", file=sys.stderr)
    INCOMPLETE_STAMP["reason"] = why
    return None


def _draw_stills(args, loaded):
    """Reads the run and draws tracks, cardinality, OSPA and, for ADMAN sensors, detections into
    --out. `loaded` is what load_matplotlib gave when --wait loaded it already."""
    started = time.monotonic()
    run_dir = Path(args.run_dir)
    out_dir = Path(args.out) if args.out else run_dir / "plots"
    try:
        if not run_dir.is_dir():
            raise InputError(f"{run_dir}: not a directory")
        scenario = read_scenario(run_dir)
        truth, truth_classes = read_truth(run_dir / "truth.csv")
        tracks, _, _ = read_tracks(run_dir / "tracks.csv")
        sensors = read_sensors(run_dir, scenario)
        ticks, k_true, k, ospa, source = read_per_tick(run_dir, scenario, truth, tracks)
        summary = read_metrics_summary(run_dir)
        observations = few_observations(run_dir / "observations.csv")
        detections = read_detections(run_dir, scenario, truth) if scenario["sensor_kind"] == "adman" else None
    except InputError as error:
        print(f"plot_run.py: {error}", file=sys.stderr)
        return EXIT_BAD_INPUT
    except ToolMissing as error:
        print(f"plot_run.py: {error}", file=sys.stderr)
        return EXIT_TOOL_MISSING

    matplotlib, import_error = loaded or load_matplotlib(args.dpi, warm_up=False)
    if matplotlib is None:
        print(f"plot_run.py: matplotlib is not available to {sys.executable} ({import_error}); "
              "on Debian: apt-get install python3-matplotlib", file=sys.stderr)
        return EXIT_TOOL_MISSING

    try:
        out_dir.mkdir(parents=True, exist_ok=True)
    except OSError as error:
        print(f"plot_run.py: {out_dir}: cannot create ({error.strerror})", file=sys.stderr)
        return EXIT_BAD_INPUT
    written = []
    plots = [("tracks", lambda path: plot_tracks(matplotlib, scenario, sensors, truth, tracks, summary, path,
                                                 observations, truth_classes)),
             ("cardinality", lambda path: plot_cardinality(matplotlib, scenario, ticks, k_true, k, summary, path)),
             ("ospa", lambda path: plot_ospa(matplotlib, scenario, ticks, ospa, source, path, summary))]
    if detections is not None:
        plots.append(("detections", lambda path: plot_detections(matplotlib, scenario, detections, path)))
    for name, draw in plots:
        path = out_dir / f"{name}.{args.format}"
        try:
            draw(path)
        except OSError as error:
            print(f"plot_run.py: {path}: cannot write ({error.strerror})", file=sys.stderr)
            return EXIT_BAD_INPUT
        written.append(str(path))
    print(f"plot_run.py: wrote {', '.join(written)} in {time.monotonic() - started:.2f} s")
    return 0

