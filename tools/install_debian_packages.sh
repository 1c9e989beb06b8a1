#!/usr/bin/env bash
# Installs the Debian packages listed in $1 that are not installed yet; does nothing (quickly) when all are.
# On Ubuntu 20.04 with ROS Noetic from the ROS archive, set RACEBOT_SKIP_APT=1 and install the
# equivalent ros-noetic-* packages yourself (see docs/INSTALL.md).
set -euo pipefail
list=$1
[ "${RACEBOT_SKIP_APT:-0}" = 1 ] && { echo "racebot: RACEBOT_SKIP_APT=1, not checking Debian packages"; exit 0; }
if ! command -v dpkg-query >/dev/null; then
  echo "racebot: this is not a Debian-like system; install the packages of $list by hand, then set RACEBOT_SKIP_APT=1" >&2
  exit 1
fi
mapfile -t wanted < <(grep -v '^\s*#' "$list" | grep -v '^\s*$')
missing=()
for pkg in "${wanted[@]}"; do
  status=$(dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null || true)
  [ "$status" = "install ok installed" ] || missing+=("$pkg")
done
[ ${#missing[@]} -eq 0 ] && exit 0
echo "racebot: installing Debian packages: ${missing[*]}"
SUDO=""
if [ "$(id -u)" != 0 ]; then
  command -v sudo >/dev/null || { echo "racebot: not root and no sudo; run as root: apt-get install -y ${missing[*]}" >&2; exit 1; }
  SUDO=sudo
fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
