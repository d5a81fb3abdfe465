#!/usr/bin/env bash
# Installs the packages clothlab needs (only the missing ones: apt-get on Debian and Ubuntu,
# Homebrew on macOS, scripts/install-packages.sh), then configures and builds it. Used by ./run.sh
# and ./test.sh; safe to run again.
#   scripts/setup.sh [BUILD_TYPE] [--with-web]   (default Release; build folder: build/)
# --with-web: also the browser build's packages (emscripten, chromium, chromedriver), in the same
# apt-get run (./test.sh; scripts/setup-web.sh builds the page).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build_type=Release
with_web=0
for argument in "$@"; do
  case "$argument" in
    --with-web) with_web=1 ;;
    -*) echo "setup.sh: unknown option $argument (known: --with-web)" >&2; exit 2 ;;
    *) build_type=$argument ;;
  esac
done

# Named as Debian names them; scripts/packages.txt gives each one's name on Ubuntu and Homebrew.
# git, python3 (and PyYAML, for the workflow's test), ImageMagick, xdotool, Xvfb and bubblewrap: the scripts and tests call them.
# gettext compiles the message catalogues (po/, docs/translating.md); fonts-dejavu-core is the
# panel's font, which has the accents of French.
packages=(
  build-essential ccache cmake make ninja-build pkg-config clang-format python3 python3-yaml git
  xz-utils
  glslang-tools gettext fonts-dejavu-core
  libglfw3-dev libglew-dev libglm-dev libimgui-dev libstb-dev libosmesa6-dev libegl-dev
  libopengl-dev libegl-mesa0
  libcli11-dev libgtest-dev libbenchmark-dev
  libgl1-mesa-dri xvfb xauth xdotool imagemagick
  bubblewrap  # the grader's sandbox: tests without network, on a read-only file system
)

if [ "$with_web" = 1 ]; then
  packages+=(emscripten chromium chromium-driver)
fi
"$root/scripts/install-packages.sh" "${packages[@]}"

# Dear ImGui and stb where the system has no package of them (Homebrew has neither; an older
# Ubuntu may lack them): their sources, once, into build-deps/. That version of Dear ImGui is one
# the code was compiled against (docs/platforms.md).
options=()
deps=$root/build-deps
if ! pkg-config --exists imgui 2>/dev/null; then
  if [ ! -f "$deps/imgui/imgui.cpp" ]; then
    git clone -q --depth 1 --branch v1.92.2b https://github.com/ocornut/imgui "$deps/imgui"
  fi
  options+=(-DCLOTHLAB_IMGUI_DIR="$deps/imgui")
fi
if ! pkg-config --exists stb 2>/dev/null; then
  if [ ! -f "$deps/stb/stb_image.h" ]; then
    git clone -q --depth 1 https://github.com/nothings/stb "$deps/stb"
  fi
  options+=(-DCLOTHLAB_STB_DIR="$deps/stb")
fi

# Ninja for a new build folder (an existing one keeps the generator it was made with): after a
# one-line edit it rebuilds a test program in a fraction of a second where make's walk through
# the targets takes two (./test.sh -L q8, docs/testing.md).
if [ ! -f "$root/build/CMakeCache.txt" ] && command -v ninja >/dev/null; then
  options+=(-G Ninja)
fi
jobs=$(getconf _NPROCESSORS_ONLN 2>/dev/null || echo 2)
cmake -S "$root" -B "$root/build" -DCMAKE_BUILD_TYPE="$build_type" ${options[@]+"${options[@]}"}
cmake --build "$root/build" -j "$jobs"
