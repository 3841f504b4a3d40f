"""Plain building blocks every layer may use: 3D math, the undo journal, limits, rates, ids, the number codec. Imports nothing of the core."""
