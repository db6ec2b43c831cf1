"""raps-gltf on every asset of the Khronos glTF-Validator's own test suite (shared/data/
gltf-validator-suite): data the project was not tuned to, most of it invalid on purpose, one
defect per file.

Each asset is validated, baked with --overwrite into the format it came in, and the output (if
any) validated again by the same validator. An asset's outcome is one of:
  baked    exit 0, and the output has no validator error code its input did not have
  nothing  exit 3 (no triangle primitive), and no file written
  refused  exit 1, a message naming the problem, no file written, and the input either has
           validator errors or uses compressed geometry raps-gltf does not decode (Draco,
           meshopt): the message must name it
Anything else fails the test: a new error code in an output, a valid asset refused, a crash, a
timeout, another exit status, a file written beside a refusal.

A code the output has more often than the input (the input's own invalid values copied onto
vertices split at seams) is not a new error: it is counted in the table's "copied" column.

usage: test_validator_suite.py RAPS_GLTF SUITE_DIR VALIDATOR_PREFIX NODE WORK_DIR [--record FILE]
  --record FILE  also write the per-folder table and every asset's outcome as Markdown
"""
import collections
import concurrent.futures
import json
import os
import shutil
import subprocess
import sys
import time

RUNNER = os.path.join(os.path.dirname(os.path.abspath(__file__)), 'validate_gltf.js')
UNDECODED = ('KHR_draco_mesh_compression', 'EXT_meshopt_compression', 'KHR_meshopt_compression')
TIMEOUT_S = 120


def suite_assets(suite):
    found = []
    for folder, _, files in os.walk(suite):
        for name in files:
            if name.endswith(('.gltf', '.glb')):
                found.append(os.path.relpath(os.path.join(folder, name), suite))
    return sorted(found)


def validate_all(validator, node, paths):
    """One Node process for many assets; returns {path: report}."""
    reports = {}
    for start in range(0, len(paths), 64):
        chunk = paths[start:start + 64]
        p = subprocess.run([node, RUNNER, validator, *chunk], capture_output=True, text=True,
                           timeout=600)
        if p.returncode != 0:
            raise SystemExit('validator did not run: ' + p.stderr)
        for line in p.stdout.splitlines():
            report = json.loads(line)
            reports[report['asset']] = report
    return reports


def error_codes(report):
    return collections.Counter(m['code'] for m in report['messages'] if m['severity'] == 0)


def bake(raps_gltf, source, output):
    os.makedirs(os.path.dirname(output), exist_ok=True)
    try:
        p = subprocess.run([raps_gltf, '--no-progress', '--overwrite', source, output],
                           capture_output=True, text=True, timeout=TIMEOUT_S)
    except subprocess.TimeoutExpired:
        return None, 'timed out after %d s' % TIMEOUT_S
    return p.returncode, p.stderr.strip()


def written_files(output):
    folder, name = os.path.split(output)
    stem = os.path.splitext(name)[0]
    if not os.path.isdir(folder):
        return []
    return [f for f in os.listdir(folder) if f == name or f.startswith(stem + '.')]


def classify(rel, input_report, status, message, output_report, leftovers):
    """(outcome, detail, failure or None)"""
    input_errors = error_codes(input_report)
    if status == 0:
        if output_report is None:
            return 'baked', '', 'exit 0 but no output file'
        output_errors = error_codes(output_report)
        new = sorted(set(output_errors) - set(input_errors))
        if new:
            return 'baked', ', '.join(new), 'new validator errors in the output: ' + ', '.join(new)
        copied = sorted(c for c in output_errors if output_errors[c] > input_errors[c])
        return ('copied' if copied else 'baked'), ', '.join(copied), None
    if status in (1, 3):
        outcome = 'refused' if status == 1 else 'nothing'
        if leftovers:
            return outcome, message, 'exit %d but wrote %s' % (status, ', '.join(leftovers))
        if not message:
            return outcome, '', 'exit %d without a message' % status
        if status == 1 and not input_errors:
            if any(name in message for name in UNDECODED):
                return 'undecoded', message, None
            return outcome, message, 'a valid asset (validator: 0 errors) refused: ' + message
        return outcome, message, None
    if status is None:
        return 'crash', message, message
    return 'crash', message, 'exit status %d: %s' % (status, message[-300:])


def provenance():
    """The commit and date of this run (the commit is 'unknown' outside a git checkout)."""
    try:
        commit = subprocess.run(['git', 'rev-parse', '--short', 'HEAD'], capture_output=True,
                                text=True, cwd=os.path.dirname(os.path.abspath(__file__)),
                                timeout=60).stdout.strip() or 'unknown'
    except OSError:
        commit = 'unknown'
    return commit, time.strftime('%Y-%m-%d', time.gmtime())


def record(path, rows, table):
    """Markdown: the per-folder table, then every asset's outcome."""
    commit, date = provenance()
    lines = ['# raps-gltf on the Khronos glTF-Validator suite', '',
             'Written by `ctest -R validator_suite` in a build tree (the file lands in',
             '`build/tests/validator_suite.md`), commit %s, %s. Outcomes as' % (commit, date),
             '`tests/cli/test_validator_suite.py` defines them; "valid": the validator finds no',
             'error in the input; "copied": an error code the input already had, more often in the',
             'output (the input\'s invalid values copied onto vertices split at seams).',
             '', *table, '', '| asset | validator errors in the input | outcome | detail |',
             '|---|---|---|---|']
    for rel, input_errors, outcome, detail, _ in rows:
        detail = detail.split(rel + ': ', 1)[-1]
        codes = ', '.join(sorted(input_errors)) or '0'
        lines.append('| %s | %s | %s | %s |' % (rel, codes, outcome,
                                                 detail.replace('|', '\\|').replace('\n', ' ')[:160]))
    with open(path, 'w') as fh:
        fh.write('\n'.join(lines) + '\n')


def main(argv):
    if len(argv) not in (6, 8) or (len(argv) == 8 and argv[6] != '--record'):
        raise SystemExit(__doc__)
    raps_gltf, suite, validator, node, work = argv[1:6]
    suite = os.path.abspath(suite)
    if os.path.isdir(work):
        shutil.rmtree(work)
    assets = suite_assets(suite)
    if len(assets) < 200:
        raise SystemExit('%s holds %d assets, expected the whole suite' % (suite, len(assets)))
    inputs = validate_all(validator, node, [os.path.join(suite, a) for a in assets])
    outputs = {a: os.path.join(work, a) for a in assets}
    with concurrent.futures.ThreadPoolExecutor(max_workers=os.cpu_count() or 2) as pool:
        runs = dict(zip(assets, pool.map(lambda a: bake(raps_gltf, os.path.join(suite, a),
                                                        outputs[a]), assets)))
    baked = [outputs[a] for a in assets if runs[a][0] == 0 and os.path.isfile(outputs[a])]
    output_reports = validate_all(validator, node, baked)

    rows, failures = [], []
    per_folder = collections.defaultdict(collections.Counter)
    for a in assets:
        status, message = runs[a]
        leftovers = written_files(outputs[a]) if status != 0 else []
        outcome, detail, failure = classify(a, inputs[os.path.join(suite, a)], status, message,
                                            output_reports.get(outputs[a]), leftovers)
        rows.append((a, error_codes(inputs[os.path.join(suite, a)]), outcome, detail, failure))
        folder = a.split(os.sep)[0] if os.sep in a else '.'
        per_folder[folder]['assets'] += 1
        per_folder[folder]['valid'] += not error_codes(inputs[os.path.join(suite, a)])
        per_folder[folder][outcome] += 1
        per_folder[folder]['failed'] += failure is not None
        if failure:
            failures.append('%s: %s' % (a, failure))

    columns = ['assets', 'valid', 'baked', 'copied', 'nothing', 'refused', 'undecoded', 'failed']
    table = ['| folder | ' + ' | '.join(columns) + ' |', '|---' * (len(columns) + 1) + '|']
    total = collections.Counter()
    for folder in sorted(per_folder):
        total.update(per_folder[folder])
        table.append('| %s | ' % folder + ' | '.join(str(per_folder[folder][c]) for c in columns) +
                     ' |')
    table.append('| all | ' + ' | '.join(str(total[c]) for c in columns) + ' |')
    print('\n'.join(table))
    if len(argv) == 8:
        record(argv[7], rows, table)
    for f in failures:
        print('FAIL ' + f)
    print('%d passed, %d failed' % (len(assets) - len(failures), len(failures)))
    return 1 if failures else 0


if __name__ == '__main__':
    sys.exit(main(sys.argv))
