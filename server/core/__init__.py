"""The simulation core, without I/O (no sockets, no event loop, no web framework).

Its folders are its layers, lowest first; each imports only the layers before it
(tests/test_imports.py holds them to it):

- ``kit``: 3D math, the undo journal, limits, rates, ids, the number codec;
- ``physics``: PyBullet bodies, contacts, rays, hulls, collision envelopes, mesh files;
- ``model``: nodes, parts, motors, robots, sensors and their readings, hands, GLTF parts,
  page meshes, the part figures; a node knows its scene only as ``model.node.World``;
- ``scene``: one scene: its registry of nodes, change feed and frames, camera, bodies,
  what a tick observes, and the Scene tying them to undo and the clock;
- ``protocol``: messages, the API table, arguments, operations, ownership, sessions,
  reports, scene documents, the command log, generated client artefacts.
"""
