"""Where the replay animation's frames go: a GIF (Pillow) or an HTML page with a player, both with
one palette shared by every frame, or an MP4 through ffmpeg; and the progress shown while drawing.
A sink takes RGBA frames with add(rgba, tick) and writes its file in finish()."""

import json
import sys


class Progress:
    """'frame n/N' on stderr: redrawn in place on a terminal, else a line every tenth of the way."""

    def __init__(self, total, quiet):
        self.total, self.quiet = total, quiet
        self.tty = sys.stderr.isatty()
        self.last_line = -1

    def show(self, done, what):
        if self.quiet:
            return
        if self.tty:
            sys.stderr.write(f"\rplot_run.py: {what} frame {done}/{self.total}")
            if done == self.total:
                sys.stderr.write("\n")
            sys.stderr.flush()
        elif done * 10 // self.total > self.last_line or done == self.total:
            self.last_line = done * 10 // self.total
            print(f"plot_run.py: {what} frame {done}/{self.total}", file=sys.stderr, flush=True)


HTML_PAGE = """<!DOCTYPE html>
<!-- {title}: written by wsntrack's plot_run.py --animate; every frame is embedded, nothing is loaded. -->
<html lang="en"><head><meta charset="utf-8"><title>{title}</title>
<style>
body {{ font-family: sans-serif; margin: 1em; color: #222; }}
#frame {{ max-width: 100%; height: auto; border: 1px solid #ccc; display: block; }}
.bar {{ display: flex; align-items: center; gap: 0.5em; margin: 0.5em 0; max-width: {width}px; }}
.bar button {{ font-size: 1.1em; min-width: 2.4em; }}
#slider {{ flex: 1; }}
#label {{ font-variant-numeric: tabular-nums; min-width: 9em; }}
.hint {{ color: #777; font-size: 0.85em; }}
</style></head><body>
<img id="frame" width="{width}" height="{height}" alt="{title}">
<div class="bar">
<button id="first" title="first tick (Home)">&#x23EE;</button>
<button id="back" title="previous tick (&#x2190;)">&#x25C0;</button>
<button id="play" title="play / pause (space)">&#x25B6;</button>
<button id="next" title="next tick (&#x2192;)">&#x25B6;&#xFE0E;|</button>
<button id="last" title="last tick (End)">&#x23ED;</button>
<input id="slider" type="range" min="0" max="{last_index}" value="0">
<span id="label"></span>
<label>speed <select id="speed"><option value="0.25">&#xBC;&#xD7;</option><option value="0.5">&#xBD;&#xD7;</option>
<option value="1" selected>1&#xD7;</option><option value="2">2&#xD7;</option><option value="4">4&#xD7;</option></select></label>
<label><input id="loop" type="checkbox" checked> loop</label>
</div>
<div class="hint">{fps} frames per second at 1&#xD7;; keys: space, &#x2190; &#x2192;, Home, End</div>
<script>
const ticks = {ticks};
const frames = [
{frames}
];
const img = document.getElementById("frame"), slider = document.getElementById("slider"),
      label = document.getElementById("label"), play = document.getElementById("play");
let index = 0, timer = null;
function show(i) {{
  index = Math.max(0, Math.min(frames.length - 1, i));
  img.src = "data:image/png;base64," + frames[index];
  slider.value = index;
  label.textContent = "tick " + ticks[index] + " (" + (index + 1) + "/" + frames.length + ")";
}}
function stop() {{ clearInterval(timer); timer = null; play.innerHTML = "&#x25B6;"; }}
function start() {{
  if (index >= frames.length - 1) show(0);
  const speed = parseFloat(document.getElementById("speed").value);
  timer = setInterval(() => {{
    if (index < frames.length - 1) show(index + 1);
    else if (document.getElementById("loop").checked) show(0);
    else stop();
  }}, 1000 / ({fps} * speed));
  play.innerHTML = "&#x23F8;";
}}
play.onclick = () => timer ? stop() : start();
document.getElementById("first").onclick = () => {{ stop(); show(0); }};
document.getElementById("last").onclick = () => {{ stop(); show(frames.length - 1); }};
document.getElementById("back").onclick = () => {{ stop(); show(index - 1); }};
document.getElementById("next").onclick = () => {{ stop(); show(index + 1); }};
document.getElementById("speed").onchange = () => {{ if (timer) {{ stop(); start(); }} }};
slider.oninput = () => {{ stop(); show(parseInt(slider.value)); }};
document.addEventListener("keydown", (e) => {{
  if (e.target.tagName === "SELECT") return;
  const keys = {{" ": () => play.onclick(), "ArrowLeft": () => {{ stop(); show(index - 1); }},
                "ArrowRight": () => {{ stop(); show(index + 1); }}, "Home": () => {{ stop(); show(0); }},
                "End": () => {{ stop(); show(frames.length - 1); }}}};
  if (keys[e.key]) {{ keys[e.key](); e.preventDefault(); }}
}});
show(0);
</script>
</body></html>
"""


def _rgb_image(rgba):
    """A Pillow RGB image of an (h, w, 4) RGBA array, without an intermediate copy of the array."""
    from PIL import Image
    height, width = rgba.shape[:2]
    return Image.frombuffer("RGBA", (width, height), rgba, "raw", "RGBA", 0, 1).convert("RGB")


class PaletteSink:
    """Frames reduced to one 256-colour palette shared by all, made from sample frames spread over
    the ticks (animate() draws them first). The frames are flat colours and their anti-aliasing
    shades, so the palette costs nothing visible; sharing it makes the GIF quick (Pillow compares
    frames without converting them back to RGB) and the HTML's PNGs a third of RGB ones."""

    SAMPLES = 8

    palette = None

    def set_samples(self, samples):
        from PIL import Image
        import numpy as np
        probe = np.concatenate([sample[:, :, :3] for sample in samples], axis=0)
        # The octree's 224 most used colours and a ramp of 32 greys: alone, the octree merges light
        # greys (faint curves, sensors) into tinted neighbours, which shows as beige lines.
        octree = Image.fromarray(probe).quantize(224, method=Image.Quantize.FASTOCTREE, dither=Image.Dither.NONE)
        greys = [round(255 * k / 31) for k in range(32)]
        self.palette = Image.new("P", (1, 1))
        self.palette.putpalette(octree.getpalette()[:224 * 3] + [v for g in greys for v in (g, g, g)])

    def quantize(self, rgba):
        # No dithering: it would only speckle the flat areas.
        from PIL import Image
        image = _rgb_image(rgba)
        if self.palette is None:
            return image.quantize(256, method=Image.Quantize.FASTOCTREE, dither=Image.Dither.NONE)
        return image.quantize(palette=self.palette, dither=Image.Dither.NONE)


class HtmlSink(PaletteSink):
    """A self-contained HTML page: the frames as base64 PNG in the page, and a small player."""

    def __init__(self, path, fps, size, title):
        self.path, self.fps, self.size, self.title = path, fps, size, title
        self.frames, self.ticks = [], []

    def add(self, rgba, tick):
        import base64
        import io
        buffer = io.BytesIO()
        self.quantize(rgba).save(buffer, format="png")
        self.frames.append(base64.b64encode(buffer.getvalue()).decode("ascii"))
        self.ticks.append(tick)

    def finish(self):
        import html
        page = HTML_PAGE.format(title=html.escape(self.title), width=self.size[0], height=self.size[1],
                                last_index=len(self.frames) - 1, fps=self.fps, ticks=json.dumps(self.ticks),
                                frames=",\n".join(f'"{frame}"' for frame in self.frames))
        self.path.write_text(page, encoding="utf-8")


class GifSink(PaletteSink):
    """An animated GIF through Pillow, every frame with the shared palette. Pillow keeps every
    frame until the end: about 1 MB a frame at 1280 x 720."""

    def __init__(self, path, fps, hold_s):
        self.path, self.fps, self.hold_s = path, fps, hold_s
        self.frames = []

    def add(self, rgba, tick):
        self.frames.append(self.quantize(rgba))

    def finish(self):
        # GIF frames carry their own duration, so the held last frame is one frame.
        durations = [round(1000 / self.fps)] * len(self.frames)
        durations[-1] += round(1000 * self.hold_s)
        self.frames[0].save(self.path, format="GIF", save_all=True, append_images=self.frames[1:],
                            duration=durations, loop=0, optimize=False, disposal=1)


class Mp4Sink:
    """H.264 in MP4 through ffmpeg, fed raw RGB frames on a pipe (yuv420p, which every player takes)."""

    def __init__(self, path, fps, size, hold_s, ffmpeg):
        import subprocess
        import tempfile
        self.hold_frames = round(hold_s * fps)
        self.last = None
        self.log = tempfile.TemporaryFile()
        self.process = subprocess.Popen(
            [ffmpeg, "-nostdin", "-y", "-loglevel", "error", "-f", "rawvideo", "-pix_fmt", "rgb24",
             "-s", f"{size[0]}x{size[1]}", "-r", str(fps), "-i", "pipe:0", "-c:v", "libx264", "-preset", "medium",
             "-crf", "20", "-pix_fmt", "yuv420p", "-movflags", "+faststart", "-f", "mp4", str(path)],
            stdin=subprocess.PIPE, stdout=self.log, stderr=subprocess.STDOUT)

    def add(self, rgba, tick):
        self.last = rgba[:, :, :3].tobytes()
        self._write(self.last)

    def _write(self, data):
        try:
            self.process.stdin.write(data)
        except BrokenPipeError:
            self.finish()  # ffmpeg has ended: finish() says why

    def finish(self):
        if not self.process.stdin.closed:
            try:
                for _ in range(self.hold_frames if self.last else 0):
                    self.process.stdin.write(self.last)
                self.process.stdin.close()
            except BrokenPipeError:
                pass
        code = self.process.wait()
        if code != 0:
            self.log.seek(0)
            lines = self.log.read().decode("utf-8", "replace").strip().splitlines()
            raise EncoderError(f"ffmpeg exit {code}: {lines[-1] if lines else 'no message'}")


class EncoderError(Exception):
    """The video encoder failed: exit status 1."""
