#!/usr/bin/env bash
# Builds lineloc when needed and runs every test: unit tests, tests against the
# private PostGIS cluster and real DDS participants on loopback, the fuzz
# targets' replay runs and the end-to-end integration tests.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD_DIR="${LINELOC_BUILD_DIR:-$ROOT/build}"

"$ROOT/deploy/build.sh"
cd "$BUILD_DIR"
ctest --output-on-failure -j "$(nproc)" --timeout 900 "$@"
