#!/usr/bin/env python3
"""Fails on a dependency that a Cargo.toml declares and no code uses.

For every package of the workspace (the root one and the members; fuzz/
and peers/, workspaces of their own, too), each dependency of
[dependencies], [dev-dependencies], [build-dependencies] and their
[target.*] forms must be named, as its crate name (`hider-scene` ->
`hider_scene`, or the `package = ...` rename's key), in a Rust file of that
package (below its folder, less the packages nested in it). And every entry of
[workspace.dependencies] must be used by some package. A name counts when
it stands as a whole word outside a plain `//` comment (`hider_scene::`,
`use glam`, `serde::Deserialize` in a derive, a doc link), so a crate used only through a macro of another still has to
be named once: allow-list it below with the reason.

Usage: python3 .ci/unused_deps.py [ROOT]  (exit status 1 on a finding)
"""

import os
import re
import sys
import tomllib
from pathlib import Path

# (package, dependency) pairs used without their crate name in the
# package's Rust code, with the reason. Keep it short: an entry is a
# dependency this check cannot see.
ALLOWED = {
    # None today; an entry looks like
    # ("hider-python", "pyo3"),  # only through its feature, named nowhere
}

DEP_TABLES = ("dependencies", "dev-dependencies", "build-dependencies")


def declared(manifest):
    """The dependency keys of a manifest, with the table each is in."""
    tables = [(t, manifest.get(t, {})) for t in DEP_TABLES]
    for target, spec in manifest.get("target", {}).items():
        tables += [(f"target.{target}.{t}", spec.get(t, {})) for t in DEP_TABLES]
    for table, deps in tables:
        for key in deps:
            yield table, key


def rust_sources(package_dir):
    """The Rust files of a package: every one below its folder but those of
    packages nested in it (their own Cargo.toml) and of target/."""
    files = []
    for folder, subfolders, names in os.walk(package_dir):
        here = Path(folder)
        subfolders[:] = [
            s
            for s in subfolders
            if s not in ("target", ".git") and not (here / s / "Cargo.toml").is_file()
        ]
        files += [here / n for n in sorted(names) if n.endswith(".rs")]
    return files


def code(path):
    """A Rust file less its plain `//` comments (doc comments stay: their
    links to a crate need it)."""
    text = path.read_text(errors="replace")
    return re.sub(r"//(?![/!]).*", "", text)


def main():
    root = Path(sys.argv[1] if len(sys.argv) > 1 else ".").resolve()
    top = tomllib.loads((root / "Cargo.toml").read_text())
    workspace = top.get("workspace", {})
    packages = [root] if "package" in top else []
    packages += [root / m for m in workspace.get("members", [])]
    # The workspaces of their own beside the main one.
    for extra in ("fuzz", "peers"):
        if (root / extra / "Cargo.toml").is_file():
            packages.append(root / extra)
    problems = []
    used_anywhere = set()
    for package_dir in packages:
        manifest = tomllib.loads((package_dir / "Cargo.toml").read_text())
        name = manifest["package"]["name"]
        text = "\n".join(code(p) for p in rust_sources(package_dir))
        for table, key in declared(manifest):
            used_anywhere.add(key)
            crate = key.replace("-", "_")
            if (name, key) in ALLOWED:
                continue
            if not re.search(rf"\b{re.escape(crate)}\b", text):
                rel = (package_dir / "Cargo.toml").relative_to(root)
                problems.append(f"{rel}: [{table}] {key}: `{crate}` is named in no Rust file")
    for key in workspace.get("dependencies", {}):
        if key not in used_anywhere:
            problems.append(f"Cargo.toml: [workspace.dependencies] {key}: no package uses it")
    for p in problems:
        print(p)
    print(f"unused dependencies: {len(problems)} found in {len(packages)} packages")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
