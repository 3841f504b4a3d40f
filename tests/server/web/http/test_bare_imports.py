"""JavaScript served with its bare imports resolved, so 1.0 pages need no import map."""

from __future__ import annotations

import httpx

from server.web.http.bare_imports import IMPORT_MAP, rewrite


def test_bare_imports_of_three_lil_gui_uplot_and_addons_are_resolved():
    source = ("import * as THREE from 'three';\nimport GUI from \"lil-gui\";\nimport uPlot from 'uplot';\n"
              "export * from 'three';\nimport { OrbitControls } from 'three/addons/controls/OrbitControls.js';\n"
              "const m = await import('three');\nimport { x } from './three.js';\n")
    out = rewrite(source)
    assert f"from '{IMPORT_MAP['three']}'" in out and f'from "{IMPORT_MAP["lil-gui"]}"' in out
    assert f"export * from '{IMPORT_MAP['three']}'" in out and f"from '{IMPORT_MAP['uplot']}'" in out
    assert "'/vendor/three/examples/jsm/controls/OrbitControls.js'" in out
    assert f"import('{IMPORT_MAP['three']}')" in out
    assert "from './three.js'" in out       # relative imports stay as they are


def test_the_client_and_addons_are_served_resolved_with_revalidation(server):
    client = httpx.get(f"{server.http}/client/virtual-prosthetics.js")
    assert client.status_code == 200 and "javascript" in client.headers["content-type"]
    assert "from 'three'" not in client.text and IMPORT_MAP["three"] in client.text
    addon = httpx.get(f"{server.http}/vendor/three/examples/jsm/controls/OrbitControls.js")
    assert "from 'three'" not in addon.text
    again = httpx.get(f"{server.http}/client/virtual-prosthetics.js",
                      headers={"if-none-match": client.headers["etag"]})
    assert again.status_code == 304
