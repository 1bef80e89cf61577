#!/usr/bin/env bash
# Installs the Debian 12 packages physhand needs. Idempotent: packages already present
# are left alone and apt is not touched at all when nothing is missing.
set -euo pipefail

packages=(
    cmake g++ clang make pkg-config
    libbullet-dev libeigen3-dev nlohmann-json3-dev
    libgtest-dev libbenchmark-dev
    libopenxr-dev libopenxr-loader1 libopenxr-utils openxr-layer-corevalidation
    libvulkan-dev glslang-tools mesa-vulkan-drivers vulkan-validationlayers
    libpng-dev
)

missing=()
for p in "${packages[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0

sudo=()
if [ "$(id -u)" -ne 0 ]; then
    if command -v sudo >/dev/null 2>&1; then
        sudo=(sudo)
    else
        echo "install-deps: missing packages (${missing[*]}) and not root, and sudo is not installed" >&2
        exit 1
    fi
fi
echo "install-deps: installing ${missing[*]}"
"${sudo[@]}" apt-get update
DEBIAN_FRONTEND=noninteractive "${sudo[@]}" apt-get install -y --no-install-recommends "${missing[@]}"
