"""A scene's own process: its loop (sessions, requests, ticks), how it makes its scene at
start (:mod:`.scene_start`), the typed messages it and the server exchange
(:mod:`.messages`), saving, its figures, its heap, and ending with the server.

May import ``recording``, ``connections`` (what a message is sent as), ``storage`` and the
core; never the event loop's side."""
