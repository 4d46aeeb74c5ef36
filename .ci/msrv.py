"""The Rust version the lock file needs: the largest `rust-version` among
the locked registry dependencies (read from their unpacked sources in
Cargo's registry cache). With `--check`, fails unless the workspace's
`rust-version` in Cargo.toml is at least that. Run after a build, so the
sources are unpacked."""

import glob
import os
import re
import sys


def version(text):
    # "1.89" and "1.89.0" are the same version: pad to three parts.
    parts = [int(x) for x in text.split(".")]
    return tuple(parts + [0] * (3 - len(parts)))


def needed():
    lock = open("Cargo.lock").read()
    locked = set(
        re.findall(r'name = "([^"]+)"\nversion = "([^"]+)"\nsource = "registry', lock)
    )
    home = os.environ.get("CARGO_HOME", os.path.expanduser("~/.cargo"))
    found, best = set(), ((0,), "none")
    for toml in glob.glob(os.path.join(home, "registry/src/*/*/Cargo.toml")):
        base = os.path.basename(os.path.dirname(toml))
        m = re.match(r"(.+)-(\d+\.\d+\.\d+.*)$", base)
        if not m or (m.group(1), m.group(2)) not in locked:
            continue
        found.add((m.group(1), m.group(2)))
        r = re.search(r'^rust-version\s*=\s*"([^"]+)"', open(toml).read(), re.M)
        if r and version(r.group(1)) > best[0]:
            best = (version(r.group(1)), base)
    return best, len(locked - found)


def main():
    (v, crate), missing = needed()
    text = ".".join(map(str, v))
    print(f"locked dependencies need Rust {text} ({crate}); {missing} locked crates not unpacked")
    if "--check" in sys.argv:
        ws = re.search(r'^rust-version\s*=\s*"([^"]+)"', open("Cargo.toml").read(), re.M)
        if not ws or version(ws.group(1)) < v:
            sys.exit(f"Cargo.toml rust-version is below {text}: raise it")


main()
