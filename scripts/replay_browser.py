#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Opens chainbench replay pages in headless Chromium (Debian's chromium, driven through the
DevTools protocol on a pipe: no network, no other package), plays each to its last step, saves a
screenshot and prints how long opening and playing took.

    scripts/replay_browser.py PAGE.html... [--shots DIR] [--speed X] [--json TIMINGS.json]

A screenshot is written beside each page (PAGE.png) unless --shots names a folder. --speed is
the playback speed (1: the simulation's own pace; default 8). Exit status 2 when Chromium is
missing or a page does not play; the message names the page.
"""
import argparse
import base64
import fcntl
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time

CHROMIUM = os.environ.get("CHROMIUM", "/usr/bin/chromium")


class BrowserError(Exception):
    """Chromium could not be started, or a page did not load or play: one line, for people."""


class Browser:
    """One headless Chromium, spoken to in DevTools protocol messages over its pipe (fds 3 and 4
    of the child: it reads commands on 3 and writes replies on 4, each message ending in NUL)."""

    def __init__(self, width=1400, height=900):
        if not os.access(CHROMIUM, os.X_OK):
            raise BrowserError(f"{CHROMIUM} not found (scripts/deps.sh installs Debian's chromium)")
        self.profile = tempfile.mkdtemp(prefix="chainbench-chromium-")
        to_child, self.commands = os.pipe()
        self.replies, from_child = os.pipe()

        def child_fds():
            # Moved above 4 first, so that placing one on 3 or 4 cannot close the other.
            low = [fcntl.fcntl(fd, fcntl.F_DUPFD, 10) for fd in (to_child, from_child)]
            os.dup2(low[0], 3)
            os.dup2(low[1], 4)

        args = [CHROMIUM, "--headless", "--remote-debugging-pipe", "--no-sandbox", "--disable-gpu",
                "--no-first-run", "--disable-extensions", "--hide-scrollbars", "--mute-audio",
                f"--user-data-dir={self.profile}", f"--window-size={width},{height}",
                "--force-device-scale-factor=1", "about:blank"]
        self.process = subprocess.Popen(args, preexec_fn=child_fds, pass_fds=(3, 4),
                                        stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                                        stderr=subprocess.DEVNULL)
        os.close(to_child)
        os.close(from_child)
        self.buffer, self.next_id, self.session = b"", 0, None
        self.width, self.height = width, height

    def call(self, method, params=None, timeout=60.0):
        """Sends one command and waits for its reply; raises BrowserError on an error reply."""
        self.next_id += 1
        message = {"id": self.next_id, "method": method, "params": params or {}}
        if self.session and not method.startswith("Target."):
            message["sessionId"] = self.session
        os.write(self.commands, json.dumps(message).encode() + b"\0")
        deadline = time.monotonic() + timeout
        while True:
            while b"\0" not in self.buffer:
                if time.monotonic() > deadline:
                    raise BrowserError(f"no reply to {method} within {timeout:g} s")
                chunk = os.read(self.replies, 1 << 20)
                if not chunk:
                    raise BrowserError(f"chromium closed its pipe during {method}")
                self.buffer += chunk
            text, _, self.buffer = self.buffer.partition(b"\0")
            reply = json.loads(text)
            if reply.get("id") == self.next_id:
                if "error" in reply:
                    raise BrowserError(f"{method}: {reply['error'].get('message')}")
                return reply.get("result", {})

    def open(self, url):
        """Opens url in a new tab and attaches to it."""
        target = self.call("Target.createTarget", {"url": "about:blank"})["targetId"]
        self.session = self.call("Target.attachToTarget", {"targetId": target,
                                                           "flatten": True})["sessionId"]
        self.call("Page.enable")
        self.call("Emulation.setDeviceMetricsOverride", {"width": self.width, "height": self.height,
                                                         "deviceScaleFactor": 1, "mobile": False})
        self.call("Page.navigate", {"url": url})

    def evaluate(self, expression, timeout=60.0):
        """The value of a JavaScript expression in the page (awaited if it is a promise)."""
        result = self.call("Runtime.evaluate", {"expression": expression, "returnByValue": True,
                                                "awaitPromise": True}, timeout)
        if "exceptionDetails" in result:
            details = result["exceptionDetails"]
            text = details.get("exception", {}).get("description") or details.get("text")
            raise BrowserError(f"the page threw: {text}")
        return result["result"].get("value")

    def wait_for(self, expression, timeout=60.0, what="the page"):
        deadline = time.monotonic() + timeout
        while not self.evaluate(expression):
            if time.monotonic() > deadline:
                raise BrowserError(f"{what} not done within {timeout:g} s ({expression})")
            time.sleep(0.02)

    def screenshot(self, path):
        data = self.call("Page.captureScreenshot", {"format": "png"})["data"]
        with open(path, "wb") as f:
            f.write(base64.b64decode(data))

    def close(self):
        try:
            self.call("Browser.close", timeout=10)
        except (BrowserError, OSError):
            pass
        try:
            self.process.wait(timeout=10)
        except subprocess.TimeoutExpired:
            self.process.kill()
            self.process.wait()
        for fd in (self.commands, self.replies):
            os.close(fd)
        shutil.rmtree(self.profile, ignore_errors=True)

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()


def play_page(browser, page, speed, shot=None, timeout=120.0):
    """Opens a replay page, waits until it is ready, plays it from step 0 to its last step at
    `speed` and saves a screenshot there. Returns the timings and the page's frame statistics."""
    start = time.monotonic()
    browser.open("file://" + os.path.abspath(page))
    browser.wait_for("window.replay !== undefined && window.replay.ready === true", timeout,
                     f"{page}: opening")
    opened = time.monotonic() - start
    steps = browser.evaluate("replay.steps")
    browser.evaluate(f"replay.pause(); replay.seek(0); replay.resetStats(); replay.setSpeed({speed});"
                     " replay.play(); true")
    start = time.monotonic()
    browser.wait_for(f"!replay.playing && replay.step === {steps}", timeout, f"{page}: playing")
    played = time.monotonic() - start
    stats = browser.evaluate("replay.stats()")
    if shot:
        browser.screenshot(shot)
    return {"page": page, "bytes": os.path.getsize(page), "steps": steps, "open_s": opened,
            "play_s": played, "speed": speed, "frames": stats}


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("pages", nargs="+", metavar="PAGE.html")
    parser.add_argument("--shots", metavar="DIR", help="folder for the screenshots")
    parser.add_argument("--speed", type=float, default=8.0)
    parser.add_argument("--json", metavar="FILE", help="write every page's timings here")
    args = parser.parse_args(argv)
    results = []
    try:
        with Browser() as browser:
            for page in args.pages:
                stem = os.path.splitext(os.path.basename(page))[0]
                folder = args.shots or os.path.dirname(os.path.abspath(page))
                os.makedirs(folder, exist_ok=True)
                r = play_page(browser, page, args.speed, os.path.join(folder, stem + ".png"))
                results.append(r)
                f = r["frames"]
                print(f"{page}: {r['bytes'] / 1e6:.2f} MB, opened in {r['open_s']:.2f} s, "
                      f"{r['steps']} steps played at {args.speed:g}x in {r['play_s']:.2f} s; "
                      f"{f['frames']} frames drawn in {f['draw_ms']['mean']:.1f} ms on average "
                      f"(p95 {f['draw_ms']['p95']:.1f}, max {f['draw_ms']['max']:.1f}), "
                      f"{f['interval_ms']['mean']:.0f} ms between frames on average "
                      f"(p95 {f['interval_ms']['p95']:.0f})")
    except BrowserError as e:
        print(f"replay_browser.py: {e}", file=sys.stderr)
        return 2
    if args.json:
        with open(args.json, "w", encoding="utf-8") as f:
            json.dump(results, f, indent=2)
    return 0


if __name__ == "__main__":
    sys.exit(main())
