#!/usr/bin/python3
"""The browser map of `wsntrack watch --http` in a real headless Chromium (Debian's chromium and
chromium-driver, driven by python3-selenium): the page loads; while the cluster runs, the tick on the
page advances; at the end every tick's track count on the page is that of tracks.csv at the same
tick, and the one shown when scrubbed to a tick too; a screenshot is
not empty; after the run the page says it finished and scrubs back to any tick; a finished run is
served from its files; the server answers nothing but its three GET routes.

Usage: browser_map_test.py WSNTRACK SOURCE_DIR WORK_DIR
Exit 77 (skipped) with the reason when Chromium, its driver or Selenium is not installed."""

import csv
import os
import re
import shutil
import signal
import subprocess
import sys
import time
import unittest
import urllib.error
import urllib.request
from collections import Counter
from pathlib import Path

WSNTRACK, SOURCE, WORK = (Path(a).resolve() for a in sys.argv[1:4])
CHROMIUM, CHROMEDRIVER = shutil.which("chromium"), shutil.which("chromedriver")
TICKS = 60


def missing():
    """What this test needs and this machine lacks, or None."""
    try:
        import selenium  # noqa: F401
    except ImportError:
        return "python3-selenium is not installed"
    if not CHROMIUM or not CHROMEDRIVER:
        return "chromium or chromium-driver is not installed"
    return None


def start(command, stderr):
    return subprocess.Popen(command, stdout=subprocess.DEVNULL, stderr=stderr, stdin=subprocess.DEVNULL)


def stop(process, timeout=15):
    """Stops one process we started, by its PID: SIGTERM, SIGKILL after `timeout` s; its exit status."""
    if process.poll() is None:
        process.send_signal(signal.SIGTERM)
        try:
            return process.wait(timeout=timeout)
        except subprocess.TimeoutExpired:
            process.kill()
    return process.wait()


def url_of(log_path, process, deadline_s=30):
    """The map's URL from the watch's stderr."""
    deadline = time.monotonic() + deadline_s
    while time.monotonic() < deadline:
        found = re.search(r"http://127\.0\.0\.1:\d+/", log_path.read_text(encoding="utf-8", errors="replace"))
        if found:
            return found.group(0)
        if process.poll() is not None:
            break
        time.sleep(0.1)
    raise AssertionError(f"no map URL from the watch: {log_path.read_text(encoding='utf-8', errors='replace')}")


def tracks_per_tick(run_dir):
    with open(run_dir / "tracks.csv", newline="", encoding="utf-8") as f:
        return Counter(int(row["tick"]) for row in csv.DictReader(f))


def browser():
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service
    options = webdriver.ChromeOptions()
    options.binary_location = CHROMIUM
    for argument in ("--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage",
                     "--window-size=1200,800"):
        options.add_argument(argument)
    return webdriver.Chrome(service=Service(CHROMEDRIVER), options=options)


def page_state(driver):
    """(tick, track count, state) as the page shows them, from its elements."""
    return driver.execute_script(
        "return [document.getElementById('tick').textContent, document.getElementById('track-count').textContent, "
        "document.body.dataset.state || ''];")


def wait_for(driver, condition, what, timeout_s=30):
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline:
        state = page_state(driver)
        if condition(state):
            return state
        time.sleep(0.1)
    raise AssertionError(f"the page never showed {what}; it shows {page_state(driver)}")


def not_empty(png):
    """(distinct colours, share of pixels that are not the background) of a screenshot."""
    from PIL import Image
    image = Image.open(png).convert("RGB")
    colours = image.getcolors(maxcolors=1 << 20) or []
    background = max(colours)[1] if colours else None
    share = 1.0 - (max(colours)[0] / (image.width * image.height) if colours else 1.0)
    return len(colours), share, background


class LiveMap(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        shutil.rmtree(WORK, ignore_errors=True)
        WORK.mkdir(parents=True)
        cls.run_dir = WORK / "run"
        cls.cluster = start([str(WSNTRACK), "run", str(SOURCE / "scenarios/oh_quadrants.yaml"), "--ticks", str(TICKS),
                         "--tick-interval", "0.15", "--out", str(cls.run_dir), "--quiet", "--no-plot"],
                        open(WORK / "run.err", "w"))
        cls.watch_log = WORK / "watch.err"
        cls.watch = start([str(WSNTRACK), "watch", str(cls.run_dir), "--http", "127.0.0.1:0", "--plain"],
                          open(cls.watch_log, "w"))
        cls.url = url_of(cls.watch_log, cls.watch)
        cls.driver = browser()

    @classmethod
    def tearDownClass(cls):
        cls.driver.quit()
        stop(cls.watch)
        stop(cls.cluster)

    def test_1_follows_the_run_then_scrubs_it(self):
        self.driver.get(self.url)
        first = wait_for(self.driver, lambda s: s[0].isdigit(), "a tick")
        self.assertEqual(self.driver.title, "wsntrack map: oh_quadrants")
        samples = [first]
        for _ in range(3):
            time.sleep(1.0)
            samples.append(page_state(self.driver))
        ticks = [int(s[0]) for s in samples]
        self.assertEqual(ticks, sorted(ticks), samples)
        self.assertGreater(ticks[-1], ticks[0], f"the tick on the page did not advance: {samples}")
        self.assertTrue(all(s[2] == "live" for s in samples), samples)
        live_png = WORK / "live.png"
        self.driver.save_screenshot(str(live_png))
        colours, share, _ = not_empty(live_png)
        self.assertGreater(colours, 20, "the screenshot has almost no colours: an empty page")
        self.assertGreater(share, 0.05, "the screenshot is nearly all background")

        self.assertEqual(self.cluster.wait(timeout=60), 0, (WORK / "run.err").read_text())
        final = wait_for(self.driver, lambda s: s[2] == "finished", "the end of the run")
        counts = tracks_per_tick(self.run_dir)
        self.assertEqual(final[0], str(TICKS))
        self.assertEqual(int(final[1]), counts.get(TICKS, 0), f"track count at tick {TICKS}")
        # Every tick the page holds has the tracks tracks.csv has at that tick (a tick whose tracks came
        # after its metrics was sent again whole: the page keeps the last).
        held = dict(self.driver.execute_script(
            "return Array.from(wsnMap.ticks.entries()).map(([t, e]) => [t, e.tracks.length]);"))
        self.assertEqual(held, {t: counts.get(t, 0) for t in range(1, TICKS + 1)})
        # Scrubbing back: every tick is there, also those before the watch joined (from the files).
        for tick in (1, 10, 37):
            self.driver.execute_script(f"wsnMap.show({tick});")
            state = page_state(self.driver)
            self.assertEqual(state[:2], [str(tick), str(counts.get(tick, 0))])
        received = self.driver.execute_script("return wsnMap.ticks.size;")
        self.assertEqual(received, TICKS)
        print(f"live samples {samples}, final {final}; screenshot {colours} colours, {share:.0%} not background",
              file=sys.stderr)

    def test_2_read_only(self):
        for path in ("/files/truth.csv", "/../run.json", "/api/other"):
            with self.assertRaises(urllib.error.HTTPError) as caught:
                urllib.request.urlopen(self.url.rstrip("/") + path, timeout=5)
            self.assertEqual(caught.exception.code, 404, path)
        request = urllib.request.Request(self.url + "api/run", data=b"{}", method="POST")
        with self.assertRaises(urllib.error.HTTPError):
            urllib.request.urlopen(request, timeout=5)


class FinishedRun(unittest.TestCase):
    def test_served_from_its_files(self):
        run_dir = WORK / "run"
        if not (run_dir / "metrics.json").is_file():
            self.skipTest("the live case did not finish its run")
        log = WORK / "finished.err"
        watch = start([str(WSNTRACK), "watch", str(run_dir), "--http", "0"], open(log, "w"))
        driver = browser()
        try:
            driver.get(url_of(log, watch))
            state = wait_for(driver, lambda s: s[2] == "finished" and s[0] == str(TICKS), "the finished run")
            self.assertEqual(int(state[1]), tracks_per_tick(run_dir).get(TICKS, 0))
            self.assertIn("has finished; its map (60 ticks, from its files)", log.read_text())
            driver.save_screenshot(str(WORK / "finished.png"))
        finally:
            driver.quit()
            self.assertEqual(stop(watch), 0, log.read_text())


if __name__ == "__main__":
    why = missing()
    if why:
        print(f"SKIP: {why}; ./setup.sh test installs chromium, chromium-driver and python3-selenium")
        sys.exit(77)
    cases = unittest.TestSuite([unittest.defaultTestLoader.loadTestsFromTestCase(LiveMap),
                                unittest.defaultTestLoader.loadTestsFromTestCase(FinishedRun)])
    result = unittest.TextTestRunner(verbosity=2).run(cases)
    sys.exit(0 if result.wasSuccessful() and result.testsRun == 3 and not result.skipped else 1)
