#!/usr/bin/env bash
# Prints the deb822 entry for Debian's bookworm-backports suite, derived from the machine's
# own Debian source entries, so that a machine using a mirror or a proxy, or reaching only
# its configured archive, gets backports from that same archive and keyring.
#
# Reads ROOT/etc/apt/sources.list, ROOT/etc/apt/sources.list.d/*.list (one-line format:
# `deb [signed-by=KEYRING] URI bookworm main`) and ROOT/etc/apt/sources.list.d/*.sources
# (deb822: Types/URIs/Suites/Components/Signed-By stanzas). The first enabled `deb` entry
# for suite bookworm or bookworm-updates that is not the security archive gives the URI
# and the keyring; without one, deb.debian.org and Debian's archive keyring.
#
# Usage: apt_backports_source.sh [ROOT]   (sourced: the function apt_backports_source)
set -euo pipefail

readonly APT_BACKPORTS_DEFAULT_URI=http://deb.debian.org/debian
readonly APT_BACKPORTS_DEFAULT_KEYRING=/usr/share/keyrings/debian-archive-keyring.gpg

# Whether a suite and URI name the main archive (not security, not backports already).
_apt_backports_main_suite() {
  case "$1" in bookworm | bookworm-updates) ;; *) return 1 ;; esac
  case "$2" in *security*) return 1 ;; esac
  return 0
}

# One-line format: prints "URI KEYRING" of the first matching line, or nothing.
_apt_backports_from_list() {
  local file=$1 line options uri suite keyring rest
  while IFS= read -r line || [ -n "$line" ]; do
    line=${line%%#*}
    read -r -a words <<<"$line" || true
    [ ${#words[@]} -ge 3 ] && [ "${words[0]}" = deb ] || continue
    options="" keyring=""
    rest=("${words[@]:1}")
    if [[ ${rest[0]} == \[* ]]; then
      # Options run to the word ending in "]": [arch=amd64 signed-by=/k.gpg]
      while :; do
        options+=" ${rest[0]}"
        local last=${rest[0]}
        rest=("${rest[@]:1}")
        [[ $last == *\] ]] && break
        [ ${#rest[@]} -gt 0 ] || break
      done
      options=${options//[\[\]]/}
      for option in $options; do
        case "$option" in signed-by=*) keyring=${option#signed-by=} ;; esac
      done
    fi
    [ ${#rest[@]} -ge 2 ] || continue
    uri=${rest[0]} suite=${rest[1]}
    if _apt_backports_main_suite "$suite" "$uri"; then
      echo "$uri ${keyring:-$APT_BACKPORTS_DEFAULT_KEYRING}"
      return 0
    fi
  done <"$file"
}

# deb822 format: prints "URI KEYRING" of the first matching stanza, or nothing.
_apt_backports_from_sources() {
  local file=$1
  awk -v default_keyring="$APT_BACKPORTS_DEFAULT_KEYRING" '
    function flush() {
      if (types ~ /(^| )deb( |$)/ && enabled != "no" && uris != "") {
        n = split(suites, s, " ")
        for (i = 1; i <= n; ++i) {
          if ((s[i] == "bookworm" || s[i] == "bookworm-updates") && uris !~ /security/) {
            split(uris, u, " ")
            # An inline key (a multi-line Signed-By) cannot be pointed to: use the default.
            print u[1], (keyring ~ /^\// ? keyring : default_keyring)
            found = 1
            exit
          }
        }
      }
      types = uris = suites = keyring = enabled = ""; field = ""
    }
    /^[ \t]*#/ { next }
    /^[ \t]*$/ { flush(); next }
    /^[ \t]/ { next }  # a continuation line (an inline key)
    {
      colon = index($0, ":")
      field = tolower(substr($0, 1, colon - 1))
      value = substr($0, colon + 1)
      gsub(/^[ \t]+|[ \t]+$/, "", value)
      if (field == "types") types = value
      else if (field == "uris") uris = value
      else if (field == "suites") suites = value
      else if (field == "signed-by") keyring = value
      else if (field == "enabled") enabled = tolower(value)
    }
    END { if (!found) flush() }
  ' "$file"
}

apt_backports_source() {
  local root=${1:-} found="" file
  local candidates=()
  [ -f "$root/etc/apt/sources.list" ] && candidates+=("$root/etc/apt/sources.list")
  for file in "$root"/etc/apt/sources.list.d/*.list "$root"/etc/apt/sources.list.d/*.sources; do
    [ -f "$file" ] && candidates+=("$file")
  done
  for file in "${candidates[@]}"; do
    case "$file" in
      *.sources) found=$(_apt_backports_from_sources "$file") ;;
      *) found=$(_apt_backports_from_list "$file") ;;
    esac
    [ -n "$found" ] && break
  done
  local uri=${found%% *} keyring=${found#* }
  if [ -z "$found" ]; then
    uri=$APT_BACKPORTS_DEFAULT_URI keyring=$APT_BACKPORTS_DEFAULT_KEYRING
  fi
  printf 'Types: deb\nURIs: %s\nSuites: bookworm-backports\nComponents: main\nSigned-By: %s\n' \
    "$uri" "$keyring"
}

if [ "${BASH_SOURCE[0]}" = "$0" ]; then
  apt_backports_source "${1:-}"
fi
