"""The core's adapter to the world: WebSockets, REST, pages, scene processes, files.

Its folders import only those before them (a test says so): ``storage`` (files kept),
``connections`` (what a socket is sent), ``recording`` (recordings' folder and files),
``process`` (a scene's own process and its typed messages), ``scenes`` (the hubs and
runners the event loop drives), ``http`` (the FastAPI application and its routes)."""
