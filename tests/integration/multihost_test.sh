#!/usr/bin/env bash
# One run over three "hosts": Linux network namespaces joined by a bridge (in a namespace of its
# own), each with its own address, the launcher in the first and roles started in the others with
# `ip netns exec`. DDS traffic between them crosses the bridge by unicast; nothing leaves the
# namespaces this test makes, and the test removes them at its end.
# Usage: multihost_test.sh BIN_DIR SOURCE_DIR WORK_DIR CASE
# Exit status 77 (ctest: skipped, with the reason) where namespaces cannot be made (not root, no
# `ip`, a container without CAP_SYS_ADMIN).
set -uo pipefail
bin="$1"; src="$2"; work="$3"; case_name="$4"
wsntrack="$bin/wsntrack"
rm -rf "$work/$case_name"; mkdir -p "$work/$case_name"; cd "$work/$case_name" || exit 1

fail() { echo "FAIL: $*" >&2; exit 1; }
skip() { echo "SKIPPED: $*" >&2; exit 77; }

# Namespace names unique to this test process: concurrent runs of the suite do not meet.
ns="wsnt$$"
cleanup() { for n in "$ns-h1" "$ns-h2" "$ns-h3" "$ns-sw"; do ip netns delete "$n" 2>/dev/null; done; }
trap cleanup EXIT

command -v ip >/dev/null || skip "no 'ip' command (Debian: iproute2) to make network namespaces"
ip netns add "$ns-sw" 2>netns.err || skip "cannot make a network namespace here ($(cat netns.err)); run as root"
ip -n "$ns-sw" link add br0 type bridge && ip -n "$ns-sw" link set br0 up || fail "cannot make the bridge"
for i in 1 2 3; do
  ip netns add "$ns-h$i" &&
    ip -n "$ns-h$i" link set lo up &&
    ip -n "$ns-h$i" link add eth0 type veth peer name p$i netns "$ns-sw" &&
    ip -n "$ns-sw" link set p$i master br0 up &&
    ip -n "$ns-h$i" addr add "10.77.0.$i/24" dev eth0 &&
    ip -n "$ns-h$i" link set eth0 up || fail "cannot set up host $i"
done

# Bytes host $1's port on the bridge has carried, both ways.
bridged_bytes() { ip -n "$ns-sw" -s -j link show "p$1" | python3 -c 'import json, sys; s = json.load(sys.stdin)[0]["stats64"]; print(s["rx"]["bytes"] + s["tx"]["bytes"])'; }

# The hosts file: the launcher's host h1 runs the network model and the aggregator; h2 and h3 each
# a tile and two supernodes. $1: how h3 starts a process (a YAML flow list).
hosts_file() {
  cat <<EOF
hosts:
  - name: h1
    address: 10.77.0.1
    roles: [network, aggregator]
  - name: h2
    address: 10.77.0.2
    start: ip netns exec $ns-h2
    roles: [node 0, supernode 0-1]
  - name: h3
    address: 10.77.0.3
    start: $1
    roles: [node 1, supernode 2-3]
EOF
}

same_outputs() {
  for f in tracks.csv tracks_supernode.csv tracks_settled.csv observations.csv truth.csv network.json metrics_per_tick.csv scenario.yaml; do
    cmp -s "$1/$f" "$2/$f" || fail "$f differs between $1 and $2"
  done
  diff <(grep -v -e '"timing"' -e '"provenance"' "$1/metrics.json") <(grep -v -e '"timing"' -e '"provenance"' "$2/metrics.json") >/dev/null ||
    fail "metrics.json differs between $1 and $2"
}

# Runs scenario $1 on this host (loopback) into $2, and over the three hosts into $3.
run_both() {
  timeout 300 "$wsntrack" run "$1" --quiet --no-plot --out "$PWD/$2" >"$2.stdout" 2>"$2.stderr" ||
    { cat "$2.stderr" >&2; fail "the single-host run of $1 failed"; }
  timeout 300 ip netns exec "$ns-h1" "$wsntrack" run "$1" --quiet --no-plot --out "$PWD/$3" --hosts hosts.yaml \
    >"$3.stdout" 2>"$3.stderr" ||
    { cat "$3.stderr" >&2; for f in "$3"/logs/*.log; do echo "== $f" >&2; tail -5 "$f" >&2; done; fail "the run over three hosts failed"; }
}

# shellcheck source=common.sh
. "$(dirname "$0")/common.sh"

case "$case_name" in
  outputs)
    # The same scenario and seed on one host and over three: byte-identical outputs, with and
    # without faults (the kill, pause and restart of roles on other hosts enacted by the roles
    # themselves, not by the launcher's signals).
    hosts_file "[ip, netns, exec, $ns-h3]" >hosts.yaml
    before=( "$(bridged_bytes 1)" "$(bridged_bytes 2)" "$(bridged_bytes 3)" )
    run_both "$src/scenarios/oh_quadrants.yaml" one three
    same_outputs one three
    for i in 1 2 3; do
      [ "$(bridged_bytes $i)" -gt $(( ${before[i-1]} + 10000 )) ] || fail "host $i's DDS traffic did not cross the bridge"
    done
    grep -q "over 3 hosts (h1 10.77.0.1, h2 10.77.0.2, h3 10.77.0.3)" three.stderr || { cat three.stderr >&2; fail "the start line does not name the hosts"; }
    grep -q "node 0@h2 .*supernode 3@h3 .*aggregator 0@h1 " three.stdout || { cat three.stdout >&2; fail "the summary does not say where each process ran"; }
    grep -q "multi-process over DDS, over 3 hosts" three.stdout || { cat three.stdout >&2; fail "the summary's mode does not count the hosts"; }
    cmp -s hosts.yaml three/hosts.yaml || fail "the run directory does not keep the hosts file"
    [ -f three/cyclonedds-h2.xml ] && grep -q '<NetworkInterface address="10.77.0.2"/>' three/cyclonedds-h2.xml ||
      fail "no Cyclone configuration of h2 with its own address"
    grep -q '<Peer address="10.77.0.1"/><Peer address="10.77.0.2"/><Peer address="10.77.0.3"/>' three/cyclonedds.xml ||
      fail "the launcher's host does not list every host as a peer"

    # A launcher started outside the first host, and a host whose start command fails, are named.
    "$wsntrack" run "$src/scenarios/oh_quadrants.yaml" --quiet --no-plot --out "$PWD/outside" --hosts hosts.yaml \
      >outside.stdout 2>outside.stderr; rc=$?
    [ "$rc" -eq 2 ] || { cat outside.stderr >&2; fail "a launcher outside h1 gave exit $rc, expected 2"; }
    grep -qF "hosts.yaml:2: the first host (h1) is the launcher's own, but no interface here has 10.77.0.1" outside.stderr ||
      { cat outside.stderr >&2; fail "no clear message for a launcher outside h1"; }
    hosts_file "[ip, netns, exec, $ns-nowhere]" >bad_start.yaml
    timeout 60 ip netns exec "$ns-h1" "$wsntrack" run "$src/scenarios/oh_quadrants.yaml" --quiet --no-plot \
      --out "$PWD/bad_start" --hosts bad_start.yaml >bad_start.stdout 2>bad_start.stderr; rc=$?
    [ "$rc" -eq 1 ] || { cat bad_start.stderr >&2; fail "a failing start command gave exit $rc, expected 1"; }
    grep -qF "(on host h3, started by 'ip netns exec $ns-nowhere', hosts file line 9)" bad_start.stderr ||
      { cat bad_start.stderr >&2; fail "the failure does not name the host and its start command"; }
    grep -q '"status": "failed"' bad_start/run.json || fail "the run with a failing start command is not marked failed"

    run_both "$src/scenarios/oh_quadrants_faults.yaml" one_faults three_faults
    same_outputs one_faults three_faults
    grep -q "ended as the scenario's faults asked (kill of supernode 2 at tick 40)" three_faults/logs/supernode-2.log ||
      fail "supernode 2 on h3 did not enact its own kill"
    [ -f three_faults/logs/supernode-2-from-80.log ] || fail "supernode 2 was not restarted on h3"
    grep -q "restart of supernode 2 at tick 80: [1-9][0-9]* tracks taken back" three_faults.stdout ||
      { cat three_faults.stdout >&2; fail "the summary does not report the restart"; }
    no_leftovers ;;
  lifeline)
    # A start command that does not become the role (as ssh does not: the role runs under sshd on
    # the other host, not under the launcher): h3's roles run as children of a shell. Killed with
    # -9, the launcher cannot stop them; their standard input, the launcher's pipe, closes, and
    # they end within their stop grace (2 s).
    hosts_file "[ip, netns, exec, $ns-h3, sh, -c, '\"\$@\"; exit \$?', sh]" >hosts.yaml
    ip netns exec "$ns-h1" "$wsntrack" run "$src/scenarios/oh_quadrants.yaml" --quiet --no-plot --out "$PWD/run" \
      --hosts hosts.yaml --tick-interval 0.2 >run.stdout 2>run.stderr &
    launcher=$!
    for _ in $(seq 1 100); do pgrep -f "wsntrack-supernode.*--run-dir $PWD/run .*--index 3" >/dev/null && break; sleep 0.1; done
    sleep 1  # into the tick loop (100 ticks paced at 0.2 s)
    # A viewer outside the launcher's namespace is told where to watch from.
    "$wsntrack" watch "$PWD/run" --plain --timeout 5 >watch.stdout 2>watch.stderr; rc=$?
    [ "$rc" -eq 1 ] || { cat watch.stderr >&2; fail "watch outside h1 gave exit $rc, expected 1"; }
    grep -qF "this run's launcher host uses address 10.77.0.1, which no interface here has" watch.stderr ||
      { cat watch.stderr >&2; fail "watch outside h1 does not say where to watch from"; }
    pgrep -f "wsntrack-supernode.*--run-dir $PWD/run .*--index 3" >/dev/null || { cat run.stderr >&2; fail "supernode 3 is not running on h3"; }
    kill -9 "$launcher"; wait "$launcher" 2>/dev/null
    for _ in $(seq 1 50); do pgrep -f "wsntrack-.*--run-dir $PWD/run " >/dev/null || break; sleep 0.1; done
    if pgrep -f "wsntrack-.*--run-dir $PWD/run " >/dev/null; then
      pgrep -af "wsntrack-.*--run-dir $PWD/run " >&2
      for pid in $(pgrep -f "wsntrack-.*--run-dir $PWD/run "); do kill -9 "$pid"; done
      fail "roles outlived their launcher by 5 s"
    fi
    grep -q "standard input (the launcher's lifeline) closed: stopping" run/logs/supernode-3.log ||
      { cat run/logs/supernode-3.log >&2; fail "supernode 3 did not say why it stopped"; }
    no_leftovers ;;
  *) fail "unknown case $case_name" ;;
esac
echo "PASS: multihost.$case_name"
