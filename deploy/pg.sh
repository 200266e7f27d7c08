#!/usr/bin/env bash
# A private PostgreSQL 15 + PostGIS cluster for lineloc: its own data directory
# and port, run as an unprivileged OS user when invoked as root. Nothing here
# touches a system-wide cluster.
#
#   deploy/pg.sh start             initialise (first time) and start; idempotent
#   deploy/pg.sh stop              stop, keeping the data
#   deploy/pg.sh status            exit 0 when running
#   deploy/pg.sh conninfo [ROLE]   print the libpq connection string of database
#                                  'lineloc' for ROLE: lineloc_owner (default;
#                                  lineloc-migrate), lineloc_writer (lineloc-load),
#                                  lineloc_reader (lineloc-backbone) or
#                                  lineloc_enricher (lineloc-enrich)
#   deploy/pg.sh rotate-passwords  give every role a new password
#   deploy/pg.sh destroy           stop and delete the data directory
#   deploy/pg.sh replicate PORT    make this port's cluster a read-only streaming
#                                  replica of the cluster on PORT (running, on
#                                  this machine) and start it; start, stop,
#                                  status, conninfo and destroy then work on it
#                                  as on any cluster
#
# Every role logs in with a scram-sha-256 password; pg_hba.conf trusts no one.
# The passwords are random, made here, and kept in the data directory's pgpass
# file (mode 0600, the cluster's OS user's), which the printed connection
# string names. The superuser, lineloc, serves this script's setup alone; the
# roles and what each may do are in docs/production.md.
#
# The data directory is made private (mkdir -m 700); a directory at its path
# that is a symbolic link, not the cluster's OS user's, or open to other users
# is refused, and every file in it is written as the cluster's OS user.
#
# A replica is a copy of its primary's data directory (pg_basebackup) that
# follows its write-ahead log: the same roles and passwords (its own copy of
# the pgpass file, made again by replicate after rotate-passwords), read-only
# for every role. The primary lets the role lineloc_replication stream from
# 127.0.0.1 alone. A program that reads (lineloc-backbone) may name several
# clusters in one libpq connection string ("host=127.0.0.1,127.0.0.1
# port=55433,55432 target_session_attrs=prefer-standby"); it then uses the
# first that answers and another when that one fails.
#
# Environment: LINELOC_PG_PORT (default 55432), LINELOC_PG_DIR (default
# /tmp/lineloc-pg-<port>), LINELOC_PG_USER (OS user when run as root; default
# lineloc), LINELOC_PG_PRIMARY_DIR (replicate: the primary's data directory;
# default /tmp/lineloc-pg-<its port>).
set -euo pipefail

PORT="${LINELOC_PG_PORT:-55432}"
DATA_DIR="${LINELOC_PG_DIR:-${TMPDIR:-/tmp}/lineloc-pg-${PORT}}"
OS_USER="${LINELOC_PG_USER:-lineloc}"
PG_BIN="$(ls -d /usr/lib/postgresql/15/bin 2>/dev/null || true)"
PGPASS="$DATA_DIR/pgpass"
SUPERUSER="lineloc"
OWNER="lineloc_owner"
WRITER="lineloc_writer"
READER="lineloc_reader"
ENRICHER="lineloc_enricher"
REPLICATION="lineloc_replication"
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

# As as_owner, with this script's stdin passed through a pipe of the OS user's
# own, so the command may open /dev/stdin (a pipe root made is closed to it).
as_owner_reading_stdin() { as_owner sh -c 'cat | "$@"' sh "$@"; }

# Writes (or, with >>, appends) stdin to a file in the data directory as the
# cluster's OS user, readable by it alone (a file written is made anew).
write_as_owner() { as_owner sh -c 'umask 077 && rm -f "$1" && cat >"$1"' sh "$1"; }
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

new_password() { head -c 24 /dev/urandom | base64 | tr -d '+/='; }

# A pgpass file's lines (host:port:database:user:password) with a new password
# for every role, on any port: a replica's roles and passwords are its
# primary's, and one connection string may name both.
new_pgpass() {
  local role
  for role in "$SUPERUSER" "$OWNER" "$WRITER" "$READER" "$ENRICHER" "$REPLICATION"; do
    echo "*:*:*:$role:$(new_password)"
  done
}

# The password of role $2 in the pgpass lines $1.
password_in() { awk -F: -v role="$2" '$4 == role { print $5 }' <<<"$1"; }

# The pgpass file's lines, with a new password for a program role it lacks
# (written to it).
completed_pgpass() {
  local pgpass role complete=true
  pgpass="$(as_owner cat "$PGPASS")"
  if grep -q "^\*:$PORT:" <<<"$pgpass"; then
    pgpass="$(sed "s/^\*:$PORT:/*:*:/" <<<"$pgpass")"
    complete=false
  fi
  for role in "$OWNER" "$WRITER" "$READER" "$ENRICHER" "$REPLICATION"; do
    if [ -z "$(password_in "$pgpass" "$role")" ]; then
      pgpass+=$'\n'"*:*:*:$role:$(new_password)"
      complete=false
    fi
  done
  $complete || write_as_owner "$PGPASS" <<<"$pgpass"
  echo "$pgpass"
}

write_hba() {
  write_as_owner "$DATA_DIR/pg_hba.conf" <<'HBA'
# Every role logs in with its password, on the socket and on loopback alike;
# a replica on this machine streams as lineloc_replication, which may do
# nothing else ("all" does not match replication connections).
# TYPE  DATABASE     USER                 ADDRESS       METHOD
local   all          lineloc_replication                reject
host    all          lineloc_replication  127.0.0.1/32  reject
local   all          all                                scram-sha-256
host    all          all                  127.0.0.1/32  scram-sha-256
host    replication  lineloc_replication  127.0.0.1/32  scram-sha-256
HBA
}

psql_superuser() {
  as_owner env PGPASSFILE="$PGPASS" "$PG_BIN/psql" -X -q -w -v ON_ERROR_STOP=1 -h 127.0.0.1 \
    -p "$PORT" -U "$SUPERUSER" "$@"
}

is_running() {
  [ -f "$DATA_DIR/PG_VERSION" ] && as_owner "$PG_BIN/pg_ctl" -D "$DATA_DIR" status >/dev/null 2>&1
}

initialise() {
  ensure_os_user
  [ -d "$DATA_DIR" ] || create_data_dir
  local pgpass output
  pgpass="$(new_pgpass)"
  output="$(password_in "$pgpass" "$SUPERUSER" | as_owner_reading_stdin "$PG_BIN/initdb" \
    -D "$DATA_DIR" -U "$SUPERUSER" --auth=scram-sha-256 --pwfile=/dev/stdin -E UTF8 \
    --locale=C.UTF-8 2>&1)" || { echo "$output" >&2; die "initdb failed"; }
  append_as_owner "$DATA_DIR/postgresql.conf" <<CONF
listen_addresses = '127.0.0.1'
port = $PORT
unix_socket_directories = '$DATA_DIR'
max_connections = 200
shared_buffers = 256MB
fsync = on
password_encryption = 'scram-sha-256'
CONF
  write_hba
  write_as_owner "$PGPASS" <<<"$pgpass"
}

# A cluster without a pgpass file trusted every local user: it is stopped, its
# superuser given a password (in single-user mode, so nobody may log in
# meanwhile) and its pg_hba.conf replaced; start then gives the other roles
# passwords and hands its databases over.
secure_trusting_cluster() {
  echo "pg.sh: $DATA_DIR trusts every local user; giving its roles passwords"
  if is_running; then
    as_owner "$PG_BIN/pg_ctl" -D "$DATA_DIR" -m fast -w stop >/dev/null
  fi
  local pgpass output
  pgpass="$(new_pgpass)"
  output="$(as_owner "$PG_BIN/postgres" --single -D "$DATA_DIR" postgres 2>&1 \
    <<<"ALTER ROLE $SUPERUSER PASSWORD '$(password_in "$pgpass" "$SUPERUSER")'")" \
    || { echo "$output" >&2; die "could not give the superuser a password"; }
  write_hba
  write_as_owner "$PGPASS" <<<"$pgpass"
}

# The roles lineloc's programs log in as, with the passwords in $1: none a
# superuser; the owner may create databases (the tests make their own).
apply_roles() {
  psql_superuser -d postgres <<SQL
SELECT format('CREATE ROLE %I', role)
  FROM unnest(ARRAY['$OWNER', '$WRITER', '$READER', '$ENRICHER', '$REPLICATION']) AS role
  WHERE NOT EXISTS (SELECT FROM pg_roles WHERE rolname = role) \gexec
ALTER ROLE $OWNER LOGIN NOSUPERUSER CREATEDB NOCREATEROLE PASSWORD '$(password_in "$1" "$OWNER")';
ALTER ROLE $WRITER LOGIN NOSUPERUSER NOCREATEDB NOCREATEROLE PASSWORD '$(password_in "$1" "$WRITER")';
ALTER ROLE $READER LOGIN NOSUPERUSER NOCREATEDB NOCREATEROLE PASSWORD '$(password_in "$1" "$READER")';
ALTER ROLE $ENRICHER LOGIN NOSUPERUSER NOCREATEDB NOCREATEROLE PASSWORD '$(password_in "$1" "$ENRICHER")';
ALTER ROLE $REPLICATION LOGIN REPLICATION NOSUPERUSER NOCREATEDB NOCREATEROLE
  PASSWORD '$(password_in "$1" "$REPLICATION")';
ALTER ROLE $SUPERUSER PASSWORD '$(password_in "$1" "$SUPERUSER")';
SQL
}

# Every database but the system's, and what the superuser made in its schema
# public (outside extensions), belongs to the owner role: a database the
# superuser owns (one from a cluster that trusted every local user) is handed
# over whole, in one transaction.
hand_over_databases() {
  local database
  for database in $(psql_superuser -d postgres -tA -c "SELECT datname FROM pg_database
      WHERE datdba = '$SUPERUSER'::regrole AND datname NOT IN ('postgres', 'template0', 'template1')"); do
    psql_superuser --single-transaction -d "$database" <<SQL
ALTER DATABASE "$database" OWNER TO $OWNER;
SELECT format('ALTER %s %s OWNER TO $OWNER', CASE WHEN c.relkind = 'v' THEN 'VIEW' ELSE 'TABLE' END,
              c.oid::regclass)
  FROM pg_class c
  WHERE c.relnamespace = 'public'::regnamespace AND c.relkind IN ('r', 'v')
    AND c.relowner = '$SUPERUSER'::regrole
    AND NOT EXISTS (SELECT FROM pg_depend d WHERE d.classid = 'pg_class'::regclass
                    AND d.objid = c.oid AND d.deptype = 'e') \gexec
SELECT format('ALTER FUNCTION %s OWNER TO $OWNER', p.oid::regprocedure)
  FROM pg_proc p
  WHERE p.pronamespace = 'public'::regnamespace AND p.proowner = '$SUPERUSER'::regrole
    AND NOT EXISTS (SELECT FROM pg_depend d WHERE d.classid = 'pg_proc'::regclass
                    AND d.objid = p.oid AND d.deptype = 'e') \gexec
SQL
  done
}

start() {
  check_data_dir
  if [ ! -f "$DATA_DIR/PG_VERSION" ]; then
    initialise
  elif [ ! -f "$PGPASS" ]; then
    secure_trusting_cluster
  fi
  if [ -f "$DATA_DIR/standby.signal" ]; then
    is_running || start_server
    echo "pg.sh: running on port $PORT ($DATA_DIR), a replica"
    return 0
  fi
  # A cluster of an earlier pg.sh is brought up to this one's rules whether
  # it runs already or not.
  write_hba
  if is_running; then
    as_owner "$PG_BIN/pg_ctl" -D "$DATA_DIR" reload >/dev/null
  else
    start_server
  fi
  apply_roles "$(completed_pgpass)"
  # Extensions in template1 so every database created later (tests) has them.
  psql_superuser -d template1 \
    -c "CREATE EXTENSION IF NOT EXISTS postgis; CREATE EXTENSION IF NOT EXISTS postgis_sfcgal;"
  psql_superuser -d postgres <<SQL
SELECT 'CREATE DATABASE $DB_NAME OWNER $OWNER'
  WHERE NOT EXISTS (SELECT FROM pg_database WHERE datname = '$DB_NAME') \gexec
SQL
  hand_over_databases
  echo "pg.sh: running on port $PORT ($DATA_DIR)"
}

start_server() {
  as_owner "$PG_BIN/pg_ctl" -D "$DATA_DIR" -l "$DATA_DIR/server.log" -w -t 60 start >/dev/null \
    || { as_owner tail -20 "$DATA_DIR/server.log" >&2; die "server did not start"; }
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

# New passwords are set first, then written to the pgpass file.
rotate_passwords() {
  check_data_dir
  is_running || die "not running; start it first"
  local pgpass
  pgpass="$(new_pgpass)"
  apply_roles "$pgpass"
  write_as_owner "$PGPASS" <<<"$pgpass"
  echo "pg.sh: new passwords in $PGPASS"
}

conninfo() {
  local role="${1:-$OWNER}"
  case "$role" in
    "$OWNER" | "$WRITER" | "$READER" | "$ENRICHER") ;;
    *) die "conninfo: no role $role (one of $OWNER, $WRITER, $READER, $ENRICHER)" ;;
  esac
  echo "host=127.0.0.1 port=$PORT user=$role dbname=$DB_NAME passfile='$PGPASS'"
}

# This port's cluster as a streaming replica of the one on $1 (see above).
replicate() {
  local primary_port="$1" primary_dir primary_pgpass
  if [[ ! "$primary_port" =~ ^[0-9]+$ ]] || [ "$primary_port" = "$PORT" ]; then
    die "replicate: give the primary's port, not this cluster's ($PORT)"
  fi
  primary_dir="${LINELOC_PG_PRIMARY_DIR:-${TMPDIR:-/tmp}/lineloc-pg-${primary_port}}"
  primary_pgpass="$primary_dir/pgpass"
  check_data_dir
  [ ! -f "$DATA_DIR/PG_VERSION" ] || die "$DATA_DIR holds a cluster already; destroy it first"
  LINELOC_PG_PORT="$primary_port" LINELOC_PG_DIR="$primary_dir" "$0" status >/dev/null \
    || die "no cluster runs on port $primary_port ($primary_dir)"
  ensure_os_user
  [ -d "$DATA_DIR" ] || create_data_dir
  local output
  output="$(as_owner env PGPASSFILE="$primary_pgpass" "$PG_BIN/pg_basebackup" -w \
    -h 127.0.0.1 -p "$primary_port" -U "$REPLICATION" -D "$DATA_DIR" -R -X stream --checkpoint=fast \
    2>&1)" \
    || { echo "$output" >&2; die "pg_basebackup from port $primary_port failed"; }
  as_owner chmod 700 "$DATA_DIR"
  append_as_owner "$DATA_DIR/postgresql.conf" <<CONF
port = $PORT
unix_socket_directories = '$DATA_DIR'
hot_standby = on
CONF
  as_owner cat "$primary_pgpass" | write_as_owner "$PGPASS"
  start_server
  echo "pg.sh: replica of port $primary_port started on port $PORT ($DATA_DIR)"
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
  conninfo) conninfo "${2:-}" ;;
  rotate-passwords) rotate_passwords ;;
  destroy) destroy ;;
  replicate) replicate "${2:-}" ;;
  *) echo "usage: $0 start|stop|status|conninfo [ROLE]|rotate-passwords|destroy|replicate PORT" >&2; exit 2 ;;
esac
