#!/usr/bin/env python3
"""The sources list from which ./run.sh --web fetches Dear ImGui's sources, for each platform.
Usage: check_imgui_source_list.py PROJECT_ROOT

scripts/imgui-source-list is run on the os-release and the apt index targets (the lines of
`apt-get indextargets`) of Ubuntu 22.04 and 24.04, Debian 12 and Debian unstable, written as
those systems have them, and must name the release's own mirror and suite with the components
that hold the source package imgui: universe on Ubuntu (where main lacks it), main on Debian."""
import subprocess
import sys
import tempfile
from pathlib import Path

root = Path(sys.argv[1]).resolve()


def ubuntu_targets(mirror, codename):
    """An Ubuntu installation's default sources: four components in the release and its updates
    and backports pockets, the security pocket on its own host."""
    lines = []
    for suite in (codename, f"{codename}-updates", f"{codename}-backports"):
        lines += [f"{mirror} {suite} {c}" for c in ("main", "restricted", "universe", "multiverse")]
    lines += [f"http://security.ubuntu.com/ubuntu/ {codename}-security {c}"
              for c in ("main", "restricted", "universe", "multiverse")]
    return lines


CASES = [
    ("Ubuntu 22.04", "NAME=\"Ubuntu\"\nID=ubuntu\nVERSION_ID=\"22.04\"\nVERSION_CODENAME=jammy\n"
     "UBUNTU_CODENAME=jammy\n", ubuntu_targets("http://archive.ubuntu.com/ubuntu/", "jammy"),
     "deb-src http://archive.ubuntu.com/ubuntu/ jammy main restricted universe multiverse"),
    ("Ubuntu 24.04 (arm64, the ports mirror)",
     "NAME=\"Ubuntu\"\nID=ubuntu\nVERSION_ID=\"24.04\"\nVERSION_CODENAME=noble\n",
     ubuntu_targets("http://ports.ubuntu.com/ubuntu-ports/", "noble"),
     "deb-src http://ports.ubuntu.com/ubuntu-ports/ noble main restricted universe multiverse"),
    ("Debian 12", "PRETTY_NAME=\"Debian GNU/Linux 12 (bookworm)\"\nID=debian\n"
     "VERSION_CODENAME=bookworm\n",
     ["http://deb.debian.org/debian/ bookworm main", "http://deb.debian.org/debian/ bookworm main",
      "http://deb.debian.org/debian/ bookworm-updates main",
      "http://deb.debian.org/debian-security/ bookworm-security main"],
     "deb-src http://deb.debian.org/debian/ bookworm main"),
    ("Debian unstable (os-release names the next release)",
     "PRETTY_NAME=\"Debian GNU/Linux forky/sid\"\nID=debian\nVERSION_CODENAME=forky\n",
     ["http://deb.debian.org/debian/ sid main"], "deb-src http://deb.debian.org/debian/ sid main"),
]

problems = []
with tempfile.TemporaryDirectory(prefix="clothlab-source-list-") as folder:
    for name, os_release, targets, expected in CASES:
        release_file = Path(folder) / "os-release"
        targets_file = Path(folder) / "targets"
        release_file.write_text(os_release)
        targets_file.write_text("\n".join(targets) + "\n")
        made = subprocess.run([root / "scripts/imgui-source-list", release_file, targets_file],
                              capture_output=True, text=True)
        got = made.stdout.strip()
        print(f"{name}: {got}")
        if made.returncode != 0 or got != expected:
            problems.append(f"{name}: exit {made.returncode}, {got!r}{made.stderr}; "
                            f"expected {expected!r}")
    # No mirror of the release at all: exit 1 and nothing printed (setup-web.sh says why).
    (Path(folder) / "targets").write_text("")
    made = subprocess.run([root / "scripts/imgui-source-list", Path(folder) / "os-release",
                           Path(folder) / "targets"], capture_output=True, text=True)
    if made.returncode != 1 or made.stdout:
        problems.append(f"no mirror: exit {made.returncode}, {made.stdout!r}; expected 1 and "
                        f"nothing")
for problem in problems:
    print("FAILED: " + problem)
sys.exit(1 if problems else 0)
