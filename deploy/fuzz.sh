#!/usr/bin/env bash
# Fuzzes every parser of outside data: builds each fuzz target (tests/fuzz/)
# as a libFuzzer binary with clang, AddressSanitizer and
# UndefinedBehaviorSanitizer into build-fuzz/, then runs each for
# LINELOC_FUZZ_SECONDS (600) from its seed corpus, as many at once as there
# are cores. Fails on the first finding; the crashing input is kept in
# build-fuzz/fuzz-findings/, the inputs that found new code in
# build-fuzz/fuzz-corpus/ (a later run starts from them too).
#
#   deploy/fuzz.sh                 every target
#   deploy/fuzz.sh -R cityjson     those whose name matches (ctest's -R)
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD_DIR="${LINELOC_FUZZ_BUILD_DIR:-$ROOT/build-fuzz}"
SECONDS_EACH="${LINELOC_FUZZ_SECONDS:-600}"

"$ROOT/deploy/install-deps.sh"
command -v clang++ >/dev/null || {
  SUDO=""
  [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  $SUDO apt-get install -y -q --no-install-recommends clang
}
cmake -S "$ROOT" -B "$BUILD_DIR" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DLINELOC_FUZZ=ON -DLINELOC_SANITIZE=ON \
  -DLINELOC_FUZZ_SECONDS="$SECONDS_EACH" -DLINELOC_BUILD_BENCH=OFF \
  -DLINELOC_BUILD_INTEGRATION=OFF >/dev/null
cd "$BUILD_DIR"
mapfile -t targets < <(ctest -N -L fuzz "$@" | sed -n 's/^ *Test *#[0-9]*: //p')
[ ${#targets[@]} -gt 0 ] || { echo "fuzz.sh: no fuzz target matches" >&2; exit 1; }
cmake --build . -j "$(nproc)" --target "${targets[@]}"
echo "fuzz.sh: ${#targets[@]} targets, ${SECONDS_EACH} s each"
ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
  ctest --output-on-failure -j "$(nproc)" -L fuzz "$@"
