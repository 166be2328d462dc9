"""Time to the first drawn frame: the offline page (`main.py SCENE --html`) against the local page
(`main.py SCENE`), in the same headless Chromium, in one run.

    python -m benchmarks.first_frame [--scene vertical] [--repeats 5]

Each repeat opens both, alternately, in a fresh browser context: the offline file from file://
(every other request refused: it needs none), and the local page from its server (`main.py SCENE
--no-browser --port P`, started before the clock starts, as a teacher's is before they open the
tab). The clock starts when the browser is asked for the page and stops at the first screenshot
in which the first mass is drawn in its colour (lit, shaded or seen through); screenshots are
taken one after another, so each figure is late by at most one screenshot's time, for both
pages alike. Medians are printed with their ratio, offline / local: the issue's target is at
most 1. The size of the offline file is printed beside them (target: at most 7 MB).

Software WebGL (SwiftShader) draws two or three frames a second here, so the figures are those
of a slow school laptop rather than a fast one; the ratio is what compares.
"""
from __future__ import annotations

import argparse
import os
import re
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "tests"))
sys.path.insert(0, str(ROOT))

from benchmarks.common import load_average  # noqa: E402
from browser_support import CHROMIUM, CHROMIUM_ARGS, free_port, shaded_like  # noqa: E402
from export.palette import MASS_COLOURS  # noqa: E402

TIMEOUT = 180.0   # s: a page that draws nothing by then counts as a failure


def drawn(image) -> bool:
    """Whether the first mass shows, in its colour, lit, shaded or seen through."""
    return shaded_like(image, MASS_COLOURS[0]) > 30


def first_frame(browser, url: str, *, only: str | None = None) -> float:
    """Seconds from asking for `url` to the first screenshot showing the mass drawn."""
    import io

    from PIL import Image

    context = browser.new_context(viewport={"width": 1280, "height": 800})
    if only is not None:
        context.route("**/*", lambda route: route.continue_() if route.request.url.split("#")[0] == only
                      else route.abort())
    page = context.new_page()
    try:
        start = time.monotonic()
        page.goto(url, wait_until="commit", timeout=TIMEOUT * 1000)
        while time.monotonic() - start < TIMEOUT:
            canvas = page.locator("canvas").first
            if canvas.count() and canvas.is_visible():
                shot = Image.open(io.BytesIO(canvas.screenshot(timeout=TIMEOUT * 1000))).convert("RGB")
                if drawn(shot):
                    return time.monotonic() - start
            else:
                page.wait_for_timeout(20)
        raise RuntimeError(f"{url}: no frame drawn within {TIMEOUT:.0f} s")
    finally:
        context.close()


def local_page(scene: str):
    """`main.py SCENE --no-browser --port P` running, and its URL."""
    port = free_port()
    process = subprocess.Popen([sys.executable, str(ROOT / "main.py"), scene, "--no-browser", "--port", str(port)],
                               cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                               env={**os.environ, "VPYTHON_NO_LAUNCH_BROWSER": "1"})
    deadline = time.monotonic() + 60
    for line in process.stdout:
        found = re.search(r"http://\S+", line)
        if found:
            return process, found[0]
        if time.monotonic() > deadline:
            break
    process.kill()
    raise RuntimeError("the local page did not start")


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(prog="python -m benchmarks.first_frame", description=__doc__.split("\n\n")[0])
    parser.add_argument("--scene", default="vertical")
    parser.add_argument("--repeats", type=int, default=5)
    args = parser.parse_args(argv)
    from playwright.sync_api import sync_playwright

    folder = Path(tempfile.mkdtemp(prefix="first-frame-"))
    offline = folder / f"{args.scene}.html"
    subprocess.run([sys.executable, str(ROOT / "main.py"), args.scene, "--html", str(offline)], cwd=ROOT, check=True,
                   capture_output=True)
    times = {"offline": [], "local": []}
    with sync_playwright() as playwright:
        browser = playwright.chromium.launch(executable_path=CHROMIUM, args=CHROMIUM_ARGS)
        try:
            for _ in range(args.repeats):
                times["offline"].append(first_frame(browser, offline.as_uri(), only=offline.as_uri()))
                process, url = local_page(args.scene)
                try:
                    times["local"].append(first_frame(browser, url))
                finally:
                    process.terminate()
                    process.wait(timeout=30)
        finally:
            browser.close()
    offline_s, local_s = statistics.median(times["offline"]), statistics.median(times["local"])
    print(f"first drawn frame, {args.scene}, median of {args.repeats} (headless Chromium, software WebGL, "
          f"load {load_average()}):")
    print(f"  offline page (file://): {offline_s:6.2f} s   runs: " + ", ".join(f"{t:.2f}" for t in times["offline"]))
    print(f"  local page (server):    {local_s:6.2f} s   runs: " + ", ".join(f"{t:.2f}" for t in times["local"]))
    print(f"  offline / local = {offline_s / local_s:.2f} (target: at most 1)")
    print(f"  offline file: {offline.stat().st_size / 1e6:.2f} MB (target: at most 7 MB)")
    offline.unlink()
    folder.rmdir()
    return 0


if __name__ == "__main__":
    sys.exit(main())
