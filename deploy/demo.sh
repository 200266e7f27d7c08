#!/usr/bin/env bash
# The main job: builds lineloc when needed, starts the private PostGIS cluster,
# brings the database to the newest schema, loads a building, starts the
# backbone, and runs a robot on a real image sequence over DDS on loopback.
# The robot's received poses go to out/demo/poses.tum.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD_DIR="${LINELOC_BUILD_DIR:-$ROOT/build}"
OUT="$ROOT/out/demo"
BIN="$BUILD_DIR/bin"
DOMAIN_ID="${LINELOC_DEMO_DOMAIN:-42}"
IMAGES_DIR=/usr/share/doc/opencv-doc/examples/data

"$ROOT/deploy/build.sh"
mkdir -p "$OUT"
"$ROOT/deploy/pg.sh" start
CONNINFO="$("$ROOT/deploy/pg.sh" conninfo)"
"$BIN/lineloc-migrate" --db "$CONNINFO"
psql -X -q -v ON_ERROR_STOP=1 "$CONNINFO" -f "$ROOT/deploy/demo/box_building.sql"

# The camera sequence: OpenCV's own calibrated camera (opencv-doc), its views in order.
[ -f "$IMAGES_DIR/left_intrinsics.yml" ] || { echo "demo: opencv-doc images missing" >&2; exit 1; }
rm -rf "$OUT/images" && mkdir -p "$OUT/images"
cp "$IMAGES_DIR"/left[0-9][0-9].jpg "$OUT/images/"

"$BIN/lineloc-backbone" --domain-id "$DOMAIN_ID" --dds-config "$ROOT/deploy/cyclonedds.xml" \
  --db "$CONNINFO" --site demo --stats-file "$OUT/backbone-stats.json" >"$OUT/backbone.log" 2>&1 &
BACKBONE_PID=$!
trap 'kill "$BACKBONE_PID" 2>/dev/null || true' EXIT

"$BIN/lineloc-robot" --domain-id "$DOMAIN_ID" --dds-config "$ROOT/deploy/cyclonedds.xml" \
  --robot-id demo-robot --images "$OUT/images" --calibration "$IMAGES_DIR/left_intrinsics.yml" \
  --predicted-pose 5 -20 1.5 0 0 0 1 --rate-hz 10 --trajectory-out "$OUT/poses.tum"

kill -TERM "$BACKBONE_PID" && wait "$BACKBONE_PID" || true
trap - EXIT
cat "$OUT/backbone.log" | grep -v "^\[" || true
echo "demo: poses in $OUT/poses.tum, backbone counters in $OUT/backbone-stats.json"
