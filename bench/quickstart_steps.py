#!/usr/bin/python3
"""Where `./quickstart test` spends its time: runs it (or any command given), prefixes each line
of its output with the seconds since the start, and ends with one row per step: what ran before
each tree's `ctest` (its build), each `ctest` run, the fuzzing and the rest. docs/ci-time.md has
the figures.

usage: quickstart_steps.py [COMMAND...]   (default: ./quickstart test, in the current folder)
"""

import re
import subprocess
import sys
import time


def main():
    command = sys.argv[1:] or ['./quickstart', 'test']
    start = time.monotonic()
    steps, mark, name = [], 0.0, ''  # (step, seconds); the end of the previous step; the tree
    proc = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
    for raw in iter(proc.stdout.readline, b''):
        now = time.monotonic() - start
        line = raw.decode(errors='replace')
        sys.stdout.write('%7.1f %s' % (now, line))
        sys.stdout.flush()
        tree = re.match(r'Test project (\S+)', line)
        if tree:
            name = tree.group(1).rstrip('/').rsplit('/', 1)[-1]
            steps.append(('build, until ' + name + "'s ctest", now - mark))
            mark = now
        elif re.match(r'Total Test time', line):
            steps.append(('ctest in ' + name, now - mark))
            mark = now
        elif line.startswith('quickstart: fuzzed') and not any(s == 'fuzzing' for s, _ in steps):
            steps.append(('fuzzing', now - mark))
            mark = now
    proc.wait()
    end = time.monotonic() - start
    steps.append(('the rest', end - mark))
    print('\n| step | seconds |\n|---|---:|')
    for step, seconds in steps:
        print('| %s | %.0f |' % (step, seconds))
    print('| total (exit status %d) | %.0f |' % (proc.returncode, end))
    sys.exit(proc.returncode)


if __name__ == '__main__':
    main()
