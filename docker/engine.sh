#!/usr/bin/env bash
# A Docker engine for `make test-container`: the one running, or Debian's docker.io
# installed and its dockerd started (as root) where there is none.
set -euo pipefail
if docker info >/dev/null 2>&1; then
    exit 0
fi
sudo=$([ "$(id -u)" = 0 ] || echo sudo)
if ! command -v dockerd >/dev/null; then
    $sudo apt-get update -q >&2
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -q --no-install-recommends docker.io >&2
fi
if ! docker info >/dev/null 2>&1; then
    echo "starting dockerd (its log: /tmp/dockerd.log)" >&2
    $sudo sh -c 'nohup dockerd >/tmp/dockerd.log 2>&1 &'
    for _ in $(seq 60); do
        docker info >/dev/null 2>&1 && exit 0
        sleep 1
    done
    echo "dockerd did not start; see /tmp/dockerd.log" >&2
    exit 1
fi
