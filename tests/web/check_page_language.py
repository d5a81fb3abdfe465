#!/usr/bin/env python3
"""The page in the visitor's language (docs/translating.md), in headless chromium.

    check_page_language.py SITE [--out DIR]

?lang=fr in the address gives the French page (its status line under the canvas, its panel:
window.clothlab.status.language is "fr" and the line reads "étape ... pas/s"); a browser whose
language is French (chromium --lang=fr-FR --accept-lang=fr-FR) gives it without ?lang; ?lang=en overrides the
browser's French; and a plain browser gets English. With --out, the French page's screenshot is
written there (french.png), to be looked at. Exit 1 with what failed.
"""
import argparse
import os
import sys

sys.dont_write_bytecode = True
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import browser  # noqa: E402

STATUS = "const s = window.clothlab && window.clothlab.status; return s && s.text ? s : null;"


def page_language(site, path, arguments, out=None):
    with browser.page_session(site, path=path, arguments=arguments) as page:
        s = page.wait_for(STATUS, f"the page's first status ({path or 'index.html'}, "
                                  f"{' '.join(arguments) or 'no argument'})", timeout=120)
        bar = page.run("return document.getElementById('bar').textContent;")
        if out:
            page.wait_for("const s = window.clothlab.status; return s.time > 0.5;",
                          "half a second of simulated time", timeout=60)
            page.screenshot().write_png(os.path.join(out, "french.png"))
        return s.get("language"), bar


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("site")
    parser.add_argument("--out")
    args = parser.parse_args()
    if not os.path.isfile(os.path.join(args.site, "index.html")):
        print(f"FAIL: the page is not built ({args.site}): scripts/setup-web.sh builds it")
        return 1
    if args.out:
        os.makedirs(args.out, exist_ok=True)
    cases = [
        ("index.html?lang=fr", [], "fr", "pas/s", args.out),
        ("index.html", ["--lang=fr-FR", "--accept-lang=fr-FR"], "fr", "pas/s", None),
        ("index.html?lang=en", ["--lang=fr-FR", "--accept-lang=fr-FR"], "en", "steps/s", None),
        ("index.html", ["--lang=en-US", "--accept-lang=en-US"], "en", "steps/s", None),
    ]
    failed = 0
    for path, arguments, language, words, out in cases:
        what = f"{path} with {' '.join(arguments) or 'no argument'}"
        try:
            got, bar = page_language(args.site, path, arguments, out)
        except browser.browser_error as error:
            print(f"FAIL: {what}: {error}")
            failed += 1
            continue
        if got != language or words not in bar:
            print(f"FAIL: {what}: the page speaks {got!r} ('{bar}'), not {language!r}")
            failed += 1
        else:
            print(f"ok: {what}: {language} ('{bar}')")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
