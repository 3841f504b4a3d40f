"""CORS answers for pages of the origins the access policy allows, so that a page served
from elsewhere (a user's own folder) reads the REST API as well as it controls scenes.

Starlette's middleware does the protocol (preflights, ``Vary``, the headers); it is asked
:meth:`AccessPolicy.allows_origin` instead of a fixed list, because the policy allows
loopback pages by rule. Changes still need the control token (:func:`changing_allowed`).
"""

from __future__ import annotations

from typing import Any

from starlette.middleware.cors import CORSMiddleware

from .access import AccessPolicy

METHODS = ["GET", "POST", "PUT", "DELETE"]
HEADERS = ["Authorization", "Content-Type"]


class PageOrigins(CORSMiddleware):
    """CORS headers for the pages ``policy`` allows; none for others (the browser then
    keeps the answer from the page)."""

    def __init__(self, app: Any, policy: AccessPolicy) -> None:
        super().__init__(app, allow_origins=(), allow_methods=METHODS, allow_headers=HEADERS,
                         max_age=600)
        self.policy = policy

    def is_allowed_origin(self, origin: str) -> bool:
        return self.policy.allows_origin(origin)
