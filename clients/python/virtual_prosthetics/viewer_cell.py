"""The live viewer of a scene in a Jupyter cell (``session.show()``), as MeshCat and viser
show theirs: an IFrame of the server's ``/view`` page.

It relies on Jupyter's display protocol (``_repr_html_``), not on IPython, so the client
needs nothing more; outside a notebook it prints as the viewer's address."""

from __future__ import annotations

from html import escape
from urllib.parse import urlencode


def http_of(ws_url: str) -> str:
    """The http(s)://host:port of a ws(s)://host:port server address."""
    return "https" + ws_url[3:] if ws_url.startswith("wss") else "http" + ws_url[2:]


def viewer_url(ws_url: str, scene: str, role: str = "viewer", token: str | None = None) -> str:
    """Where a browser watches ``scene`` (``role="controller"``: with motor panels and the
    record button)."""
    query = {"scene": scene, **({"role": role} if role != "viewer" else {}),
             **({"token": token} if token else {})}
    return f"{http_of(ws_url).rstrip('/')}/view?{urlencode(query)}"


class ViewerCell:
    """A scene's viewer as a notebook shows it (an IFrame ``width`` × ``height`` pixels)."""

    def __init__(self, url: str, width: int = 800, height: int = 500) -> None:
        self.url, self.width, self.height = url, width, height

    def _repr_html_(self) -> str:
        return (f'<iframe src="{escape(self.url)}" width="{self.width}" height="{self.height}" '
                f'style="border: 0" allow="fullscreen"></iframe>')

    def __repr__(self) -> str:
        return f"watch at {self.url}"
