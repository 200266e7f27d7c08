#!/usr/bin/env bash
# A fleet on this machine: N_BACKBONES lineloc-backbone processes sharing
# N_ROBOTS robots on one DDS domain (each robot served by one backbone alive),
# every robot replaying a drive of its own pre-rendered by lineloc-sim, its
# camera at 10 Hz so that the fleet fits two cores. It is the demo
# (deploy/demo.sh) with more of each; its environment applies, and
# LINELOC_DEMO_KILL_BACKBONE_AT_S=S kills the first backbone S seconds in to
# show the others taking its robots over. Outputs in out/fleet/.
#
#   deploy/fleet.sh N_BACKBONES N_ROBOTS
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
[[ "${1:-}" =~ ^[1-9][0-9]*$ && "${2:-}" =~ ^[1-9][0-9]*$ ]] ||
  { echo "usage: $0 N_BACKBONES N_ROBOTS" >&2; exit 2; }
export LINELOC_DEMO_BACKBONES="$1"
export LINELOC_DEMO_ROBOTS="$2"
export LINELOC_DEMO_CAMERA_HZ="${LINELOC_DEMO_CAMERA_HZ:-10}"
export LINELOC_DEMO_DURATION_S="${LINELOC_DEMO_DURATION_S:-60}"
export LINELOC_DEMO_OUT="${LINELOC_DEMO_OUT:-$ROOT/out/fleet}"
# Robots and backbones time-shared: several robots' front ends under SCHED_FIFO
# would keep the cores from the backbones they share them with.
export LINELOC_DEMO_REALTIME_PRIORITY="${LINELOC_DEMO_REALTIME_PRIORITY:-0}"
export LINELOC_DEMO_BACKBONE_REALTIME_PRIORITY="${LINELOC_DEMO_BACKBONE_REALTIME_PRIORITY:-0}"
exec "$ROOT/deploy/demo.sh"
