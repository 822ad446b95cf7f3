"""onera_table.py's command line: reads the runs of each algorithm, pools them and prints the table
(and with --plot draws it); --help (SUMMARY and DESCRIPTION below) says everything."""

import argparse
import sys
from pathlib import Path

from ..figures import load_matplotlib
from ..rundir import InputError
from .blocks import read_run
from .paper import PAPER_TARGETS
from .plot import plot
from .pooling import average_reported, average_runs, pool_classification, pool_stop_mode, target_classes
from .table import table

PLOT_FORMATS = (".png", ".svg")
PLOT_DPI = 120

SUMMARY = """Table II of Pannetier et al. (FUSION 2014) beside our runs: per target RSE and TLR of algorithm 1
(with the road network) and algorithm 2 (without), the share of the target's life in which the
sensors reported it at all and, when the runs were scored with the classification metric, its true
class and class accuracy, as a Markdown table on stdout; then the paper's statistics and, with the
classification metric, the run-level classification scores and confusion matrices and, with the
stop_mode metric, the mean stop probability of the tracks while their targets stand still and move.

  onera_table.py --a1 RUN_DIR... --a2 RUN_DIR...   both algorithms, with the A1 - A2 deltas
  onera_table.py --a2 RUN_DIR...                   algorithm 2 only, beside the paper's A1 and A2
  onera_table.py RUN_DIR...                        the same as --a2 RUN_DIR...
  onera_table.py ... --plot FILE.png|FILE.svg       the table, and bar charts of it in FILE

Standard library only, so that it runs with any python3; --plot
alone needs matplotlib (Debian's python3-matplotlib, for /usr/bin/python3), imported only then.
"""

DESCRIPTION = SUMMARY + """
Each RUN_DIR is a run directory written by 'wsntrack run' (or its metrics.json itself). The tool reads
metrics.json's track_quality block (docs/METRICS.md): per target, in file order (increasing target id),
rse_position, tlr (associated ticks / alive ticks) and tlr_length (associated path length / path
length). Target N of the table is the N-th target of the file, which onera2014_like numbers as the
paper does. Several runs of an algorithm (one per seed, say) are averaged per target: RSE over the
runs in which the target was ever associated (errors_defined), TLR over every run. Every run must
have the same number of targets.

The "reported" column tells how much of a target's life the sensors covered at all: the share of its
alive ticks (the distinct ticks of truth.csv's rows with that target) in which at least one report of
it was delivered (the distinct tick_generated of observations.csv's rows with that target and fate
'delivered'; lost reports and false alarms, target -1, do not count). It is read from the run
directory's truth.csv and observations.csv, those of the A2 runs when given, else of the A1 runs (runs
of the same seeds have the same reports), computed per run and averaged over the runs. Target N is the
N-th target id of truth.csv in increasing order. It explains a low TLR but does not bound it (a track
can coast through unreported ticks). When a run has no truth.csv or observations.csv (or a metrics.json
path was given), a malformed one, or truth.csv's number of targets differs from metrics.json's, a note
on stderr names the file and the column is '-'.

The table lists the paper's A1 and A2 values, ours (RSE, TLR, TLR_len), and the A1 - A2 deltas of
the paper and, with both --a1 and --a2, of ours; between the two, "reported". Below it, the statistics the paper's text draws from
Table II: mean and median RSE and TLR, the number of targets on which A1's RSE is lower, and on which
A1's TLR is higher, equal or lower (compared at the paper's two decimals, as its table gives them);
and, when every target's "reported" is defined, its mean and median and, per algorithm, the mean TLR
divided by the mean reported share. Targets whose RSE is undefined in every run are left out of the
RSE statistics and shown as '-'.

Runs whose metrics.json has the classification block (docs/METRICS.md) add, per target, a "class"
column after "target" and, after each algorithm's TLR_len, an "A1 acc" / "A2 acc" column:
  class     the target's true class (wheeled_light, wheeled_heavy, tracked, human, group, aerial or
            unknown), the class of classification.targets' entry with the id of the N-th entry of
            track_quality.targets; it must be the same in every run of both algorithms. '-' when no run
            lists the target (only targets ever associated are listed).
  A1 acc    class accuracy pooled over the algorithm's runs: sum of ticks_correct / sum of ticks_declared
            (ticks its track declared the true class / ticks it declared a class). '-' when no tick was
            declared or the class is unknown. The mean and median rows are over the targets with one.
Below the statistics, a "Classification" section gives for each algorithm given the run totals summed
over its runs (these count only the targets of known class): declared share = ticks_declared /
ticks_associated and accuracy = ticks_correct / ticks_declared, with the counts ('-' for 0/0), then the
confusion matrix summed over the runs as a Markdown table: rows the true classes met (unknown included),
columns the declared classes that are a row or have a non-zero count, then "none" (associated ticks
whose track declared no class); classes in the order listed above. Runs scored before the classification
metric existed have no block: without it in any run the table is as before and there is no section;
when only one algorithm's runs have it, the other gets no acc column and a line saying its runs have no
block. Some runs of one algorithm with the block and some without is an error.

Runs whose metrics.json has the stop_mode block (docs/METRICS.md, "Stop mode") add, after the
classification section, a "Stop mode" section: for each algorithm given, the mean probability its
tracks give the stop model of their IMM over the associated ticks in which the target stands still
(true velocity exactly 0) and over those in which it moves, pooled over the algorithm's runs as
sum(mean * ticks) / sum(ticks), with the summed tick counts ('-' for no tick), and the associated
ticks of tracks whose engine has no stop model when there are any; then one line with, per target
that stands still in some associated tick of some algorithm's runs (target N being the N-th entry of
track_quality.targets, by the id of stop_mode.targets' entries), each algorithm's mean while stopped
pooled the same way and its ticks. Without the block in any run there is no section; when only one
algorithm's runs have it, the other gets a line saying its runs have no block. Some runs of one
algorithm with the block and some without is an error, as for classification.

With --plot FILE (FILE ending .png or .svg, which chooses the format) the tool also draws the table
in FILE: two panels stacked, per-target RSE (m) above and per-target TLR below, as grouped bars for
targets 1..20 (more if the runs have more): ours A1 and ours A2 (those given), then the paper's A1 and
A2, hatched and lighter. A target with an undefined RSE gets no RSE bar. The title gives the number
of runs per algorithm. The figure is written under a temporary name in FILE's directory and renamed
to FILE when complete, so a failure leaves no partial FILE; a line on stderr says where it was
written. matplotlib is imported (with the Agg backend) only for --plot; when it cannot be, the tool
says so before printing anything and exits with status 1.

Exit status: 0, 1 when a run directory or its metrics.json is missing or malformed (the message
names the file and what was expected; this includes a malformed classification or stop_mode block,
runs of one algorithm with and without either block, and a target whose class differs between runs),
when --plot is given but matplotlib cannot be imported, or when FILE cannot be written; 2 on a usage
error (such as --plot FILE with another extension)."""

def main(argv):
    """onera_table.py ARGV: prints the table; returns the exit status (0, 1 for a run that cannot be
    tabulated or a plot that cannot be drawn, 2 for a usage error)."""
    parser = argparse.ArgumentParser(prog="onera_table.py", description=DESCRIPTION,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("runs", nargs="*", metavar="RUN_DIR",
                        help="runs of algorithm 2 (without the road network), as with --a2")
    parser.add_argument("--a1", nargs="+", metavar="RUN_DIR", default=[],
                        help="runs of algorithm 1 (with the road network)")
    parser.add_argument("--a2", nargs="+", metavar="RUN_DIR", default=[],
                        help="runs of algorithm 2 (without the road network)")
    parser.add_argument("--plot", metavar="FILE",
                        help="also draw per-target RSE and TLR, ours beside the paper's, in FILE "
                             "(.png or .svg; needs matplotlib)")
    args = parser.parse_args(argv)
    if args.plot is not None and Path(args.plot).suffix.lower() not in PLOT_FORMATS:
        suffix = Path(args.plot).suffix
        parser.error(f"--plot {args.plot}: " + (f"unknown extension '{suffix}'" if suffix else "no extension")
                     + " (expected a file name ending .png or .svg)")
    if args.runs and args.a2:
        parser.error("give algorithm 2's runs either as RUN_DIR... or after --a2, not both")
    a2_args = args.a2 or args.runs
    if not args.a1 and not a2_args:
        parser.error("no run directories: give RUN_DIR..., --a2 RUN_DIR... and/or --a1 RUN_DIR...")
    try:
        a1_read = [(arg, *read_run(arg)) for arg in args.a1]
        a2_read = [(arg, *read_run(arg)) for arg in a2_args]
        a1_runs = [(arg, rows) for arg, _, rows, _, _ in a1_read]
        a2_runs = [(arg, rows) for arg, _, rows, _, _ in a2_read]
        a1 = average_runs(a1_runs, "--a1") if a1_runs else None
        a2 = average_runs(a2_runs, "--a2") if a2_runs else None
        if a1 is not None and a2 is not None and len(a1) != len(a2):
            raise InputError(f"the A1 runs have {len(a1)} targets and the A2 runs {len(a2)}: they must be "
                             "runs of the same scenario")
        pooled = {"A1": pool_classification(a1_read, "--a1") if a1_read else None,
                  "A2": pool_classification(a2_read, "--a2") if a2_read else None}
        classes = (target_classes(a1_read + a2_read)
                   if any(c is not None for c in pooled.values()) else None)
        stop = {"A1": pool_stop_mode(a1_read, "--a1") if a1_read else None,
                "A2": pool_stop_mode(a2_read, "--a2") if a2_read else None}
    except InputError as error:
        print(f"onera_table.py: {error}", file=sys.stderr)
        return 1
    for name, rows in (("A1", a1), ("A2", a2)):
        if rows is not None and len(rows) != PAPER_TARGETS:
            print(f"onera_table.py: note: the {name} runs have {len(rows)} targets, Table II has {PAPER_TARGETS}; "
                  "rows are matched by position", file=sys.stderr)
        if rows is not None and any(r[2] is None for r in rows):
            print(f"onera_table.py: note: some {name} run has no tlr_length (scored before it existed): "
                  "TLR_len is shown as '-'", file=sys.stderr)
    matplotlib = None
    if args.plot is not None:
        matplotlib, import_error = load_matplotlib(PLOT_DPI)
        if matplotlib is None:
            print(f"onera_table.py: --plot: matplotlib is not available to {sys.executable} ({import_error}); "
                  "on Debian: apt-get install python3-matplotlib (or leave out --plot)", file=sys.stderr)
            return 1
    reported_from = "A2" if a2_runs else "A1"
    reported = average_reported(a2_runs or a1_runs)
    print("\n".join(table(a1, a2, len(a1_runs), len(a2_runs), reported, reported_from, classes, pooled, stop)),
          flush=True)
    if matplotlib is not None:
        try:
            plot(matplotlib, args.plot, a1, a2, len(a1_runs), len(a2_runs))
        except OSError as error:
            print(f"onera_table.py: {args.plot}: cannot write the plot "
                  f"({error.strerror or error})", file=sys.stderr)
            return 1
        print(f"onera_table.py: wrote the plot to {args.plot}", file=sys.stderr)
    return 0

