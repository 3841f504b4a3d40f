"""What a WebSocket connection is sent and how: frames made into WebSocket bytes once for
every socket, each connection's outbox, the connection limits and the client ids handed out.

May import ``storage`` (the key client ids are signed with) and the core."""
