"""Recordings outside the core's MCAP writer and reader: the folder they are kept in and
the file a scene's process writes (their REST routes are ``http.recording_routes``).

May import ``connections``, ``storage`` and the core."""
