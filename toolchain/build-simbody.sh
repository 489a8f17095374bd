#!/usr/bin/env bash
# Builds Debian's own Simbody source package (the same 3.7 as libsimbody-dev) optimised and
# with NDEBUG into a private prefix, for the simulator.
#
# Why: Debian's binary libsimbody is built without NDEBUG, so Simbody's index checks and
# state-cache dynamic_casts run on every small-matrix access. This build of the same source
# gives bit-identical trajectories about 2.2x faster (tests/bench/RESULTS.md). Stride's own
# patches in toolchain/simbody-patches/ are applied after Debian's; each keeps every result
# bit for bit and says why it exists in its header.
# CMake picks this prefix up when it exists and otherwise falls back to Debian's library.
#
#   toolchain/build-simbody.sh            build into $STRIDE_SIMBODY_PREFIX
#                                         (default /opt/stride/simbody-3.7)
# Idempotent: skips the build when the prefix already holds this version. Needs curl, cmake,
# ninja, a C++ compiler and liblapack-dev (toolchain/install-deps.sh installs them first).
# The sources come from Debian's archive and are checked against pinned SHA-256 sums.
set -euo pipefail

version="3.7+dfsg"
debian_revision="3"
prefix="${STRIDE_SIMBODY_PREFIX:-/opt/stride/simbody-3.7}"
# The archive is the Debian mirror apt is configured with (its stable suite's repository), so
# the build fetches from wherever this machine's packages come from; STRIDE_DEBIAN_ARCHIVE
# overrides it.
archive="${STRIDE_DEBIAN_ARCHIVE:-$(apt-get indextargets --format '$(REPO_URI) $(RELEASE)' 2>/dev/null |
  awk '$2 !~ /-/ { sub(/\/$/, "", $1); print $1; exit }')}"
if [[ -z "$archive" ]]; then
  echo "build-simbody: no Debian archive found in apt's sources; set STRIDE_DEBIAN_ARCHIVE" >&2
  exit 1
fi
orig="simbody_${version}.orig.tar.xz"
orig_sha256="c2e2a3e7def05ba4fda4b216d04d41bdc6477c0cfcec20bfce98c1005532dfb6"
debian="simbody_${version}-${debian_revision}.debian.tar.xz"
debian_sha256="eab5eaa72bfc015a82b0a2d1c55e38a59b66920ce8f94fc9cc842198b852314b"
stamp="$prefix/share/stride-simbody-build"
patches_dir="$(cd "$(dirname "$0")" && pwd)/simbody-patches"
shopt -s nullglob
stride_patches=("$patches_dir"/*.patch)
shopt -u nullglob
# The stamp names the patch set by a digest of its text, so adding or changing a patch
# rebuilds an existing prefix. It ends in "NDEBUG", which cmake/StrideSimbody.cmake looks for.
patches_digest=$(cat "${stride_patches[@]}" </dev/null | sha256sum | cut -c1-12)
stamp_text="simbody ${version}-${debian_revision} +stride-${patches_digest} -O3 NDEBUG"

if [[ -f "$stamp" && "$(cat "$stamp")" == "$stamp_text" ]]; then
  echo "build-simbody: $prefix already holds $stamp_text"
  exit 0
fi

sudo_cmd=()
if [[ $(id -u) -ne 0 ]]; then sudo_cmd=(sudo); fi

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
echo "build-simbody: fetching Debian's simbody ${version}-${debian_revision} source"
for f in "$orig" "$debian"; do
  curl -fsS --retry 3 -o "$work/$f" "$archive/pool/main/s/simbody/$f"
done
(cd "$work" && printf '%s  %s\n%s  %s\n' "$orig_sha256" "$orig" "$debian_sha256" "$debian" |
  sha256sum --check --quiet)

tar -xf "$work/$orig" -C "$work"
tar -xf "$work/$debian" -C "$work"
src=$(find "$work" -mindepth 1 -maxdepth 1 -type d -name 'simbody-*')
while read -r patch; do
  [[ -z "$patch" || "$patch" == \#* ]] && continue
  patch -d "$src" -p1 -s <"$work/debian/patches/$patch"
done <"$work/debian/patches/series"
for patch in "${stride_patches[@]}"; do
  echo "build-simbody: applying $(basename "$patch")"
  patch -d "$src" -p1 -s <"$patch"
done

# -O3 and -fno-semantic-interposition let GCC inline Simbody's small-matrix templates and its
# calls within a library (upstream's Release is -O2: 1.6x faster than Debian's here, this 2.2x;
# no -ffast-math and no -march, so the arithmetic, and every result, stays the same).
# Libraries only. They find each other through their RUNPATH, so a program never mixes them
# with Debian's copies.
echo "build-simbody: building the libraries into $prefix (about 4-7 minutes on 2 cores)"
cmake -S "$src" -B "$work/build" -G Ninja -DCMAKE_BUILD_TYPE=None \
  -DCMAKE_CXX_FLAGS="-O3 -DNDEBUG -fno-semantic-interposition" -DCMAKE_C_FLAGS="-O3 -DNDEBUG" \
  -DBUILD_TESTING=OFF -DBUILD_EXAMPLES=OFF -DBUILD_VISUALIZER=OFF -DINSTALL_DOCS=OFF \
  -DSIMBODY_VISUALIZER_INSTALL_DIR="$prefix/libexec" \
  -DCMAKE_INSTALL_PREFIX="$prefix" -DCMAKE_INSTALL_LIBDIR=lib \
  -DCMAKE_INSTALL_RPATH="$prefix/lib" >"$work/configure.log" 2>&1 ||
  { tail -n 30 "$work/configure.log" >&2; exit 1; }
cmake --build "$work/build" -j "$(nproc)" >"$work/build.log" 2>&1 ||
  { tail -n 30 "$work/build.log" >&2; exit 1; }
"${sudo_cmd[@]}" cmake --install "$work/build" >/dev/null
echo "$stamp_text" | "${sudo_cmd[@]}" tee "$stamp" >/dev/null
echo "build-simbody: done ($prefix)"
