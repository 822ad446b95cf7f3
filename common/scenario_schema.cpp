#include "common/scenario_schema.hpp"

#include <cmath>

namespace wsn::common::schema {
namespace {

using namespace config;

template <typename C>
Field<C> unsetWhenZero(Field<C> f) {
  f.zero_means_unset = true;
  return f;
}

constexpr Range kCoordinate = closed(-kMaxCoordinate, kMaxCoordinate);

}  // namespace

const FieldTable<Scenario>& topLevel() {
  static const FieldTable<Scenario> table{
      "",
      {withNotes(text<Scenario>("name", &Scenario::name, "names the run and its run directory"),
                 "1–100 characters from `A-Z a-z 0-9 _ - .`")}};
  return table;
}

const FieldTable<Rect>& region() {
  static const FieldTable<Rect> table{
      "region",
      {
          real<Rect>("x_min", &Rect::x_min, kCoordinate, "separations", "left edge"),
          real<Rect>("y_min", &Rect::y_min, kCoordinate, "separations", "bottom edge"),
          withNotes(real<Rect>("x_max", &Rect::x_max, kCoordinate, "separations", "right edge"),
                    "[−1e6, 1e6], > `x_min`", "100"),
          withNotes(real<Rect>("y_max", &Rect::y_max, kCoordinate, "separations", "top edge"),
                    "[−1e6, 1e6], > `y_min`", "100"),
      }};
  // (Rect{} is the empty rectangle; a scenario's region defaults to [0, 100]^2.)
  return table;
}

const FieldTable<SensorLayoutConfig>& sensors() {
  using C = SensorLayoutConfig;
  static const FieldTable<C> table{
      "sensors",
      {
          choice<C>("layout", &C::kind, {"grid", "random", "list"},
                    "`grid`: sensors at the cell centres (x_min + (i + ½) spacing, …), as in §VII. `random`: `count` "
                    "sensors placed uniformly, drawn from the seed. `list`: each sensor of `list` placed by hand "
                    "(ONERA Table I), for a sensor model with sensor types"),
          withNotes(real<C>("spacing", &C::spacing, kPositive, "separations", "grid separation"),
                    "(0, 1e6]; a grid must hold 1 to 10^7 sensors"),
          withNotes(integer<C>("count", &C::count, 1, kMaxSensors, "sensors",
                               "number of sensors of a `random` layout; of a `list` layout, its length"),
                    "[1, 10^7]"),
          nested<C>("list", "list of sensors", "`[]`", "`layout: list` only",
                    "the sensors of a `list` layout, in id order; each item's keys in `sensors.list[]`"),
      }};
  return table;
}

const FieldTable<PlacedSensorConfig>& placedSensor() {
  using C = PlacedSensorConfig;
  static const FieldTable<C> table{
      "sensors.list[]",
      {
          withNotes(text<C>("name", &C::name, "names the sensor; unique in the list"), "non-empty text"),
          withNotes(text<C>("type", &C::type, "the sensor's type, one of the sensor model's types"),
                    "a type of `sensor_model.kind`"),
          withNotes(real<C>("x", [](C& c) -> double& { return c.position.x; }, kCoordinate, "distance",
                            "true position (the believed one adds the localisation error)"),
                    "inside the region"),
          withNotes(real<C>("y", [](C& c) -> double& { return c.position.y; }, kCoordinate, "distance",
                            "true position"),
                    "inside the region"),
          real<C>("heading", &C::heading_deg, closed(-360.0, 360.0), "degrees",
                  "centre of the field of view, counter-clockwise from +x; the sensor's angles are measured from it"),
          unsetWhenZero(withNotes(real<C>("fov", &C::fov_deg, openClosed(0.0, 360.0), "degrees",
                                          "width of the field of view, centred on the heading"),
                                  "(0, 360]", "the type's `fov`")),
          unsetWhenZero(withNotes(real<C>("range", &C::range, kNonNegative, "distance",
                                          "coverage radius: farther targets are not detected"),
                                  "[0, 1e6]; 0: the type's", "the type's `range`")),
          unsetWhenZero(withNotes(real<C>("height", &C::height, closed(0.0, 1e3), "distance",
                                          "mast height above the ground (cameras: φ = atan2(−h, ρ))"),
                                  "[0, 1e3]; 0: the type's", "the type's `height`")),
      }};
  return table;
}

const FieldTable<SensorModelConfig>& sensorModel() {
  using C = SensorModelConfig;
  static const FieldTable<C> table{
      "sensor_model",
      {
          withNotes(text<C>("kind", &C::kind, "which sensors. Each model's own keys follow in its table below"),
                    "a sensor model of `wsntrack components`"),
          real<C>("sensing_range", &C::sensing_range, kPositive, "separations",
                  "Rs, how far a sensor detects a target. §VII-A finds 1.5 best. Acoustic: the default SR of a "
                  "target, the distance at which one emission of its sound equals cs (Pt = cs SR^α). Node tiles are "
                  "made of cells of side 2 Rs"),
      }};
  return table;
}

const FieldTable<LocalisationConfig>& localisation() {
  using C = LocalisationConfig;
  static const FieldTable<C> table{
      "localisation",
      {real<C>("sigma", &C::sigma, closed(0.0, 1e3), "separations", "a sensor believes it is at s* + N(0, σ² I)")}};
  return table;
}

const FieldTable<TargetsConfig>& targets() {
  using C = TargetsConfig;
  static const FieldTable<C> table{
      "targets",
      {
          withNotes(real<C>("birth_rate", &C::birth_rate, kNonNegative, "1/(tick · separation²)",
                            "λb: Poisson(λb V) births per tick, where V is the region's area"),
                    "[0, 1e6]; `birth_rate` × area ≤ 1000"),
          real<C>("death_probability", &C::death_probability, kProbability, "per tick",
                  "pz. Applies to randomly born targets only"),
          choice<C>("speed_class", &C::speed_class, {"slow", "medium", "fast"},
                    "initial speeds of born targets, §VII-A. Each of \\|vx\\| and \\|vy\\| is uniform in [0, 1], "
                    "[1, 2] or [2, 5] per tick, with a random sign"),
          integer<C>("count", &C::count, 0, 1e4, "targets",
                     "targets drawn at random for each seed, Oh §VII-A's \"10 targets appear and disappear at random "
                     "times\": a lifetime L in [`lifetime_min`, `lifetime_max`] (at most the run), an appear tick "
                     "so that the life fits the run, a `speed_class` velocity and a start from which the straight "
                     "path stays in the region (5 % in from its edges) as long as it can. Ids follow the scripted ones"),
          integer<C>("lifetime_min", &C::lifetime_min, 1, 1e6, "ticks", "shortest life of a drawn target"),
          withNotes(integer<C>("lifetime_max", &C::lifetime_max, 1, 1e6, "ticks", "longest life of a drawn target"),
                    "[`lifetime_min`, 10^6]"),
          nested<C>("scripted", "list", "`[]`", "see below",
                    "targets placed explicitly. They get ids 0…n−1 in file order"),
      }};
  return table;
}

const FieldTable<TargetSpec>& scriptedTarget() {
  using C = TargetSpec;
  static const FieldTable<C> table{
      "targets.scripted[]",
      {
          integer<C>("appear_tick", &C::appear_tick, 1, 1e6, "tick", "first tick the target exists"),
          withNotes(integer<C>("disappear_tick", &C::disappear_tick, 0, 1e6, "tick",
                               "first tick it no longer exists. 0 means it never disappears, though it still "
                               "vanishes when it leaves R"),
                    "0, or (`appear_tick`, 10^6]"),
          withNotes(real<C>("x", [](C& t) -> double& { return t.position.x; }, kCoordinate, "separations",
                            "position at `appear_tick`"),
                    "inside the region", "required without `waypoints`"),
          withNotes(real<C>("y", [](C& t) -> double& { return t.position.y; }, kCoordinate, "separations",
                            "position at `appear_tick`"),
                    "inside the region", "required without `waypoints`"),
          withNotes(real<C>("vx", [](C& t) -> double& { return t.velocity.x; }, kCoordinate, "separations/tick",
                            "velocity at `appear_tick`. `speed_class` does not constrain it"),
                    "", "required without `waypoints`"),
          withNotes(real<C>("vy", [](C& t) -> double& { return t.velocity.y; }, kCoordinate, "separations/tick",
                            "velocity at `appear_tick`. `speed_class` does not constrain it"),
                    "", "required without `waypoints`"),
          unsetWhenZero(withNotes(real<C>("sensing_range", &C::sensing_range, kPositive, "separations",
                                          "the target's sensing range SR, i.e. its sound power Pt = cs SR^α (An "
                                          "et al. 2014 Table 1)"),
                                  "(0, 1e6]; for models that read it (`acoustic_doppler`)", "`sensor_model.sensing_range`")),
          nested<C>("waypoints", "list of `[x, y]`", "none", "2 or more points inside the region, no two in a row equal",
                    "a route instead of `x`, `y`, `vx`, `vy`: the target appears at the first waypoint, drives "
                    "the polyline at `speed` exactly (a tick that passes a waypoint goes on along the next leg), "
                    "without eq. (8)'s noise, and is gone the tick after it reaches the last one"),
          unsetWhenZero(withNotes(real<C>("speed", &C::speed, kPositive, "separations/tick",
                                          "distance a waypoint target covers per tick"),
                                  "(0, 1e6]; with `waypoints` only", "required with `waypoints`, unless `speeds`")),
          nested<C>("speeds", "list of numbers", "none",
                    "one per waypoint, each in (0, 1e6]; with `waypoints`, instead of `speed`",
                    "separations/tick: the speed as the target passes each waypoint. Along a leg it changes at a "
                    "constant acceleration from one waypoint's speed to the next's (a target that speeds up across "
                    "a gap, or slows into a bend)"),
          nested<C>("stops", "list of `{at, ticks}`", "`[]`", "with `waypoints` only; `at` increasing",
                    "halts: `ticks` ticks at rest (velocity 0) at waypoint number `at` (from 0), after the tick "
                    "that reaches it; that tick ends at the waypoint"),
          unsetWhenZero(choice<C>("class", &C::target_class, targetClassNames(),
                                  "what the target is, ONERA eq. (1) (`docs/ONERA.md`): truth.csv's `class`, "
                                  "scored against the tracks' classes (metrics.json's `classification`)")),
      }};
  return table;
}

const FieldTable<WaypointStop>& waypointStop() {
  using C = WaypointStop;
  static const FieldTable<C> table{
      "targets.scripted[].stops[]",
      {
          withNotes(integer<C>("at", &C::at, 0, 1e6, "waypoint", "the waypoint's number in `waypoints`, from 0"),
                    "a waypoint of the target, after the previous stop's", "required"),
          withNotes(integer<C>("ticks", &C::ticks, 1, 1e6, "ticks", "how long the target rests there"), "[1, 10^6]",
                    "required"),
      }};
  return table;
}

const FieldTable<DynamicsConfig>& dynamics() {
  using C = DynamicsConfig;
  static const FieldTable<C> table{
      "dynamics",
      {
          real<C>("delta", &C::delta, openClosed(0.0, 1e3), "ticks", "δ, the sampling interval"),
          real<C>("process_noise_sigma", &C::process_noise_sigma, closed(0.0, 1e3), "separations/tick²",
                  "q. §VII gives Q = diag(0.15², 0.15²)"),
      }};
  return table;
}

const FieldTable<Vec2>& supernode() {
  static const FieldTable<Vec2> table{
      "supernodes[]",
      {
          withNotes(real<Vec2>("x", &Vec2::x, kCoordinate, "separations", "position"), "inside the region", "required"),
          withNotes(real<Vec2>("y", &Vec2::y, kCoordinate, "separations", "position"), "inside the region", "required"),
      }};
  return table;
}

const FieldTable<TerrainConfig>& terrain() {
  using C = TerrainConfig;
  static const FieldTable<C> table{
      "terrain",
      {
          nested<C>("roads", "list", "`[]`", "see below",
                    "road centre lines. Where roads share a vertex (exactly) is a junction; a section is the part "
                    "of a road between junctions or ends"),
          nested<C>("masks", "list", "`[]`", "see below", "areas that hide targets from sight"),
      }};
  return table;
}

const FieldTable<RoadLine>& road() {
  using C = RoadLine;
  static const FieldTable<C> table{
      "terrain.roads[]",
      {
          withNotes(text<C>("name", &C::name, "names the road"),
                    "1–100 characters from `A-Z a-z 0-9 _ - .`, unique among roads", "required"),
          nested<C>("points", "list of `[x, y]`", "required",
                    "2 or more points inside the region, no two in a row equal", "the centre line, a polyline"),
      }};
  return table;
}

const FieldTable<Mask>& mask() {
  using C = Mask;
  static const FieldTable<C> table{
      "terrain.masks[]",
      {
          withNotes(text<C>("name", &C::name, "names the mask"),
                    "1–100 characters from `A-Z a-z 0-9 _ - .`, unique among masks", "required"),
          withNotes(choice<C>("kind", &C::kind, {"building", "vegetation"},
                              "what hides: a building blocks every line of sight through it; vegetation blocks "
                              "optical sight (cameras, PIR) but not radar or acoustic sensing"),
                    "`building`, `vegetation`", "required"),
          nested<C>("polygon", "list of `[x, y]`", "required",
                    "3 or more points inside the region, a simple polygon (no crossing edges)",
                    "the outline, closed from the last point back to the first"),
      }};
  return table;
}

const FieldTable<FaultSpec>& fault() {
  using C = FaultSpec;
  static const FieldTable<C> table{
      "faults[]",
      {
          withNotes(integer<C>("tick", &C::tick, 1, 1e6, "ticks", "the first tick the fault holds"),
                    "[1, run.ticks]", "required"),
          withNotes(choice<C>("action", &C::action, {"kill", "pause", "partition", "burst_loss", "restart"},
                              "`kill`: the process dies (for good, unless a later `restart` brings it back); "
                              "`pause`: it stops for `ticks` ticks and comes back (a supernode afresh); "
                              "`partition`: the handoffs between two supernodes are lost; `burst_loss`: every hop "
                              "fails with probability `pte`; `restart`: a new process takes a killed supernode's "
                              "place from `tick` on, afresh, and its group is handed back to it"),
                    "`kill`, `pause`, `partition`, `burst_loss`, `restart`", "required"),
          withNotes(choice<C>("role", &C::role, {"node", "supernode"},
                              "kill, pause, restart: a node tile (its sensors fall silent) or a supernode (its "
                              "tracking group is re-homed to the nearest live supernodes, which adopt its last "
                              "tracks); only a supernode restarts"),
                    "`node`, `supernode`", "required by kill, pause and restart"),
          withNotes(integer<C>("index", &C::index, 0, 1e6, "", "kill, pause, restart: which tile or supernode"),
                    "below run.node_processes or the number of supernodes",
                    "required by pause and restart; by kill unless it has `count`"),
          withNotes(integer<C>("count", &C::count, 0, 1e6, "",
                               "kill, in place of `index`: how many tiles or supernodes die at once, drawn from "
                               "run.seed among those no other fault of the list names (0: none, the baseline of "
                               "a sweep over it)"),
                    "[0, the processes free to draw from]", "none"),
          withNotes(integer<C>("ticks", &C::ticks, 1, 1e6, "ticks", "pause, partition, burst_loss: how long it holds"),
                    "[1, 10^6]", "required by pause, partition and burst_loss"),
          withNotes(real<C>("pte", &C::pte, kProbability, "", "burst_loss: the per-hop transmission failure rate "
                                                           "meanwhile, in place of network.pte"),
                    "[0, 1]", "required by burst_loss"),
          nested<C>("between", "`[[supernode, A], [supernode, B]]`", "required by partition",
                    "two different supernodes", "partition: the two supernodes whose handoffs are lost"),
      }};
  return table;
}

const FieldTable<NetworkConfig>& network() {
  using C = NetworkConfig;
  static const FieldTable<C> table{
      "network",
      {
          real<C>("communication_range", &C::communication_range, kPositive, "separations",
                  "radio range of the communication graph; the default is calibrated against Oh §VII-E, see "
                  "`docs/NETWORK.md`"),
          real<C>("pte", &C::pte, kProbability, "per hop",
                  "transmission failure rate. A report k hops away arrives with probability 1 − (1 − (1 − "
                  "pte)^k)^k"),
          real<C>("pde", &C::pde, kProbability, "per hop", "delay rate. The delay is NegBin(k, pde) ticks, eq. (7)"),
      }};
  return table;
}

const FieldTable<TrackerConfig>& tracker() {
  using C = TrackerConfig;
  static const FieldTable<C> table{
      "tracker",
      {
          withNotes(text<C>("engine", &C::engine,
                            "the engine every supernode runs: `mcmcda` (sliding-window MCMCDA), `gnn` (the "
                            "baseline), `rulebased` (An et al.'s centroid tracker, `docs/RULEBASED.md`) or `sbmht` (the ONERA "
                            "structured-branching MHT, `docs/ONERA.md`)"),
                    "a registered engine (`wsntrack components`)"),
          integer<C>("window_size", &C::window_size, 1, 1000, "ticks",
                     "ws, the sliding window of delivered observations (§VI–VII). A report delayed by ws ticks or "
                     "more cannot be placed"),
          nested<C>("params", "mapping name → number", "`{}`", "names and ranges per engine",
                    "engine parameters. A parameter left out takes the engine's default"),
      }};
  return table;
}

const FieldTable<AggregatorConfig>& aggregator() {
  using C = AggregatorConfig;
  static const FieldTable<C> table{
      "aggregator",
      {
          withNotes(text<C>("association", &C::association,
                            "`mcmcda`: the supernodes' tracks at their observed ticks form Yc and sliding-window "
                            "MCMCDA links them into global tracks; `gated`: the one-scan gated merge of each tick's "
                            "tracks (`docs/AGGREGATION.md`)"),
                    "a registered method (`wsntrack components`)"),
          nested<C>("params", "mapping name → number", "`{}`", "names and ranges per method",
                    "method parameters; one left out takes its default"),
      }};
  return table;
}

const FieldTable<MetricsConfig>& metrics() {
  using C = MetricsConfig;
  constexpr Range kOrder = closed(1.0, 100.0);
  static const FieldTable<C> table{
      "metrics",
      {
          real<C>("ospa_c", &C::ospa_c, kPositive, "separations",
                  "OSPA cut-off c (Schuhmacher, Vo & Vo 2008): the error charged for a missed or false target"),
          real<C>("ospa_p", &C::ospa_p, kOrder, "", "OSPA order p"),
          real<C>("eps_x_gate", &C::eps_x_gate, kPositive, "separations",
                  "eps_x_gated: Oh eq. (10) counting only the matched pairs closer than this (eps_x counts every "
                  "pair, as the paper does)"),
          real<C>("gospa_c", &C::gospa_c, kPositive, "separations",
                  "GOSPA cut-off c (α = 2, Rahmathullah et al. 2017): a missed or false target costs c^p / 2"),
          real<C>("gospa_p", &C::gospa_p, kOrder, "", "GOSPA order p"),
          real<C>("mot_threshold", &C::mot_threshold, kPositive, "separations",
                  "CLEAR-MOT match threshold T (Bernardin & Stiefelhagen 2008): a track corresponds to a target "
                  "only closer than T. Also the distance within which a second track on a tracked target is a "
                  "duplicate"),
          real<C>("quality_gate", &C::quality_gate, kPositive, "separations",
                  "RSE, TLR and ⟨dx⟩: a track is associated with a target only within this distance"),
          real<C>("boundary_band", &C::boundary_band, kNonNegative, "separations",
                  "a target at most this far from the bisector between its nearest and second-nearest supernode "
                  "is at a tracking-group boundary; its duplicates, identity switches and fragmentations are "
                  "counted apart from the interior ones. With one supernode everything is interior"),
      }};
  return table;
}

const FieldTable<RunConfig>& run() {
  using C = RunConfig;
  static const FieldTable<C> table{
      "run",
      {
          withNotes(integer<C>("ticks", &C::ticks, 1, 1e6, "ticks",
                               "T, the length of the run. `wsntrack run --ticks` overrides it"),
                    "[1, 10^6]"),
          unsigned64<C>("seed", &C::seed, "", "the seed of every random stream. `--seed` overrides it"),
          withNotes(integer<C>("node_processes", &C::node_processes, 1, 64, "processes",
                               "sensor-node tiles, one process each. The results do not depend on it. `--nodes` "
                               "overrides it"),
                    "[1, 64], at most the number of 2 Rs cells over the region"),
          integer<C>("max_ticks_in_flight", &C::max_ticks_in_flight, 1, 64, "ticks",
                     "back-pressure bound of the lockstep pipeline"),
          integer<C>("supernode_processes", &C::supernode_processes, 0, 1024, "processes",
                     "processes the supernodes run in, each a group of consecutive supernodes sharing one DDS "
                     "participant (a supernode the faults kill or pause runs alone). 0: one per supernode up to "
                     "16 supernodes, else 16, as discovery grows with the participants. The results do not "
                     "depend on it"),
          choice<C>("security", &C::security, {"on", "off"},
                    "DDS Security: on, every participant authenticates with credentials the launcher makes for "
                    "the run and may only write its role's topics, so nothing else on the host can join, inject "
                    "or read the run (docs/SECURITY.md); off, any program on the host can. `wsntrack run "
                    "--security` overrides it. The results do not depend on it"),
          choice<C>("message_protection", &C::message_protection, {"sign", "encrypt"},
                    "with security on, how every message is protected: encrypt (AES-GCM and a MAC: nothing "
                    "unauthenticated gets in, nor can anything on the host read it) or sign (the MAC alone). They "
                    "cost the same (docs/SECURITY.md)"),
      }};
  return table;
}

const std::vector<std::string>& sectionNames() {
  static const std::vector<std::string> names = {"name",     "region",   "sensors",    "sensor_model", "localisation",
                                                 "targets",  "dynamics", "supernodes", "terrain", "network",      "tracker",
                                                 "aggregator", "metrics", "run", "faults"};
  return names;
}

std::vector<std::pair<std::string, std::string>> markdownTables() {
  return {
      {"name", markdownTable(topLevel())},
      {"region", markdownTable(region())},
      {"sensors", markdownTable(sensors())},
      {"sensors.list[]", markdownTable(placedSensor())},
      {"sensor_model", markdownTable(sensorModel())},
      {"localisation", markdownTable(localisation())},
      {"targets", markdownTable(targets())},
      {"targets.scripted[]", markdownTable(scriptedTarget())},
      {"targets.scripted[].stops[]", markdownTable(waypointStop())},
      {"dynamics", markdownTable(dynamics())},
      {"supernodes[]", markdownTable(supernode())},
      {"terrain", markdownTable(terrain())},
      {"terrain.roads[]", markdownTable(road())},
      {"terrain.masks[]", markdownTable(mask())},
      {"network", markdownTable(network())},
      {"tracker", markdownTable(tracker())},
      {"aggregator", markdownTable(aggregator())},
      {"metrics", markdownTable(metrics())},
      {"run", markdownTable(run())},
      {"faults[]", markdownTable(fault())},
  };
}

std::vector<config::KeyTable> keyTables() {
  using config::keyTable;
  return {keyTable("name", "", topLevel()),
          keyTable("region", "region", region()),
          keyTable("sensors", "sensors", sensors()),
          keyTable("sensors.list[]", "sensors.list[]", placedSensor()),
          keyTable("sensor_model", "sensor_model", sensorModel()),
          keyTable("localisation", "localisation", localisation()),
          keyTable("targets", "targets", targets()),
          keyTable("targets.scripted[]", "targets.scripted[]", scriptedTarget()),
          keyTable("targets.scripted[].stops[]", "targets.scripted[].stops[]", waypointStop()),
          keyTable("dynamics", "dynamics", dynamics()),
          keyTable("supernodes[]", "supernodes[]", supernode()),
          keyTable("terrain", "terrain", terrain()),
          keyTable("terrain.roads[]", "terrain.roads[]", road()),
          keyTable("terrain.masks[]", "terrain.masks[]", mask()),
          keyTable("network", "network", network()),
          keyTable("tracker", "tracker", tracker()),
          keyTable("aggregator", "aggregator", aggregator()),
          keyTable("metrics", "metrics", metrics()),
          keyTable("run", "run", run()),
          keyTable("faults[]", "faults[]", fault())};
}

}  // namespace wsn::common::schema
