#!/usr/bin/python3
"""Checks that each binding README shows its example file verbatim (CTest:
bindings_readme_examples). The examples themselves run as python_example, csharp_example and
rust_example, so what a reader copies from a README is what CI ran.

A README marks its example with an HTML comment naming the file, right above the code block:

    <!-- example: example.py -->
    ```python
    ...the file's contents...
    ```
"""

import os
import re
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
READMES = ["csharp/README.md", "rust/README.md", "python/README.md"]
BLOCK = re.compile(r"<!-- example: (\S+) -->\n```\w*\n(.*?)```\n", re.DOTALL)


def main():
    failures = []
    for readme in READMES:
        path = os.path.join(HERE, readme)
        with open(path, encoding="utf-8") as stream:
            text = stream.read()
        blocks = BLOCK.findall(text)
        if not blocks:
            failures.append("%s: no '<!-- example: FILE -->' code block" % readme)
        for relative, shown in blocks:
            example = os.path.join(os.path.dirname(path), relative)
            with open(example, encoding="utf-8") as stream:
                actual = stream.read()
            if shown != actual:
                failures.append("%s: the block differs from %s; paste the file in again"
                                % (readme, relative))
            else:
                print("%s shows %s verbatim" % (readme, relative))
    for failure in failures:
        print("check_readme_examples: " + failure, file=sys.stderr)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
