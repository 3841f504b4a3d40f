"""``/docs`` (Swagger UI) and ``/redoc`` (ReDoc): the REST API's pages, from the npm packages
the project installs (``clients/js/node_modules``), not from a CDN: they work offline.

FastAPI's own pages load their scripts from jsDelivr; a machine without the internet showed
a blank ``/docs`` (``SwaggerUIBundle is not defined``)."""

from __future__ import annotations

from fastapi import FastAPI
from fastapi.openapi.docs import get_redoc_html, get_swagger_ui_html
from fastapi.responses import HTMLResponse

SWAGGER = "/vendor/swagger-ui-dist"
REDOC = "/vendor/redoc/bundles/redoc.standalone.js"
FAVICON = f"{SWAGGER}/favicon-32x32.png"


def mount_api_docs(app: FastAPI) -> None:
    """Add ``/docs`` and ``/redoc`` (the app is made with ``docs_url=None, redoc_url=None``;
    the packages' folders are mounted by :func:`.pages.mount_pages`)."""
    title = f"{app.title}: the REST API"

    @app.get("/docs", include_in_schema=False)
    async def swagger_ui() -> HTMLResponse:
        return get_swagger_ui_html(openapi_url=app.openapi_url or "/openapi.json", title=title,
                                   swagger_js_url=f"{SWAGGER}/swagger-ui-bundle.js",
                                   swagger_css_url=f"{SWAGGER}/swagger-ui.css",
                                   swagger_favicon_url=FAVICON)

    @app.get("/redoc", include_in_schema=False)
    async def redoc() -> HTMLResponse:
        return get_redoc_html(openapi_url=app.openapi_url or "/openapi.json", title=title,
                              redoc_js_url=REDOC, redoc_favicon_url=FAVICON,
                              with_google_fonts=False)
