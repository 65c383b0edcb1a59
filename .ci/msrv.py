#!/usr/bin/env python3
"""The workspace's `rust-version` is exactly what Cargo.lock needs.

Reads `cargo metadata --locked` for this platform, walks the dependency graph from the
workspace members along normal, dev and build edges (all three are compiled by `cargo test`),
and takes the highest `rust-version` any crate in it declares (crates declaring none are
ignored). The root Cargo.toml's `[workspace.package]` and every member (the root `[package]`
included) must declare exactly that: lower and the locked crates would not build with the
toolchain we claim; higher and we would claim more than we need.

Standard library only (CPython 3.11+); exits 1 on a mismatch, naming the crates that need most.
"""

import json
import subprocess
import sys
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def version(text):
    """'1.86' and '1.86.0' compare equal: (1, 86, 0)."""
    parts = [int(p) for p in text.split(".")]
    return tuple(parts + [0] * (3 - len(parts)))


def show(v):
    """(1, 86, 0) -> '1.86'; a patch level only when it is not 0."""
    return ".".join(map(str, v[:2] if v[2] == 0 else v))


def metadata():
    """cargo metadata for the host platform; offline first (no network wait when the crates are
    cached), online when they are not (a fresh CI machine)."""
    host = subprocess.run(["rustc", "-vV"], capture_output=True, text=True, check=True).stdout
    triple = next(l.split(":", 1)[1].strip() for l in host.splitlines() if l.startswith("host:"))
    cmd = ["cargo", "metadata", "--format-version", "1", "--locked", "--filter-platform", triple]
    for extra in (["--offline"], []):
        out = subprocess.run(cmd + extra, cwd=ROOT, capture_output=True, text=True)
        if out.returncode == 0:
            return json.loads(out.stdout)
    sys.exit(f"msrv: {' '.join(cmd)} failed:\n{out.stderr}")


def main():
    meta = metadata()
    packages = {p["id"]: p for p in meta["packages"]}
    deps = {n["id"]: n["deps"] for n in meta["resolve"]["nodes"]}
    members = set(meta["workspace_members"])

    # Everything the members build on this platform (--filter-platform already dropped the rest).
    used, todo = set(), list(members)
    while todo:
        pkg = todo.pop()
        if pkg not in used:
            used.add(pkg)
            todo += [d["pkg"] for d in deps[pkg]
                     if any(k["kind"] in (None, "dev", "build") for k in d["dep_kinds"])]

    needs = {}  # version -> ["crate vX", ...]
    for pkg in used - members:
        p = packages[pkg]
        if p.get("rust_version"):
            needs.setdefault(version(p["rust_version"]), []).append(f"{p['name']} v{p['version']}")
    need = max(needs)
    highest = ", ".join(sorted(needs[need]))

    declared = {"[workspace.package] in Cargo.toml":
                tomllib.loads((ROOT / "Cargo.toml").read_text())
                .get("workspace", {}).get("package", {}).get("rust-version")}
    declared |= {f"member {packages[m]['name']}": packages[m].get("rust_version") for m in members}

    wrong = {where: rv for where, rv in declared.items() if rv is None or version(rv) != need}
    if not wrong:
        rv = next(iter(declared.values()))
        print(f"rust-version {rv} matches the lock (highest need: {highest})")
        return

    print(f"msrv: the lock needs Rust {show(need)} ({highest}), but:")
    by_value = {}
    for where, rv in sorted(wrong.items()):
        by_value.setdefault(rv or "(none)", []).append(where)
    for rv, wheres in by_value.items():
        print(f"  rust-version {rv}: {', '.join(wheres)}")
    if any(rv and version(rv) < need for rv in wrong.values()):
        print("  crates needing more than the lowest declared version:")
        low = min(version(rv) for rv in wrong.values() if rv)
        for v in sorted(v for v in needs if v > low):
            print(f"    {show(v)}: {', '.join(sorted(needs[v]))}")
    print(f"Set rust-version = \"{show(need)}\" in the root Cargo.toml ([package] and"
          " [workspace.package]); members inherit it (rust-version.workspace = true).")
    sys.exit(1)


if __name__ == "__main__":
    main()
