#!/usr/bin/env bash
# Installs Debian's headless-capable Chromium for the viewer's end-to-end tests (the tests
# drive it with playwright-core and never download a browser of their own). Does nothing
# when /usr/bin/chromium is already there. Needs root (CI runs as root).
set -euo pipefail
if [ -x /usr/bin/chromium ]; then
  exit 0
fi
if [ "$(id -u)" -ne 0 ]; then
  echo "pliant: /usr/bin/chromium is missing; run this script as root (it uses apt-get)" >&2
  exit 1
fi
export DEBIAN_FRONTEND=noninteractive
apt-get update -q
apt-get install -y -q --no-install-recommends chromium fonts-dejavu-core
