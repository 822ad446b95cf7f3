"""Table II of Pannetier, Dezert and Sella (FUSION 2014) beside our runs (tools/onera_table.py):
blocks reads one run's metrics.json, pooling makes one of several runs of an algorithm (with the
share of each target's life the sensors reported), table writes the Markdown, plot the bar charts
(--plot, matplotlib), paper holds the paper's numbers, cli the command line. Standard library only
but for --plot."""
