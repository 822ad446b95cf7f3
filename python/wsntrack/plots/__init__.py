"""The pictures of one run directory (tools/plot_run.py): tracks.FORMAT, the tracks against the
truth on the sensor field (tracks_map); cardinality, OSPA and ADMAN detections per tick (charts);
and the replay animation (animation, written through sinks, driven by replay). cli is the command
line. matplotlib is imported only when something is drawn."""
