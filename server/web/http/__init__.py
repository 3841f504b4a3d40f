"""The server's endpoints: the FastAPI application and its routes (REST inspection,
uploads, robots, recordings, pictures, pages, docs, Prometheus), the ``/ws`` WebSocket
endpoint, the access policy and CORS.

The top of the web's folders: it may import every other one (and the core); only the
command line and the cluster's gateway import it."""
