"""What a server keeps on disk: the state folder's layout, one scene's document and
journal, and the upload folder (meshes and robot files kept under their hash).

May import the core only."""
