#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Checks the Markdown of the repository: links, images, anchors and code snippets.

Usage: check_links.py [--root DIR] [FILE.md ...]

Without files: README.md and every docs/**/*.md of the root (default: the repository).
- every relative link and image ([text](path), ![alt](path), [id]: path, <img src>, <a href>)
  must name a tracked file or directory (git ls-files; every file on disk when the root is no
  git work tree), inside the root;
- every #anchor, on the same page or another .md page, must be a heading of that page under
  GitHub's slug rules (lower case, punctuation dropped, spaces to hyphens, -1, -2 for repeats)
  or an id/name attribute there;
- a fenced code block right after <!-- snippet: PATH --> must equal the lines of PATH between
  the lines holding "readme:begin" and "readme:end", so that the page cannot drift from code
  the build compiles.
External links (http, https, mailto) are not fetched. Exit status 0 when all hold, 1 naming
every failure as FILE:LINE: what, 2 bad usage.
"""
import os
import re
import subprocess
import sys

LINK = re.compile(r"!?\[(?:[^\[\]]|\[[^\]]*\])*\]\(\s*(<[^>]*>|[^)\s]+)(?:\s+(?:\"[^\"]*\"|'[^']*'))?\s*\)")
REF_DEF = re.compile(r"^ {0,3}\[[^\]]+\]:\s*(\S+)")
HTML_LINK = re.compile(r"<(?:img|a)\b[^>]*?\b(?:src|href)\s*=\s*\"([^\"]*)\"", re.I)
HTML_ID = re.compile(r"<[a-z][^>]*?\b(?:id|name)\s*=\s*\"([^\"]*)\"", re.I)
FENCE = re.compile(r"^ {0,3}(`{3,}|~{3,})")
ATX = re.compile(r"^ {0,3}(#{1,6})\s+(.*?)(?:\s+#+)?\s*$")
SNIPPET = re.compile(r"^<!--\s*snippet:\s*(\S+)\s*-->\s*$")
EXTERNAL = re.compile(r"^[a-z][a-z0-9+.-]*:", re.I)


def tracked_files(root):
    """Paths relative to root, with '/' separators: git's index, or every file on disk."""
    try:
        out = subprocess.run(["git", "-C", root, "ls-files", "-z"], capture_output=True, check=True)
        top = subprocess.run(["git", "-C", root, "rev-parse", "--show-prefix"], capture_output=True,
                             check=True, text=True).stdout.strip()
        if top == "":
            return set(p for p in out.stdout.decode().split("\0") if p)
    except (OSError, subprocess.CalledProcessError):
        pass
    found = set()
    for d, dirs, files in os.walk(root):
        dirs[:] = [x for x in dirs if x != ".git"]
        for f in files:
            found.add(os.path.relpath(os.path.join(d, f), root).replace(os.sep, "/"))
    return found


def scan(text):
    """(lines outside code, [(line number, fence info, code lines, the line before the fence)]).
    Lines inside fenced or indented code are blanked, so that nothing in code counts as a link."""
    lines = text.split("\n")
    prose, blocks = [], []
    i, prev_blank = 0, True
    while i < len(lines):
        line = lines[i]
        m = FENCE.match(line)
        if m:
            mark, start, body = m.group(1), i, []
            before = next((lines[k] for k in range(i - 1, -1, -1) if lines[k].strip()), "")
            i += 1
            while i < len(lines) and not (lines[i].strip().startswith(mark[0] * len(mark)) and
                                          lines[i].strip().strip(mark[0]) == ""):
                body.append(lines[i])
                i += 1
            blocks.append((start + 1, body, before))
            prose.extend([""] * (i - start + 1))
            i += 1
            prev_blank = True
            continue
        if prev_blank and line.startswith("    ") and line.strip():
            prose.append("")  # indented code: only after a blank line, as in CommonMark
            i += 1
            continue
        prose.append(line)
        prev_blank = not line.strip()
        i += 1
    return prose[:len(lines)], blocks


def strip_code_spans(line):
    return re.sub(r"(`+)(.+?)\1", lambda m: " " * len(m.group(0)), line)


def heading_text(raw):
    """The text GitHub renders of a heading's Markdown: links to their text, no code marks or emphasis."""
    t = re.sub(r"!?\[([^\]]*)\]\([^)]*\)", r"\1", raw)
    t = re.sub(r"<[^>]+>", "", t)
    return t.replace("`", "").replace("*", "")


def slug(text):
    s = re.sub(r"[^\w\- ]", "", text.strip().lower())
    return s.replace(" ", "-")


def anchors(text):
    """Every anchor a page has: its headings' slugs (repeats numbered) and id/name attributes."""
    prose, _ = scan(text)
    seen, found = {}, set()
    for k, line in enumerate(prose):
        m = ATX.match(line)
        raw = m.group(2) if m else None
        if raw is None and k + 1 < len(prose) and line.strip() and not line.lstrip().startswith(("|", "-", "*", ">")):
            if re.match(r"^ {0,3}(=+|-+)\s*$", prose[k + 1]) and (k == 0 or not prose[k - 1].strip() or ATX.match(prose[k - 1])):
                raw = line.strip()
        if raw is not None:
            base = slug(heading_text(raw))
            n = seen.get(base, 0)
            found.add(base if n == 0 else "%s-%d" % (base, n))
            seen[base] = n + 1
        for a in HTML_ID.findall(line):
            found.add(a)
    return found


def snippet_lines(path):
    with open(path, encoding="utf-8") as f:
        lines = f.read().split("\n")
    begin = [k for k, s in enumerate(lines) if "readme:begin" in s]
    end = [k for k, s in enumerate(lines) if "readme:end" in s]
    if len(begin) != 1 or len(end) != 1 or end[0] < begin[0]:
        return None
    return lines[begin[0] + 1:end[0]]


class Checker:
    def __init__(self, root):
        self.root = os.path.abspath(root)
        self.tracked = tracked_files(self.root)
        self.dirs = set()
        for p in self.tracked:
            parts = p.split("/")
            for k in range(1, len(parts)):
                self.dirs.add("/".join(parts[:k]))
        self.anchor_cache = {}
        self.errors = []

    def error(self, page, line, what):
        self.errors.append("%s:%d: %s" % (page, line, what))

    def page_anchors(self, rel):
        if rel not in self.anchor_cache:
            with open(os.path.join(self.root, rel), encoding="utf-8") as f:
                self.anchor_cache[rel] = anchors(f.read())
        return self.anchor_cache[rel]

    def check_target(self, page, line, target):
        if target.startswith("<") and target.endswith(">"):
            target = target[1:-1]
        if not target or EXTERNAL.match(target) or target.startswith("//"):
            return
        path, _, anchor = target.partition("#")
        path = re.sub(r"%20", " ", path.split("?")[0])
        if path:
            joined = os.path.normpath(os.path.join(os.path.dirname(page), path)).replace(os.sep, "/")
            if joined.startswith("../") or joined == ".." or os.path.isabs(path):
                self.error(page, line, "link '%s' leaves the repository" % target)
                return
            if joined not in self.tracked and joined not in self.dirs and joined != ".":
                self.error(page, line, "link '%s': no tracked file %s" % (target, joined))
                return
        else:
            joined = page
        if anchor and joined.endswith(".md") and joined in self.tracked:
            if anchor not in self.page_anchors(joined):
                self.error(page, line, "link '%s': %s has no heading #%s" % (target, joined, anchor))

    def check_page(self, page):
        with open(os.path.join(self.root, page), encoding="utf-8") as f:
            text = f.read()
        prose, blocks = scan(text)
        for k, line in enumerate(prose, 1):
            line = strip_code_spans(line)
            targets = [m.group(1) for m in LINK.finditer(line)] + HTML_LINK.findall(line)
            m = REF_DEF.match(line)
            if m:
                targets.append(m.group(1))
            for t in targets:
                self.check_target(page, k, t)
        for start, body, before in blocks:
            m = SNIPPET.match(before.strip())
            if m:
                self.check_snippet(page, start, body, m.group(1))
        markers = sum(1 for s in text.split("\n") if SNIPPET.match(s.strip()))
        if markers != sum(1 for _, _, b in blocks if SNIPPET.match(b.strip())):
            self.error(page, 1, "a <!-- snippet: ... --> marker not followed by a fenced code block")

    def check_snippet(self, page, line, body, source):
        rel = os.path.normpath(os.path.join(os.path.dirname(page), source)).replace(os.sep, "/")
        if rel not in self.tracked:
            self.error(page, line, "snippet source %s is not a tracked file" % rel)
            return
        want = snippet_lines(os.path.join(self.root, rel))
        if want is None:
            self.error(page, line, "snippet source %s has no single readme:begin ... readme:end pair" % rel)
            return
        if body != want:
            k = next((k for k in range(min(len(body), len(want))) if body[k] != want[k]), min(len(body), len(want)))
            self.error(page, line + 1 + k, "snippet differs from %s (its line %d of the marked lines: %r, here %r)"
                       % (rel, k + 1, want[k] if k < len(want) else "<end>", body[k] if k < len(body) else "<end>"))


def main(argv):
    root, pages = None, []
    args = list(argv)
    while args:
        a = args.pop(0)
        if a == "--root" and args:
            root = args.pop(0)
        elif a in ("-h", "--help"):
            print(__doc__)
            return 0
        elif a.startswith("-"):
            print("usage: check_links.py [--root DIR] [FILE.md ...]", file=sys.stderr)
            return 2
        else:
            pages.append(a)
    if root is None:
        root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
    checker = Checker(root)
    if not pages:
        pages = sorted(p for p in checker.tracked
                       if p == "README.md" or (p.startswith("docs/") and p.endswith(".md")))
    else:
        pages = [os.path.relpath(os.path.abspath(p), checker.root).replace(os.sep, "/") for p in pages]
    for page in pages:
        checker.check_page(page)
    for e in checker.errors:
        print(e)
    print("check_links.py: %d page(s), %s" % (len(pages), "%d failure(s)" % len(checker.errors)
                                               if checker.errors else "every link, anchor and snippet resolves"),
          file=sys.stderr)
    return 1 if checker.errors else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
