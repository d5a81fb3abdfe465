#!/usr/bin/env bash
# The browser build (docs/web.md): installs emscripten (only if missing), fetches Dear
# ImGui's sources from the source package of the same version as libimgui-dev (into
# build-web/deps/, once), and builds the page into build-web/site/. Used by ./run.sh --web and
# ./test.sh; safe to run again.
#   scripts/setup-web.sh [--with-browser]   --with-browser: also chromium and chromedriver, for
#                                           the browser test (tests/web) and
#                                           scripts/benchmark-web
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
web=$root/build-web

# For the browser test, which may start while this runs (./test.sh builds the page while the
# other tests run): build.pid names this build while it runs, build.status holds its exit status
# once it has ended (tests/web/browser.py, wait_for_page_build).
mkdir -p "$web"
rm -f "$web/build.status"
echo $$ >"$web/build.pid"
trap 'echo $? >"$web/build.status.new" && mv "$web/build.status.new" "$web/build.status"' EXIT

# (xz-utils: tar unpacks Dear ImGui's sources, a .tar.xz, with it; a minimal Debian lacks it.)
# (gettext compiles the message catalogues, fonts-dejavu-core is the panel's font: both packed
# into the page.)
packages=(emscripten cmake make python3 xz-utils libimgui-dev libglm-dev libstb-dev gettext
          fonts-dejavu-core)
if [ "${1:-}" = "--with-browser" ]; then
  packages+=(chromium chromium-driver)
fi
"$root/scripts/install-packages.sh" "${packages[@]}"

# Dear ImGui's sources. The package libimgui-dev (scripts/setup.sh) ships a library for this
# machine, not its sources; the distribution's source package of the same version has them. It is
# fetched with apt-get source from the mirror this machine already uses (Debian's or Ubuntu's),
# with a sources list of our own (this machine's apt configuration is not changed), and checked
# by apt against the mirror's signed index.
imgui_version=$(dpkg-query -W -f='${source:Version}' libimgui-dev)
upstream=${imgui_version%-*}    # 1.86+ds-1 -> 1.86+ds
imgui_dir=$web/deps/imgui-${upstream%+*}
if [ ! -f "$imgui_dir/imgui.cpp" ]; then
  # The mirror of this machine's own release, with the components its sources list there
  # (Dear ImGui's source package is in Debian's main, Ubuntu's universe): scripts/imgui-source-list.
  fetch=$web/deps/apt
  rm -rf "$fetch"
  mkdir -p "$fetch/lists/partial"
  if ! "$root/scripts/imgui-source-list" >"$fetch/sources.list"; then
    echo "clothlab: no mirror of this machine's release in its apt sources:" \
         "cannot fetch Dear ImGui's sources (apt-get source imgui)" >&2
    exit 1
  fi
  mirror=$(awk '{print $2}' "$fetch/sources.list")
  apt_options=(-o "Dir::Etc::SourceList=$fetch/sources.list" -o Dir::Etc::SourceParts=/dev/null
               -o "Dir::State::Lists=$fetch/lists" -o APT::Sandbox::User=root)
  echo "clothlab: fetching Dear ImGui's sources (source package imgui $imgui_version" \
       "from $mirror)"
  apt-get "${apt_options[@]}" update -q >/dev/null
  (cd "$fetch" && apt-get "${apt_options[@]}" source --download-only -q "imgui=$imgui_version")
  mkdir -p "$imgui_dir.partial"
  tar -xJf "$fetch"/imgui_"$upstream".orig.tar.xz -C "$imgui_dir.partial" --strip-components=1
  rm -rf "$imgui_dir" && mv "$imgui_dir.partial" "$imgui_dir"
  rm -rf "$fetch"
fi

# emscripten 3.1.6's JavaScript optimiser needs Debian's node modules (acorn), which a newer
# Node.js on the PATH does not look in.
export NODE_PATH=/usr/share/nodejs${NODE_PATH:+:$NODE_PATH}
jobs=$(nproc 2>/dev/null || echo 2)
emcmake cmake -S "$root" -B "$web/cmake" -DCMAKE_BUILD_TYPE=Release \
  -DCLOTHLAB_IMGUI_DIR="$imgui_dir" -DCLOTHLAB_WEB_SITE_DIR="$web/site" >/dev/null
cmake --build "$web/cmake" -j "$jobs"
echo "clothlab: the page is in build-web/site/ (index.html, clothlab.js, clothlab.wasm," \
     "clothlab.data): any static web server can serve that folder"
