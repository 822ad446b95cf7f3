/* watch_tracks: follows a running wsntrack cluster from outside the project, in plain C against
 * the types idlc generates from idl/wsntrack.idl, and prints one line per tick:
 *
 *   tick=37 K=9 K*=10 OSPA=3.214 GOSPA=12.302 epsK=0.0412 tracks=[1125899906842628@(34.47,96.28) ...]
 *
 * It joins the run the way every process of the cluster does: the run directory's
 * cyclonedds.xml (loopback only, the run's discovery tag) through CYCLONEDDS_URI, with its
 * participant index from WSN_PARTICIPANT_INDEX (one of the run's viewer slots, run.json), on the
 * run's domain id. See examples/README.md.
 *
 * Usage: CYCLONEDDS_URI=file://RUN_DIR/cyclonedds.xml WSN_PARTICIPANT_INDEX=N \
 *          watch_tracks DOMAIN RUN_ID [TIMEOUT_S]
 * Exit status: 0 when the aggregator reported DONE, 1 when the run failed or nothing arrived
 * for TIMEOUT_S seconds (default 60), 2 for bad arguments. */
#include <dds/dds.h>
#include <inttypes.h>
#include <math.h>
#include <signal.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "wsntrack.h"

#define MAX_SAMPLES 16

static volatile sig_atomic_t interrupted = 0;
static void on_signal(int sig) {
  (void)sig;
  interrupted = 1;
}

/* The tick whose tracks are held until its TickMetrics arrive (they follow on another topic). */
struct held_tick {
  int valid;
  int32_t tick;
  dds_time_t arrived;
  char *line; /* "K=.. " part and the track list, built when the batch arrived */
  int has_metrics;
  double truth_targets, ospa, gospa, eps_k; /* copied out: the sample's strings go with its loan */
};

/* TickMetrics carries every metric's values by name (docs/METRICS.md); NAN if one is absent. */
static double metric_value(const wsn_msg_TickMetrics *m, const char *name) {
  for (uint32_t i = 0; i < m->values._length; i++)
    if (strcmp(m->values._buffer[i].name, name) == 0) return m->values._buffer[i].value;
  return NAN;
}

/* Appends printf-formatted text to a growing heap string. */
static void append(char **text, size_t *used, size_t *size, const char *format, ...) {
  va_list args;
  va_start(args, format);
  const int needed = vsnprintf(NULL, 0, format, args);
  va_end(args);
  if (needed < 0) abort();
  if (*used + (size_t)needed + 1 > *size) {
    *size = 2 * (*used + (size_t)needed + 1);
    *text = realloc(*text, *size);
    if (*text == NULL) abort();
  }
  va_start(args, format);
  vsnprintf(*text + *used, *size - *used, format, args);
  va_end(args);
  *used += (size_t)needed;
}

static char *describe_tracks(const wsn_msg_GlobalTrackBatch *batch) {
  char *text = NULL;
  size_t used = 0, size = 0;
  append(&text, &used, &size, "tracks=[");
  for (uint32_t i = 0; i < batch->tracks._length; i++) {
    const wsn_msg_TrackEstimate *t = &batch->tracks._buffer[i];
    append(&text, &used, &size, "%s%" PRIu64 "@(%.2f,%.2f)", i ? " " : "", t->track, t->x, t->y);
  }
  append(&text, &used, &size, "]");
  return text;
}

static void print_held(struct held_tick *held, uint32_t tracks) {
  if (!held->valid) return;
  if (held->has_metrics)
    printf("tick=%" PRId32 " K=%u K*=%.0f OSPA=%.3f GOSPA=%.3f epsK=%.4f %s\n", held->tick, tracks, held->truth_targets,
           held->ospa, held->gospa, held->eps_k, held->line);
  else
    printf("tick=%" PRId32 " K=%u K*=n/a OSPA=n/a GOSPA=n/a epsK=n/a %s\n", held->tick, tracks, held->line);
  fflush(stdout);
  free(held->line);
  held->line = NULL;
  held->valid = 0;
}

static int fail(const char *what, dds_return_t rc) {
  fprintf(stderr, "watch_tracks: %s: %s\n", what, dds_strretcode(rc));
  return 1;
}

struct options {
  long domain;
  uint64_t run_id;
  double timeout_s;
};

/* Reads DOMAIN RUN_ID [TIMEOUT_S] and checks the environment; 0 when usable, else the exit status. */
static int parse_options(int argc, char **argv, struct options *o) {
  if (argc < 3 || argc > 4) {
    fprintf(stderr,
            "usage: CYCLONEDDS_URI=file://RUN_DIR/cyclonedds.xml WSN_PARTICIPANT_INDEX=N %s DOMAIN RUN_ID [TIMEOUT_S]\n"
            "  DOMAIN, RUN_ID (hex) and the viewer participant indices are in RUN_DIR/run.json\n",
            argv[0]);
    return 2;
  }
  /* Cyclone's default configuration would multicast on the outer interface: only ever join
   * with the run's own configuration. */
  const char *uri = getenv("CYCLONEDDS_URI");
  if (uri == NULL || uri[0] == '\0' || getenv("WSN_PARTICIPANT_INDEX") == NULL) {
    fprintf(stderr, "watch_tracks: set CYCLONEDDS_URI to the run's cyclonedds.xml and WSN_PARTICIPANT_INDEX to a "
                    "viewer slot of run.json\n");
    return 2;
  }
  char *end = NULL;
  o->domain = strtol(argv[1], &end, 10);
  if (*end != '\0' || o->domain < 0 || o->domain > 230) {
    fprintf(stderr, "watch_tracks: DOMAIN must be a number in [0, 230], got '%s'\n", argv[1]);
    return 2;
  }
  o->run_id = strtoull(argv[2], &end, 16);
  if (*end != '\0' || o->run_id == 0) {
    fprintf(stderr, "watch_tracks: RUN_ID must be the run's hexadecimal id, got '%s'\n", argv[2]);
    return 2;
  }
  o->timeout_s = argc == 4 ? strtod(argv[3], &end) : 60.0;
  if (argc == 4 && (*end != '\0' || !(o->timeout_s > 0))) {
    fprintf(stderr, "watch_tracks: TIMEOUT_S must be a positive number of seconds, got '%s'\n", argv[3]);
    return 2;
  }
  return 0;
}

struct readers {
  dds_entity_t participant, tracks, metrics, status, waitset;
};

/* Joins the domain and reads the cluster's three live-view topics, all attached to one waitset;
 * 0 when done, else the exit status (the reason printed). */
static int open_readers(long domain, struct readers *r) {
  r->participant = dds_create_participant((dds_domainid_t)domain, NULL, NULL);
  if (r->participant < 0) return fail("dds_create_participant (is the participant index free?)", r->participant);
  /* The topic names and types of the cluster (common/dds/role_runtime.hpp). */
  const dds_entity_t tracks_topic =
      dds_create_topic(r->participant, &wsn_msg_GlobalTrackBatch_desc, "wsn_global_track_batch", NULL, NULL);
  const dds_entity_t metrics_topic =
      dds_create_topic(r->participant, &wsn_msg_TickMetrics_desc, "wsn_tick_metrics", NULL, NULL);
  const dds_entity_t status_topic =
      dds_create_topic(r->participant, &wsn_msg_ProcessStatus_desc, "wsn_process_status", NULL, NULL);
  if (tracks_topic < 0 || metrics_topic < 0 || status_topic < 0) return fail("dds_create_topic", -1);

  /* The batches: reliable and KEEP_ALL like their writers, so that no tick is missed. */
  dds_qos_t *qos = dds_create_qos();
  dds_qset_reliability(qos, DDS_RELIABILITY_RELIABLE, DDS_SECS(30));
  dds_qset_history(qos, DDS_HISTORY_KEEP_ALL, 0);
  r->tracks = dds_create_reader(r->participant, tracks_topic, qos, NULL);
  r->metrics = dds_create_reader(r->participant, metrics_topic, qos, NULL);
  /* The status: TRANSIENT_LOCAL, so that a late joiner still gets every process's last state. */
  dds_qset_history(qos, DDS_HISTORY_KEEP_LAST, 1);
  dds_qset_durability(qos, DDS_DURABILITY_TRANSIENT_LOCAL);
  r->status = dds_create_reader(r->participant, status_topic, qos, NULL);
  dds_delete_qos(qos);
  if (r->tracks < 0 || r->metrics < 0 || r->status < 0) return fail("dds_create_reader", -1);

  r->waitset = dds_create_waitset(r->participant);
  const dds_entity_t readers[3] = {r->tracks, r->metrics, r->status};
  for (int i = 0; i < 3; i++) {
    const dds_entity_t condition = dds_create_readcondition(readers[i], DDS_ANY_STATE);
    if (condition < 0 || dds_waitset_attach(r->waitset, condition, readers[i]) < 0) return fail("waitset", -1);
  }
  return 0;
}

/* What the watch knows between two wake-ups. */
struct watch_state {
  uint64_t run_id;
  dds_time_t now; /* of the current wake-up */
  struct held_tick held;
  uint32_t held_tracks;
  int32_t done_tick, last_printed;
  dds_time_t done_at, last_data;
  int exit_code; /* -1 while watching */
};

static void on_tracks(const void *sample, struct watch_state *w) {
  const wsn_msg_GlobalTrackBatch *batch = sample;
  if (batch->run_id != w->run_id) return;
  print_held(&w->held, w->held_tracks); /* its metrics never came: print without */
  w->held.valid = 1;
  w->held.tick = batch->tick;
  w->held.arrived = w->now;
  w->held.line = describe_tracks(batch);
  w->held.has_metrics = 0;
  w->held_tracks = batch->tracks._length;
  w->last_data = w->now;
}

static void on_metrics(const void *sample, struct watch_state *w) {
  const wsn_msg_TickMetrics *m = sample;
  if (m->run_id != w->run_id || !w->held.valid || w->held.tick != m->tick) return;
  w->held.truth_targets = metric_value(m, "truth_targets");
  w->held.ospa = metric_value(m, "ospa");
  w->held.gospa = metric_value(m, "gospa");
  w->held.eps_k = metric_value(m, "eps_k_running");
  w->held.has_metrics = 1;
}

static void on_status(const void *sample, struct watch_state *w) {
  const wsn_msg_ProcessStatus *s = sample;
  if (s->run_id != w->run_id) return;
  w->last_data = w->now;
  if (s->state == wsn_msg_FAILED) {
    fprintf(stderr, "watch_tracks: %s %" PRIu32 " FAILED: %s\n", s->role, s->index, s->message);
    w->exit_code = 1;
  } else if (s->state == wsn_msg_DONE && strcmp(s->role, "aggregator") == 0 && w->done_tick < 0) {
    w->done_tick = s->tick;
    w->done_at = w->now;
  }
}

/* Hands every valid sample the reader holds to `handle`, returning each loan. */
static void take_all(dds_entity_t reader, void (*handle)(const void *sample, struct watch_state *w),
                     struct watch_state *w) {
  void *samples[MAX_SAMPLES];
  dds_sample_info_t infos[MAX_SAMPLES];
  dds_return_t n;
  memset(samples, 0, sizeof samples);
  while ((n = dds_take(reader, samples, infos, MAX_SAMPLES, MAX_SAMPLES)) > 0) {
    for (dds_return_t i = 0; i < n; i++)
      if (infos[i].valid_data) handle(samples[i], w);
    dds_return_loan(reader, samples, n);
    memset(samples, 0, sizeof samples);
  }
}

/* Prints what is due and decides whether the watch is over. */
static void settle(const struct readers *r, double timeout_s, struct watch_state *w) {
  /* A held tick is printed once its metrics are in, or when they will not come: no writer of
   * them, or half a second went by. */
  dds_subscription_matched_status_t metrics_writers;
  dds_get_subscription_matched_status(r->metrics, &metrics_writers);
  if (w->held.valid &&
      (w->held.has_metrics || metrics_writers.current_count == 0 || w->now - w->held.arrived > DDS_MSECS(500))) {
    w->last_printed = w->held.tick;
    print_held(&w->held, w->held_tracks);
  }
  /* The end: DONE, and the last tick printed (or two seconds' grace for it). */
  if (w->done_tick >= 0 && (w->last_printed >= w->done_tick || w->now - w->done_at > DDS_SECS(2))) {
    if (w->held.valid) {
      w->last_printed = w->held.tick;
      print_held(&w->held, w->held_tracks);
    }
    printf("done at tick %" PRId32 "\n", w->done_tick);
    w->exit_code = 0;
  }
  if (w->exit_code < 0 && (double)(w->now - w->last_data) / 1e9 > timeout_s) {
    fprintf(stderr, "watch_tracks: nothing from run %" PRIx64 " for %.1f s\n", w->run_id, timeout_s);
    w->exit_code = 1;
  }
}

/* Follows the run until it is done, failed, silent for the timeout, or interrupted; the exit status. */
static int watch(const struct readers *r, const struct options *o) {
  struct watch_state w = {0};
  w.run_id = o->run_id;
  w.done_tick = -1;
  w.last_data = dds_time();
  w.exit_code = -1;
  while (w.exit_code < 0) {
    if (interrupted) {
      w.exit_code = 130;
      break;
    }
    dds_attach_t triggered[3];
    dds_waitset_wait(r->waitset, triggered, 3, DDS_MSECS(100));
    w.now = dds_time();
    take_all(r->tracks, on_tracks, &w);
    take_all(r->metrics, on_metrics, &w);
    take_all(r->status, on_status, &w);
    settle(r, o->timeout_s, &w);
  }
  free(w.held.line);
  return w.exit_code;
}

int main(int argc, char **argv) {
  struct options options;
  const int usage = parse_options(argc, argv, &options);
  if (usage != 0) return usage;
  signal(SIGINT, on_signal);
  signal(SIGTERM, on_signal);
  struct readers readers;
  const int opened = open_readers(options.domain, &readers);
  if (opened != 0) return opened;
  const int exit_code = watch(&readers, &options);
  dds_delete(readers.participant);
  return exit_code;
}
