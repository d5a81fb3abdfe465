#!/usr/bin/env python3
"""The browser test of the web build (docs/web.md): the page in Debian's headless chromium
(WebGL2 on the CPU, SwiftShader), driven through chromedriver as a user would drive it.

    tests/web/check_page.py SITE_DIR [--out DIR] [--update-reference]

Checks, in order, each waiting for the page (never for a fixed time):
  1. the page loads and its first frame comes, with no error on the console;
  2. the simulated time advances;
  3. the keys 1, 2, 3 switch the stage;
  4. G moves the cloth to the GPU path (fragment shaders) and time advances there; G again
     brings it back to the CPU (WebGL2 has no compute shaders: that path is not offered);
  5. N (pause after one step) then R (reset): the initial cloth, whose picture (the scene, right
     of the panel) matches tests/web/reference/initial_cloth.png within a tolerance, and is
     neither blank nor NaN-coloured;
  6. P downloads a PNG of the canvas's size, with the scene in it;
  7. the mouse: one notch of the wheel zooms in by the window's step, the wheel over the panel
     scrolls it; a drag on the sky orbits the view, a drag that starts on the cloth grabs it;
  8. still no error on the console (the page's and the browser's, WebGL's warnings included).
Exit status 0 when all pass, 1 at the first failure (what failed, in a sentence), 2 for bad
usage. --out DIR keeps the screenshots; --update-reference rewrites the reference from this run
(after a change that moves the picture on purpose: look at it before committing it).
"""
import argparse
import base64
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import browser  # noqa: E402

here = os.path.dirname(os.path.abspath(__file__))
reference_path = os.path.join(here, "reference", "initial_cloth.png")
width, height = 1280, 800
bar_height = 22  # web/index.html: the status bar under the canvas
# The scene, right of the panel (410 px wide at the default font) and inside the canvas.
scene_box = (430, 10, width - 440, height - bar_height - 20)  # left, top, width, height
# The panel, left of the scene, and a point on it (its sections, below the readouts).
panel_box = (0, 0, 410, height - bar_height)
panel_point = (200, 500)
# A point of the initial cloth, in page pixels (tests/web/reference/initial_cloth.png, plus
# scene_box's corner).
cloth_point = (430 + 520, 10 + 255)
tolerance = 40  # per channel, of 255: SwiftShader versions round differently
max_differing_fraction = 0.01


class failure(Exception):
    pass


def console_errors(page, seen):
    """The page's recorded errors and the browser's console errors and WebGL warnings since
    the start (accumulated in `seen`)."""
    for level, message in page.console():
        if level == "SEVERE" or (level == "WARNING" and ("WebGL" in message or "GL_" in message)):
            seen.append(f"{level}: {message}")
    return (page.run("return window.clothlab ? window.clothlab.errors : ['no window.clothlab']")
            or []) + seen


def status(page):
    return page.run("return window.clothlab && window.clothlab.status")


def wait_status(page, condition, what, seen, timeout=60):
    """Waits until the status satisfies the JavaScript condition on `s` (the status)."""
    def early():
        errors = console_errors(page, seen)
        return f"the page reported an error: {errors[0]}" if errors else None
    try:
        page.wait_for(f"const s = window.clothlab && window.clothlab.status; "
                      f"return !!s && ({condition});", what, timeout, early)
    except browser.browser_error as e:
        raise failure(f"{e}; the last status: {status(page)}") from None
    return status(page)


def picture_problems(scene, reference, measured=None):
    """What is wrong with the scene's picture: blank, NaN-coloured, or unlike the reference.
    measured: a dict that receives the fraction of differing pixels."""
    pixels = scene.pixels
    count = scene.width * scene.height
    colours = {pixels[i:i + 3] for i in range(0, len(pixels), 3 * 97)}
    if len(colours) < 20:
        return f"the scene is blank: {len(colours)} distinct colours in a sample"
    black = sum(1 for i in range(0, len(pixels), 3) if pixels[i:i + 3] == b"\0\0\0")
    if black > 0.01 * count:
        return f"{100 * black / count:.1f}% of the scene is pure black (NaN colours?)"
    if reference is None:
        return None
    if (reference.width, reference.height) != (scene.width, scene.height):
        return (f"the reference is {reference.width} x {reference.height}, the scene "
                f"{scene.width} x {scene.height}")
    differing = 0
    for i in range(0, len(pixels), 3):
        if (abs(pixels[i] - reference.pixels[i]) > tolerance or
                abs(pixels[i + 1] - reference.pixels[i + 1]) > tolerance or
                abs(pixels[i + 2] - reference.pixels[i + 2]) > tolerance):
            differing += 1
    if measured is not None:
        measured["differing"] = differing / count
    if differing > max_differing_fraction * count:
        return (f"{100 * differing / count:.1f}% of the scene's pixels differ from the reference "
                f"by more than {tolerance}/255 (at most {100 * max_differing_fraction:.0f}% may)")
    return None


def check_screenshot_key(page, out):
    """P: the page hands the frame to the browser as a PNG download of the canvas's size."""
    page.press("p")
    download = page.wait_for("const d = window.clothlab.downloads; return d && d[0];",
                             "key P: a screenshot downloaded", timeout=60)
    png = page.run_async("""
        const done = arguments[arguments.length - 1];
        fetch(arguments[0]).then((r) => r.arrayBuffer()).then((b) => {
          let s = ''; new Uint8Array(b).forEach((v) => { s += String.fromCharCode(v); });
          done(btoa(s));
        }).catch((e) => done('error: ' + e));""", download["url"])
    if png.startswith("error"):
        raise failure(f"key P: the download {download['name']} cannot be read back: {png}")
    image = browser.read_png(base64.b64decode(png))
    canvas = page.run("const c = document.getElementById('canvas'); return [c.width, c.height];")
    if [image.width, image.height] != canvas:
        raise failure(f"key P: {download['name']} is {image.width} x {image.height}, the canvas "
                      f"{canvas[0]} x {canvas[1]}")
    problem = picture_problems(image.crop(*scene_box), None)
    if problem:
        raise failure(f"key P: {download['name']}: {problem}")
    if out:
        image.write_png(os.path.join(out, "key_p_download.png"))
    print(f"ok: P downloads {download['name']}, {image.width} x {image.height}, the scene in it")


def red_pixels(image):
    """The pixels of the cloth's red squares (nothing else in the scene is that red)."""
    p = image.pixels
    return sum(1 for i in range(0, len(p), 3) if p[i] > 150 and p[i + 1] < 90 and p[i + 2] < 90)


def check_wheel(page, before):
    """The wheel, one notch towards the screen, zooms in by the window's step (x 1/0.9): the
    cloth covers about 1/0.9^2 = 1.23 times as many pixels (the browser's wheel deltas, pixels
    and downwards, converted to GLFW's notches: web_main.cpp)."""
    frames = page.run("return window.clothlab.frames")
    page._call("POST", page._session + "/actions", {"actions": [
        {"type": "pointer", "id": "mouse", "parameters": {"pointerType": "mouse"},
         "actions": [{"type": "pointerMove", "duration": 0, "x": cloth_point[0],
                      "y": cloth_point[1] + 200}]},
        {"type": "wheel", "id": "wheel", "actions": [
            {"type": "scroll", "x": cloth_point[0], "y": cloth_point[1] + 200, "deltaX": 0,
             "deltaY": -100, "duration": 0}]}]})
    page.wait_for(f"return window.clothlab.frames >= {frames} + 3", "frames after the wheel", 60)
    after = page.screenshot().crop(*scene_box)
    ratio = red_pixels(after) / max(red_pixels(before), 1)
    if not 1.1 <= ratio <= 1.4:
        raise failure(f"one notch of the wheel made the cloth cover {ratio:.2f} times as many "
                      "pixels (a zoom of 1/0.9 gives about 1.23)")
    print(f"ok: one notch of the wheel zooms in (the cloth covers {ratio:.2f} x the pixels)")


def differing_fraction(a, b):
    """The fraction of the pixels of two images of one size that differ by more than
    `tolerance` in a channel."""
    count = len(a.pixels) // 3
    differing = sum(1 for i in range(0, len(a.pixels), 3)
                    if max(abs(a.pixels[i + c] - b.pixels[i + c]) for c in range(3)) > tolerance)
    return differing / count


def check_panel_wheel(page):
    """The wheel over the panel scrolls the panel (Dear ImGui takes it from the page's own
    listener, web_main.cpp): a notch away from the user moves its sections up. Its live
    numbers change from frame to frame too, so the scroll must change many times more pixels
    than two frames without it do."""
    def panel():
        return page.screenshot().crop(*panel_box)

    def after_frames(count):
        frames = page.run("return window.clothlab.frames")
        page.wait_for(f"return window.clothlab.frames >= {frames + count}", "the next frames", 60)

    page._call("POST", page._session + "/actions", {"actions": [
        {"type": "pointer", "id": "mouse", "parameters": {"pointerType": "mouse"},
         "actions": [{"type": "pointerMove", "duration": 0, "x": panel_point[0],
                      "y": panel_point[1]}]}]})
    after_frames(3)
    first = panel()
    after_frames(3)
    still = differing_fraction(first, panel())
    page._call("POST", page._session + "/actions", {"actions": [
        {"type": "wheel", "id": "wheel", "actions": [
            {"type": "scroll", "x": panel_point[0], "y": panel_point[1], "deltaX": 0,
             "deltaY": 300, "duration": 0}]}]})
    after_frames(3)
    scrolled = differing_fraction(first, panel())
    if scrolled < max(0.05, 5 * still):
        raise failure(f"three notches of the wheel over the panel changed {100 * scrolled:.1f}% of "
                      f"its pixels, no more than its own numbers do ({100 * still:.1f}% between two "
                      "frames): the panel did not scroll")
    print(f"ok: the wheel scrolls the panel ({100 * scrolled:.0f}% of its pixels change, "
          f"{100 * still:.1f}% without it)")


def drag(page, start, end, shift=False):
    """A left-button drag from `start` to `end` (page pixels), Shift held if asked. The window
    reads the button's state once a frame, so each move waits for the page's next frame (a drag
    quicker than a frame would go unseen on a loaded machine)."""
    def act(source):
        page._call("POST", page._session + "/actions", {"actions": [source]})

    def pointer(*steps):
        act({"type": "pointer", "id": "mouse", "parameters": {"pointerType": "mouse"},
             "actions": list(steps)})

    def next_frames(count):
        frames = page.run("return window.clothlab.frames")
        page.wait_for(f"return window.clothlab.frames >= {frames + count}", "the next frame", 60)

    if shift:
        act({"type": "key", "id": "keyboard", "actions": [{"type": "keyDown", "value": "\ue008"}]})
    pointer({"type": "pointerMove", "duration": 0, "x": start[0], "y": start[1]})
    next_frames(1)
    pointer({"type": "pointerDown", "button": 0})
    next_frames(2)
    for i in range(1, 9):
        pointer({"type": "pointerMove", "duration": 0,
                 "x": start[0] + (end[0] - start[0]) * i // 8,
                 "y": start[1] + (end[1] - start[1]) * i // 8})
        next_frames(1)
    pointer({"type": "pointerUp", "button": 0})
    next_frames(2)
    if shift:
        act({"type": "key", "id": "keyboard", "actions": [{"type": "keyUp", "value": "\ue008"}]})


def check_mouse(page, seen):
    """The mouse, as on the desktop: a drag on the sky orbits the camera, a drag that starts
    on the cloth grabs it (the window prints each drag's end: window.clothlab.log)."""
    log_length = page.run("return window.clothlab.log.length")
    drag(page, (1100, 80), (900, 120))
    orbit = wait_log(page, log_length, "left drag ended (orbit)", "a drag on the sky", seen)
    log_length = page.run("return window.clothlab.log.length")
    drag(page, cloth_point, (cloth_point[0], cloth_point[1] - 60))
    wait_log(page, log_length, "left drag ended (grab)", "a drag on the cloth", seen)
    print(f"ok: the mouse orbits the view and grabs the cloth ({orbit.split(': ', 1)[1]})")


def wait_log(page, start, text, what, seen):
    script = (f"return window.clothlab.log.slice({start})"
              f".find((line) => line.includes({text!r}));")
    try:
        return page.wait_for(script, f"{what}: the line '{text}'", timeout=30)
    except browser.browser_error as e:
        lines = page.run(f"return window.clothlab.log.slice({start})")
        raise failure(f"{e}; the page printed {lines}") from None


def main():
    parser = argparse.ArgumentParser(description="The browser test of the web build.")
    parser.add_argument("site", help="the built page's folder (build-web/site)")
    parser.add_argument("--out", help="a folder to keep the screenshots in")
    parser.add_argument("--update-reference", action="store_true")
    args = parser.parse_args()
    problem = browser.wait_for_page_build(os.path.dirname(os.path.abspath(args.site)))
    if problem:
        print(f"FAIL: {problem}")
        return 1
    if not os.path.isfile(os.path.join(args.site, "clothlab.wasm")) and \
            not os.path.isfile(os.path.join(args.site, "index.html")):
        print(f"FAIL: the page is not built ({args.site} is empty or missing): ./test.sh builds "
              "it with scripts/setup-web.sh --with-browser, which installs emscripten and "
              "chromium; or ./run.sh --web-build-only")
        return 1
    if args.out:
        os.makedirs(args.out, exist_ok=True)
    seen = []
    try:
        with browser.page_session(args.site, width=width, height=height) as page:
            s = wait_status(page, "true", "the page's first frame", seen, timeout=120)
            print(f"ok: the page loads and draws (stage {s['stage']}, cloth on {s['backend']}, "
                  f"N = {s['grid_size']})")
            s = wait_status(page, "s.time > 0.05", "the simulated time to start", seen)
            t0 = s["time"]
            s = wait_status(page, f"s.time > {t0} + 0.05", "the simulated time to advance", seen)
            print(f"ok: the simulated time advances ({t0:.3f} s, then {s['time']:.3f} s; "
                  f"{s['steps_per_second']:.0f} steps/s, {s['frames_per_second']:.0f} frames/s)")
            for key, stage in (("1", "spring"), ("2", "coupled"), ("3", "cloth")):
                page.press(key)
                wait_status(page, f"s.stage === '{stage}'", f"key {key}: stage {stage}", seen)
            print("ok: keys 1, 2, 3 switch to the spring, the chain, the cloth")
            page.press("g")
            s = wait_status(page, "s.backend === 'gpu'", "key G: the cloth on the GPU", seen)
            t0 = s["time"]
            s = wait_status(page, f"s.backend === 'gpu' && s.time > {t0} + 0.05",
                            "the time to advance on the GPU", seen)
            if args.out:
                page.screenshot().write_png(os.path.join(args.out, "gpu.png"))
            page.press("g")
            wait_status(page, "s.backend === 'cpu'", "key G again: the cloth back on the CPU",
                        seen)
            print(f"ok: G runs the cloth on the GPU ({t0:.3f} s, then {s['time']:.3f} s) and "
                  "back on the CPU")
            page.press("n")
            page.press("r")
            s = wait_status(page, "s.time === 0", "keys N then R: the paused initial state", seen)
            frames = page.run("return window.clothlab.frames")
            page.wait_for(f"return window.clothlab.frames >= {frames} + 3",
                          "three frames of the initial state", timeout=60)
            shot = page.screenshot()
            if args.out:
                shot.write_png(os.path.join(args.out, "initial_cloth_page.png"))
            scene = shot.crop(*scene_box)
            if args.update_reference:
                os.makedirs(os.path.dirname(reference_path), exist_ok=True)
                scene.write_png(reference_path)
                print(f"check_page: wrote {reference_path}: look at it before committing it")
            reference = (browser.read_png(open(reference_path, "rb").read())
                         if os.path.exists(reference_path) else None)
            problem = picture_problems(scene, None)  # blank, NaN-coloured
            if problem is None and reference is None:
                raise failure(f"no reference picture {reference_path} "
                              "(--update-reference makes it)")
            measured = {}
            problem = problem or picture_problems(scene, reference, measured)
            if problem:
                if args.out:
                    scene.write_png(os.path.join(args.out, "initial_cloth.png"))
                raise failure(f"the canvas does not show the initial cloth: {problem}")
            print(f"ok: the canvas shows the initial cloth ({100 * measured['differing']:.2f}% of "
                  f"its pixels differ from the reference by more than {tolerance}/255; at most "
                  f"{100 * max_differing_fraction:.0f}% may)")
            check_screenshot_key(page, args.out)
            check_wheel(page, scene)
            check_panel_wheel(page)
            check_mouse(page, seen)
            errors = console_errors(page, seen)
            if errors:
                raise failure(f"the console has {len(errors)} error(s), the first: {errors[0]}")
            print("ok: no error on the console")
    except failure as e:
        print(f"FAIL: {e}")
        return 1
    except browser.browser_error as e:
        print(f"FAIL: {e}")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
