"""plot_run.py --animate ('wsntrack replay'): its options checked, the run read, the animation drawn
(wsntrack.plots.animation) and written under a temporary name, renamed when complete."""

import os
import sys
import time
from pathlib import Path

from ..figures import load_matplotlib
from ..rundir import InputError, ToolMissing, read_csv, read_observations, read_per_tick, read_scenario, read_tracks
from .animation import animate
from .inputs import read_sensors
from .sinks import EncoderError, GifSink, HtmlSink, Mp4Sink

EXIT_BAD_INPUT = 2
EXIT_TOOL_MISSING = 3

ANIMATION_FORMATS = ("gif", "mp4", "html")
ANIMATION_SUFFIXES = {".gif": "gif", ".mp4": "mp4", ".html": "html", ".htm": "html"}
ANIMATION_NAME = "replay"
ANIMATION_DEFAULTS = {"fps": 5, "size": "1280x720", "trail": 10, "hold": 1.0}


def animation_target(out, run_dir, chosen_format):
    """(path, format) of the animation: --out names the file when it ends in .gif, .mp4 or .html
    (.htm), else a directory (default RUN_DIR/plots) which gets replay.FORMAT; the format is
    --animate-format, else the file's suffix, else gif."""
    path = Path(out) if out else None
    suffix_format = None
    if path is not None and path.suffix.lower() in ANIMATION_SUFFIXES and not path.is_dir():
        suffix_format = ANIMATION_SUFFIXES[path.suffix.lower()]
        if chosen_format and chosen_format != suffix_format:
            raise InputError(f"--out {out}: the suffix says {suffix_format}, --animate-format says {chosen_format}")
        return path, suffix_format
    if path is not None and path.suffix and not path.is_dir():
        raise InputError(f"--out {out}: an animation is written to a .gif, .mp4 or .html file, or into a "
                         f"directory (which a name ending in '{path.suffix}' is not, unless it exists)")
    chosen_format = chosen_format or "gif"
    directory = path if path is not None else run_dir / "plots"
    return directory / f"{ANIMATION_NAME}.{chosen_format}", chosen_format


def parse_size(text):
    """'WIDTHxHEIGHT' in pixels, rounded down to even numbers (as H.264 needs)."""
    try:
        width, height = (int(v) for v in text.lower().split("x"))
    except ValueError:
        raise ValueError(f"--size must be WIDTHxHEIGHT in pixels, e.g. 1280x720, got '{text}'") from None
    if not (320 <= width <= 3840 and 240 <= height <= 2160):
        raise ValueError(f"--size must be within 320x240 .. 3840x2160, got '{text}'")
    return width - width % 2, height - height % 2


class AnimationOptions:
    """What animate() needs besides the run: ticks, trail, frame size, progress and the output."""

    def __init__(self, **fields):
        self.__dict__.update(fields)


def _check_options(parser, args):
    """Fills in the defaults and checks the ranges (a usage error exits 2); returns the frame size."""
    for name, value in ANIMATION_DEFAULTS.items():
        if getattr(args, name) is None:
            setattr(args, name, value)
    if not 0.1 <= args.fps <= 60:
        parser.error(f"--fps must be in [0.1, 60], got {args.fps:g}")
    if not 0 <= args.trail <= 1000:
        parser.error(f"--trail must be in [0, 1000], got {args.trail}")
    if not 0 <= args.hold <= 60:
        parser.error(f"--hold must be in [0, 60] seconds, got {args.hold:g}")
    try:
        return parse_size(args.size)
    except ValueError as error:
        parser.error(str(error))


def _read_run(args, run_dir):
    """The run as the animation draws it: scenario, ticks drawn, truth, tracks, reports, sensors and
    the numbers per tick. Raises InputError or ToolMissing."""
    if not run_dir.is_dir():
        raise InputError(f"{run_dir}: not a directory")
    scenario = read_scenario(run_dir)
    first = 1 if args.first is None else args.first
    last = scenario["ticks"] if args.last is None else args.last
    if not 1 <= first <= last <= scenario["ticks"]:
        raise InputError(f"--first {first} --last {last}: the ticks drawn must satisfy "
                         f"1 <= first <= last <= {scenario['ticks']} (the run's ticks)")
    truth = read_csv(run_dir / "truth.csv", ["tick", "target", "x", "y", "vx", "vy"],
                     [int, int, float, float, float, float])
    tracks, _, _ = read_tracks(run_dir / "tracks.csv")
    observations = read_observations(run_dir / "observations.csv")
    sensors = read_sensors(run_dir, scenario)
    ticks, k_true, k, ospa, _ = read_per_tick(run_dir, scenario, truth, tracks)
    return dict(scenario=scenario, first=first, last=last, truth=truth, tracks=tracks, observations=observations,
                sensors=sensors, per_tick=(ticks, k_true, k, ospa))


def _load_tools(chosen):
    """(matplotlib, ffmpeg or None), or the message of the tool that is missing (exit 3)."""
    matplotlib, import_error = load_matplotlib(100, warm_up=False)
    if matplotlib is None:
        return None, (f"matplotlib is not available to {sys.executable} ({import_error}); "
                      "on Debian: apt-get install python3-matplotlib")
    try:
        import importlib
        for module in ("numpy", "PIL.Image"):  # matplotlib needs both too, but not at import
            importlib.import_module(module)
    except ImportError as error:
        return None, (f"--animate needs numpy and Pillow, which {sys.executable} lacks ({error}); "
                      "on Debian: apt-get install python3-numpy python3-pil")
    ffmpeg = None
    if chosen == "mp4":
        import shutil
        ffmpeg = shutil.which("ffmpeg")
        if ffmpeg is None:
            return None, ("an MP4 needs ffmpeg, which is not on PATH; on Debian: apt-get install ffmpeg "
                          "(or write a GIF or an HTML page: --animate-format gif|html)")
    return (matplotlib, ffmpeg), None


def animate_main(parser, args):
    """plot_run.py --animate: checks, reads, draws and writes; returns the exit status."""
    started = time.monotonic()
    size = _check_options(parser, args)
    run_dir = Path(args.run_dir)
    try:
        path, chosen = animation_target(args.out, run_dir, args.animate_format)
        run = _read_run(args, run_dir)
    except (InputError, ToolMissing) as error:
        print(f"plot_run.py: {error}", file=sys.stderr)
        return EXIT_TOOL_MISSING if isinstance(error, ToolMissing) else EXIT_BAD_INPUT
    tools, missing = _load_tools(chosen)
    if tools is None:
        print(f"plot_run.py: {missing}", file=sys.stderr)
        return EXIT_TOOL_MISSING
    matplotlib, ffmpeg = tools
    scenario, first, last = run["scenario"], run["first"], run["last"]

    # Written under a temporary name and renamed when complete: a failed or interrupted render
    # never leaves a truncated animation behind under the real name.
    partial = path.with_name(f".{path.name}.{os.getpid()}.partial")

    def make_sink():
        if chosen == "gif":
            return GifSink(partial, args.fps, args.hold)
        if chosen == "mp4":
            return Mp4Sink(partial, args.fps, size, args.hold, ffmpeg)
        return HtmlSink(partial, args.fps, size, f"{scenario['name']}, seed {scenario['seed']}: ticks {first}-{last}")

    options = AnimationOptions(first=first, last=last, trail=args.trail, size=size, quiet=args.quiet,
                               make_sink=make_sink)
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        frames = animate(matplotlib, scenario, run["sensors"], run["truth"], run["tracks"], run["observations"],
                         run["per_tick"], options)
        os.replace(partial, path)
    except OSError as error:
        print(f"plot_run.py: {error.filename or path}: cannot write ({error.strerror})", file=sys.stderr)
        return EXIT_BAD_INPUT
    except EncoderError as error:
        print(f"plot_run.py: {path}: {error}", file=sys.stderr)
        return 1
    finally:
        if partial.exists():
            partial.unlink()
    print(f"plot_run.py: wrote {path} ({frames} frames, ticks {first}-{last}, {size[0]}x{size[1]}, "
          f"{args.fps:g} fps) in {time.monotonic() - started:.1f} s")
    return 0
