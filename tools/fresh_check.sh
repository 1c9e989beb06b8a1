#!/usr/bin/env bash
# make fresh-check: the README's `make test` on a brand-new minimal Debian 12, as a new user would run it.
#
# Builds a minimal bookworm root (mmdebstrap --variant=minbase, plus only git, make, sudo and
# ca-certificates: what the README tells a user to add), clones the commit under test into it and
# runs `make test` there as root, with nothing else installed by hand. Whatever the suite calls must
# therefore come from `make setup`. The root is unmounted and removed afterwards, whatever happened.
# Exit status: that of `make test` in the root (non-zero also when the root cannot be built).
# `tools/fresh_check.sh 'COMMAND'` runs another shell command there instead, in the clone (e.g. a
# `make run` smoke check).
#
# Needs root (chroot, mount) and mmdebstrap (`make setup` installs it). Environment:
#   RACEBOT_FRESH_KEEP=1   keep the root in /var/tmp for a look afterwards (it is still unmounted)
#   RACEBOT_FRESH_MIRROR   the Debian mirror (default: mmdebstrap's, deb.debian.org)
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
[ "$(id -u)" = 0 ] || { echo "racebot fresh-check: needs root (chroot and mount); run it as root or with sudo" >&2; exit 2; }
command -v mmdebstrap >/dev/null || { echo "racebot fresh-check: mmdebstrap is missing; run 'make setup' first" >&2; exit 2; }
command=${1:-make test}
commit=$(git -C "$repo" rev-parse HEAD)
if [ -n "$(git -C "$repo" status --porcelain --untracked-files=no)" ]; then
  echo "racebot fresh-check: note: uncommitted changes are not tested; the root gets commit $commit" >&2
fi

work=$(mktemp -d /var/tmp/racebot-fresh.XXXXXX)
root=$work/root
mounts=()
child=
cleanup() {
  local status=$?
  [ -n "$child" ] && kill "$child" 2>/dev/null && wait "$child" 2>/dev/null
  # Processes the suite left behind would keep the mounts busy.
  if [ -d "$root/proc" ]; then
    for pid in $(ls /proc | grep -E '^[0-9]+$'); do
      [ "$(readlink "/proc/$pid/root" 2>/dev/null)" = "$root" ] && kill -9 "$pid" 2>/dev/null || true
    done
  fi
  for ((i = ${#mounts[@]} - 1; i >= 0; i--)); do
    umount "${mounts[i]}" 2>/dev/null || umount -l "${mounts[i]}" 2>/dev/null || true
  done
  if grep -q " $work/" /proc/mounts; then
    # Never rm -rf through a mount (the root has a bind of the host's /dev).
    echo "racebot fresh-check: something is still mounted below $work; not removing it:" >&2
    grep " $work/" /proc/mounts >&2
  elif [ "${RACEBOT_FRESH_KEEP:-0}" = 1 ]; then
    echo "racebot fresh-check: root kept in $root"
  else
    rm -rf "$work"
  fi
  exit $status
}
trap cleanup EXIT
trap 'exit 130' INT TERM
in_background() {  # runs a long step as a child that the traps can stop (bash defers traps while it waits on a foreground one)
  "$@" &
  child=$!
  wait "$child"
  local status=$?
  child=
  return $status
}

start=$(date +%s)
echo "racebot fresh-check: building a minimal Debian 12 root in $root"
in_background mmdebstrap --quiet --variant=minbase --include=ca-certificates,git,make,sudo bookworm "$root" \
  ${RACEBOT_FRESH_MIRROR:+"$RACEBOT_FRESH_MIRROR"}
mount_in() {  # mount_in TARGET MOUNT-ARGS...: mount, and remember it for the clean-up
  local target=$root$1; shift
  mkdir -p "$target"
  mount "$@" "$target"
  mounts+=("$target")
}
mount_in /proc -t proc proc
mount_in /sys -t sysfs sysfs
mount_in /dev --bind /dev
mount_in /dev/shm -t tmpfs tmpfs
# Network set-up a real install has: name servers, this network's CA bundle (TLS to the package
# registries), and /etc/hosts with localhost and the machine's own name.
cp /etc/resolv.conf "$root/etc/resolv.conf"
cp /etc/ssl/certs/ca-certificates.crt "$root/etc/ssl/certs/ca-certificates.crt"
printf '127.0.0.1\tlocalhost\n127.0.1.1\t%s\n::1\tlocalhost ip6-localhost ip6-loopback\n' "$(hostname)" \
  > "$root/etc/hosts"
git clone -q "$repo" "$root/root/racebot"
git -C "$root/root/racebot" checkout -q "$commit"
echo "racebot fresh-check: root ready in $(( $(date +%s) - start )) s; running '$command' on commit ${commit:0:12}"

# A clean environment, as a login on the new machine would have; only the CA variables of this
# network pass through (they name the bundle copied in above).
env_vars=(HOME=/root PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin LANG=C.UTF-8 TERM=dumb)
for var in PIP_CERT REQUESTS_CA_BUNDLE SSL_CERT_FILE CURL_CA_BUNDLE GIT_SSL_CAINFO; do
  [ -n "${!var:-}" ] && env_vars+=("$var=${!var}")
done
set +e
in_background chroot "$root" /usr/bin/env -i "${env_vars[@]}" /bin/bash -c "cd /root/racebot && $command"
status=$?
set -e
echo "racebot fresh-check: '$command' in the fresh root exited $status after $(( $(date +%s) - start )) s in all"
exit $status
