#!/usr/bin/env bash
# Installs every Debian package Stride needs to build, test and run on the host (Debian 12)
# (Chromium, node and npm included, for the report pages' browser test, and puppeteer-core
# from npm into /opt/stride/browser-test),
# then builds Debian's Simbody source optimised, with NDEBUG, for the simulator
# (toolchain/build-simbody.sh; skipped with STRIDE_SIMBODY=debian, and if it fails the build
# falls back to Debian's slower libsimbody with a warning).
# Idempotent: packages already present are skipped; safe to run again. Needs root (or sudo).
#
#   toolchain/install-deps.sh            host build, tests, benchmarks, MPI
#   toolchain/install-deps.sh --cross    also the aarch64 cross compiler and qemu-user
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config ccache git
  libeigen3-dev nlohmann-json3-dev libserialport-dev libedit-dev
  libsimbody-dev libmujoco-dev libqhull-dev liburdfdom-dev liburdfdom-headers-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libnlopt-dev   # stride calibrate: bounded derivative-free fitting (BOBYQA)
  libopenmpi-dev openmpi-bin
  clang libclang-rt-14-dev clang-format
  python3 curl xz-utils
  chromium
  libjs-three   # three.js r111, inlined into the report pages' 3D replay at report time
)
# node and npm drive Chromium in the browser test (tests/browser/). Debian's nodejs and npm
# packages are installed unless a node with npm is already there: NodeSource's nodejs bundles
# npm and conflicts with Debian's npm package, so both are left alone then.
if ! command -v node >/dev/null || ! command -v npm >/dev/null; then
  packages+=(nodejs npm)
fi
cross=0
if [[ "${1:-}" == "--cross" ]]; then
  cross=1
  packages+=(g++-aarch64-linux-gnu qemu-user
             libserialport-dev:arm64 libgtest-dev:arm64 libgmock-dev:arm64 libstdc++6:arm64)
fi

sudo_cmd=()
if [[ $(id -u) -ne 0 ]]; then sudo_cmd=(sudo); fi

# The arm64 libraries come from Debian's multiarch archive.
if ((cross)) && ! dpkg --print-foreign-architectures | grep -qx arm64; then
  "${sudo_cmd[@]}" dpkg --add-architecture arm64
  added_arch=1
fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if ((${#missing[@]} == 0)) && [[ -z "${added_arch:-}" ]]; then
  echo "install-deps: all ${#packages[@]} packages present"
else
  echo "install-deps: installing ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  "${sudo_cmd[@]}" apt-get update -qq
  "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

# puppeteer-core (pinned by tests/browser/package-lock.json) for the browser test, into
# /opt/stride/browser-test; it drives the system's chromium and never downloads a browser.
browser_src="$(cd "$(dirname "$0")/.." && pwd)/tests/browser"
browser_dir=/opt/stride/browser-test
if ! cmp -s "$browser_src/package-lock.json" "$browser_dir/package-lock.json" ||
  [[ ! -f "$browser_dir/node_modules/puppeteer-core/package.json" ]]; then
  echo "install-deps: puppeteer-core into $browser_dir (npm ci)"
  "${sudo_cmd[@]}" mkdir -p "$browser_dir"
  "${sudo_cmd[@]}" cp "$browser_src/package.json" "$browser_src/package-lock.json" "$browser_dir/"
  if ! (cd "$browser_dir" && "${sudo_cmd[@]}" env PUPPETEER_SKIP_DOWNLOAD=1 \
    npm ci --no-audit --no-fund --ignore-scripts >/dev/null); then
    "${sudo_cmd[@]}" rm -f "$browser_dir/package-lock.json"
    echo "install-deps: warning: npm ci of puppeteer-core failed; the browser test will try" \
      "again into its build folder" >&2
  fi
fi

if [[ "${STRIDE_SIMBODY:-release}" != "debian" ]] &&
  ! bash "$(dirname "$0")/build-simbody.sh"; then
  echo "install-deps: warning: building the optimised Simbody failed; the simulator will use" \
    "Debian's libsimbody, about 2.2x slower" >&2
fi
echo "install-deps: done"
