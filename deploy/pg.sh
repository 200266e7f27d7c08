#!/usr/bin/env bash
# A private PostgreSQL 15 + PostGIS cluster for lineloc: its own data directory
# and port, run as an unprivileged OS user when invoked as root. Nothing here
# touches a system-wide cluster.
#
#   deploy/pg.sh start    initialise (first time) and start; idempotent
#   deploy/pg.sh stop     stop, keeping the data
#   deploy/pg.sh status   exit 0 when running
#   deploy/pg.sh conninfo print the libpq connection string of database 'lineloc'
#   deploy/pg.sh destroy  stop and delete the data directory
#
# The data directory is made private (mkdir -m 700); a directory at its path
# that is a symbolic link, not the cluster's OS user's, or open to other users
# is refused, and every file in it is written as the cluster's OS user.
#
# Environment: LINELOC_PG_PORT (default 55432), LINELOC_PG_DIR (default
# /tmp/lineloc-pg-<port>), LINELOC_PG_USER (OS user when run as root; default lineloc).
set -euo pipefail

PORT="${LINELOC_PG_PORT:-55432}"
DATA_DIR="${LINELOC_PG_DIR:-${TMPDIR:-/tmp}/lineloc-pg-${PORT}}"
OS_USER="${LINELOC_PG_USER:-lineloc}"
PG_BIN="$(ls -d /usr/lib/postgresql/15/bin 2>/dev/null || true)"
DB_ROLE="lineloc"
DB_NAME="lineloc"

die() { echo "pg.sh: $*" >&2; exit 1; }
[ -x "$PG_BIN/pg_ctl" ] || die "PostgreSQL 15 server not found; run deploy/install-deps.sh"

as_owner() {
  if [ "$(id -u)" -eq 0 ]; then
    runuser -u "$OS_USER" -- "$@"
  else
    "$@"
  fi
}

# Appends stdin to a file in the data directory as the cluster's OS user.
append_as_owner() { as_owner sh -c 'umask 077 && cat >>"$1"' sh "$1"; }

cluster_uid() {
  if [ "$(id -u)" -eq 0 ]; then
    id -u "$OS_USER" 2>/dev/null || die "OS user $OS_USER does not exist"
  else
    id -u
  fi
}

ensure_os_user() {
  if [ "$(id -u)" -eq 0 ] && ! id "$OS_USER" >/dev/null 2>&1; then
    useradd --system --no-create-home --shell /usr/sbin/nologin "$OS_USER"
  fi
}

# What is at the data directory's path, when anything is, must be a directory
# (not a symbolic link) that the cluster's OS user owns and no one else may
# enter: anything else may have been planted by another user.
check_data_dir() {
  if [ ! -e "$DATA_DIR" ] && [ ! -L "$DATA_DIR" ]; then
    return 0
  fi
  local refuse="refusing to use it: remove it, or set LINELOC_PG_DIR"
  [ ! -L "$DATA_DIR" ] || die "$DATA_DIR is a symbolic link; $refuse"
  [ -d "$DATA_DIR" ] || die "$DATA_DIR is not a directory; $refuse"
  [ "$(stat -c %u "$DATA_DIR")" -eq "$(cluster_uid)" ] \
    || die "$DATA_DIR belongs to $(stat -c %U "$DATA_DIR"), not $(id -un "$(cluster_uid)"); $refuse"
  [ "$(stat -c %a "$DATA_DIR")" = 700 ] \
    || die "$DATA_DIR is open to other users (mode $(stat -c %a "$DATA_DIR")); $refuse"
}

# mkdir -m 700 in a parent no other user can rename entries of: one that is
# root's or this user's, and sticky (as /tmp is) when others may write to it.
create_data_dir() {
  local parent
  parent="$(dirname "$DATA_DIR")"
  [ -d "$parent" ] || die "$parent does not exist"
  local parent_uid parent_mode
  parent_uid="$(stat -L -c %u "$parent")"
  parent_mode="$(stat -L -c %a "$parent")"
  [ "$parent_uid" -eq 0 ] || [ "$parent_uid" -eq "$(id -u)" ] \
    || die "$parent belongs to another user, who could replace $DATA_DIR; set LINELOC_PG_DIR"
  if (((8#$parent_mode & 8#022) != 0)) && [ ! -k "$parent" ]; then
    die "$parent is writable by other users and not sticky; set LINELOC_PG_DIR"
  fi
  mkdir -m 700 "$DATA_DIR" || die "could not create $DATA_DIR"
  if [ "$(id -u)" -eq 0 ]; then
    chown -h "$OS_USER" "$DATA_DIR"
  fi
}

psql_as_owner() {
  as_owner "$PG_BIN/psql" -X -q -v ON_ERROR_STOP=1 -h 127.0.0.1 -p "$PORT" -U "$DB_ROLE" "$@"
}

is_running() {
  [ -f "$DATA_DIR/PG_VERSION" ] && as_owner "$PG_BIN/pg_ctl" -D "$DATA_DIR" status >/dev/null 2>&1
}

initialise() {
  ensure_os_user
  [ -d "$DATA_DIR" ] || create_data_dir
  local output
  output="$(as_owner "$PG_BIN/initdb" -D "$DATA_DIR" -U "$DB_ROLE" --auth=trust -E UTF8 \
    --locale=C.UTF-8 2>&1)" || { echo "$output" >&2; die "initdb failed"; }
  append_as_owner "$DATA_DIR/postgresql.conf" <<CONF
listen_addresses = '127.0.0.1'
port = $PORT
unix_socket_directories = '$DATA_DIR'
max_connections = 200
shared_buffers = 256MB
fsync = on
CONF
}

start() {
  check_data_dir
  if is_running; then
    echo "pg.sh: running on port $PORT ($DATA_DIR)"
    return 0
  fi
  [ -f "$DATA_DIR/PG_VERSION" ] || initialise
  as_owner "$PG_BIN/pg_ctl" -D "$DATA_DIR" -l "$DATA_DIR/server.log" -w -t 60 start >/dev/null \
    || { as_owner tail -20 "$DATA_DIR/server.log" >&2; die "server did not start"; }
  # Extensions in template1 so every database created later (tests) has them.
  psql_as_owner -d template1 -c "CREATE EXTENSION IF NOT EXISTS postgis; CREATE EXTENSION IF NOT EXISTS postgis_sfcgal;"
  if ! psql_as_owner -d postgres -tAc "SELECT 1 FROM pg_database WHERE datname = '$DB_NAME'" | grep -q 1; then
    psql_as_owner -d postgres -c "CREATE DATABASE $DB_NAME"
  fi
  echo "pg.sh: started on port $PORT ($DATA_DIR)"
}

stop() {
  check_data_dir
  if is_running; then
    as_owner "$PG_BIN/pg_ctl" -D "$DATA_DIR" -m fast -w stop >/dev/null
    echo "pg.sh: stopped"
  else
    echo "pg.sh: not running"
  fi
}

destroy() {
  stop
  as_owner rm -rf "$DATA_DIR"
  echo "pg.sh: removed $DATA_DIR"
}

case "${1:-}" in
  start) start ;;
  stop) stop ;;
  status)
    check_data_dir
    if is_running; then echo "pg.sh: running on port $PORT"; else echo "pg.sh: not running"; exit 1; fi
    ;;
  # conninfo [ROLE]: the owner (writes: loader, migrations) or, e.g., lineloc_reader (backbone).
  conninfo) echo "host=127.0.0.1 port=$PORT user=${2:-$DB_ROLE} dbname=$DB_NAME" ;;
  destroy) destroy ;;
  *) echo "usage: $0 start|stop|status|conninfo [ROLE]|destroy" >&2; exit 2 ;;
esac
