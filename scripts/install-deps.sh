#!/usr/bin/env bash
# Installs the Debian packages listed in debian-packages.txt that are missing. Run as root on a
# fresh Debian 12 machine; does nothing (and needs no root) when everything is there.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
mapfile -t wanted < <(grep -v '^\s*#' "$here/debian-packages.txt" | grep -v '^\s*$')
missing=()
for p in "${wanted[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
# apt-get install, as root (once with an apt-get update first).
updated=0
apt_install() {
  echo "whatnext: installing $*"
  if [ "$(id -u)" -ne 0 ]; then
    echo "whatnext: these Debian packages are missing and installing them needs root: $*" >&2
    exit 1
  fi
  export DEBIAN_FRONTEND=noninteractive
  [ "$updated" -eq 1 ] || apt-get update
  updated=1
  apt-get install -y --no-install-recommends "$@"
}
if [ ${#missing[@]} -gt 0 ]; then
  apt_install "${missing[@]}"
fi
# npm (for the web page): Debian 12's nodejs 18 comes without it, while the nodejs 20 some
# machines are offered brings its own and conflicts with Debian's npm package.
if ! command -v npm >/dev/null 2>&1; then
  apt_install npm
fi
