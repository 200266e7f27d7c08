#!/usr/bin/env bash
# The Debian packages as a site would install them: cpack builds
# lineloc-robot and lineloc-backbone from BUILD_DIR; unpacked into a fresh
# root, they lay out the programs, the systemd units and the configurations
# (conffiles) each unit names; the programs run from there and read the
# installed configurations; the robot's package depends on no database and
# no ray tracer.
# Usage: test_debian_packages.sh BUILD_DIR VERSION
set -euo pipefail
BUILD_DIR="$1"
VERSION="$2"
WORK="$(mktemp -d)"
trap 'rm -rf "$WORK"' EXIT

fail() {
  echo "FAIL: $*" >&2
  exit 1
}

(cd "$BUILD_DIR" && cpack -G DEB -B "$WORK/packages" >"$WORK/cpack.log" 2>&1) ||
  { cat "$WORK/cpack.log" >&2; fail "cpack -G DEB"; }
ROOT="$WORK/root"
mkdir -p "$ROOT"
for component in robot backbone; do
  deb="$WORK/packages/lineloc-${component}_${VERSION}_$(dpkg --print-architecture).deb"
  [[ -f "$deb" ]] || fail "no package $deb"
  [[ "$(dpkg-deb -f "$deb" Package)" == "lineloc-$component" ]] || fail "$deb: wrong name"
  dpkg-deb -x "$deb" "$ROOT"
  dpkg-deb -e "$deb" "$WORK/control-$component"
  grep -qx "/etc/lineloc/$component.yml" "$WORK/control-$component/conffiles" ||
    fail "$deb: /etc/lineloc/$component.yml is not a conffile"

  unit="$ROOT/lib/systemd/system/lineloc-$component.service"
  [[ -f "$unit" ]] || fail "$deb: no systemd unit"
  exec_start="$(sed -n 's/^ExecStart=//p' "$unit")"
  read -r program config_flag config <<<"$exec_start"
  [[ "$config_flag" == "--config" ]] || fail "$unit: ExecStart takes no --config"
  [[ -x "$ROOT$program" ]] || fail "$unit: $program is not in the package"
  [[ -f "$ROOT$config" ]] || fail "$unit: $config is not in the package"
  grep -q '^WantedBy=multi-user.target' "$unit" || fail "$unit: not wanted by multi-user.target"

  "$ROOT$program" --version | grep -qx "lineloc-$component (lineloc $VERSION)" ||
    fail "$program --version"
  "$ROOT$program" --config "$ROOT$config" --print-config >/dev/null ||
    fail "$program cannot read its installed $config"
done

for program in lineloc-calibrate lineloc-features lineloc-load lineloc-migrate lineloc-enrich \
  lineloc-enrichment; do
  [[ -x "$ROOT/usr/bin/$program" ]] || fail "$program is not installed"
done
robot_depends="$(dpkg-deb -f "$WORK/packages/lineloc-robot_${VERSION}_$(dpkg --print-architecture).deb" Depends)"
[[ "$robot_depends" == *libddsc* ]] || fail "lineloc-robot does not depend on Cyclone DDS"
for server_only in libpq libembree; do
  [[ "$robot_depends" != *"$server_only"* ]] || fail "lineloc-robot depends on $server_only"
done
if readelf -d "$ROOT/usr/bin/lineloc-robot" | grep -q 'NEEDED.*libpq'; then
  fail "lineloc-robot links libpq"
fi
echo "packages lineloc-robot and lineloc-backbone $VERSION: installed layout, units and configs as named"
