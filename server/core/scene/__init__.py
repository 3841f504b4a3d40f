"""One scene: the registry of its nodes, undo, the change feed and frames, the bodies in its physics world, the clock. Imports the model, physics and the kit."""
