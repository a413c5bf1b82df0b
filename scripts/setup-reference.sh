#!/usr/bin/env bash
# Installs the reference Triangle 1.6 from Debian's non-free section (`triangle-bin`,
# `libtriangle-dev`) when it is missing: the differential tests and benchmarks compare against it.
# Idempotent; needs root (apt) only when something is missing.
set -euo pipefail
if [ -e /usr/lib/libtriangle-1.6.so ] && [ -x /usr/bin/triangle ] && [ -e /usr/include/triangle.h ]; then
  exit 0
fi
SUDO=""
if [ "$(id -u)" != 0 ]; then SUDO="sudo"; fi
if [ -f /etc/apt/sources.list.d/debian.sources ]; then
  $SUDO sed -i -E '/^Components:/{/non-free([^-]|$)/!s/$/ non-free/}' /etc/apt/sources.list.d/debian.sources
fi
if [ -f /etc/apt/sources.list ] && grep -qE '^deb .* bookworm( |$)' /etc/apt/sources.list; then
  $SUDO sed -i -E '/^deb .* bookworm /{/non-free([^-]|$)/!s/$/ non-free/}' /etc/apt/sources.list
fi
$SUDO apt-get update -qq
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq triangle-bin libtriangle-dev >/dev/null
