#!/usr/bin/env python3
"""The pack phase of two raps-param builds, side by side, on every shared mesh.

For each mesh the two builds run in turn, RUNS times each (so both see the same load), with
`raps-param --atlas MESH` and the flags given after `--`; it prints the median of each build's
`time_ms.pack`, their ratio, and whether the two written OBJ files are the same bytes (a speed
change that keeps every layout says "same" on every row).

    python3 bench/pack_time.py --reference OLD/samples/raps-param \\
        --candidate build/samples/raps-param --data ../shared/data --runs 5 -- --threads 1
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile


def pack_ms(binary, mesh, flags, out):
    run = subprocess.run([binary, "--atlas", mesh, "-o", out] + flags,
                         capture_output=True, text=True, check=False)
    if run.returncode != 0:
        sys.exit(f"{binary} failed on {mesh}: {run.stderr.strip()}")
    return json.loads(run.stdout)["time_ms"]["pack"]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--reference", required=True)
    parser.add_argument("--candidate", required=True)
    parser.add_argument("--data", required=True, help="the shared data folder")
    parser.add_argument("--runs", type=int, default=5)
    parser.add_argument("flags", nargs="*", help="raps-param flags, after --")
    args = parser.parse_args()
    meshes_dir = os.path.join(args.data, "meshes")
    print(f"| mesh | reference ms | candidate ms | ratio | outputs |")
    print(f"|---|---:|---:|---:|---|")
    ratios = []
    with tempfile.TemporaryDirectory() as work:
        ref_out, new_out = os.path.join(work, "ref.obj"), os.path.join(work, "new.obj")
        for name in sorted(os.listdir(meshes_dir)):
            mesh = os.path.join(meshes_dir, name)
            ref, new = [], []
            for _ in range(args.runs):
                ref.append(pack_ms(args.reference, mesh, args.flags, ref_out))
                new.append(pack_ms(args.candidate, mesh, args.flags, new_out))
            with open(ref_out, "rb") as a, open(new_out, "rb") as b:
                same = a.read() == b.read()
            r, n = statistics.median(ref), statistics.median(new)
            ratios.append(n / r)
            print(f"| {name} | {r:.1f} | {n:.1f} | {n / r:.2f} | {'same' if same else 'differ'} |")
    print(f"| median ratio | | | {statistics.median(ratios):.2f} | |")


if __name__ == "__main__":
    main()
