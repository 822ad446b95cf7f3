"""The conversions of a loaded run (wsntrack.loader.Run) to Stone Soup's types, when the
`stonesoup` package is importable: ground-truth paths, tracks with their covariances, and the
detections delivered per tick. Written against Stone Soup's documented types
(stonesoup.types.groundtruth, .track, .state, .detection); untested against Stone Soup itself, which
Debian does not package (tests/tools/loader_test.py checks the calls against a stand-in)."""

import numpy as np

from .rundir import InputError

#: Stone Soup's usual state order is (x, vx, y, vy), as its ConstantVelocity models and a
#: LinearGaussian measurement model with mapping (0, 2) expect; wsntrack's is (x, y, vx, vy).
#: ``state[STONESOUP_ORDER]`` reorders a wsntrack state, ``P[np.ix_(o, o)]`` a covariance.
STONESOUP_ORDER = [0, 2, 1, 3]


class StoneSoupConversions:
    """The Stone Soup side of a loaded run: needs its truth, tracks, supernode_tracks, observations
    and ticks, and by_id()."""

    def timestamp(self, tick, start=None, tick_seconds=1.0):
        """The datetime of `tick`: `start` (default 1970-01-01 00:00, naive like Stone Soup's
        examples) + tick * tick_seconds."""
        import datetime
        start = datetime.datetime(1970, 1, 1) if start is None else start
        return start + datetime.timedelta(seconds=float(tick) * tick_seconds)

    def _stone_soup_state(self, row, tick_seconds):
        """State vector (x, vx, y, vy) and covariance in Stone Soup's order, velocities per second."""
        scale = np.array([1.0, 1.0, 1.0 / tick_seconds, 1.0 / tick_seconds])
        state = np.array([row.x, row.y, row.vx, row.vy]) * scale
        covariance = row.covariance * np.outer(scale, scale)
        o = STONESOUP_ORDER
        return state[o].reshape(-1, 1), covariance[np.ix_(o, o)]

    def stonesoup_truths(self, start=None, tick_seconds=1.0):
        """``{target: GroundTruthPath}``: one path per target of GroundTruthState (x, vx, y, vy),
        id ``"target <n>"``, metadata {"target", "tick"}. Velocities are per second: per tick
        divided by `tick_seconds` (default 1, so that a tick is a second). Needs stonesoup.
        """
        from stonesoup.types.groundtruth import GroundTruthPath, GroundTruthState
        paths = {}
        for target, rows in self.by_id(self.truth, "target").items():
            states = []
            for row in rows:
                vector = np.array([[row.x], [row.vx / tick_seconds], [row.y], [row.vy / tick_seconds]])
                states.append(GroundTruthState(vector, timestamp=self.timestamp(row.tick, start, tick_seconds),
                                               metadata={"target": int(target), "tick": int(row.tick)}))
            paths[int(target)] = GroundTruthPath(states, id=f"target {target}")
        return paths

    def stonesoup_tracks(self, supernode=None, start=None, tick_seconds=1.0):
        """``{label: Track}`` of GaussianState (x, vx, y, vy) with the covariance reordered to match,
        track id = label (``"0:1"``; ``"S<j> 0:1"`` for supernode j's tracks, with `supernode`).
        Needs stonesoup; a zero covariance (unknown) is passed on as it is."""
        from stonesoup.types.state import GaussianState
        from stonesoup.types.track import Track
        records = self.tracks if supernode is None else self.supernode_tracks[self.supernode_tracks.supernode == supernode]
        tracks = {}
        for label, rows in self.by_id(records, "label").items():
            states = []
            for row in rows:
                vector, covariance = self._stone_soup_state(row, tick_seconds)
                states.append(GaussianState(vector, covariance, timestamp=self.timestamp(row.tick, start, tick_seconds)))
            ident = label if supernode is None else f"S{supernode} {label}"
            tracks[label] = Track(states, id=ident, init_metadata={"label": label, "track": int(rows[0].track)})
        return tracks

    def stonesoup_detections(self, truths=None, measurement_model=None, start=None, tick_seconds=1.0):
        """``[(datetime of tick t, set of detections delivered at t)]`` for t = 1 .. T, the shape a
        Stone Soup DetectionReader's detections_gen() yields. A detection is a TrueDetection (its
        groundtruth_path from `truths`, as stonesoup_truths() returns them, when given) or a Clutter
        for a false alarm; its state vector is the reported (x, y), its timestamp the tick it was
        generated (earlier than t for a late report), its metadata the observations.csv row.
        `measurement_model` (e.g. LinearGaussian(ndim_state=4, mapping=(0, 2), noise_covar=...))
        is attached to every detection. Needs stonesoup."""
        from stonesoup.types.detection import Clutter, TrueDetection
        if self.observations is None:
            raise InputError(f"{self.path / 'observations.csv'}: missing (is {self.path} a finished run?)")
        truths = truths if truths is not None else {}
        delivered = {t: set() for t in range(1, self.ticks + 1)}
        for row in self.observations[self.observations.fate == "delivered"]:
            metadata = {name: row[name].item() for name in self.observations.dtype.names}
            vector = np.array([[row.x], [row.y]])
            when = self.timestamp(row.tick_generated, start, tick_seconds)
            if row.target < 0:
                detection = Clutter(vector, timestamp=when, measurement_model=measurement_model, metadata=metadata)
            else:
                detection = TrueDetection(vector, timestamp=when, measurement_model=measurement_model,
                                          metadata=metadata, groundtruth_path=truths.get(int(row.target)))
            delivered.setdefault(int(row.tick_delivered), set()).add(detection)
        return [(self.timestamp(t, start, tick_seconds), delivered[t]) for t in sorted(delivered)]

