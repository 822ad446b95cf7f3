#!/usr/bin/env bash
# Tests of the replay animation (tools/plot_run.py --animate, 'wsntrack replay') and of the run loader
# (tools/wsntrack_run.py) on a real run.
# Usage: animate_test.sh BIN_DIR SOURCE_DIR WORK_DIR CASE
#   script   GIF and HTML of a hand-made run (tests/tools/tiny_run.py, new and old tracks.csv), options,
#            default output, bad input, no matplotlib, no ffmpeg, a failing encoder (no DDS)
#   mp4      MP4 of the hand-made run
#   run      a real 20-tick cluster run: the loader's invariants, GIF and HTML and MP4, and
#            'wsntrack replay' handing over to plot_run.py
# matplotlib, numpy, Pillow and ffmpeg are required (./setup.sh installs them): a missing one fails.
set -uo pipefail
bin="$1"; src="$2"; work="$3"; case_name="$4"
python=/usr/bin/python3
plot="$src/tools/plot_run.py"
rm -rf "$work/$case_name"; mkdir -p "$work/$case_name"; cd "$work/$case_name" || exit 1

fail() { echo "FAIL: $*" >&2; exit 1; }

[ -x "$python" ] && "$python" -c "import matplotlib, numpy, PIL" 2>/dev/null \
  || fail "$python lacks matplotlib, numpy or Pillow (Debian: apt-get install python3-matplotlib python3-numpy python3-pil)"

# check_animation FILE FORMAT FRAMES WIDTH HEIGHT: the file is a FORMAT animation of FRAMES frames of
# WIDTH x HEIGHT pixels (the MP4 may hold more: its last frame is held).
check_animation() {
  "$python" - "$@" <<'EOF' || fail "$1: not the expected $2 animation (see above)"
import base64, io, json, re, subprocess, sys
from PIL import Image
path, kind, frames, width, height = sys.argv[1], sys.argv[2], int(sys.argv[3]), int(sys.argv[4]), int(sys.argv[5])
if kind == "gif":
    image = Image.open(path)
    assert image.format == "GIF", image.format
    assert image.n_frames == frames, f"{image.n_frames} frames, expected {frames}"
    assert image.size == (width, height), image.size
    assert image.info.get("loop") == 0, "does not loop"
elif kind == "html":
    text = open(path, encoding="utf-8").read()
    assert text.startswith("<!DOCTYPE html>"), "not an HTML page"
    # Self-contained: nothing fetched from anywhere (the frames are data: URIs).
    assert not re.search(r"""(src|href)\s*=\s*["'](?!data:)""", text), "refers to an outside resource"
    assert not re.search(r"https?://", text.replace("data:image/png;base64,", "")[:20000]), "a URL"
    found = re.findall(r'^"([A-Za-z0-9+/=]+)"', text, re.M)
    assert len(found) == frames, f"{len(found)} frames, expected {frames}"
    ticks = json.loads(re.search(r"const ticks = (\[.*?\]);", text).group(1))
    assert len(ticks) == frames, ticks
    for frame in (found[0], found[-1]):
        image = Image.open(io.BytesIO(base64.b64decode(frame)))
        assert image.format == "PNG" and image.size == (width, height), (image.format, image.size)
elif kind == "mp4":
    probe = subprocess.run(["ffprobe", "-v", "error", "-select_streams", "v:0", "-count_frames", "-show_entries",
                            "stream=codec_name,width,height,pix_fmt,nb_read_frames", "-of", "json", path],
                           capture_output=True, text=True, check=True)
    stream = json.loads(probe.stdout)["streams"][0]
    assert stream["codec_name"] == "h264" and stream["pix_fmt"] == "yuv420p", stream
    assert (stream["width"], stream["height"]) == (width, height), stream
    assert int(stream["nb_read_frames"]) >= frames, stream
EOF
}

# expect_exit CODE PATTERN ARGS...: plot_run.py ARGS exits CODE with PATTERN on stderr and no traceback
# (run under 'env $RUN_ENV' when RUN_ENV is set, e.g. to change its PATH but not this script's).
expect_exit() {
  local want="$1" pattern="$2"; shift 2
  env ${RUN_ENV:-} "$python" "$plot" "$@" >out.txt 2>err.txt
  local code=$?
  [ "$code" -eq "$want" ] || { cat err.txt >&2; fail "plot_run.py $*: exit $code, expected $want"; }
  grep -Eq -- "$pattern" err.txt || { cat err.txt >&2; fail "plot_run.py $*: message lacks /$pattern/"; }
  grep -q "Traceback" err.txt && { cat err.txt >&2; fail "plot_run.py $*: traceback"; }
  return 0
}

case "$case_name" in
  script)
    "$python" -B "$src/tests/tools/tiny_run.py" tiny || fail "tiny_run.py"

    "$python" "$plot" --help >help.txt || fail "--help"
    for word in --animate --animate-format --fps --size --first --last --trail --hold replay.FORMAT "Exit status"; do
      grep -q -- "$word" help.txt || fail "--help does not mention $word"
    done

    # Default: a GIF of every tick in RUN_DIR/plots/replay.gif, progress on stderr, one line on stdout.
    "$python" "$plot" --animate tiny >out.txt 2>err.txt || { cat err.txt >&2; fail "--animate"; }
    check_animation tiny/plots/replay.gif gif 10 1280 720
    grep -q "wrote tiny/plots/replay.gif (10 frames, ticks 1-10, 1280x720, 5 fps)" out.txt || { cat out.txt >&2; fail "stdout"; }
    grep -q "drew frame 10/10" err.txt || { cat err.txt >&2; fail "no progress on stderr"; }
    ls -a tiny/plots | grep -q partial && fail "a partial file was left behind"

    # The frames show the run: tick 2 has a false alarm (magenta x), tick 1 none; the legend has one too.
    "$python" "$plot" --animate tiny --out "$PWD/ticks12.gif" --first 1 --last 2 --quiet >/dev/null 2>err.txt \
      || { cat err.txt >&2; fail "--first/--last"; }
    [ -s err.txt ] && { cat err.txt >&2; fail "--quiet printed progress"; }
    check_animation ticks12.gif gif 2 1280 720
    "$python" - ticks12.gif <<'EOF' || fail "the false alarm of tick 2 is not drawn"
import sys
import numpy as np
from PIL import Image
image = Image.open(sys.argv[1])
def magenta(frame):
    image.seek(frame)
    rgb = np.asarray(image.convert("RGB")).astype(int)
    return int((np.abs(rgb - [0xe0, 0x11, 0x5f]).sum(axis=2) < 60).sum())
assert magenta(1) > magenta(0) > 0, (magenta(0), magenta(1))
EOF

    # HTML: one page, every frame inside, by --animate-format or by the suffix of --out.
    "$python" "$plot" --animate tiny --animate-format html --out "$PWD/htmldir" --size 960x540 --quiet >out.txt 2>&1 \
      || { cat out.txt >&2; fail "html into a directory"; }
    check_animation htmldir/replay.html html 10 960 540
    "$python" "$plot" --animate tiny --out "$PWD/page.html" --first 3 --trail 2 --fps 2 --quiet >out.txt 2>&1 \
      || { cat out.txt >&2; fail "html by suffix"; }
    check_animation page.html html 8 1280 720
    grep -q '"3' <(grep -o 'const ticks = \[[0-9, ]*' page.html | tr -d '[ ' | sed 's/.*=/"/') \
      || fail "page.html does not start at tick 3"

    # An odd size is rounded down to even numbers; a narrow frame drops the side panel but works.
    "$python" "$plot" --animate tiny --out "$PWD/small.gif" --size 641x481 --quiet >/dev/null 2>err.txt \
      || { cat err.txt >&2; fail "--size 641x481"; }
    check_animation small.gif gif 10 640 480
    "$python" "$plot" --animate tiny --out "$PWD/narrow.gif" --size 480x640 --quiet >/dev/null 2>err.txt \
      || { cat err.txt >&2; fail "--size 480x640"; }
    check_animation narrow.gif gif 10 480 640

    # A run written before tracks.csv had labels and covariances.
    "$python" -B "$src/tests/tools/tiny_run.py" old --old || fail "tiny_run.py --old"
    "$python" "$plot" --animate old --out "$PWD/old.gif" --quiet >/dev/null 2>err.txt || { cat err.txt >&2; fail "old run"; }
    check_animation old.gif gif 10 1280 720

    # Bad command lines and bad input: exit 2, one clear line.
    expect_exit 2 "--fps needs --animate" tiny --fps 3
    expect_exit 2 "--format draws the still plots, not --animate: use --animate-format" tiny --animate --format svg
    expect_exit 2 "--dpi draws the still plots, not --animate: use --size" tiny --animate --dpi 100
    expect_exit 2 "invalid choice: 'avi'" tiny --animate --animate-format avi
    expect_exit 2 "--size must be WIDTHxHEIGHT" tiny --animate --size big
    expect_exit 2 "--size must be within" tiny --animate --size 100x100
    expect_exit 2 "--fps must be in" tiny --animate --fps 0
    expect_exit 2 "--first 5 --last 3: the ticks drawn must satisfy 1 <= first <= last <= 10" tiny --animate --first 5 --last 3
    expect_exit 2 "--first 1 --last 11" tiny --animate --last 11
    expect_exit 2 "the suffix says gif, --animate-format says mp4" tiny --animate --out x.gif --animate-format mp4
    expect_exit 2 "--out x.avi: an animation is written to a .gif, .mp4 or .html file, or into a directory" tiny --animate --out x.avi
    [ -e x.avi ] && fail "--out x.avi made something"
    expect_exit 2 "nonexistent: not a directory" nonexistent --animate
    cp -r tiny bad1; rm bad1/observations.csv
    expect_exit 2 "bad1/observations.csv: missing" bad1 --animate
    cp -r tiny bad2; sed -i '3s/delivered$/vanished/' bad2/observations.csv
    expect_exit 2 "bad2/observations.csv:3: column 'fate' must be one of delivered, lost, unreachable, after_end" bad2 --animate
    cp -r tiny bad3; sed -i '4s/^\([^,]*,[^,]*,[^,]*,\)[^,]*/\1xyz/' bad3/tracks.csv
    expect_exit 2 "bad3/tracks.csv:4: column 'x' must be a number, got 'xyz'" bad3 --animate
    mkdir -p readonly && chmod 500 readonly
    if [ "$(id -u)" != 0 ]; then expect_exit 2 "cannot write" tiny --animate --out "$PWD/readonly/x.gif"; fi
    expect_exit 2 "cannot write|Not a directory" tiny --animate --out "$PWD/help.txt/x.gif"

    # Missing tools: exit 3 (no matplotlib; no ffmpeg for an MP4), nothing written.
    mkdir -p fakepy/matplotlib
    echo 'raise ImportError("simulated: no matplotlib")' >fakepy/matplotlib/__init__.py
    RUN_ENV="PYTHONPATH=$PWD/fakepy" expect_exit 3 "matplotlib is not available" tiny --animate --out "$PWD/nompl.gif"
    [ -e nompl.gif ] && fail "a GIF without matplotlib?"
    RUN_ENV="PATH=/nonexistent" expect_exit 3 "an MP4 needs ffmpeg, which is not on PATH" tiny --animate --out "$PWD/noff.mp4"
    [ -e noff.mp4 ] && fail "an MP4 without ffmpeg?"

    # An encoder that fails: exit 1 with its message, and neither the file nor a partial one is left.
    mkdir -p fakebin
    printf '#!/bin/sh\ncat >/dev/null\necho "simulated encoder failure" >&2\nexit 1\n' >fakebin/ffmpeg
    chmod +x fakebin/ffmpeg
    RUN_ENV="PATH=$PWD/fakebin:$PATH" expect_exit 1 "ffmpeg exit 1: simulated encoder failure" tiny --animate --out "$PWD/broken.mp4"
    ls -a | grep -Eq "broken|partial" && fail "a failed MP4 left a file behind"
    echo "ok" ;;

  mp4)
    command -v ffmpeg >/dev/null && command -v ffprobe >/dev/null \
      || fail "no ffmpeg/ffprobe on PATH (./setup.sh installs Debian's ffmpeg)"
    "$python" -B "$src/tests/tools/tiny_run.py" tiny || fail "tiny_run.py"
    "$python" "$plot" --animate tiny --animate-format mp4 --quiet >out.txt 2>&1 || { cat out.txt >&2; fail "mp4"; }
    # 10 ticks and the last frame held 1 s at 5 fps: 15 frames.
    check_animation tiny/plots/replay.mp4 mp4 15 1280 720
    "$python" "$plot" --animate tiny --out "$PWD/short.mp4" --hold 0 --fps 10 --size 854x480 --quiet >out.txt 2>&1 \
      || { cat out.txt >&2; fail "mp4 by suffix"; }
    check_animation short.mp4 mp4 10 854 480
    echo "ok" ;;

  run)
    wsntrack="$bin/wsntrack"
    timeout 300 "$wsntrack" run "$src/scenarios/oh_quadrants.yaml" --ticks 20 --out "$PWD/real" --no-plot --quiet \
      >run.stdout 2>run.stderr || { cat run.stderr >&2; fail "wsntrack run"; }
    # The readable id and the covariance of every track (issue 12, item 7).
    [ "$(head -1 real/tracks.csv)" = "tick,track,label,x,y,vx,vy,p_xx,p_xy,p_xvx,p_xvy,p_yy,p_yvx,p_yvy,p_vxvx,p_vxvy,p_vyvy,class,class_probability,stop_probability" ] \
      || fail "tracks.csv header: $(head -1 real/tracks.csv)"
    [ "$(head -1 real/tracks_supernode.csv)" = "tick,supernode,track,label,x,y,vx,vy,p_xx,p_xy,p_xvx,p_xvy,p_yy,p_yvx,p_yvy,p_vxvx,p_vxvy,p_vyvy,class,class_probability,stop_probability" ] \
      || fail "tracks_supernode.csv header: $(head -1 real/tracks_supernode.csv)"
    "$python" -B "$src/tests/tools/loader_test.py" "$src" "$PWD/loader" --real "$PWD/real" >loader.txt 2>&1 \
      || { cat loader.txt >&2; fail "the loader on a real run"; }
    for case in test_tracks test_every_column_of_the_files test_frames; do
      grep -q "RealRun.$case) ... ok" loader.txt || { cat loader.txt >&2; fail "the real-run test $case did not run"; }
    done

    start=$(date +%s%N)
    "$python" "$plot" --animate real --quiet >out.txt 2>&1 || { cat out.txt >&2; fail "gif of a real run"; }
    echo "GIF of 20 ticks: $(( ($(date +%s%N) - start) / 1000000 )) ms"
    check_animation real/plots/replay.gif gif 20 1280 720
    "$python" "$plot" --animate real --animate-format html --quiet >out.txt 2>&1 || { cat out.txt >&2; fail "html"; }
    check_animation real/plots/replay.html html 20 1280 720
    # ./setup.sh installs ffmpeg: its absence here is a failure, not a skip.
    command -v ffmpeg >/dev/null && command -v ffprobe >/dev/null || fail "no ffmpeg/ffprobe (./setup.sh installs them)"
    "$python" "$plot" --animate real --out "$PWD/real.mp4" --quiet >out.txt 2>&1 || { cat out.txt >&2; fail "mp4"; }
    check_animation real.mp4 mp4 20 1280 720

    # 'wsntrack replay RUN_DIR ARGS' is plot_run.py --animate RUN_DIR ARGS.
    "$wsntrack" replay --help >replay-help.txt 2>&1 || { cat replay-help.txt >&2; fail "wsntrack replay --help"; }
    grep -q -- "--animate-format" replay-help.txt || { cat replay-help.txt >&2; fail "replay --help"; }
    "$wsntrack" replay real --out "$PWD/replayed.html" --first 5 --last 9 --quiet >out.txt 2>&1 \
      || { cat out.txt >&2; fail "wsntrack replay"; }
    check_animation replayed.html html 5 1280 720
    "$wsntrack" replay real --first 0 >out.txt 2>&1
    [ $? -eq 2 ] || { cat out.txt >&2; fail "wsntrack replay with a bad option: not exit 2"; }
    "$wsntrack" replay >out.txt 2>&1
    [ $? -eq 2 ] || { cat out.txt >&2; fail "wsntrack replay without RUN_DIR: not exit 2"; }
    echo "ok" ;;

  *) fail "unknown case $case_name" ;;
esac
