#!/usr/bin/env python3
"""Checks deploy/: every YAML manifest parses, references only the image the Dockerfile
builds and the port radfluxd serves on, uses only flags radfluxd has, and only Secret keys
the Secret defines, and the runtime image installs the Debian package of every shared library
the executables load (ldd, plus Embree, which the clients dlopen). Usage:
check_manifests.py REPO_ROOT RADFLUXD [EXECUTABLE...]   (the other executables the image carries)"""
import glob
import os
import re
import subprocess
import sys

import yaml

root, radfluxd, executables = sys.argv[1], sys.argv[2], sys.argv[3:]
deploy = os.path.join(root, "deploy")
errors = []


def fail(msg):
    errors.append(msg)


def walk(node, key=None):
    """Yields (key, value) for every scalar in a parsed YAML tree."""
    if isinstance(node, dict):
        for k, v in node.items():
            yield from walk(v, k)
    elif isinstance(node, list):
        for v in node:
            yield from walk(v, key)
    else:
        yield key, node


dockerfile = open(os.path.join(deploy, "Dockerfile")).read()
froms = re.findall(r"^FROM\s+(\S+)", dockerfile, re.M)
if not froms or any(not f.startswith("debian:12") for f in froms):
    fail(f"Dockerfile stages must be Debian 12: {froms}")
if "scripts/setup.sh" not in dockerfile:
    fail("Dockerfile must install the packages of scripts/setup.sh")
if not re.search(r"--target radflux radflux-local radflux-service radfluxd", dockerfile):
    fail("Dockerfile must build radflux, radflux-local and radflux-service (the executables "
         "it dispatches to) and radfluxd")
for sibling in ("radflux-local", "radflux-service"):
    if f"/usr/local/bin/{sibling}" not in dockerfile.split("COPY --from=build")[-1]:
        fail(f"the runtime image must carry {sibling} next to radflux")
# debian:12-slim has these already (apt needs them).
BASE_PACKAGES = {"libc6", "libgcc-s1", "libstdc++6", "zlib1g"}


def package_of(path):
    """The Debian package that installed a shared library (dpkg knows it under /lib or
    /usr/lib), or None."""
    real = os.path.realpath(path)
    for candidate in {real, real.replace("/usr/lib/", "/lib/", 1), path}:
        out = subprocess.run(["dpkg", "-S", candidate], capture_output=True, text=True).stdout
        if out:
            return out.split(":")[0]
    return None


def needed_packages(binaries):
    libraries = set()
    for binary in binaries:
        out = subprocess.run(["ldd", binary], capture_output=True, text=True).stdout
        libraries |= set(re.findall(r"=> (/\S+)", out))
    return {package_of(lib) or f"(no package for {lib})" for lib in libraries}


runtime = dockerfile.split("FROM debian:12-slim")[-1]
installed = set(re.findall(r"\b(lib[a-z0-9.+-]+|zlib1g|ca-certificates)\b", runtime))
# Embree, which the clients dlopen, wherever the loader finds it.
embree = re.findall(r"libembree3\.so\.3 .*=> (\S+)",
                    subprocess.run(["ldconfig", "-p"], capture_output=True, text=True).stdout)
for package in sorted(needed_packages([radfluxd, *executables, *embree[:1]]) - BASE_PACKAGES):
    if package not in installed:
        fail(f"the runtime image does not install {package}, which the executables load")

exposed = {int(p) for p in re.findall(r"^EXPOSE\s+(\d+)", dockerfile, re.M)}
if len(exposed) != 1:
    fail(f"Dockerfile must EXPOSE exactly one port: {exposed}")
port = next(iter(exposed), 7070)

help_text = subprocess.run([radfluxd, "--help"], capture_output=True, text=True).stdout
known_flags = set(re.findall(r"(--[a-z][a-z0-9-]*)", help_text))

files = sorted(glob.glob(os.path.join(deploy, "**", "*.yaml"), recursive=True))
if not files:
    fail("no YAML manifests in deploy/")
docs = {}
for path in files:
    try:
        docs[path] = [d for d in yaml.safe_load_all(open(path)) if d is not None]
    except yaml.YAMLError as e:
        fail(f"{path}: does not parse: {e}")

compose = docs.get(os.path.join(deploy, "compose.yaml"), [{}])[0]
built = [s.get("image") for s in compose.get("services", {}).values() if "build" in s]
if len(built) != 1:
    fail(f"compose.yaml must build exactly one image: {built}")
image = built[0] if built else "radflux:0.1"
services = compose.get("services", {})
if sum(1 for s in services if s != "radfluxd") < 1 or \
        services.get("worker", {}).get("deploy", {}).get("replicas") != 3:
    fail("compose.yaml must run one radfluxd and three workers")
if "radflux-data" not in compose.get("volumes", {}):
    fail("compose.yaml needs a volume for the data directory")

kinds, secret_keys, secret_refs, service_names = set(), set(), set(), set()
for path, documents in docs.items():
    for doc in documents:
        kinds.add(doc.get("kind"))
        if doc.get("kind") == "Secret":
            secret_keys |= set(doc.get("stringData", {})) | set(doc.get("data", {}))
        if doc.get("kind") == "Service":
            service_names.add(doc["metadata"]["name"])
        if doc.get("kind") == "StatefulSet" and not doc["spec"].get("volumeClaimTemplates"):
            fail(f"{path}: the server StatefulSet needs a volumeClaimTemplate")
        for key, value in walk(doc):
            text = str(value)
            if key == "image" and value != image:
                fail(f"{path}: image {value} is not the one deploy/Dockerfile builds ({image})")
            if key in ("containerPort", "port", "targetPort") and value != port:
                fail(f"{path}: port {value} is not radfluxd's {port}")
            if key == "ports":
                published = [int(p) for p in re.findall(r"\d+", text)]
                if any(p != port for p in published):
                    fail(f"{path}: published ports {text} are not {port}")
            if key == "secretKeyRef" or (isinstance(doc, dict) and key == "key" and
                                         "secretKeyRef" in yaml.safe_dump(doc)):
                secret_refs.add(value)
            for flag in re.findall(r"(?<![\w-])(--[a-z][a-z0-9-]*)", text):
                if "radfluxd" in text or key in ("args",):
                    if flag not in known_flags:
                        fail(f"{path}: radfluxd has no flag {flag}")
            for addr_port in re.findall(r"(?:--listen|--server)[ =](\S+):(\d+)", text):
                if int(addr_port[1]) != port:
                    fail(f"{path}: {addr_port[0]}:{addr_port[1]} is not port {port}")

for needed in ("Service", "StatefulSet", "Deployment", "Secret"):
    if needed not in kinds:
        fail(f"deploy/k8s has no {needed}")
for path, documents in docs.items():
    for doc in documents:
        for key, value in walk(doc):
            if key == "key" and value not in secret_keys and doc.get("kind") != "Secret":
                fail(f"{path}: secret key {value} is not in the Secret ({sorted(secret_keys)})")
            if key == "args" and "--server" in str(value):
                host = re.search(r"--server[ =]([^:]+):", str(value))
                if host and host.group(1) not in service_names:
                    fail(f"{path}: --server {host.group(1)} is not a Service")

if errors:
    print("\n".join(errors))
    sys.exit(1)
print(f"deploy: {len(files)} manifests parse; image {image}, port {port}, "
      f"{len(secret_keys)} secret keys, flags checked against radfluxd --help, "
      f"runtime libraries of {1 + len(executables)} executables installed")
