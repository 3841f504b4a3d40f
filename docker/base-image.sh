#!/usr/bin/env bash
# The base image the Dockerfile builds FROM: $1 (default debian:bookworm-slim).
# Prints the name to build from. Where the image is neither here nor pullable (a machine
# that reaches package registries but no image registry), makes an equivalent one from
# Debian's packages with debootstrap and prints its local name instead.
set -euo pipefail
wanted="${1:-debian:bookworm-slim}"
local_name="vp-debootstrap:bookworm"
if docker image inspect "$wanted" >/dev/null 2>&1 || docker pull -q "$wanted" >/dev/null 2>&1; then
    echo "$wanted"
    exit 0
fi
if docker image inspect "$local_name" >/dev/null 2>&1; then
    echo "$local_name"
    exit 0
fi
echo "$wanted cannot be pulled: making $local_name with debootstrap (a few minutes, once)" >&2
if ! command -v debootstrap >/dev/null; then
    sudo=$([ "$(id -u)" = 0 ] || echo sudo)
    $sudo apt-get install -y -q --no-install-recommends debootstrap >&2
fi
root=$(mktemp -d)
trap 'rm -rf "$root"' EXIT
debootstrap --variant=minbase bookworm "$root" "${DEBIAN_MIRROR:-http://deb.debian.org/debian}" >&2
rm -rf "$root"/var/cache/apt/archives/*.deb "$root"/var/lib/apt/lists/*
tar -C "$root" -c . | docker import -c 'CMD ["bash"]' - "$local_name" >&2
echo "$local_name"
