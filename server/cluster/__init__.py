"""A server spread over machines on a NATS bus (``vp-server --bus nats://… --role …``).

*Gateways* (:mod:`.gateway`) terminate WebSockets and REST and serve the pages, as a
single server does; their scenes are :class:`.remote_runner.RemoteRunner`\\ s instead of
processes of their own. *Workers* (:mod:`.worker_host`) run the scene processes of
:mod:`server.web.scenes.runner` and carry their commands and events over the bus
(:mod:`.bus`; its messages are typed in :mod:`.bus_messages`). Which worker runs a
scene is a lease in the bus's key-value store (:mod:`.leases`); client ids and the resume
key's secret are shared there too (:mod:`.client_ids`). Imports run one way:
``server.cli`` → here → ``server.web``.
"""
