# One image for the server and its tests: `make` installs everything inside it.
FROM python:3.11-slim-bookworm

RUN apt-get update \
 && apt-get install -y --no-install-recommends make nodejs npm \
 && rm -rf /var/lib/apt/lists/*

WORKDIR /app
COPY . .
RUN make install

EXPOSE 8000
CMD ["make", "run", "HOST=0.0.0.0", "PORT=8000"]
