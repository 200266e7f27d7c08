#!/usr/bin/env bash
# A long run of the demo (deploy/demo.sh: a drive pre-rendered by lineloc-sim,
# replayed by lineloc-robot against lineloc-backbone in real time) that
# watches both programs' resident memory and open file descriptors every
# LINELOC_SOAK_SAMPLE_S seconds, and fails when either grows from the minute
# after the replay's first to its last minute: resident memory by more than
# LINELOC_SOAK_MAX_RSS_GROWTH_PERCENT (5), file descriptors at all.
#
# Environment: LINELOC_SOAK_DURATION_S (the drive, default 1800),
# LINELOC_SOAK_SAMPLE_S (10), LINELOC_SOAK_OUT (out/soak/: the demo's output
# and memory.tsv, one line per sample), and the demo's own (LINELOC_DEMO_CITY,
# ...); the camera runs at 10 Hz unless LINELOC_DEMO_CAMERA_HZ says otherwise.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
DURATION_S="${LINELOC_SOAK_DURATION_S:-1800}"
SAMPLE_S="${LINELOC_SOAK_SAMPLE_S:-10}"
MAX_GROWTH_PERCENT="${LINELOC_SOAK_MAX_RSS_GROWTH_PERCENT:-5}"
OUT="${LINELOC_SOAK_OUT:-$ROOT/out/soak}"
WARM_UP_S=60

export LINELOC_DEMO_OUT="$OUT/demo"
export LINELOC_DEMO_DURATION_S="$DURATION_S"
export LINELOC_DEMO_CAMERA_HZ="${LINELOC_DEMO_CAMERA_HZ:-10}"
export LINELOC_DEMO_DOMAIN="${LINELOC_DEMO_DOMAIN:-43}"
mkdir -p "$OUT"

"$ROOT/deploy/demo.sh" >"$OUT/demo.log" 2>&1 &
DEMO_PID=$!
trap 'kill "$DEMO_PID" 2>/dev/null || true' EXIT

# The pid of the demo's `program`, once it runs.
pid_of() {
  pgrep -n -f "$1 --domain-id $LINELOC_DEMO_DOMAIN " || true
}

echo "soak: rendering the ${DURATION_S} s drive (see $OUT/demo.log)"
ROBOT_PID=""
while [ -z "$ROBOT_PID" ]; do
  kill -0 "$DEMO_PID" 2>/dev/null || { cat "$OUT/demo.log" >&2; echo "soak: the demo ended early" >&2; exit 1; }
  sleep 1
  ROBOT_PID="$(pid_of lineloc-robot)"
done
BACKBONE_PID="$(pid_of lineloc-backbone)"
[ -n "$BACKBONE_PID" ] || { echo "soak: no backbone running" >&2; exit 1; }

rss_kb() { awk '/^VmRSS:/ { print $2 }' "/proc/$1/status" 2>/dev/null || echo 0; }
fds() { find "/proc/$1/fd" -mindepth 1 -maxdepth 1 2>/dev/null | wc -l; }

echo "soak: replaying; sampling robot $ROBOT_PID and backbone $BACKBONE_PID every ${SAMPLE_S} s"
printf 't_s\trobot_rss_kb\trobot_fds\tbackbone_rss_kb\tbackbone_fds\n' >"$OUT/memory.tsv"
start=$(date +%s)
while kill -0 "$ROBOT_PID" 2>/dev/null; do
  printf '%d\t%s\t%s\t%s\t%s\n' $(($(date +%s) - start)) "$(rss_kb "$ROBOT_PID")" \
    "$(fds "$ROBOT_PID")" "$(rss_kb "$BACKBONE_PID")" "$(fds "$BACKBONE_PID")" >>"$OUT/memory.tsv"
  sleep "$SAMPLE_S"
done
wait "$DEMO_PID" || { cat "$OUT/demo.log" >&2; echo "soak: the demo failed" >&2; exit 1; }
trap - EXIT
tail -n 30 "$OUT/demo.log"

# Growth: the largest value in the last minute against the largest in the
# minute after the warm-up (a file opened for a moment is no growth).
last_s="$(tail -n 1 "$OUT/memory.tsv" | cut -f1)"
awk -F'\t' -v warm_up="$WARM_UP_S" -v last="$last_s" -v max_growth="$MAX_GROWTH_PERCENT" '
  NR == 1 { next }
  $1 >= warm_up && $1 < 2 * warm_up { for (i = 2; i <= 5; ++i) if ($i > base[i]) base[i] = $i; based = 1 }
  $1 > last - warm_up && $1 >= 2 * warm_up { for (i = 2; i <= 5; ++i) if ($i > end[i]) end[i] = $i; ended = 1 }
  END {
    if (!based || !ended) { print "soak: the replay was too short to compare two minutes"; exit 1 }
    split("robot_rss robot_fds backbone_rss backbone_fds", name, " ")
    failed = 0
    for (i = 2; i <= 5; i += 2) {
      growth = 100 * (end[i] - base[i]) / base[i]
      printf "soak: %s %d kB in the minute after the first, %d kB in the last: %+.1f %%\n", name[i - 1], base[i], end[i], growth
      if (growth > max_growth) failed = 1
      printf "soak: %s %d in the minute after the first, %d in the last\n", name[i], base[i + 1], end[i + 1]
      if (end[i + 1] > base[i + 1]) failed = 1
    }
    exit failed
  }' "$OUT/memory.tsv"
