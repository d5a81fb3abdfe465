#!/usr/bin/env python3
"""The browser test can fail: on a page that behaves like clothlab's (status, keys, time) but
whose canvas draws nothing (tests/web/blank_site), tests/web/check_page.py must fail, at the
picture, saying the canvas is blank."""
import os
import subprocess
import sys

here = os.path.dirname(os.path.abspath(__file__))
run = subprocess.run([sys.executable, os.path.join(here, "check_page.py"),
                      os.path.join(here, "blank_site")], capture_output=True, text=True)
print(run.stdout, end="")
print(run.stderr, end="", file=sys.stderr)
if run.returncode != 1 or "does not show the initial cloth" not in run.stdout or \
        "blank" not in run.stdout:
    print(f"check_blank_page_fails: the browser test did not fail at the picture on a blank "
          f"page (exit {run.returncode})")
    sys.exit(1)
print("ok: the browser test fails on a blank canvas, at the picture")
