#!/usr/bin/python3
# %% [markdown]
# # A sweep and a run, in Python
#
# Notebook-style analysis with the `wsntrack` package: each `# %%` is a cell (Jupyter, VS Code and
# Spyder run them one by one); the whole file also runs as a script. It loads a sweep of Oh et al.'s
# Fig. 7 and one of its runs, and draws a figure of both: εK against the end-to-end delivery ratio
# (measured in each run, not the per-hop pte that was swept), and the run's tracks over the truth.
#
#     wsntrack sweep sweeps/oh_fig7_pte.yaml --seeds 1-3 --out runs/fig7
#     PYTHONPATH=build/python python3 examples/sweep_and_run.py runs/fig7 figure.pdf
#
# Installed (`cmake --install`, the .deb), `import wsntrack` needs no PYTHONPATH.

# %%
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")  # a file, not a window: remove in a notebook
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from wsntrack import catalogue  # noqa: E402
from wsntrack.loader import load_run  # noqa: E402
from wsntrack.sweep.results import load_sweep  # noqa: E402

SWEEP = Path(sys.argv[1]) if len(sys.argv) > 1 else Path("runs/fig7")
FIGURE = Path(sys.argv[2]) if len(sys.argv) > 2 else Path("figure.pdf")

# %% The sweep: one row per run, with every metric it tabulated
sweep = load_sweep(SWEEP)
print(sweep)
runs = sweep.results[sweep.results.status == "ok"]
(key, values), = sweep.grid.items()

# %% The x axis a reader understands: the share of reports that reached a supernode, from each run's network.json
delivery = np.array([load_run(SWEEP / run_dir).network["delivered_to_total"] for run_dir in runs.run_dir])
labels = {q["name"]: catalogue.axis_label(q["label"], q["unit"]) for q in catalogue.quantities().values()}

# %% One run of the sweep: the one with the lowest delivery that still has tracks
order = np.argsort(delivery)
chosen = next(SWEEP / runs.run_dir[i] for i in order if len(load_run(SWEEP / runs.run_dir[i]).tracks))
run = load_run(chosen)
print(run)

# %% The figure
fig, (left, right) = plt.subplots(1, 2, figsize=(10, 4.2))
for engine in sweep.engines:
    mine = runs.engine == engine
    left.scatter(delivery[mine], runs.eps_k[mine], s=12, label=engine)
left.set_xlabel(catalogue.axis_label(catalogue.network_quantities()["delivery_ratio"]["label"], ""))
left.set_ylabel(labels["eps_k"])
left.set_title(f"each run of the sweep over {key}", fontsize=9)
left.legend(fontsize=8)

for target, path in run.by_id(run.truth, "target").items():
    right.plot(path.x, path.y, color="0.6", linewidth=2)
for label, path in run.by_id(run.tracks, "label").items():
    right.plot(path.x, path.y, linewidth=1)
right.set_aspect("equal")
right.set_title(f"{chosen.name}: truth (grey) and tracks", fontsize=9)
fig.tight_layout()
fig.savefig(FIGURE)
print(f"wrote {FIGURE}")
