"""What a server keeps on disk: the state folder's layout and one scene's document and
journal.

May import the core only."""
