"""What the raps-gltf test scripts share: running the tool, running the Khronos validator (through
validate_gltf.js) and a curved grid to build assets from."""
import json
import os
import subprocess

import numpy as np

RUNNER = os.path.join(os.path.dirname(os.path.abspath(__file__)), 'validate_gltf.js')


def run_tool(raps_gltf, *args, timeout=600):
    """raps-gltf with progress off: (exit status, stdout, stderr)."""
    p = subprocess.run([raps_gltf, '--no-progress', *args], capture_output=True, text=True,
                       timeout=timeout)
    return p.returncode, p.stdout, p.stderr


def validator_report(node, validator, path, timeout=600):
    """The validator's summary of one asset (validate_gltf.js's JSON object)."""
    p = subprocess.run([node, RUNNER, validator, path], capture_output=True, text=True,
                       timeout=timeout)
    if p.returncode != 0:
        raise AssertionError('validator did not run: ' + p.stderr)
    return json.loads(p.stdout)


def grid(n, m):
    """An n x m grid over the unit square, curved in z: positions (float64) and a triangle list."""
    xs, ys = np.meshgrid(np.linspace(0, 1, n + 1), np.linspace(0, 1, m + 1))
    pos = np.column_stack([xs.ravel(), ys.ravel(), 0.2 * np.sin(3 * xs.ravel()) * ys.ravel()])
    tris = []
    for j in range(m):
        for i in range(n):
            a = j * (n + 1) + i
            tris += [a, a + 1, a + n + 2, a, a + n + 2, a + n + 1]
    return pos, tris
