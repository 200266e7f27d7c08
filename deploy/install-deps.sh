#!/usr/bin/env bash
# Installs every build, test and run-time dependency of lineloc from Debian 12
# packages. Idempotent: packages already present are left as they are.
# Run as root (or through sudo); downloads nothing but Debian packages.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config git clang-format
  cyclonedds-dev cyclonedds-tools
  libopencv-dev libopencv-contrib-dev opencv-doc
  libeigen3-dev libceres-dev
  postgresql-15 postgresql-15-postgis-3 postgresql-15-postgis-3-scripts libpq-dev
  libgeographiclib-dev libproj-dev
  libhwy-dev libembree-dev
  libsimdjson-dev nlohmann-json3-dev libssl-dev openssl
  libcli11-dev libyaml-cpp-dev libspdlog-dev libfmt-dev
  libgps-dev gpsd gpsd-clients python3-gps
  libgtest-dev libgmock-dev libbenchmark-dev
)
# The tests check the ROS 2 wire format against an npm package (tests/support/ros2_cdr):
# Node.js and npm from Debian where the machine has none.
if ! command -v npm >/dev/null 2>&1; then
  packages+=(nodejs npm)
fi

missing=()
for package in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$package")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then
  SUDO="sudo"
fi

echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -q
$SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
