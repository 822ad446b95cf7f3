#!/usr/bin/env bash
# Tests of what `cmake --install` and the .deb deliver: the installed wsntrack, run from outside the
# source and build trees, must find its role executables and plot script relative to itself.
# Usage: install_test.sh BUILD_DIR SOURCE_DIR CASE
#   prefix   cmake --install into a temporary prefix; the tree's files; a 10-tick run of the default
#            scenario from /; --help; the tools
#   deb      cpack -G DEB into a temporary directory; its control fields and file list; dpkg-deb -x and
#            a short run from there (never dpkg -i)
# The install layout comes from CMake (tests/install/CMakeLists.txt) in WSN_BINDIR, WSN_ROLE_DIR,
# WSN_DATA_DIR, WSN_DOC_DIR (relative), the package's directory under /usr and under any other prefix in
# WSN_PYTHON_DIR_USR and WSN_PYTHON_DIR_OTHER, and the version in WSN_VERSION. Exit 77: skipped.
set -uo pipefail
build="$1"; src="$2"; case_name="$3"
python=/usr/bin/python3

fail() { echo "FAIL: $*" >&2; exit 1; }
# Everything lands in a directory of its own outside both trees, removed on exit.
tmp=$(mktemp -d "${TMPDIR:-/tmp}/wsntrack-install-test.XXXXXX") || fail "mktemp"
trap 'rm -rf "$tmp"' EXIT
case "$tmp" in "$src"/* | "$build"/*) fail "$tmp is inside the source or build tree" ;; esac

have_matplotlib() { [ -x "$python" ] && "$python" -c "import matplotlib" 2>/dev/null; }

# The files of an installed tree under ROOT (a prefix, or usr/ of the extracted .deb), its python
# package in PYTHON_DIR (relative to ROOT).
check_tree() {
  local root="$1" WSN_PYTHON_DIR="$2" name
  for name in wsntrack wsntrack-network-calibrate; do
    [ -x "$root/$WSN_BINDIR/$name" ] || fail "$root/$WSN_BINDIR/$name missing or not executable"
  done
  for name in node network supernode aggregator; do
    [ -x "$root/$WSN_ROLE_DIR/wsntrack-$name" ] || fail "$root/$WSN_ROLE_DIR/wsntrack-$name missing or not executable"
    [ ! -e "$root/$WSN_BINDIR/wsntrack-$name" ] || fail "wsntrack-$name is in $WSN_BINDIR as well as $WSN_ROLE_DIR"
  done
  for name in plot_run.py sweep.py onera_table.py; do
    [ -x "$root/$WSN_DATA_DIR/tools/$name" ] || fail "$root/$WSN_DATA_DIR/tools/$name missing or not executable"
  done
  [ -x "$root/$WSN_DATA_DIR/tools/wsntrack_run.py" ] || fail "$root/$WSN_DATA_DIR/tools/wsntrack_run.py missing or not executable"
  # The package the tools are entry points over, every module of it, in the python path (the tools find
  # it through python-path), with the installed wsntrack's catalogue.
  (cd "$src/python" && find wsntrack -name '*.py' -not -path '*/__pycache__/*') | while read -r name; do
    cmp -s "$src/python/$name" "$root/$WSN_PYTHON_DIR/$name" || fail "$root/$WSN_PYTHON_DIR/$name missing or different"
  done || exit 1
  [ "$(cd "$root/$WSN_DATA_DIR/tools" && realpath "$(cat python-path)")" = "$(realpath "$root/$WSN_PYTHON_DIR")" ] ||
    fail "$root/$WSN_DATA_DIR/tools/python-path does not lead to $root/$WSN_PYTHON_DIR"
  "$python" -c "import json, sys; assert json.load(open(sys.argv[1]))['catalogue_version'] == 1" \
    "$root/$WSN_PYTHON_DIR/wsntrack/catalogue.json" || fail "$root/$WSN_PYTHON_DIR/wsntrack/catalogue.json"
  [ ! -e "$root/$WSN_DATA_DIR/python" ] || fail "the package is also in $root/$WSN_DATA_DIR/python"
  for name in "$src"/scenarios/*.yaml; do
    cmp -s "$name" "$root/$WSN_DATA_DIR/scenarios/$(basename "$name")" ||
      fail "$root/$WSN_DATA_DIR/scenarios/$(basename "$name") missing or different"
  done
  for name in "$src"/sweeps/*.yaml; do
    cmp -s "$name" "$root/$WSN_DATA_DIR/sweeps/$(basename "$name")" ||
      fail "$root/$WSN_DATA_DIR/sweeps/$(basename "$name") missing or different"
  done
  cmp -s "$src/idl/wsntrack.idl" "$root/$WSN_DATA_DIR/idl/wsntrack.idl" || fail "$root/$WSN_DATA_DIR/idl/wsntrack.idl"
  local docs=(README.md scenarios/README.md examples/README.md examples/watch_tracks.c)
  for name in "$src"/docs/*.md; do docs+=("docs/$(basename "$name")"); done
  for name in "${docs[@]}"; do
    [ -f "$root/$WSN_DOC_DIR/$name" ] || fail "$root/$WSN_DOC_DIR/$name missing"
  done
  # Test, bench and example binaries are not installed.
  local stray
  stray=$(find "$root" -name 'wsn_*' -o -name 'watch_tracks' -o -name 'CMakeLists.txt' -o -name '*.a')
  [ -z "$stray" ] || fail "installed but should not be: $stray"
}

# A 10-tick run of the default scenario by the installed wsntrack, from /, into OUT.
check_run() {
  local root="$1" out="$2" log="$tmp/run.log"
  local wsntrack="$root/$WSN_BINDIR/wsntrack"
  (cd / && timeout 120 "$wsntrack" run "$root/$WSN_DATA_DIR/scenarios/oh_quadrants.yaml" --ticks 10 --out "$out" \
     --quiet >"$log" 2>&1)
  local status=$?
  [ "$status" -eq 0 ] || { cat "$log" >&2; fail "installed wsntrack run exited $status"; }
  for name in metrics.json tracks.csv truth.csv run.json; do
    [ -s "$out/$name" ] || fail "$out/$name missing after the run"
  done
  if have_matplotlib; then
    for name in tracks cardinality ospa; do
      [ -s "$out/plots/$name.png" ] || { cat "$log" "$out/logs/plot.log" >&2; fail "$out/plots/$name.png not drawn"; }
    done
  else
    grep -q "plots *none" "$log" || fail "no matplotlib, but the summary does not say why there are no plots"
  fi
  (cd / && "$wsntrack" --help) | grep -q "Usage: wsntrack" || fail "installed wsntrack --help"
}

case "$case_name" in
  prefix)
    prefix="$tmp/prefix"
    cmake --install "$build" --prefix "$prefix" >"$tmp/install.log" 2>&1 || { cat "$tmp/install.log" >&2; fail "cmake --install"; }
    check_tree "$prefix" "$WSN_PYTHON_DIR_OTHER"
    check_run "$prefix" "$tmp/run"
    wsntrack="$prefix/$WSN_BINDIR/wsntrack"
    # Without a role executable the run stops before it starts, naming both places it looked.
    mv "$prefix/$WSN_ROLE_DIR/wsntrack-node" "$tmp/moved-node"
    message=$(cd / && "$wsntrack" run "$prefix/$WSN_DATA_DIR/scenarios/oh_quadrants.yaml" --ticks 2 --out "$tmp/run-broken" 2>&1)
    status=$?
    mv "$tmp/moved-node" "$prefix/$WSN_ROLE_DIR/wsntrack-node"
    [ "$status" -eq 1 ] || fail "a missing role executable gave exit $status, expected 1: $message"
    echo "$message" | grep -qF "$prefix/$WSN_BINDIR" && echo "$message" | grep -qF "$prefix/$WSN_ROLE_DIR" ||
      fail "the missing-role message does not name both places: $message"
    [ ! -e "$tmp/run-broken" ] || fail "a run directory was made although the roles are missing"
    # The tools from their installed place.
    "$python" "$prefix/$WSN_DATA_DIR/tools/sweep.py" --help >/dev/null || fail "installed sweep.py --help"
    # An installed spec finds its scenario in the installed data directory (one seed, 5 ticks).
    (cd / && "$python" "$prefix/$WSN_DATA_DIR/tools/sweep.py" "$prefix/$WSN_DATA_DIR/sweeps/oh_fig7_pte.yaml" \
       --wsntrack "$wsntrack" --seeds 1 --set run.ticks=5 --out "$tmp/sweep-installed" >/dev/null 2>"$tmp/sweep.err") ||
      { cat "$tmp/sweep.err" >&2; fail "installed sweep spec"; }
    [ -s "$tmp/sweep-installed/summary.csv" ] || fail "installed sweep spec wrote no summary.csv"
    (cd / && "$wsntrack" replay --help) >/dev/null 2>&1 || fail "installed wsntrack replay --help (plot script not found?)"
    (cd / && PYTHONPATH="$prefix/$WSN_DATA_DIR/tools" "$python" -c "
import sys, wsntrack_run
run = wsntrack_run.load_run(sys.argv[1])
assert run.ticks == 10, run.ticks
" "$tmp/run") || fail "the installed loader cannot load the run"
    # The package itself, as analysis code imports it: its facts from the installed catalogue, with no
    # wsntrack on PATH or in WSNTRACK.
    (cd / && env -u WSNTRACK PATH=/usr/bin:/bin PYTHONPATH="$prefix/$WSN_PYTHON_DIR_OTHER" "$python" -c "
import sys, wsntrack.rundir, wsntrack.loader
assert wsntrack.rundir.TARGET_CLASSES[0] == 'wheeled_light', wsntrack.rundir.TARGET_CLASSES
run = wsntrack.loader.load_run(sys.argv[1])
assert len(run.truth) and run.settled_tracks is not None
" "$tmp/run") || fail "python3 -c 'import wsntrack.rundir' with the installed package"
    (cd / && "$prefix/$WSN_DATA_DIR/tools/wsntrack_run.py" "$tmp/run") >/dev/null || fail "the installed loader does not run alone"
    ;;
  deb)
    command -v cpack >/dev/null && command -v dpkg-deb >/dev/null || { echo "SKIP: no cpack or dpkg-deb"; exit 77; }
    # cpack runs the build's preinstall target (a no-op on a tree that is built) and installs it
    # into its own staging directory under -B, nothing into the build tree or the system.
    (cd "$tmp" && cpack -G DEB -B "$tmp/package" --config "$build/CPackConfig.cmake") >"$tmp/cpack.log" 2>&1 ||
      { cat "$tmp/cpack.log" >&2; fail "cpack -G DEB"; }
    debs=("$tmp"/package/*.deb)
    [ "${#debs[@]}" -eq 1 ] && [ -f "${debs[0]}" ] || fail "expected one .deb in $tmp/package, got: ${debs[*]}"
    deb="${debs[0]}"
    echo "package: $(basename "$deb"), $(stat -c %s "$deb") bytes"
    dpkg-deb -I "$deb" >"$tmp/info" || fail "dpkg-deb -I"
    cat "$tmp/info"
    field() { dpkg-deb -f "$deb" "$1"; }
    [ "$(field Package)" = wsntrack ] || fail "Package: $(field Package)"
    [ "$(field Version)" = "$WSN_VERSION" ] || fail "Version: $(field Version), expected $WSN_VERSION"
    [ "$(field Architecture)" = "$(dpkg --print-architecture)" ] || fail "Architecture: $(field Architecture)"
    [ -n "$(field Maintainer)" ] && [ -n "$(field Description)" ] || fail "no Maintainer or Description"
    depends=$(field Depends)
    # The Cyclone DDS run-time library (Debian: libddsc0debian) and every other library wsntrack links.
    for needed in libddsc libyaml-cpp libboost-program-options libstdc++6 libc6 python3; do
      echo "$depends" | grep -q "$needed" || fail "Depends lacks $needed: $depends"
    done
    field Recommends | grep -q python3-matplotlib || fail "Recommends lacks python3-matplotlib: $(field Recommends)"
    dpkg-deb -c "$deb" >"$tmp/contents" || fail "dpkg-deb -c"
    for name in "$WSN_BINDIR/wsntrack" "$WSN_ROLE_DIR/wsntrack-node" "$WSN_DATA_DIR/tools/plot_run.py" \
                "$WSN_DATA_DIR/scenarios/oh_quadrants.yaml" "$WSN_DATA_DIR/idl/wsntrack.idl" "$WSN_DOC_DIR/README.md"; do
      grep -q " \./usr/$name\$" "$tmp/contents" || fail "./usr/$name not in the package"
    done
    ! grep -E "wsn_[a-z_]*(tests|bench|fixture)" "$tmp/contents" || fail "test or bench binaries in the package"
    dpkg-deb -x "$deb" "$tmp/root" || fail "dpkg-deb -x"
    check_tree "$tmp/root/usr" "$WSN_PYTHON_DIR_USR"
    # Installed by dpkg, `import wsntrack` works in Debian's python3 with no PYTHONPATH.
    "$python" -c "import sys; sys.exit(0 if sys.argv[1] in sys.path else 1)" "/usr/$WSN_PYTHON_DIR_USR" ||
      fail "the package's /usr/$WSN_PYTHON_DIR_USR is not in $python's path"
    check_run "$tmp/root/usr" "$tmp/run"
    ;;
  *) fail "unknown case $case_name" ;;
esac
echo "PASS: install.$case_name"
