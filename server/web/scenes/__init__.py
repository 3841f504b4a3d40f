"""Scenes as the event loop sees them: the hub of a server's scenes, each scene's hub (its
process and its connections), the runner that starts a scene's process and talks to it,
work kept off the event loop, and how many scenes a machine holds.

May import ``process``, ``recording``, ``connections``, ``storage`` and the core."""
