"""Shapes and the engine: PyBullet bodies, contacts, rays, hulls, collision envelopes and mesh files. Imports the kit only."""
