#!/usr/bin/env python3
"""Fails when a file of the source tree points outside the repository.

The project once cited a specification kept in a folder next to the repository (its
sections as "spec" plus a section sign, its spec, design and reference files by
path or name). A clone has none of these: the project's own descriptions are docs/math.md and
docs/fastrak-protocol.md. This check walks the tree (no .git needed: it reads what
is present, as in an unpacked source archive), skips build*/ and .git/ directories
and binary files, and names every offending line as PATH:LINE: TEXT.

usage: check_outside_references.py ROOT     check the tree at ROOT (exit 1 on a hit)
       check_outside_references.py --self-test   show the check can fail
"""
import os
import re
import sys
import tempfile

# Built so that this file does not match itself.
SECTION = "\u00a7"
PATTERNS = [
    re.compile(r"\bspec " + SECTION),  # a section of the old spec
    re.compile(r"\bspec \\u00a7"),  # the same as a C++ string escape
    re.compile(r"(\.\./|/work/)shared\b"),  # the folder next to the repository
    re.compile(r"\bshared[/](spec|design|reference|hooks)\b"),
    re.compile(r"\b(twister-math|testing-without-hardware|style-examples|polhemus-devices)"
               r"[.]md\b"),
    re.compile(r"\btwister-paper[.]txt\b"),
]

ANY = re.compile("|".join(p.pattern for p in PATTERNS))


def skipped_dir(name):
    return name == ".git" or name.startswith("build")


def text_of(path):
    """The file's lines, or None for a binary or unreadable file."""
    try:
        with open(path, "rb") as f:
            data = f.read()
    except OSError:
        return None
    if b"\0" in data[:8192]:
        return None
    try:
        return data.decode("utf-8").splitlines()
    except UnicodeDecodeError:
        return None


def offending_lines(root):
    hits = []
    files = 0
    for dirpath, dirnames, filenames in os.walk(root):
        dirnames[:] = sorted(d for d in dirnames if not skipped_dir(d))
        for name in sorted(filenames):
            path = os.path.join(dirpath, name)
            lines = text_of(path)
            if lines is None:
                continue
            files += 1
            rel = os.path.relpath(path, root)
            for number, line in enumerate(lines, 1):
                if ANY.search(line):
                    hits.append(f"{rel}:{number}: {line.strip()}")
    return files, hits


def check(root):
    files, hits = offending_lines(root)
    if hits:
        print(f"{len(hits)} line(s) point outside the repository (cite docs/math.md, "
              "docs/fastrak-protocol.md or another project doc instead):")
        for h in hits:
            print("  " + h)
        return 1
    print(f"no reference outside the repository in {files} text files under {root}")
    return 0


def self_test():
    """Plants each kind of reference and expects exactly those lines named."""
    planted = {
        os.path.join("core", "a.hpp"): "// ok\n// the screw (spec " + SECTION + "2)\n",
        os.path.join("docs", "b.md"): "see `../" + "shared" + "/spec/x.md`\n",
        os.path.join("tests", "c.py"): "# from twister-" + "math.md\n",
        os.path.join("host", "d.cpp"): '"title (spec \\' + 'u00a79)"\n',
        "CMakeLists.txt": "# reads /work/" + "shared" + "/reference/x\n",
        # Ignored: build trees and binary files.
        os.path.join("build-asan", "e.md"): "spec " + SECTION + "1\n",
    }
    expected = {
        os.path.join("core", "a.hpp") + ":2",
        os.path.join("docs", "b.md") + ":1",
        os.path.join("tests", "c.py") + ":1",
        os.path.join("host", "d.cpp") + ":1",
        "CMakeLists.txt:1",
    }
    with tempfile.TemporaryDirectory() as root:
        for rel, text in planted.items():
            path = os.path.join(root, rel)
            os.makedirs(os.path.dirname(path), exist_ok=True)
            with open(path, "w", encoding="utf-8") as f:
                f.write(text)
        with open(os.path.join(root, "docs", "f.png"), "wb") as f:
            f.write(b"\x89PNG\0\0spec " + SECTION.encode() + b"3")
        _, hits = offending_lines(root)
        named = {":".join(h.split(":")[:2]) for h in hits}
        if named != expected:
            print("self-test failed: named", sorted(named), "expected", sorted(expected))
            return 1
        if check(root) != 1:
            print("self-test failed: the check passed a tree with planted references")
            return 1
    print("self-test: every planted reference named, build trees and binaries skipped")
    return 0


def main(argv):
    if len(argv) == 2 and argv[1] == "--self-test":
        return self_test()
    if len(argv) != 2:
        print(__doc__)
        return 2
    return check(argv[1])


if __name__ == "__main__":
    sys.exit(main(sys.argv))
