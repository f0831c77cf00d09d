#!/usr/bin/env bash
# All tests of the workspace, on a fresh machine with only Rust and the base system:
#
#     bash scripts/test.sh
#
# 1. Installs the system packages the tests need where they are missing (Debian/Ubuntu,
#    through apt-get; with sudo when not run as root).
# 2. Runs every test of the workspace (unit, integration, property and doc tests), with the
#    examples' plots (feature examples/plots) and the public proptest strategies of
#    interval-core and implicit-expr (features interval-core/proptest, implicit-expr/proptest).
# 3. Runs the cluster crate's tests with its MPI transport, under mpirun (feature mpi).
# 4. Runs the differential tests against the inari crate on CPUs with AVX2/FMA, built with
#    their own flags in their own target directory.
set -euo pipefail
cd "$(dirname "$0")/.."

step() { printf '\n==> %s\n' "$*"; }

# --- system packages -----------------------------------------------------------------------
# GMP and MPFR (with m4 and pkg-config) are the test oracle (rug, a dev-dependency) and
# inari's backend; the workspace links the system's libraries instead of building them from
# source (gmp-mpfr-sys feature use-system-libs). Fontconfig, FreeType and a font are for the
# plots of the examples (plotters' text, feature examples/plots). Mesa's software Vulkan
# driver (lavapipe) and the Vulkan loader give the GPU tests an adapter on machines without
# a GPU; with the CI variable set, a missing adapter fails them instead of skipping them.
# Open MPI (library, headers and mpirun) and libclang (the mpi crate generates its bindings
# with bindgen) are for the cluster crate's MPI transport and its tests under mpirun.
PACKAGES=(libgmp-dev libmpfr-dev m4 pkg-config libfontconfig1-dev libfreetype-dev
    fonts-dejavu-core mesa-vulkan-drivers libvulkan1 libopenmpi-dev openmpi-bin libclang-dev)
need=()
if command -v dpkg >/dev/null 2>&1; then
    for pkg in "${PACKAGES[@]}"; do
        dpkg -s "$pkg" >/dev/null 2>&1 || need+=("$pkg")
    done
else
    echo "no dpkg: install the equivalents of ${PACKAGES[*]} by hand"
fi
if [ "${#need[@]}" -gt 0 ]; then
    step "installing ${need[*]}"
    SUDO=""
    [ "$(id -u)" -ne 0 ] && SUDO="sudo"
    $SUDO apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${need[@]}"
fi

# --- the workspace's tests -----------------------------------------------------------------
step "cargo test --workspace --features examples/plots,interval-core/proptest,implicit-expr/proptest"
cargo test --workspace --features examples/plots,interval-core/proptest,implicit-expr/proptest

# --- the cluster crate over MPI -------------------------------------------------------------
# The render-mpi program under `mpirun --allow-run-as-root --oversubscribe -np 1, 2, 4`
# (crates/cluster/tests/mpi.rs): the same image and counters as one process, load balancing,
# a killed rank reported as an error.
step "cargo test -p beam-cluster --features mpi (mpirun with 1, 2 and 4 ranks)"
cargo test -p beam-cluster --features mpi

# --- differential tests against inari ------------------------------------------------------
# inari needs AVX2/FMA; it is built with its own RUSTFLAGS in a separate target directory so
# that the main build stays target-neutral.
step "differential tests against inari (x86-64-v3)"
if [ "$(uname -m)" = x86_64 ] && grep -qw avx2 /proc/cpuinfo && grep -qw fma /proc/cpuinfo; then
    CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-target}/v3" RUSTFLAGS="-C target-cpu=x86-64-v3" \
        cargo test -p peer-tests --features inari
else
    echo "this CPU lacks AVX2/FMA, which inari requires: differential tests not run"
fi
