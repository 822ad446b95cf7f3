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

int main(int argc, char **argv) {
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
  const long domain = strtol(argv[1], &end, 10);
  if (*end != '\0' || domain < 0 || domain > 230) {
    fprintf(stderr, "watch_tracks: DOMAIN must be a number in [0, 230], got '%s'\n", argv[1]);
    return 2;
  }
  const uint64_t run_id = strtoull(argv[2], &end, 16);
  if (*end != '\0' || run_id == 0) {
    fprintf(stderr, "watch_tracks: RUN_ID must be the run's hexadecimal id, got '%s'\n", argv[2]);
    return 2;
  }
  const double timeout_s = argc == 4 ? strtod(argv[3], &end) : 60.0;
  if (argc == 4 && (*end != '\0' || !(timeout_s > 0))) {
    fprintf(stderr, "watch_tracks: TIMEOUT_S must be a positive number of seconds, got '%s'\n", argv[3]);
    return 2;
  }
  signal(SIGINT, on_signal);
  signal(SIGTERM, on_signal);

  const dds_entity_t participant = dds_create_participant((dds_domainid_t)domain, NULL, NULL);
  if (participant < 0) return fail("dds_create_participant (is the participant index free?)", participant);
  /* The topic names and types of the cluster (common/dds/role_runtime.hpp). */
  const dds_entity_t tracks_topic =
      dds_create_topic(participant, &wsn_msg_GlobalTrackBatch_desc, "wsn_global_track_batch", NULL, NULL);
  const dds_entity_t metrics_topic = dds_create_topic(participant, &wsn_msg_TickMetrics_desc, "wsn_tick_metrics", NULL, NULL);
  const dds_entity_t status_topic =
      dds_create_topic(participant, &wsn_msg_ProcessStatus_desc, "wsn_process_status", NULL, NULL);
  if (tracks_topic < 0 || metrics_topic < 0 || status_topic < 0) return fail("dds_create_topic", -1);

  /* The batches: reliable and KEEP_ALL like their writers, so that no tick is missed. */
  dds_qos_t *qos = dds_create_qos();
  dds_qset_reliability(qos, DDS_RELIABILITY_RELIABLE, DDS_SECS(30));
  dds_qset_history(qos, DDS_HISTORY_KEEP_ALL, 0);
  const dds_entity_t tracks_reader = dds_create_reader(participant, tracks_topic, qos, NULL);
  const dds_entity_t metrics_reader = dds_create_reader(participant, metrics_topic, qos, NULL);
  /* The status: TRANSIENT_LOCAL, so that a late joiner still gets every process's last state. */
  dds_qset_history(qos, DDS_HISTORY_KEEP_LAST, 1);
  dds_qset_durability(qos, DDS_DURABILITY_TRANSIENT_LOCAL);
  const dds_entity_t status_reader = dds_create_reader(participant, status_topic, qos, NULL);
  dds_delete_qos(qos);
  if (tracks_reader < 0 || metrics_reader < 0 || status_reader < 0) return fail("dds_create_reader", -1);

  const dds_entity_t waitset = dds_create_waitset(participant);
  const dds_entity_t readers[3] = {tracks_reader, metrics_reader, status_reader};
  for (int i = 0; i < 3; i++) {
    const dds_entity_t condition = dds_create_readcondition(readers[i], DDS_ANY_STATE);
    if (condition < 0 || dds_waitset_attach(waitset, condition, readers[i]) < 0) return fail("waitset", -1);
  }

  struct held_tick held = {0};
  uint32_t held_tracks = 0;
  int32_t done_tick = -1, last_printed = 0;
  dds_time_t done_at = 0, last_data = dds_time();
  int exit_code = -1;
  void *samples[MAX_SAMPLES];
  dds_sample_info_t infos[MAX_SAMPLES];

  while (exit_code < 0) {
    if (interrupted) {
      exit_code = 130;
      break;
    }
    dds_attach_t triggered[3];
    dds_waitset_wait(waitset, triggered, 3, DDS_MSECS(100));
    const dds_time_t now = dds_time();

    dds_return_t n;
    memset(samples, 0, sizeof samples);
    while ((n = dds_take(tracks_reader, samples, infos, MAX_SAMPLES, MAX_SAMPLES)) > 0) {
      for (dds_return_t i = 0; i < n; i++) {
        const wsn_msg_GlobalTrackBatch *batch = samples[i];
        if (!infos[i].valid_data || batch->run_id != run_id) continue;
        print_held(&held, held_tracks); /* its metrics never came: print without */
        held.valid = 1;
        held.tick = batch->tick;
        held.arrived = now;
        held.line = describe_tracks(batch);
        held.has_metrics = 0;
        held_tracks = batch->tracks._length;
        last_data = now;
      }
      dds_return_loan(tracks_reader, samples, n);
      memset(samples, 0, sizeof samples);
    }
    while ((n = dds_take(metrics_reader, samples, infos, MAX_SAMPLES, MAX_SAMPLES)) > 0) {
      for (dds_return_t i = 0; i < n; i++) {
        const wsn_msg_TickMetrics *m = samples[i];
        if (!infos[i].valid_data || m->run_id != run_id) continue;
        if (held.valid && held.tick == m->tick) {
          held.truth_targets = metric_value(m, "truth_targets");
          held.ospa = metric_value(m, "ospa");
          held.gospa = metric_value(m, "gospa");
          held.eps_k = metric_value(m, "eps_k_running");
          held.has_metrics = 1;
        }
      }
      dds_return_loan(metrics_reader, samples, n);
      memset(samples, 0, sizeof samples);
    }
    while ((n = dds_take(status_reader, samples, infos, MAX_SAMPLES, MAX_SAMPLES)) > 0) {
      for (dds_return_t i = 0; i < n; i++) {
        const wsn_msg_ProcessStatus *s = samples[i];
        if (!infos[i].valid_data || s->run_id != run_id) continue;
        last_data = now;
        if (s->state == wsn_msg_FAILED) {
          fprintf(stderr, "watch_tracks: %s %" PRIu32 " FAILED: %s\n", s->role, s->index, s->message);
          exit_code = 1;
        } else if (s->state == wsn_msg_DONE && strcmp(s->role, "aggregator") == 0 && done_tick < 0) {
          done_tick = s->tick;
          done_at = now;
        }
      }
      dds_return_loan(status_reader, samples, n);
      memset(samples, 0, sizeof samples);
    }

    /* A held tick is printed once its metrics are in, or when they will not come: no writer of
     * them, or half a second went by. */
    dds_subscription_matched_status_t metrics_writers;
    dds_get_subscription_matched_status(metrics_reader, &metrics_writers);
    if (held.valid && (held.has_metrics || metrics_writers.current_count == 0 || now - held.arrived > DDS_MSECS(500))) {
      last_printed = held.tick;
      print_held(&held, held_tracks);
    }
    /* The end: DONE, and the last tick printed (or two seconds' grace for it). */
    if (done_tick >= 0 && (last_printed >= done_tick || now - done_at > DDS_SECS(2))) {
      if (held.valid) {
        last_printed = held.tick;
        print_held(&held, held_tracks);
      }
      printf("done at tick %" PRId32 "\n", done_tick);
      exit_code = 0;
    }
    if (exit_code < 0 && (double)(now - last_data) / 1e9 > timeout_s) {
      fprintf(stderr, "watch_tracks: nothing from run %" PRIx64 " for %.1f s\n", run_id, timeout_s);
      exit_code = 1;
    }
  }
  free(held.line);
  dds_delete(participant);
  return exit_code;
}
