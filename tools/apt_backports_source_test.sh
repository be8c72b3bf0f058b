#!/usr/bin/env bash
# Tests tools/apt_backports_source.sh on made-up /etc/apt trees in both formats.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
# shellcheck source=apt_backports_source.sh
source "$here/apt_backports_source.sh"
root=$(mktemp -d)
trap 'rm -rf "$root"' EXIT
failures=0

expect() {  # NAME EXPECTED_URI EXPECTED_KEYRING
  local got
  got=$(apt_backports_source "$root")
  local want
  want=$(printf 'Types: deb\nURIs: %s\nSuites: bookworm-backports\nComponents: main\nSigned-By: %s' "$2" "$3")
  if [ "$got" != "$want" ]; then
    echo "FAIL $1:"; echo "$got"; echo "--- expected:"; echo "$want"
    failures=$((failures + 1))
  else
    echo "ok   $1"
  fi
}
reset() { rm -rf "$root/etc"; mkdir -p "$root/etc/apt/sources.list.d"; }

reset
expect "no sources: the default archive" http://deb.debian.org/debian \
  /usr/share/keyrings/debian-archive-keyring.gpg

reset
cat >"$root/etc/apt/sources.list.d/debian.sources" <<'SRC'
# the Debian 12 container default, behind a mirror
Types: deb
URIs: http://mirror.example.org/debian-security
Suites: bookworm-security
Components: main
Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg

Types: deb
URIs: http://mirror.example.org/debian
Suites: bookworm bookworm-updates
Components: main
Signed-By: /etc/apt/keyrings/mirror.gpg
SRC
expect "deb822 mirror" http://mirror.example.org/debian /etc/apt/keyrings/mirror.gpg

reset
cat >"$root/etc/apt/sources.list.d/debian.sources" <<'SRC'
Types: deb
URIs: http://disabled.example.org/debian
Suites: bookworm
Components: main
Enabled: no

Types: deb-src deb
URIs: http://proxy.local:3142/debian http://second.example.org/debian
Suites: bookworm
Components: main
Signed-By:
 -----BEGIN PGP PUBLIC KEY BLOCK-----
 .
 abc
 -----END PGP PUBLIC KEY BLOCK-----
SRC
expect "deb822 disabled entry skipped, inline key" http://proxy.local:3142/debian \
  /usr/share/keyrings/debian-archive-keyring.gpg

reset
cat >"$root/etc/apt/sources.list" <<'SRC'
# one-line format
deb http://security.debian.org/debian-security bookworm-security main
deb-src http://src.example.org/debian bookworm main
deb [arch=amd64 signed-by=/etc/apt/keyrings/corp.gpg] https://apt.corp.example/debian bookworm main contrib
SRC
expect "one-line with options" https://apt.corp.example/debian /etc/apt/keyrings/corp.gpg

reset
echo "deb http://ftp.de.debian.org/debian/ bookworm-updates main" \
  >"$root/etc/apt/sources.list.d/mirror.list"
expect "one-line .list, no options" http://ftp.de.debian.org/debian/ \
  /usr/share/keyrings/debian-archive-keyring.gpg

[ $failures -eq 0 ] && echo "all passed" || { echo "$failures failed"; exit 1; }
