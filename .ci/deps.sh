#!/usr/bin/env bash
# Installs the Debian 12 packages Twister Station needs. As root: apt-get install
# (refreshing the package lists first when they are empty or stale). Otherwise:
# prints the exact command to run and exits 1 if anything is missing.
set -euo pipefail

packages=(
  # toolchain and test stack
  build-essential cmake ninja-build pkg-config git clang libclang-rt-14-dev
  clang-format clang-tidy googletest libgtest-dev libgmock-dev libbenchmark-dev
  librapidcheck-dev
  python3  # CLI tests (tests/sim/fastrak_dump_cli_test.py)
  # core
  libglm-dev
  # hal backends and the station
  libusb-1.0-0-dev libgpiod-dev libhidapi-dev libsystemd-dev libtomlplusplus-dev
  libcli11-dev umockdev libumockdev-dev
  libsodium-dev  # the display link's pre-shared-key challenge-response (hal/sodium)
  systemd  # systemd-analyze checks the deployment unit (tests/hal/twister-station)
  # host tools and display
  libpng-dev libglfw3-dev libepoxy-dev libegl-dev
  libimgui-dev  # the display's heads-up text (Dear ImGui with its OpenGL 3 back end)
  libtinygltf-dev  # .glb export (hal/meshio: twister export, twister-bridge --export, the station)
  admesh  # checks the exported STL (tests/host/twister export_command_test)
  prometheus  # promtool checks the station's metrics file (tests/hal/health)
  libgl1-mesa-dri xvfb xauth  # xvfb: the bridge's window path is tested on a virtual X server
  libcairo2-dev fonts-dejavu-core  # twister figure8 draws its SVG/PNG with cairo, text in DejaVu Sans
  imagemagick  # the showcase's figure rows and animated GIF (sim/scenarios/showcase.sh)
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "deps: all ${#packages[@]} packages present"
  exit 0
fi

if [ "$(id -u)" -ne 0 ]; then
  echo "deps: missing packages: ${missing[*]}" >&2
  echo "deps: run as root:" >&2
  echo "  sudo apt-get update && sudo apt-get install -y ${missing[*]}" >&2
  exit 1
fi

export DEBIAN_FRONTEND=noninteractive
echo "deps: installing ${missing[*]}"
lists_age_days=99999  # no package lists at all counts as stale
newest=$(ls -t /var/lib/apt/lists/*_Packages 2>/dev/null | head -n 1 || true)
if [ -n "$newest" ]; then
  lists_age_days=$(( ($(date +%s) - $(stat -c %Y "$newest")) / 86400 ))
fi
if [ "$lists_age_days" -gt 1 ]; then
  apt-get update -q
fi
if ! apt-get install -y -q --no-install-recommends "${missing[@]}"; then
  # A stale list names package versions the mirror no longer has: refresh and retry.
  apt-get update -q
  apt-get install -y -q --no-install-recommends "${missing[@]}"
fi
