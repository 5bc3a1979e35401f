#!/usr/bin/env python3
"""Builds the workspace's Rust tests and runs their binaries as many at a time as
there are cores, then the doctests.

`cargo test` runs one test binary after another, and most binaries end on one or two
long tests that leave the other core idle: on a clean clone the Rust tests took
167 s of wall for 296 s of CPU (docs/performance.md, test suite time). This runs the
same binaries, each in its package's folder with CARGO_MANIFEST_DIR set as cargo
sets it (the only variable of cargo's the tests read at run time), prints each binary's
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

CARGO_ARGS = ["--release", "--workspace", "--exclude", "thirdbody-py", "--exclude", "thirdbody-bench"]


def test_binaries():
    """(package folder, source file, executable) of every test harness."""
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
            source = os.path.relpath(message["target"]["src_path"], folder)
            binaries.append((folder, source, message["executable"]))
    return binaries


def run(binary, extra):
    folder, source, executable = binary
    env = dict(os.environ, CARGO_MANIFEST_DIR=folder)
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
                failed.append(jobs[job][1])
    doc = subprocess.run(["cargo", "test", *CARGO_ARGS, "--doc", "--", *extra])
    if doc.returncode != 0:
        failed.append("doctests")
    if failed:
        print(f"error: {len(failed)} test binaries failed: {', '.join(failed)}", file=sys.stderr)
        sys.exit(1)
    print(f"{len(binaries)} test binaries and the doctests passed")


if __name__ == "__main__":
    main()
