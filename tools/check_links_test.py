#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Test of tools/check_links.py on small hand-made trees (never on the repository's own pages,
so it does not depend on which pages exist): a good tree passes, and each kind of breakage
fails, named. Prints one line per case; exit status 0 when every case behaves, 1 otherwise."""
import os
import subprocess
import sys
import tempfile

CHECKER = os.path.join(os.path.dirname(os.path.abspath(__file__)), "check_links.py")

SOURCE = "int a;\n/* readme:begin */\nint f(void)\n{\n    return 1;\n}\n/* readme:end */\n"
INDEX = """# The index

[Other page](docs/other.md), [its section](docs/other.md#a-section-with-code-and-punctuation),
[this page's](#the-index), ![a picture](docs/pic.png), [a folder](docs),
[outside](https://example.com/not/fetched), `[in code](missing.md)`.

    [indented code](missing.md)

<!-- snippet: src/f.c -->
```c
int f(void)
{
    return 1;
}
```
"""
OTHER = """# Other

## A section with `code`, and punctuation!

[Back](../README.md#the-index), [repeat](#twice-1).

## Twice

## Twice
"""
GOOD = {"README.md": INDEX, "docs/other.md": OTHER, "docs/pic.png": "png", "src/f.c": SOURCE}

# name: (file to change, text to replace, its replacement, what the failure must name)
BROKEN = {
    "broken_file_link": ("README.md", "(docs/other.md)", "(docs/absent.md)", "no tracked file docs/absent.md"),
    "broken_image": ("README.md", "(docs/pic.png)", "(docs/pic.jpg)", "no tracked file docs/pic.jpg"),
    "broken_anchor_other_page": ("README.md", "#a-section-with-code-and-punctuation", "#a-section",
                                 "docs/other.md has no heading #a-section"),
    "broken_anchor_same_page": ("README.md", "(#the-index)", "(#no-such-heading)",
                                "README.md has no heading #no-such-heading"),
    "broken_repeat_anchor": ("docs/other.md", "(#twice-1)", "(#twice-2)", "has no heading #twice-2"),
    "link_leaves_root": ("docs/other.md", "(../README.md#the-index)", "(../../README.md)", "leaves the repository"),
    "snippet_drifted": ("README.md", "    return 1;\n}\n```", "    return 2;\n}\n```",
                        "snippet differs from src/f.c"),
    "snippet_source_unmarked": ("src/f.c", "/* readme:end */", "/* end */", "no single readme:begin"),
}


def make_tree(root, files):
    for rel, text in files.items():
        path = os.path.join(root, rel)
        os.makedirs(os.path.dirname(path), exist_ok=True)
        with open(path, "w", encoding="utf-8") as f:
            f.write(text)


def run(root):
    p = subprocess.run([sys.executable, CHECKER, "--root", root], capture_output=True, text=True)
    return p.returncode, p.stdout


def main():
    failures = 0
    with tempfile.TemporaryDirectory() as tmp:
        good = os.path.join(tmp, "good")
        make_tree(good, GOOD)
        rc, out = run(good)
        ok = rc == 0 and out == ""
        print("check_links_test:good_tree_passes:%s%s" % ("PASS" if ok else "FAIL", "" if ok else " " + out))
        failures += not ok
        for name, (rel, old, new, expect) in BROKEN.items():
            files = dict(GOOD)
            assert files[rel].count(old) == 1, name
            files[rel] = files[rel].replace(old, new)
            root = os.path.join(tmp, name)
            make_tree(root, files)
            rc, out = run(root)
            ok = rc == 1 and expect in out and len(out.strip().split("\n")) == 1
            print("check_links_test:%s:%s%s" % (name, "PASS" if ok else "FAIL",
                                                 "" if ok else " (exit %d) %s" % (rc, out.strip())))
            failures += not ok
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
