"""Runs one benchmark command and writes its output into a Markdown file under docs/, headed by
the command, the commit and the date that produced it, so that no figure in docs/ lacks its
source. Used by `cmake --build build --target bench-report` (bench/CMakeLists.txt); the file is
replaced only when the command succeeds.

usage: bench_report.py --out FILE --title TITLE --source-dir DIR [--note TEXT] [--code]
                       -- COMMAND [ARG...]

--note is a paragraph printed above the output (what the figures are, subsets, caveats);
--code puts the output in a code block (for fixed-width text rather than Markdown tables).
The command's stderr passes through; its stdout becomes the file's body.
"""
import argparse
import datetime
import os
import shlex
import subprocess
import sys
import tempfile
import time


def git(source_dir, *args):
    try:
        return subprocess.run(['git', '-C', source_dir] + list(args), capture_output=True,
                              text=True, check=True).stdout
    except (OSError, subprocess.CalledProcessError):
        return ''


def cpu_model():
    try:
        with open('/proc/cpuinfo') as f:
            for line in f:
                if line.startswith('model name'):
                    return line.split(':', 1)[1].strip()
    except OSError:
        pass
    return 'unknown CPU'


def load_average():
    try:
        return os.getloadavg()[0]
    except OSError:
        return float('nan')


def shown(path, source_dir):
    """A path as the reader would type it: relative to the source tree when inside it."""
    if os.path.isabs(path):
        rel = os.path.relpath(path, source_dir)
        if not rel.startswith('..'):
            return rel
    return path


def main():
    if '--' not in sys.argv:
        sys.exit('bench_report.py: no command (expected -- COMMAND ...)')
    split = sys.argv.index('--')
    parser = argparse.ArgumentParser()
    parser.add_argument('--out', required=True)
    parser.add_argument('--title', required=True)
    parser.add_argument('--source-dir', required=True)
    parser.add_argument('--note', default='')
    parser.add_argument('--code', action='store_true')
    args = parser.parse_args(sys.argv[1:split])
    command = sys.argv[split + 1:]
    if not command:
        sys.exit('bench_report.py: empty command')
    source_dir = os.path.abspath(args.source_dir)

    commit = git(source_dir, 'rev-parse', '--short', 'HEAD').strip() or 'unknown'
    # Uncommitted changes to what the figures depend on, named so that a reader knows the
    # figures are not exactly those of the commit.
    dirty = git(source_dir, 'status', '--porcelain', '--untracked-files=no', '--', 'src',
                'include', 'samples', 'bench', 'CMakeLists.txt')
    changed = sorted({line[3:] for line in dirty.splitlines() if len(line) > 3})
    started = datetime.datetime.now(datetime.timezone.utc)
    load_before = load_average()
    print('bench-report: ' + ' '.join(shlex.quote(shown(c, source_dir)) for c in command),
          file=sys.stderr, flush=True)
    t0 = time.monotonic()
    run = subprocess.run(command, stdout=subprocess.PIPE, text=True)
    seconds = time.monotonic() - t0
    load_after = load_average()
    if run.returncode != 0:
        sys.stdout.write(run.stdout)
        sys.exit('bench_report.py: the command exited with %d; %s left as it was'
                 % (run.returncode, args.out))

    lines = ['# ' + args.title, '',
             '<!-- Written by `cmake --build build --target bench-report` (bench/bench_report.py).'
             ' Do not edit: run the target again. -->', '',
             '- command: `%s`' % ' '.join(shlex.quote(shown(c, source_dir)) for c in command),
             '- commit: `%s`%s' % (commit, (' with uncommitted changes to ' +
                                           ', '.join('`%s`' % c for c in changed)) if changed
                                   else ''),
             '- date: %s' % started.strftime('%Y-%m-%d %H:%M UTC'),
             '- machine: %s, %d cores; load average %.2f at the start, %.2f at the end; %.0f s'
             % (cpu_model(), os.cpu_count() or 0, load_before, load_after, seconds), '']
    if max(load_before, load_after) > (os.cpu_count() or 1):
        lines += ['Other work shared the machine (a load average above its core count): times are '
                  'slower than on an idle machine, and runs on several threads the most. Figures '
                  'that are not times do not depend on it.', '']
    if args.note:
        lines += [args.note, '']
    body = run.stdout.rstrip('\n')
    lines += ['```', body, '```'] if args.code else [body]
    out = os.path.abspath(args.out)
    os.makedirs(os.path.dirname(out), exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=os.path.dirname(out), prefix='.bench-report-')
    with os.fdopen(fd, 'w') as f:
        f.write('\n'.join(lines) + '\n')
    os.chmod(tmp, 0o644)
    os.replace(tmp, out)
    print('bench-report: wrote ' + shown(out, source_dir), file=sys.stderr)


if __name__ == '__main__':
    main()
