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
    assert sorted(services) == ["balancer", "bus", "gateway1", "gateway2", "server", "tests",
                                "worker1", "worker2"]


@pytest.mark.skipif(COMPOSE is None, reason="make test installs docker-compose first")
def test_the_cluster_profile_puts_two_gateways_behind_the_balancer_and_two_workers_on_the_bus():
    config = subprocess.run([COMPOSE, "--profile", "cluster", "config"], cwd=ROOT, check=True,
                            capture_output=True, text=True, timeout=60).stdout
    roles = dict(re.findall(r"^  (\w+):\n(?:    .*\n)*?    command:\n(?:    - .*\n)*?"
                            r"    - --role\n    - (\w+)", config, re.MULTILINE))
    assert roles == {"gateway1": "gateway", "gateway2": "gateway", "worker1": "worker",
                     "worker2": "worker"}
    assert config.count("nats://bus:4222") == 4
    balancer = (ROOT / "docker" / "cluster" / "nginx.conf").read_text()
    assert re.findall(r"server (\w+):8000", balancer) == ["gateway1", "gateway2"]
    assert "proxy_set_header Upgrade $http_upgrade" in balancer  # WebSockets pass


def test_the_tests_service_runs_the_readme_test_command():
    compose = (ROOT / "docker-compose.yml").read_text()
    readme = (ROOT / "README.md").read_text()
    [command] = re.findall(r'command: \["make", "(\w+)"\]', compose)
    assert f"make {command}" in readme.split("```")[1]  # the README's first commands


def stages() -> dict[str, tuple[str, str]]:
    """The Dockerfile's stages: name -> (what it is built FROM, its lines)."""
    found = re.findall(r"^FROM (\S+) AS (\S+)\n(.*?)(?=^FROM |\Z)",
                       (ROOT / "Dockerfile").read_text(), re.MULTILINE | re.DOTALL)
    return {name: (base, body) for base, name, body in found}


def lineage(name: str) -> list[str]:
    """A stage and the stages it is built on, itself first."""
    every = stages()
    chain = [name]
    while every[chain[-1]][0] in every:
        chain.append(every[chain[-1]][0])
    return chain


def test_both_services_build_a_stage_of_the_dockerfile():
    compose = (ROOT / "docker-compose.yml").read_text()
    targets = re.findall(r"target: (\S+)", compose)
    assert targets == ["server", "tests", "bus", "balancer"] and set(targets) <= set(stages())
    assert set(lineage("tests")) >= {"tests", "server"}  # the tests run the server's image


def test_the_server_image_runs_as_a_plain_user_and_checks_its_own_health():
    _, body = stages()["server"]
    assert re.findall(r"^USER (\S+)", body, re.MULTILINE)[-1] not in ("root", "0")
    assert re.search(r"^HEALTHCHECK .*\n?.*/api/health", body, re.MULTILINE)
    assert "EXPOSE 8000" in body
    _, tests = stages()["tests"]
    assert re.findall(r"^USER (\S+)", tests, re.MULTILINE)[-1] not in ("root", "0")


def test_the_server_image_holds_no_browser_and_no_node():
    installed = " ".join(stages()[stage][1] for stage in lineage("server"))
    assert "chromium" not in installed and "nodejs" not in installed
    assert "chromium" in stages()["tests"][1]
