"""Imported last by the fork server that starts scene processes (runner.py's preload list):
everything it loaded is frozen out of garbage collection before any scene is forked.

A forked scene shares its parent's memory until it writes to it, and a collection writes
to every object it walks (its header), so a scene's first collection copied the whole
preloaded heap it walked (11 MB of an idle scene's 80). Frozen objects are never walked, so those pages
stay shared. Importing this module is its only use.
"""

import gc

gc.collect()
gc.freeze()
