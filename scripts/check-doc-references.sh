#!/usr/bin/env bash
# Checks that the repository paths cited in code comments and documentation exist, so that a
# rename or a document kept outside the repository shows up as a failing test instead of a
# dangling pointer. Three kinds of reference are checked, in every text file git tracks (or would
# track: untracked files that are not ignored); in C++ files only comments count (a string
# literal may name a missing file on purpose, e.g. in an error-message test):
#   * a path that starts with a top-level directory of the repository (docs/, tests/, core/, kernels/,
#     scene/, scheduler/, apps/, scripts/, benchmarks/, cmake/, data/) and names a file (has an
#     extension; {a,b} alternatives are expanded) or a directory (ends with /). Paths inside
#     other paths (build/apps/..., ../shared/data/...) and patterns (*, $VAR, <name>) are not
#     references to the tree and are skipped;
#   * a relative link target in a Markdown file, resolved against that file's directory;
#   * a section cited as "docs/method.md N.M" (also "section N", ranges "N.M-N.K", lists and
#     "Appendix X"), which must be a heading of docs/method.md.
# Prints each dangling reference as file:line: reference, and exits 1 if there is any.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"

exec python3 - "$root" <<'PY'
import os
import re
import subprocess
import sys

root = sys.argv[1]
TOP = r"(?:docs|tests|core|kernels|scene|scheduler|apps|scripts|benchmarks|cmake|data)"
TEXT_SUFFIXES = {".cpp", ".h", ".hpp", ".c", ".md", ".txt", ".cmake", ".sh", ".py", ".json",
                 ".yml", ".yaml", ".in", ""}
CODE_SUFFIXES = {".cpp", ".h", ".hpp", ".c"}  # only their comments are checked

# A path token: not preceded by anything that would make it part of a longer path or word.
PATH = re.compile(r"(?<![\w./$~-])(" + TOP + r"/[\w./{},*$<>-]*)")
LINK = re.compile(r"\]\(([^)\s]+)\)")
SECTION = r"(?:Appendix\s+[A-Z]|\d+(?:\.\d+)?)"
CITATION = re.compile(r"docs/method\.md(?:\s+(?:sections?|§))?\s+(" + SECTION +
                      r"(?:\s*(?:-|–|,|and)\s*" + SECTION + r")*)")


def repository_files():
    try:
        out = subprocess.run(["git", "-C", root, "ls-files", "-z", "--cached", "--others",
                              "--exclude-standard"], check=True, capture_output=True).stdout
        names = [n for n in out.decode().split("\0") if n]
    except (OSError, subprocess.CalledProcessError):
        names = []
        for directory, subdirs, files in os.walk(root):
            subdirs[:] = [d for d in subdirs if not d.startswith((".git", "build", "out"))]
            names += [os.path.relpath(os.path.join(directory, f), root) for f in files]
    return sorted(n for n in names if os.path.splitext(n)[1] in TEXT_SUFFIXES
                  and os.path.isfile(os.path.join(root, n)))


def comment_text(line, in_block):
    """The comment part of a C++ line (string literals in code are data, not citations), and
    whether a /* */ comment is still open after it."""
    text = ""
    while line:
        if in_block:
            end = line.find("*/")
            text += " " + (line if end < 0 else line[:end])
            if end < 0:
                return text, True
            line, in_block = line[end + 2:], False
            continue
        line_comment, block = line.find("//"), line.find("/*")
        if line_comment >= 0 and (block < 0 or line_comment < block):
            return text + " " + line[line_comment + 2:], False
        if block < 0:
            return text, False
        line, in_block = line[block + 2:], True
    return text, in_block


def expand_braces(token):
    m = re.search(r"\{([^{}]*)\}", token)
    if not m:
        return [token]
    out = []
    for alternative in m.group(1).split(","):
        out += expand_braces(token[:m.start()] + alternative + token[m.end():])
    return out


def path_references(token):
    """The paths a token refers to, or [] when it is not a reference to the tree."""
    token = token.rstrip(".,;:")
    if any(c in token for c in "*$<>") or "..." in token:
        return []
    paths = []
    for path in expand_braces(token):
        if "{" in path or "}" in path or "," in path:
            return []
        is_dir = path.endswith("/")
        if not is_dir and not re.search(r"\.[A-Za-z0-9]+$", os.path.basename(path)):
            continue  # no extension: an executable, a prose "a/b", a build output
        paths.append(path)
    return paths


def method_sections():
    sections = set()
    with open(os.path.join(root, "docs", "method.md"), encoding="utf-8") as f:
        for line in f:
            m = re.match(r"#{2,6}\s+(\d+(?:\.\d+)*)\.?\s", line)
            if m:
                sections.add(m.group(1))
            m = re.match(r"#{2,6}\s+(Appendix\s+[A-Z])\b", line)
            if m:
                sections.add(re.sub(r"\s+", " ", m.group(1)))
    return sections


def main():
    sections = method_sections()
    dangling = []
    for name in repository_files():
        try:
            with open(os.path.join(root, name), encoding="utf-8") as f:
                lines = f.read().split("\n")
        except UnicodeDecodeError:
            continue
        markdown = name.endswith(".md")
        source = os.path.splitext(name)[1] in CODE_SUFFIXES
        in_block = False
        for number, line in enumerate(lines, 1):
            if source:
                line, in_block = comment_text(line, in_block)
            for m in PATH.finditer(line):
                for path in path_references(m.group(1)):
                    if not os.path.exists(os.path.join(root, path)):
                        dangling.append(f"{name}:{number}: {path}")
            if markdown:
                for m in LINK.finditer(line):
                    target = m.group(1).split("#")[0]
                    if not target or re.match(r"[a-z][a-z0-9+.-]*:", target):
                        continue  # in-page anchor or a URL
                    resolved = os.path.normpath(os.path.join(os.path.dirname(name), target))
                    if not os.path.exists(os.path.join(root, resolved)):
                        dangling.append(f"{name}:{number}: {target}")
            for m in CITATION.finditer(line):
                for cited in re.findall(SECTION, m.group(1)):
                    cited = re.sub(r"\s+", " ", cited)
                    if cited not in sections:
                        dangling.append(f"{name}:{number}: docs/method.md {cited} (no such section)")
    for d in dangling:
        print(d)
    if dangling:
        print(f"{len(dangling)} dangling reference(s)", file=sys.stderr)
        return 1
    return 0


sys.exit(main())
PY
