"""A real browser on the browser build's page, for tests/web/check_page.py and
scripts/benchmark-web: the page served on 127.0.0.1, Debian's headless chromium driven through
chromedriver's WebDriver protocol (plain HTTP and JSON: nothing to install from elsewhere), and
its PNG screenshots as pixels (through ImageMagick).

    with page_session(site) as page:
        page.wait_for("return window.clothlab.status !== null", "the first frame")
        page.press("g")
        image = page.screenshot()   # rgb_image
"""
import base64
import contextlib
import functools
import http.server
import json
import os
import shutil
import socket
import subprocess
import tempfile
import threading
import time
import urllib.error
import urllib.request


class browser_error(Exception):
    """What went wrong, in a sentence for the test's output."""


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


class _quiet_handler(http.server.SimpleHTTPRequestHandler):
    extensions_map = {**http.server.SimpleHTTPRequestHandler.extensions_map,
                      ".wasm": "application/wasm", ".js": "text/javascript"}

    def log_message(self, *args):
        pass


@contextlib.contextmanager
def static_server(site):
    """Serves the folder `site` on 127.0.0.1 (a free port) while the block runs; yields its URL."""
    handler = functools.partial(_quiet_handler, directory=site)
    server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), handler)
    thread = threading.Thread(target=server.serve_forever, daemon=True)
    thread.start()
    try:
        yield f"http://127.0.0.1:{server.server_address[1]}/"
    finally:
        server.shutdown()
        server.server_close()


def wait_for_page_build(web_folder):
    """Waits while scripts/setup-web.sh builds the page (./test.sh runs it beside the other
    tests): until build.status says how it ended. Returns None when the page can be opened,
    else what went wrong. A build that is not running and left no status (the page built some
    other way, or never) is left to the caller."""
    status_path = os.path.join(web_folder, "build.status")
    pid_path = os.path.join(web_folder, "build.pid")
    while not os.path.exists(status_path):
        try:
            pid = int(open(pid_path).read())
            os.kill(pid, 0)  # the build still runs
        except (OSError, ValueError):
            if os.path.exists(status_path):
                break
            return None
        time.sleep(0.5)
    status = open(status_path).read().strip()
    if status != "0":
        return (f"the page's build failed (scripts/setup-web.sh, exit {status}): see "
                f"{os.path.join(web_folder, 'build.log')} or run ./run.sh --web-build-only")
    return None


def find_browser():
    """chromium and chromedriver, or a browser_error saying what is missing and how to get it."""
    chromium = shutil.which("chromium") or "/usr/bin/chromium"
    driver = shutil.which("chromedriver") or "/usr/bin/chromedriver"
    missing = [p for p, path in (("chromium", chromium), ("chromium-driver", driver))
               if not os.path.exists(path)]
    if missing:
        raise browser_error(
            f"{' and '.join(missing)} not installed: the browser test needs Debian's chromium "
            "and chromium-driver (./test.sh installs them: scripts/setup-web.sh --with-browser)")
    return chromium, driver


# Headless chromium with WebGL2 on the CPU (SwiftShader), no network beyond 127.0.0.1.
def chromium_arguments(width, height, profile):
    return ["--headless=new", "--no-sandbox", "--use-angle=swiftshader",
            "--enable-unsafe-swiftshader", f"--window-size={width},{height}",
            "--no-first-run", "--disable-background-networking", "--disable-component-update",
            "--disable-sync", "--disable-quic", "--disable-extensions",
            "--disable-background-timer-throttling", "--disable-renderer-backgrounding",
            "--disable-backgrounding-occluded-windows", f"--user-data-dir={profile}"]


class page_session:
    """One chromium, one tab, on `url` (or on `site` served for the session, at `path` there:
    "index.html?lang=fr"); `arguments`: chromium's own, added ("--lang=fr-FR")."""

    def __init__(self, site=None, url=None, width=1280, height=800, timeout=120, path="",
                 arguments=()):
        self.site, self.url, self.width, self.height = site, url, width, height
        self.timeout, self.path, self.arguments = timeout, path, list(arguments)
        self._stack = contextlib.ExitStack()

    def __enter__(self):
        try:
            return self._start()
        except BaseException:
            self._stack.close()
            raise

    def __exit__(self, *exc):
        self._stack.close()

    def _start(self):
        chromium, driver = find_browser()
        if self.url is None:
            self.url = self._stack.enter_context(static_server(self.site)) + self.path
        profile = self._stack.enter_context(tempfile.TemporaryDirectory(prefix="clothlab-web-"))
        port = free_port()
        log = open(os.path.join(profile, "chromedriver.log"), "w")
        self._stack.callback(log.close)
        process = subprocess.Popen([driver, f"--port={port}"], stdout=log,
                                   stderr=subprocess.STDOUT)
        self._stack.callback(_stop, process)
        self._driver = f"http://127.0.0.1:{port}"
        self._wait_for_driver(process)
        capabilities = {"browserName": "chrome",
                        "goog:chromeOptions": {
                            "binary": chromium,
                            "args": chromium_arguments(self.width, self.height,
                                                       os.path.join(profile, "chromium"))
                            + self.arguments},
                        "goog:loggingPrefs": {"browser": "ALL"}}
        answer = self._call("POST", "/session",
                            {"capabilities": {"alwaysMatch": capabilities}})
        self._session = f"/session/{answer['sessionId']}"
        self._stack.callback(self._end_session)
        self._call("POST", self._session + "/timeouts", {"script": self.timeout * 1000})
        # The page's viewport exactly width x height CSS pixels at one device pixel each (the
        # window's size would include the browser's own frame).
        self._call("POST", self._session + "/goog/cdp/execute", {
            "cmd": "Emulation.setDeviceMetricsOverride",
            "params": {"width": self.width, "height": self.height, "deviceScaleFactor": 1,
                       "mobile": False}})
        self._call("POST", self._session + "/url", {"url": self.url})
        return self

    def _wait_for_driver(self, process):
        deadline = time.monotonic() + 30
        while time.monotonic() < deadline:
            if process.poll() is not None:
                raise browser_error(f"chromedriver exited at start (status {process.returncode})")
            try:
                if self._call("GET", "/status").get("ready"):
                    return
            except (OSError, browser_error):
                pass
            time.sleep(0.1)
        raise browser_error("chromedriver did not answer within 30 s")

    def _end_session(self):
        with contextlib.suppress(Exception):
            self._call("DELETE", self._session)

    def _call(self, method, path, body=None):
        data = json.dumps(body).encode() if body is not None else None
        request = urllib.request.Request(self._driver + path, data=data, method=method,
                                         headers={"Content-Type": "application/json"})
        try:
            with urllib.request.urlopen(request, timeout=self.timeout + 30) as response:
                return json.loads(response.read() or b"{}").get("value")
        except urllib.error.HTTPError as error:
            try:
                value = json.loads(error.read()).get("value", {})
                message = f"{value.get('error')}: {value.get('message', '').splitlines()[0]}"
            except (ValueError, AttributeError, IndexError):
                message = str(error)
            raise browser_error(f"WebDriver {method} {path.split('/')[-1]}: {message}") from None

    def run(self, script, *arguments):
        """The value of a JavaScript function body (`return ...`) run in the page."""
        return self._call("POST", self._session + "/execute/sync",
                          {"script": script, "args": list(arguments)})

    def run_async(self, script, *arguments):
        """The same for a body that calls arguments[arguments.length - 1](value) when done."""
        return self._call("POST", self._session + "/execute/async",
                          {"script": script, "args": list(arguments)})

    def wait_for(self, condition, what, timeout=60, fail_on=None):
        """Waits until the JavaScript expression body `condition` returns a true value, and
        returns it; browser_error naming `what` after `timeout` s. fail_on(): a message that
        ends the wait early (e.g. an error the page reported), or None."""
        deadline = time.monotonic() + timeout
        while True:
            value = self.run(condition)
            if value:
                return value
            if fail_on is not None:
                reason = fail_on()
                if reason:
                    raise browser_error(f"waiting for {what}: {reason}")
            if time.monotonic() > deadline:
                raise browser_error(f"{what}: not within {timeout} s")
            time.sleep(0.1)

    def press(self, key):
        """A key pressed and released, as a user would (keydown, keypress, keyup)."""
        self._call("POST", self._session + "/actions", {"actions": [{
            "type": "key", "id": "keyboard",
            "actions": [{"type": "keyDown", "value": key}, {"type": "keyUp", "value": key}]}]})

    def screenshot(self):
        """The tab's viewport, as an rgb_image."""
        png = base64.b64decode(self._call("GET", self._session + "/screenshot"))
        return read_png(png)

    def console(self):
        """The browser's console messages since the last call: [(level, message)]."""
        try:
            entries = self._call("POST", self._session + "/se/log", {"type": "browser"})
        except browser_error:
            return []
        return [(e.get("level", ""), e.get("message", "")) for e in entries or []]


def _stop(process):
    process.terminate()
    try:
        process.wait(timeout=10)
    except subprocess.TimeoutExpired:
        process.kill()
        process.wait()


class rgb_image:
    """8-bit RGB pixels, top row first."""

    def __init__(self, width, height, pixels):
        self.width, self.height, self.pixels = width, height, pixels  # bytes, 3 per pixel

    def pixel(self, x, y):
        i = 3 * (y * self.width + x)
        return self.pixels[i], self.pixels[i + 1], self.pixels[i + 2]

    def crop(self, left, top, width, height):
        rows = [self.pixels[3 * ((top + y) * self.width + left):
                            3 * ((top + y) * self.width + left + width)]
                for y in range(height)]
        return rgb_image(width, height, b"".join(rows))

    def write_png(self, path):
        subprocess.run(["convert", "-size", f"{self.width}x{self.height}", "-depth", "8",
                        "rgb:-", path], input=self.pixels, check=True)


def read_png(data):
    """An rgb_image from PNG bytes (decoded by ImageMagick, which scripts/setup.sh installs)."""
    size = subprocess.run(["identify", "-format", "%w %h", "png:-"], input=data,
                          capture_output=True, check=True).stdout.split()
    width, height = int(size[0]), int(size[1])
    pixels = subprocess.run(["convert", "png:-", "-depth", "8", "rgb:-"], input=data,
                            capture_output=True, check=True).stdout
    if len(pixels) != 3 * width * height:
        raise browser_error(f"a {width} x {height} PNG decoded to {len(pixels)} bytes")
    return rgb_image(width, height, pixels)
