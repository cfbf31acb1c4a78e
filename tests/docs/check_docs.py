#!/usr/bin/env python3
"""The documentation's own rules, checked (ctest Docs.Check, label docs).

    check_docs.py [SOURCE_DIR]

Fails, naming every offending file and line, when
- a tracked file's name, or a line of a tracked source, test, script or documentation file, names a tracker item or a list entry by
  its number ("issue" or "reading" followed by a number): cite pages and stable headings instead;
- README.md is longer than 250 lines, or a page in docs/ longer than 600;
- a source file (C++, Python, CMake) is longer than 800 lines: split it by concern;
- a page in docs/ is not linked from README.md directly;
- a relative link in README.md, docs/*.md or benchmarks/README.md does not lead to an existing
  file (the #anchor part is not checked).
The files are those `git ls-files` lists inside a git checkout, else every file under SOURCE_DIR
(a clean clone and an unpacked archive give the same answer).
"""
import os
import re
import subprocess
import sys

README_MAX_LINES = 250
PAGE_MAX_LINES = 600
SOURCE_MAX_LINES = 800
CODE_SUFFIXES = (".h", ".cxx", ".cpp", ".py", ".cmake")
# Case-insensitive; the pattern is built from pieces so that this file does not match itself.
NUMBERED_NAME = re.compile("iss" + "ue ?[0-9]|read" + "ing [0-9]+", re.IGNORECASE)
SOURCE_SUFFIXES = (".h", ".cxx", ".cpp", ".py", ".cmake", ".in", ".xml", ".md", ".sh", ".json")
TEXT_FOLDERS = ("scripts/", "docs/", "tests/", "cmake/", "benchmarks/", "examples/", "cli/",
                "filters/", "paraview-plugin/")
SKIPPED_FOLDERS = ("tests/fuzz/corpus/",)  # generated fuzzer inputs, not prose
LINK = re.compile(r"\[[^\]]*\]\(([^)\s]+)(?:\s+\"[^\"]*\")?\)")


def tracked_files(root):
    try:
        out = subprocess.run(["git", "-C", root, "ls-files", "-z"], check=True, capture_output=True)
        files = [f for f in out.stdout.decode().split("\0") if f]
        if files:
            return [f for f in files if os.path.isfile(os.path.join(root, f))]
    except (OSError, subprocess.CalledProcessError):
        pass
    files = []
    for folder, dirs, names in os.walk(root):
        rel = os.path.relpath(folder, root)
        dirs[:] = [d for d in dirs if not d.startswith(".") and not (rel == "." and d.startswith("build"))]
        for name in names:
            files.append(os.path.normpath(os.path.join(rel, name)).replace(os.sep, "/"))
    return files


def is_checked_source(path):
    if path.startswith(SKIPPED_FOLDERS):
        return False
    name = os.path.basename(path)
    if name == "CMakeLists.txt" or path.endswith(SOURCE_SUFFIXES):
        return True
    return path.startswith(TEXT_FOLDERS) and "." not in name  # scripts without a suffix


def read_lines(root, path):
    try:
        with open(os.path.join(root, path), encoding="utf-8") as f:
            return f.read().split("\n")
    except (UnicodeDecodeError, OSError):
        return None


def main():
    root = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", ".."))
    files = tracked_files(root)
    this = os.path.relpath(os.path.abspath(__file__), root).replace(os.sep, "/")
    failures = []

    for path in sorted(files):
        if NUMBERED_NAME.search(path.replace("-", " ").replace("_", " ")) or re.search("iss" + "ue[0-9]", path, re.I):
            failures.append(f"{path}: its name holds a number from the tracker or a list")
    for path in sorted(f for f in files if is_checked_source(f)):
        lines = read_lines(root, path)
        if lines is None:
            continue
        for number, line in enumerate(lines, 1):
            if NUMBERED_NAME.search(line) and not (path == this and "NUMBERED_NAME = " in line):
                failures.append(f"{path}:{number}: names something by a number (use a page and a stable heading): {line.strip()}")

    for path in sorted(f for f in files if f.endswith(CODE_SUFFIXES) or os.path.basename(f) == "CMakeLists.txt"):
        count = len(read_lines(root, path) or [""]) - 1  # lines as wc -l counts them
        if count > SOURCE_MAX_LINES:
            failures.append(f"{path}: {count} lines, at most {SOURCE_MAX_LINES} (split it by concern)")

    pages = sorted(f for f in files if f.startswith("docs/") and f.endswith(".md") and f.count("/") == 1)
    readme = read_lines(root, "README.md") or []
    if len(readme) - 1 > README_MAX_LINES:
        failures.append(f"README.md: {len(readme) - 1} lines, at most {README_MAX_LINES}")
    for page in pages:
        count = len(read_lines(root, page) or []) - 1
        if count > PAGE_MAX_LINES:
            failures.append(f"{page}: {count} lines, at most {PAGE_MAX_LINES}")

    linked = set()
    for doc in ["README.md", "benchmarks/README.md"] + pages:
        lines = read_lines(root, doc)
        if lines is None:
            if doc == "README.md":
                failures.append("README.md: missing")
            continue
        in_code = False
        for number, line in enumerate(lines, 1):
            if line.lstrip().startswith("```"):
                in_code = not in_code
                continue
            if in_code:
                continue
            for target in LINK.findall(line):
                if re.match(r"^[a-z][a-z0-9+.-]*:", target, re.IGNORECASE) or target.startswith("#"):
                    continue  # a URL or an anchor in the same page
                file_part = target.split("#", 1)[0]
                resolved = os.path.normpath(os.path.join(os.path.dirname(doc), file_part)).replace(os.sep, "/")
                if doc == "README.md":
                    linked.add(resolved)
                if not os.path.exists(os.path.join(root, resolved)):
                    failures.append(f"{doc}:{number}: link to {target}: no such file ({resolved})")
    for page in pages:
        if page not in linked:
            failures.append(f"{page}: not linked from README.md")

    if failures:
        print("check_docs: %d problem(s):" % len(failures))
        for failure in failures:
            print("  " + failure)
        return 1
    print(f"check_docs: {len(files)} files; README {len(readme) - 1} lines; {len(pages)} pages in docs/, "
          "each linked from README and within its length; every relative link resolves; no numbered names; "
          f"no source over {SOURCE_MAX_LINES} lines")
    return 0


if __name__ == "__main__":
    sys.exit(main())
