#!/usr/bin/env bash
# Installs the dependencies when missing and builds lineloc (Release) into
# build/ (or $LINELOC_BUILD_DIR). Extra CMake arguments: $LINELOC_CMAKE_ARGS.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD_DIR="${LINELOC_BUILD_DIR:-$ROOT/build}"

"$ROOT/deploy/install-deps.sh"
# shellcheck disable=SC2086
cmake -S "$ROOT" -B "$BUILD_DIR" -G Ninja ${LINELOC_CMAKE_ARGS:-} >/dev/null
cmake --build "$BUILD_DIR" -j "$(nproc)"
