"""Recordings in MCAP: the writer a scene records with, the reader replays seek in, the
re-simulation that checks a recording against a fresh run, what a damaged file says.
The core's top layer: it may import every other."""
