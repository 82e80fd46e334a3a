#!/usr/bin/env bash
# Installs what Lantern needs on Debian, idempotently (safe to run again; it skips what is there):
#   - chromium:   headless Chromium for the browser tests, and the SwiftShader Vulkan driver that
#                 Dawn falls back to on a machine without a GPU;
#   - libvulkan1: the Vulkan loader Dawn (the `webgpu` npm package) opens;
#   - freedoom:   the Freedoom IWADs (BSD licence), the Doom maps the tests load and render;
#   - redis-server: the queue the farm's fault test (tests/cli/farm.test.ts) runs BullMQ on; the
#                 test starts its own server on a free port (the package's service is not used);
#   - npm packages, reinstalled only when package-lock.json changed.
set -euo pipefail
cd "$(dirname "$0")/.."

if ! command -v node >/dev/null || [ "$(node -p 'process.versions.node.split(".")[0]')" -lt 20 ]; then
  echo "setup: Lantern needs Node.js 20 or newer (found: $(node --version 2>/dev/null || echo none))" >&2
  exit 1
fi

packages=()
[ -x /usr/bin/chromium ] && [ -f /usr/lib/chromium/vk_swiftshader_icd.json ] || packages+=(chromium)
/sbin/ldconfig -p 2>/dev/null | grep -q 'libvulkan\.so\.1' || packages+=(libvulkan1)
[ -f /usr/share/games/doom/freedoom1.wad ] && [ -f /usr/share/games/doom/freedoom2.wad ] || packages+=(freedoom)
command -v redis-server >/dev/null || packages+=(redis-server)
if [ ${#packages[@]} -gt 0 ]; then
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  echo "setup: installing ${packages[*]} with apt-get" >&2
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${packages[@]}" >/dev/null
fi

stamp=node_modules/.lantern-lock-sha256
want=$(sha256sum package-lock.json | cut -d' ' -f1)
if [ ! -f "$stamp" ] || [ "$(cat "$stamp")" != "$want" ]; then
  echo "setup: installing npm packages" >&2
  npm ci --no-audit --no-fund --loglevel=error
  echo "$want" > "$stamp"
fi
