#!/usr/bin/env python3
"""Lists the crates whose features differ between the tests' build and the Python
package's build, and exits non-zero if there is any.

Cargo compiles a crate again for each distinct set of its features (and every crate
above it), so a difference here makes `./test.sh` compile much of the workspace
twice. `crates/thirdbody-feature-pins` switches such features on in both builds;
after adding or upgrading a dependency, run this and pin what it lists there.
"""

import subprocess
import sys

TESTS = ["--workspace", "--exclude", "thirdbody-py", "--exclude", "thirdbody-bench", "-e", "normal,build,dev"]
PYTHON = ["-p", "thirdbody-py", "-e", "normal,build"]


def features(selection):
    """{"name vX.Y.Z": {features}} of every crate in one build's resolution."""
    tree = subprocess.run(
        ["cargo", "tree", *selection, "-f", "{p}|{f}", "--prefix", "none"],
        stdout=subprocess.PIPE,
        text=True,
        check=True,
    )
    crates = {}
    for line in tree.stdout.splitlines():
        if "|" not in line:
            continue
        # " (*)" marks a crate already listed above.
        package, enabled = line.removesuffix(" (*)").split("|", 1)
        name = package.split(" (")[0]
        crates.setdefault(name, set()).update(f for f in enabled.split(",") if f)
    return crates


def main():
    tests, python = features(TESTS), features(PYTHON)
    differ = [c for c in sorted(tests.keys() & python.keys()) if tests[c] != python[c]]
    for crate in differ:
        only_tests = sorted(tests[crate] - python[crate])
        only_python = sorted(python[crate] - tests[crate])
        print(f"{crate}: tests only {only_tests}, Python package only {only_python}")
    if differ:
        sys.exit(1)
    print(f"the two builds agree on the features of the {len(tests.keys() & python.keys())} crates they share")


if __name__ == "__main__":
    main()
