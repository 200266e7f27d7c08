#!/usr/bin/env bash
# The main job over many drives: deploy/demo.sh in CITY on seeds FIRST..FIRST+N-1,
# each its own route, clutter and sensor noise, LINELOC_DEMO_DURATION_S long
# (default 20 s here), then one row per seed and the totals: fixes OK, the
# answers from the first OK fix on (the OK share of those is the availability
# once the robot has been found), fixes beyond chi2_6(0.9973) of their own
# covariance (precise wrong poses, which the system must never give), when the
# robot received its first OK fix, from the start and from when it first moved
# (negative: before), the position and attitude RMSE from then on,
# the exposure -> fix latency's 99th percentile over all answers and over
# those with a pose, and the robot's reported states beyond chi2_6(0.9973) of
# their own covariance from its first OK fix on (the robot sure of a wrong pose).
# Exits 1 when any seed gave a precise wrong pose, 2 when a run failed.
#
# Usage: deploy/seeds.sh [CITY=delft] [N=50] [FIRST=1]   (about 45 s per 20 s drive)
# CITY as deploy/demo.sh's LINELOC_DEMO_CITY: delft, denhaag, or a CityJSON
# file (with LINELOC_DEMO_SITE_CRS and LINELOC_DEMO_SITE_ORIGIN). The other
# LINELOC_DEMO_* variables but LINELOC_DEMO_SEED and LINELOC_DEMO_OUT reach
# every run, e.g. a stressed start on each drive:
#   LINELOC_DEMO_SIM_ARGS="--compass-bias-deg 5 --gps-initial-error-m 10" deploy/seeds.sh denhaag 5 101
# Each run's files stay in out/seeds/<city>/<seed>/.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
export LINELOC_DEMO_CITY="${1:-delft}"
SEEDS="${2:-50}"
FIRST_SEED="${3:-1}"
case "$SEEDS$FIRST_SEED" in
  *[!0-9]*) echo "usage: deploy/seeds.sh [CITY=delft] [N=50] [FIRST=1]" >&2; exit 2 ;;
esac
export LINELOC_DEMO_DURATION_S="${LINELOC_DEMO_DURATION_S:-20}"
OUT="$ROOT/out/seeds/$(basename "$LINELOC_DEMO_CITY" | sed 's/\..*//')"
mkdir -p "$OUT"

# One row from a demo's report (lineloc-robot's summary and lineloc-eval's
# tables, whose "after the first OK fix" part follows the full-run part).
summarise() {
  awk -v seed="$1" '
    /exposure -> fix median/ {
      for (i = 1; i <= NF; ++i) {
        if ($i == "p99") latency_p99[++p99s] = $(i + 1) + 0
      }
    }
    /^fixes: / {
      answers = $2; ok = $4; beyond = 0; from_first = 0
      if (match($0, /the [0-9]+ from the first/)) from_first = substr($0, RSTART + 4, RLENGTH - 19) + 0
      if (match($0, /; [0-9]+ beyond/)) beyond = substr($0, RSTART + 2, RLENGTH - 9) + 0
    }
    /^robot states: / {
      if (match($0, /; [0-9]+ beyond/)) states_beyond = substr($0, RSTART + 2, RLENGTH - 9) + 0
    }
    /^after the first OK fix/ { after = 1; first_fix = $7 }
    /^the robot first moved/ { fix_after_moving = $18 }
    after && /^position / { position_rmse = $2 }
    after && /^attitude / { attitude_rmse = $2 }
    END {
      if (answers == "") { exit 1 }
      if (first_fix == "") { first_fix = "-"; position_rmse = "-"; attitude_rmse = "-" }
      if (fix_after_moving == "") { fix_after_moving = "-" }
      if (states_beyond == "") { states_beyond = "-" }
      printf "%5d %8d %6d %10d %7d %10s %12s %9s %10s %8s %9s %13s\n", seed, answers, ok,
             from_first, beyond, first_fix, fix_after_moving, position_rmse, attitude_rmse,
             latency_p99[1], latency_p99[2], states_beyond
    }' "$2"
}

header="$(printf "%5s %8s %6s %10s %7s %10s %12s %9s %10s %8s %9s %13s" seed answers ok \
  from_first beyond first_ok_s after_moving_s pos_rmse_m att_rmse_deg p99_ms ok_p99_ms \
  states_beyond)"
rows=""
failed=0
# Progress, one line per drive: how many are done and, at the mean time per
# drive so far, how long the rest take.
progress() {
  local done=$1 elapsed_s=$SECONDS left=""
  if ((done > 0)); then
    left=", about $(((SEEDS - done) * elapsed_s / done / 60 + 1)) min left"
  fi
  echo "seeds: $done/$SEEDS drives done in $((elapsed_s / 60)) min $((elapsed_s % 60)) s$left; seed $2 next"
}

SECONDS=0
for ((seed = FIRST_SEED; seed < FIRST_SEED + SEEDS; ++seed)); do
  log="$OUT/$seed.log"
  progress $((seed - FIRST_SEED)) "$seed"
  if ! LINELOC_DEMO_SEED="$seed" LINELOC_DEMO_OUT="$OUT/$seed" "$ROOT/deploy/demo.sh" >"$log" 2>&1 ||
    ! row="$(summarise "$seed" "$log")"; then
    echo "seeds: seed $seed failed, see $log" >&2
    failed=1
    continue
  fi
  rows+="$row"$'\n'
done

echo "$header"
printf "%s" "$rows"
# The first OK fix after the robot first moved, sorted (a fix before it counts as 0 s),
# for the median.
after_moving="$(printf "%s" "$rows" | awk '$7 != "-" { print ($7 < 0 ? 0 : $7) }' | sort -g)"
median_after_moving="$(printf "%s\n" "$after_moving" | awk 'NF { v[++n] = $1 }
  END { if (n) print (n % 2 ? v[(n + 1) / 2] : (v[n / 2] + v[n / 2 + 1]) / 2); else print "-" }')"
printf "%s" "$rows" | awk -v median="$median_after_moving" '
  { answers += $2; ok += $3; from_first += $4; beyond += $5; states_beyond += $12; ++runs
    if ($6 == "-") ++never
    if ($7 != "-" && $7 <= 5) ++within_5_s
    if ($7 != "-" && $7 <= 15) ++within_15_s }
  END {
    printf "total: %d runs, %d answers, %d OK (%.1f %%; %.1f %% of the %d from each first OK fix on), " \
           "%d beyond 3 sigma, %d never fixed, %d robot states beyond 3 sigma; first OK fix " \
           "after first moving: within 5 s on %d, within 15 s on %d, median %s s\n", runs, answers,
           ok, answers ? 100.0 * ok / answers : 0, from_first ? 100.0 * ok / from_first : 0,
           from_first, beyond, never, states_beyond, within_5_s, within_15_s, median
    exit beyond > 0
  }' || exit 1
exit $((failed * 2))
