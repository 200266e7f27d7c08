#!/usr/bin/env bash
# The main job, a localisation run on a simulated drive through a city:
# builds lineloc when needed, starts the private PostGIS cluster, brings the
# database to the newest schema, loads the city model (the bundled Delft tile
# unless told otherwise), simulates a drive through its streets (camera, IMU,
# DGPS, compass, ground truth), runs lineloc-backbone and lineloc-robot as
# separate processes over DDS on loopback in real time, and prints
# lineloc-eval's report against the ground truth.
#
# Environment: LINELOC_DEMO_CITY (delft, the bundled tile; denhaag, Den Haag's
# centre from ../shared/data; or a CityJSON file, with LINELOC_DEMO_SITE_CRS,
# default the one it names, and LINELOC_DEMO_SITE_ORIGIN, "x y z" in its CRS
# near its centre), LINELOC_DEMO_DURATION_S (default 120), LINELOC_DEMO_SEED (1),
# LINELOC_DEMO_CAMERA_HZ (30), LINELOC_DEMO_DOMAIN (DDS domain, 42),
# LINELOC_DEMO_OUT (where everything goes, out/demo/),
# LINELOC_DEMO_REALTIME_PRIORITY (the robot's --realtime-priority, 10; 0: off),
# LINELOC_DEMO_BACKBONE_REALTIME_PRIORITY (the backbone's, 5, and with it
# Cyclone DDS's receive threads'; 0: off), LINELOC_DEMO_ROBOT_START_S (the
# robot's --start-at-s, default 0: it replays the drive from that far in, as a
# robot whose software restarted while driving), LINELOC_DEMO_SIM_ARGS (words
# appended to lineloc-sim's command line, split at blanks, e.g. the stress of
# a poor start and a covered camera: "--compass-bias-deg 5
# --gps-initial-error-m 10 --camera-covered-s 10 3"; default none),
# LINELOC_DEMO_DDS_SECURITY (1: the robot and the backbone talk through DDS
# Security, deploy/dds-security.sh, with the CA in LINELOC_DDS_SECURITY_DIR,
# default out/dds-security/; 0: unsecured, for development),
# LINELOC_DEMO_LEARNT_LINES (1: the backbone matches the site's confirmed
# learnt lines, lineloc-enrich, with the model's; 0: the model's alone),
# LINELOC_DEMO_LEARN (1: the backbone learns lines from the frames it answers
# into the site's enrichment, --learning-db; 0: it does not, the default),
# LINELOC_DEMO_ROBOT_ID (the robot's id, demo-robot; a pass of learning is
# one robot's day).
#
# A fleet (deploy/fleet.sh): LINELOC_DEMO_BACKBONES backbones (default 1)
# sharing LINELOC_DEMO_ROBOTS robots (default 1), robot i driving seed
# SEED + i - 1 with its outputs in robot-i/; LINELOC_DEMO_KILL_BACKBONE_AT_S
# (default 0: never) kills the first backbone (SIGKILL) that long after the
# robots start, and the others take its robots over.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD_DIR="${LINELOC_BUILD_DIR:-$ROOT/build}"
BIN="$BUILD_DIR/bin"
OUT="${LINELOC_DEMO_OUT:-$ROOT/out/demo}"
DOMAIN_ID="${LINELOC_DEMO_DOMAIN:-42}"
DURATION_S="${LINELOC_DEMO_DURATION_S:-120}"
SEED="${LINELOC_DEMO_SEED:-1}"
CAMERA_HZ="${LINELOC_DEMO_CAMERA_HZ:-30}"
ROBOT_START_S="${LINELOC_DEMO_ROBOT_START_S:-0}"
read -r -a SIM_ARGS <<<"${LINELOC_DEMO_SIM_ARGS:-}"
# The robot's front end runs ahead of the backbone's threads on the cores
# they share here, as it would on a computer of its own (thread_priority.h).
REALTIME_PRIORITY="${LINELOC_DEMO_REALTIME_PRIORITY:-10}"
# The backbone's answering threads below it, above the backbone's searches and
# the replay's decoding.
BACKBONE_REALTIME_PRIORITY="${LINELOC_DEMO_BACKBONE_REALTIME_PRIORITY:-5}"
CITY="${LINELOC_DEMO_CITY:-delft}"
DDS_SECURITY="${LINELOC_DEMO_DDS_SECURITY:-1}"
BACKBONES="${LINELOC_DEMO_BACKBONES:-1}"
ROBOTS="${LINELOC_DEMO_ROBOTS:-1}"
KILL_BACKBONE_AT_S="${LINELOC_DEMO_KILL_BACKBONE_AT_S:-0}"
ROBOT_ID="${LINELOC_DEMO_ROBOT_ID:-demo-robot}"
case "${LINELOC_DEMO_LEARN:-0}" in
  1 | 0) LEARN="${LINELOC_DEMO_LEARN:-0}" ;;
  *) echo "demo: LINELOC_DEMO_LEARN is 1 or 0" >&2; exit 2 ;;
esac
case "${LINELOC_DEMO_LEARNT_LINES:-1}" in
  1) LEARNT_LINES=true ;;
  0) LEARNT_LINES=false ;;
  *) echo "demo: LINELOC_DEMO_LEARNT_LINES is 1 or 0" >&2; exit 2 ;;
esac
MODEL_CRS=()
# Site frame: the site's CRS minus an origin near the model's centre; for the
# named cities EPSG:7415 (RD New + NAP height).
case "$CITY" in
  delft)
    CITY_MODEL="$ROOT/data/citymodels/delft.json"
    SITE=delft
    SITE_CRS=EPSG:7415
    SITE_ORIGIN=(84900 447600 0)
    ;;
  denhaag)
    CITY_MODEL="$ROOT/../shared/data/citymodels/denhaag_01.city.json"
    SITE=denhaag
    SITE_CRS=EPSG:7415
    SITE_ORIGIN=(78650 457950 0)
    ;;
  *)
    CITY_MODEL="$CITY"
    SITE="$(basename "$CITY" | sed 's/\..*//')"
    SITE_CRS="${LINELOC_DEMO_SITE_CRS:-}"
    # A CRS given for a file that names none.
    [ -z "$SITE_CRS" ] || MODEL_CRS=(--city-model-crs "$SITE_CRS")
    read -r -a SITE_ORIGIN <<<"${LINELOC_DEMO_SITE_ORIGIN:-}"
    if [ ${#SITE_ORIGIN[@]} -ne 3 ]; then
      echo "demo: a city model file needs LINELOC_DEMO_SITE_ORIGIN=\"x y z\" (its CRS, near its centre)" >&2
      exit 1
    fi
    if [ -z "$SITE_CRS" ]; then
      SITE_CRS="EPSG:$(grep -o 'EPSG/0/[0-9]*\|EPSG::[0-9]*\|EPSG:[0-9]*' "$CITY_MODEL" | head -1 | grep -o '[0-9]*$')"
    fi
    ;;
esac
DDS_CONFIG="$ROOT/deploy/cyclonedds.xml"
# With them, Cyclone's receive thread (deploy/cyclonedds-realtime.xml), where
# the machine grants SCHED_FIFO: without it Cyclone could not start at all.
if [ "$BACKBONE_REALTIME_PRIORITY" -gt 0 ] && chrt -f 6 true 2>/dev/null; then
  DDS_CONFIG+=",$ROOT/deploy/cyclonedds-realtime.xml"
fi
# One robot's id and folder, or robot $1's of a fleet; backbone $1's name and
# the prefix of its log and counters.
robot_id() { if [ "$ROBOTS" -eq 1 ]; then echo "$ROBOT_ID"; else echo "$ROBOT_ID-$1"; fi; }
robot_out() { if [ "$ROBOTS" -eq 1 ]; then echo "$OUT"; else echo "$OUT/robot-$1"; fi; }
backbone_name() { if [ "$BACKBONES" -eq 1 ]; then echo demo; else echo "demo-$1"; fi; }
backbone_out() { if [ "$BACKBONES" -eq 1 ]; then echo "$OUT/backbone"; else echo "$OUT/backbone-$1"; fi; }
# DDS Security (deploy/dds-security.sh): each backbone and robot with an
# identity of the site's CA, kept in $LINELOC_DDS_SECURITY_DIR. The DDS
# configuration of participant $1 ("backbone" or "robot") named $2, its
# identity issued when there is none yet; fails when it cannot be issued.
# Called in the foreground, one at a time: the CA issues one identity at once.
dds_config_of() {
  if [ "$DDS_SECURITY" = 1 ]; then
    local overlay
    overlay="$("$ROOT/deploy/dds-security.sh" config "$1-$2" 2>/dev/null ||
      "$ROOT/deploy/dds-security.sh" issue "$1" "$2")" ||
      { echo "demo: no DDS Security identity for $1 $2" >&2; return 1; }
    echo "$DDS_CONFIG,$overlay"
  else
    echo "$DDS_CONFIG"
  fi
}
# The simulated robot's camera rides this high above the road; the robot knows
# it as a constant of its build and tells the backbone.
CAMERA_HEIGHT_M=1.5
# The drive starts on a sunny April morning (UTC). The simulator renders the
# city under the sun that stands over it then (over Delft about 137 deg from
# grid north and 40 deg high); the backbone works the sun out from each
# LineSet's time, as it would on the street.
START_UTC=2026-04-14T09:30:00Z

[ -f "$CITY_MODEL" ] || { echo "demo: city model $CITY_MODEL missing" >&2; exit 1; }
[ "$SITE_CRS" != "EPSG:" ] || { echo "demo: $CITY_MODEL names no CRS: give LINELOC_DEMO_SITE_CRS" >&2; exit 1; }
"$ROOT/deploy/build.sh"
rm -rf "$OUT" && mkdir -p "$OUT"

"$ROOT/deploy/pg.sh" start
# Each program logs in as the role it needs (docs/production.md): the owner
# migrates the schema, the writer loads rows, the backbone only reads.
OWNER_CONNINFO="$("$ROOT/deploy/pg.sh" conninfo lineloc_owner)"
WRITER_CONNINFO="$("$ROOT/deploy/pg.sh" conninfo lineloc_writer)"
READER_CONNINFO="$("$ROOT/deploy/pg.sh" conninfo lineloc_reader)"
LEARNING=()
if [ "$LEARN" -eq 1 ]; then
  LEARNING=(--learning-db "$("$ROOT/deploy/pg.sh" conninfo lineloc_enricher) connect_timeout=5")
fi
"$BIN/lineloc-migrate" --db "$OWNER_CONNINFO"
"$BIN/lineloc-load" --db "$WRITER_CONNINFO" --site "$SITE" "${MODEL_CRS[@]}" --site-crs "$SITE_CRS" \
  --site-origin "${SITE_ORIGIN[@]}" "$CITY_MODEL"

for robot in $(seq 1 "$ROBOTS"); do
  seed=$((SEED + robot - 1))
  echo "demo: simulating a ${DURATION_S} s drive through $SITE (seed $seed, camera ${CAMERA_HZ} Hz)${SIM_ARGS[*]:+, ${SIM_ARGS[*]}}"
  mkdir -p "$(robot_out "$robot")"
  "$BIN/lineloc-sim" --city-model "$CITY_MODEL" "${MODEL_CRS[@]}" --site-origin "${SITE_ORIGIN[@]}" \
    --out "$(robot_out "$robot")/dataset" --seed "$seed" --duration-s "$DURATION_S" \
    --camera-height-m "$CAMERA_HEIGHT_M" --camera-rate-hz "$CAMERA_HZ" \
    --start-utc "$START_UTC" --sun-from-clock "${SIM_ARGS[@]}"
done

BACKBONE_PIDS=()
trap 'kill "${BACKBONE_PIDS[@]}" 2>/dev/null || true' EXIT
for backbone in $(seq 1 "$BACKBONES"); do
  dds_config="$(dds_config_of backbone "$(backbone_name "$backbone")")"
  "$BIN/lineloc-backbone" --domain-id "$DOMAIN_ID" --dds-config "$dds_config" \
    --backbone-name "$(backbone_name "$backbone")" --db "$READER_CONNINFO" --site "$SITE" \
    --use-learnt-lines "$LEARNT_LINES" "${LEARNING[@]}" --sun-from-clock \
    --realtime-priority "$BACKBONE_REALTIME_PRIORITY" \
    --stats-file "$(backbone_out "$backbone")-stats.json" >"$(backbone_out "$backbone").log" 2>&1 &
  BACKBONE_PIDS+=($!)
done

echo "demo: $ROBOTS robot(s) and $BACKBONES backbone(s) running in real time over DDS"
ROBOT_PIDS=()
for robot in $(seq 1 "$ROBOTS"); do
  dir="$(robot_out "$robot")"
  dds_config="$(dds_config_of robot "$(robot_id "$robot")")"
  "$BIN/lineloc-robot" --domain-id "$DOMAIN_ID" --dds-config "$dds_config" \
    --robot-id "$(robot_id "$robot")" --images "$dir/dataset" \
    --camera-calibration "$dir/dataset/cam0/calibration.yaml" --site-crs "$SITE_CRS" \
    --camera-height-m "$CAMERA_HEIGHT_M" --realtime-priority "$REALTIME_PRIORITY" \
    --start-at-s "$ROBOT_START_S" --site-origin "${SITE_ORIGIN[@]}" --trajectory-out "$dir/fixes.tum" \
    --fix-log-out "$dir/fixes.txt" --state-log-out "$dir/states.txt" \
    --fused-trajectory-out "$dir/fused.tum" 2>"$dir/robot.log" &
  ROBOT_PIDS+=($!)
done
if [ "$KILL_BACKBONE_AT_S" != 0 ]; then
  (sleep "$KILL_BACKBONE_AT_S" && kill -KILL "${BACKBONE_PIDS[0]}" &&
    echo "demo: backbone $(backbone_name 1) killed ${KILL_BACKBONE_AT_S} s after the robots started") &
fi
robots_failed=0
for pid in "${ROBOT_PIDS[@]}"; do
  wait "$pid" || robots_failed=$((robots_failed + 1))
done

for pid in "${BACKBONE_PIDS[@]}"; do
  kill -TERM "$pid" 2>/dev/null && wait "$pid" || true
done
trap - EXIT
for backbone in $(seq 1 "$BACKBONES"); do
  grep -v "^\[" "$(backbone_out "$backbone").log" || true
done

for robot in $(seq 1 "$ROBOTS"); do
  dir="$(robot_out "$robot")"
  echo "demo: robot $(robot_id "$robot")'s pose at each frame (what it knew then) against the ground truth"
  "$BIN/lineloc-eval" --ground-truth "$dir/dataset/groundtruth_cam0.tum" --estimate "$dir/fused.tum" \
    --fix-log "$dir/fixes.txt" --state-log "$dir/states.txt" --city-model "$CITY_MODEL" \
    --site-origin "${SITE_ORIGIN[@]}" --plot "$dir/evaluation.png"
  echo "demo: plot in $dir/evaluation.png; fixes in $dir/fixes.tum"
done
echo "demo: backbone counters in $(backbone_out 1)-stats.json$([ "$BACKBONES" -gt 1 ] && echo " and the others beside it")"
[ "$robots_failed" -eq 0 ] || { echo "demo: $robots_failed robot(s) failed; see their robot.log" >&2; exit 1; }
