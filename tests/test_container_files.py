"""The container files, checked without an engine (`make test-container` builds and runs
them for real): docker-compose reads them, and they say what the README promises."""

from __future__ import annotations

import re
import shutil
import subprocess

import pytest

from tests.conftest import ROOT

COMPOSE = shutil.which("docker-compose")


@pytest.mark.skipif(COMPOSE is None, reason="make test installs docker-compose first")
def test_docker_compose_reads_the_file_and_finds_both_services():
    subprocess.run([COMPOSE, "config", "-q"], cwd=ROOT, check=True, timeout=60)
    services = subprocess.run([COMPOSE, "config", "--services"], cwd=ROOT, check=True,
                              capture_output=True, text=True, timeout=60).stdout.split()
    assert sorted(services) == ["server", "tests"]


def test_the_tests_service_runs_the_readme_test_command():
    compose = (ROOT / "docker-compose.yml").read_text()
    readme = (ROOT / "README.md").read_text()
    [command] = re.findall(r'command: \["make", "(\w+)"\]', compose)
    assert f"make {command}" in readme.split("```")[1]  # the README's first commands


def test_the_image_runs_as_a_plain_user_and_checks_its_own_health():
    dockerfile = (ROOT / "Dockerfile").read_text()
    users = re.findall(r"^USER (\S+)", dockerfile, re.MULTILINE)
    assert users and users[-1] not in ("root", "0")
    assert re.search(r"^HEALTHCHECK .*\n?.*/api/health", dockerfile, re.MULTILINE)
    assert "EXPOSE 8000" in dockerfile
