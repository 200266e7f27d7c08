#!/usr/bin/env bash
# deploy/pg.sh refuses a data directory path another user could have planted
# (a symbolic link, a file, a directory not the cluster user's alone, a parent
# others may rename entries of) with a message saying so, and changes nothing
# it finds there; it refuses to replicate without a primary. No cluster is
# started.
#
#   test_pg_sh.sh PATH/TO/pg.sh
set -euo pipefail
PG_SH="$1"
WORK="$(mktemp -d)"
trap 'rm -rf "$WORK"' EXIT
failures=0

# expect_refusal NAME MESSAGE [ARGUMENTS...]: pg.sh ARGUMENTS (default start)
# on $WORK/NAME fails, saying MESSAGE.
expect_refusal() {
  local name="$1" message="$2" output
  shift 2
  [ $# -gt 0 ] || set -- start
  if output="$(LINELOC_PG_PORT=55449 LINELOC_PG_DIR="$WORK/$name" "$PG_SH" "$@" 2>&1)"; then
    echo "FAIL: pg.sh $* succeeded on $name: $output"
    failures=$((failures + 1))
  elif [[ "$output" != *"$message"* ]]; then
    echo "FAIL: pg.sh $* refused $name without saying '$message': $output"
    failures=$((failures + 1))
  else
    echo "ok: $* on $name: $output"
  fi
}

mkdir -m 700 "$WORK/target"
ln -s "$WORK/target" "$WORK/symlink"
expect_refusal symlink "is a symbolic link; refusing to use it"
if [ -n "$(ls -A "$WORK/target")" ] || [ "$(stat -c %u:%a "$WORK/target")" != "$(id -u):700" ]; then
  echo "FAIL: pg.sh changed the symbolic link's target"
  failures=$((failures + 1))
fi

echo planted >"$WORK/file"
expect_refusal file "is not a directory; refusing to use it"
[ "$(cat "$WORK/file")" = planted ] || { echo "FAIL: pg.sh wrote to the file"; failures=$((failures + 1)); }

# Open to others when this user runs the cluster; another user's when root
# runs it (as the unprivileged cluster user).
mkdir -m 755 "$WORK/open"
expect_refusal open "refusing to use it"

mkdir -m 777 "$WORK/shared"
expect_refusal shared/cluster "writable by other users and not sticky"
[ ! -e "$WORK/shared/cluster" ] || { echo "FAIL: pg.sh created shared/cluster"; failures=$((failures + 1)); }

# replicate needs another cluster's port, and one running there; nothing is made without.
for port in "" 55449 1; do
  message="give the primary's port"
  [ "$port" != 1 ] || message="no cluster runs on port 1"
  expect_refusal replica "$message" replicate "$port"
  [ ! -e "$WORK/replica" ] || { echo "FAIL: pg.sh created the replica"; failures=$((failures + 1)); }
done

[ "$failures" -eq 0 ]
