#!/usr/bin/env python3
"""Builds the workspace's Rust tests and runs their binaries as many at a time as
there are cores, then the doctests.

`cargo test` runs one test binary after another, and most binaries end on one or two
long tests that leave the other core idle: the Rust tests kept 1.2 of 2 cores busy
on average (docs/performance.md, test suite time). This runs the same binaries, each
in its package's folder with the variables cargo gives it, prints each binary's
output whole when it ends, and exits non-zero if any failed. It does for one
machine what cargo-nextest does, without a tool to install; arguments after `--`
go to every binary (e.g. `-- --include-ignored`).
"""

import concurrent.futures
import json
import os
import subprocess
import sys
import time

CARGO_ARGS = ["--release", "--workspace", "--exclude", "thirdbody-py"]


def test_binaries():
    """(package folder, package name, source, executable) of every test harness."""
    build = subprocess.run(
        ["cargo", "test", *CARGO_ARGS, "--no-run", "--message-format=json-render-diagnostics"],
        stdout=subprocess.PIPE,
        text=True,
    )
    if build.returncode != 0:
        sys.exit(build.returncode)
    binaries = []
    for line in build.stdout.splitlines():
        message = json.loads(line)
        if (
            message.get("reason") == "compiler-artifact"
            and message["profile"]["test"]
            and message.get("executable")
        ):
            folder = os.path.dirname(message["manifest_path"])
            package = message["package_id"]
            name = message["target"]["name"]
            source = os.path.relpath(message["target"]["src_path"], folder)
            binaries.append((folder, name, source, message["executable"], package))
    return binaries


def run(binary, extra):
    folder, name, source, executable, package = binary
    env = dict(os.environ, CARGO_MANIFEST_DIR=folder, CARGO_PKG_NAME=os.path.basename(folder))
    start = time.monotonic()
    done = subprocess.run(
        [executable, *extra],
        cwd=folder,
        env=env,
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
        text=True,
    )
    elapsed = time.monotonic() - start
    header = f"     Running {source} ({os.path.relpath(executable)}) [{elapsed:.1f} s]"
    return done.returncode, header + "\n" + done.stdout


def main():
    extra = sys.argv[sys.argv.index("--") + 1 :] if "--" in sys.argv else []
    binaries = test_binaries()
    failed = []
    with concurrent.futures.ThreadPoolExecutor(max_workers=os.cpu_count() or 2) as pool:
        jobs = {pool.submit(run, b, extra): b for b in binaries}
        for job in concurrent.futures.as_completed(jobs):
            code, output = job.result()
            print(output, flush=True)
            if code != 0:
                failed.append(jobs[job][2])
    doc = subprocess.run(["cargo", "test", *CARGO_ARGS, "--doc", "--", *extra])
    if doc.returncode != 0:
        failed.append("doctests")
    if failed:
        print(f"error: {len(failed)} test binaries failed: {', '.join(failed)}", file=sys.stderr)
        sys.exit(1)
    print(f"{len(binaries)} test binaries and the doctests passed")


if __name__ == "__main__":
    main()
