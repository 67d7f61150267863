#!/usr/bin/python3
"""Checks that the documentation's links and repository paths resolve.

    check_links.py SOURCE_DIR      check the documentation of the tree at SOURCE_DIR
    check_links.py --self-test     check that the checker finds the faults it should

Pages checked: README.md, docs/*.md, results/**/README.md and data/**/README.md. A page
fails, with FILE:LINE and the dead link, on
  - a relative Markdown link (inline or reference style) to a file or folder that does not
    exist, or to an anchor (#heading) that the target page has no heading for;
  - a repository path that does not exist: a word, in backticks or in a code block, whose
    first part is one of the tree's top-level folders (or, in a page below the top, one of
    the page's own neighbours); `*` globs must match something, {a,b} lists are expanded,
    and words with <placeholders>, ... or $VARIABLES are not paths;
and the tree fails when a docs/*.md page is not linked from README.md.
Exit status 0 when everything resolves, 1 with one line per fault on stderr otherwise.
"""
import fnmatch
import glob
import os
import re
import sys
import tempfile
import unicodedata
import urllib.parse

FENCE = re.compile(r"^\s*(```|~~~)")
ATX_HEADING = re.compile(r"^ {0,3}(#{1,6})\s+(.*?)\s*#*\s*$")
SETEXT_UNDERLINE = re.compile(r"^ {0,3}(=+|-+)\s*$")
INLINE_CODE = re.compile(r"(`+)(.+?)\1")
INLINE_LINK = re.compile(r"!?\[(?:[^\[\]]|\[[^\]]*\])*\]\(\s*<?([^)\s>]+)>?(?:\s+\"[^\"]*\")?\s*\)")
REFERENCE_DEFINITION = re.compile(r"^ {0,3}\[[^\]]+\]:\s*<?(\S+?)>?(?:\s+.*)?$")
PATH_WORD = re.compile(r"^[A-Za-z0-9_.*{},/+-]+$")
NOT_A_PATH = re.compile(r"<|>|\.\.\.|…|\$|%|=|\\")
SCHEME = re.compile(r"^[A-Za-z][A-Za-z0-9+.-]*:")
WORD_EDGES = "\"'(),;:.!?[]"


class Fault:
    def __init__(self, page, line, message):
        self.page, self.line, self.message = page, line, message

    def __str__(self):
        return f"{self.page}:{self.line}: {self.message}"


def pages(root):
    """The documentation pages of the tree, as paths relative to root."""
    found = ["README.md"] if os.path.isfile(os.path.join(root, "README.md")) else []
    found += sorted(glob.glob("docs/*.md", root_dir=root))
    for top in ("results", "data"):
        found += sorted(glob.glob(f"{top}/**/README.md", root_dir=root, recursive=True))
    return found


def ignored_top_names(root):
    """Top-level patterns of .gitignore (build outputs): paths under them are not checked."""
    patterns = []
    try:
        with open(os.path.join(root, ".gitignore"), encoding="utf-8") as f:
            for raw in f:
                line = raw.strip()
                if line.startswith("/") and "/" not in line.strip("/"):
                    patterns.append(line.strip("/"))
    except FileNotFoundError:
        pass
    return patterns


def top_level_folders(root):
    ignored = ignored_top_names(root)
    return {name for name in os.listdir(root)
            if os.path.isdir(os.path.join(root, name)) and name != ".git"
            and not any(fnmatch.fnmatch(name, p) for p in ignored)}


def slug(heading):
    """GitHub's anchor for a heading: lower case, markup and punctuation dropped, spaces to '-'."""
    text = re.sub(r"!?\[([^\]]*)\]\([^)]*\)", r"\1", heading)
    text = text.replace("`", "").lower()
    kept = []
    for ch in text:
        if ch in " -_" or unicodedata.category(ch)[0] in "LN":
            kept.append(ch)
    return "".join(kept).replace(" ", "-")


def scan(text):
    """Lines of a page: (line number, text, kind), kind "fence" inside a fenced code block
    (its fences included), "indented" in an indented code block (four spaces after a blank
    line, not a list item), "prose" otherwise."""
    result = []
    fence = None
    previous_kind, previous_blank = "prose", True
    for number, line in enumerate(text.split("\n"), 1):
        match = FENCE.match(line)
        if fence is not None:
            kind = "fence"
            if match and match.group(1) == fence:
                fence = None
        elif match:
            kind, fence = "fence", match.group(1)
        elif line.startswith("    ") and line.strip() and (previous_blank or previous_kind == "indented") \
                and not re.match(r"\s*([-*+]|\d+[.)])\s", line):
            kind = "indented"
        else:
            kind = "prose"
        result.append((number, line, kind))
        if line.strip():
            previous_kind = kind
        previous_blank = not line.strip()
    return result


def anchors_of(path, cache):
    if path not in cache:
        with open(path, encoding="utf-8") as f:
            lines = scan(f.read())
        seen = {}
        anchors = set()
        previous = None
        for _, line, kind in lines:
            in_code = kind != "prose"
            heading = None
            if not in_code:
                atx = ATX_HEADING.match(line)
                if atx:
                    heading = atx.group(2)
                elif previous and previous.strip() and SETEXT_UNDERLINE.match(line) \
                        and not previous.lstrip().startswith(("|", "-", "*")):
                    heading = previous.strip()
            if heading is not None:
                base = slug(heading)
                count = seen.get(base, 0)
                anchors.add(base if count == 0 else f"{base}-{count}")
                seen[base] = count + 1
            previous = None if in_code else line
        cache[path] = anchors
    return cache[path]


def check_link(root, page, number, target, anchors_cache):
    """Faults of one link target written on `page` (relative to root)."""
    if SCHEME.match(target) or target.startswith("//"):
        return []
    target = urllib.parse.unquote(target)
    path_part, _, anchor = target.partition("#")
    page_dir = os.path.dirname(os.path.join(root, page))
    resolved = os.path.normpath(os.path.join(page_dir, path_part)) if path_part else os.path.join(root, page)
    inside = os.path.commonpath([os.path.abspath(resolved), os.path.abspath(root)]) == os.path.abspath(root)
    if not inside:
        return [Fault(page, number, f"dead link '{target}': it leaves the repository")]
    if not os.path.exists(resolved):
        return [Fault(page, number, f"dead link '{target}': no file or folder {os.path.relpath(resolved, root)}")]
    if anchor:
        if not (os.path.isfile(resolved) and resolved.endswith(".md")):
            return [Fault(page, number, f"dead link '{target}': an anchor on something that is not a Markdown page")]
        if anchor.lower() not in anchors_of(resolved, anchors_cache):
            return [Fault(page, number,
                          f"dead link '{target}': no heading '#{anchor}' in {os.path.relpath(resolved, root)}")]
    return []


def expand_braces(word):
    match = re.search(r"\{([^{}]*)\}", word)
    if not match:
        return [word]
    words = []
    for choice in match.group(1).split(","):
        words += expand_braces(word[:match.start()] + choice + word[match.end():])
    return words


def path_candidates(root, page, text):
    """The words of `text` that name repository paths, each with the folder it is relative to."""
    tops = top_level_folders(root)
    page_dir = os.path.dirname(os.path.join(root, page))
    neighbours = set(os.listdir(page_dir)) if os.path.abspath(page_dir) != os.path.abspath(root) else set()
    for raw in text.split():
        word = raw.strip(WORD_EDGES)
        if "/" not in word or NOT_A_PATH.search(raw) or not PATH_WORD.match(word):
            continue
        if word.startswith("/") or SCHEME.match(word):
            continue
        first = word.split("/", 1)[0]
        if first in tops:
            yield word, root
        elif first in neighbours and os.path.isdir(os.path.join(page_dir, first)):
            yield word, page_dir


def check_path(root, page, number, word, base):
    for candidate in expand_braces(word):
        full = os.path.join(base, candidate)
        exists = glob.glob(full) if any(c in candidate for c in "*?[") else os.path.exists(full)
        if not exists:
            shown = os.path.relpath(full, root)
            return [Fault(page, number, f"dead path '{word}': no file or folder {shown}")]
    return []


def check_page(root, page, anchors_cache):
    with open(os.path.join(root, page), encoding="utf-8") as f:
        text = f.read()
    faults = []
    linked = set()
    for number, line, kind in scan(text):
        if kind != "prose":
            for word, base in path_candidates(root, page, line):
                faults += check_path(root, page, number, word, base)
            if kind == "fence":
                continue
        else:
            for code in INLINE_CODE.finditer(line):
                for word, base in path_candidates(root, page, code.group(2)):
                    faults += check_path(root, page, number, word, base)
        prose = INLINE_CODE.sub("", line)
        targets = [m.group(1) for m in INLINE_LINK.finditer(prose)]
        definition = REFERENCE_DEFINITION.match(prose)
        if definition:
            targets.append(definition.group(1))
        for target in targets:
            faults += check_link(root, page, number, target, anchors_cache)
            if not SCHEME.match(target):
                resolved = os.path.normpath(os.path.join(os.path.dirname(page), urllib.parse.unquote(target.split("#")[0])))
                linked.add(resolved)
    return faults, linked


def check_tree(root):
    anchors_cache = {}
    faults = []
    linked_from_readme = set()
    for page in pages(root):
        page_faults, linked = check_page(root, page, anchors_cache)
        faults += page_faults
        if page == "README.md":
            linked_from_readme = linked
    for doc in sorted(glob.glob("docs/*.md", root_dir=root)):
        if doc not in linked_from_readme:
            faults.append(Fault("README.md", 1, f"docs page '{doc}' is not linked from README.md"))
    return faults


def self_test():
    """Builds a small tree with known faults and checks that each is reported, and no other."""
    files = {
        ".gitignore": "/build*/\n",
        "README.md": (
            "# Top\n\n[guide](docs/guide.md), [gone](docs/gone.md), [heading](docs/guide.md#usage)\n"
            "[no heading](docs/guide.md#nowhere) and `src/real.cpp`, `src/missing.cpp`\n"
            "```sh\nsrc/tool.sh --flag\nsrc/old_tool.sh\n```\n"
            "`build/out.bin` `src/<name>.cpp` `src/*.cpp` `src/*.hpp` `data/{a,b}.txt`\n"
            "[site](https://example.org/x) [here](#top) [there](#elsewhere)\n"),
        "docs/guide.md": "# Guide\n\n## Usage\n\n[back](../README.md) [up](../README.md#top)\n",
        "docs/orphan.md": "# Orphan\n\n[results](../results/run/README.md#figures)\n",
        "results/run/README.md": "# Run\n\n## Numbers\n\n`table.txt` `sub/file.txt` `sub/nothing.txt`\n",
        "results/run/sub/file.txt": "",
        "src/real.cpp": "",
        "src/tool.sh": "",
        "data/a.txt": "",
    }
    expected = {
        "README.md:3: dead link 'docs/gone.md'",
        "README.md:4: dead link 'docs/guide.md#nowhere'",
        "README.md:4: dead path 'src/missing.cpp'",
        "README.md:7: dead path 'src/old_tool.sh'",
        "README.md:9: dead path 'src/*.hpp'",
        "README.md:9: dead path 'data/{a,b}.txt'",
        "README.md:10: dead link '#elsewhere'",
        "README.md:1: docs page 'docs/orphan.md' is not linked",
        "docs/orphan.md:3: dead link '../results/run/README.md#figures'",
        "results/run/README.md:5: dead path 'sub/nothing.txt'",
    }
    with tempfile.TemporaryDirectory() as root:
        for name, content in files.items():
            os.makedirs(os.path.dirname(os.path.join(root, name)) or root, exist_ok=True)
            with open(os.path.join(root, name), "w", encoding="utf-8") as f:
                f.write(content)
        reported = [str(f) for f in check_tree(root)]
    missed = [e for e in sorted(expected) if not any(r.startswith(e) for r in reported)]
    extra = [r for r in reported if not any(r.startswith(e) for e in expected)]
    for line in missed:
        print(f"self-test: not reported: {line}", file=sys.stderr)
    for line in extra:
        print(f"self-test: reported but not a fault: {line}", file=sys.stderr)
    if missed or extra:
        return 1
    print(f"self-test: all {len(expected)} planted faults reported, nothing else")
    return 0


def main(argv):
    if len(argv) != 2:
        print(__doc__, file=sys.stderr)
        return 2
    if argv[1] == "--self-test":
        return self_test()
    root = argv[1]
    if not os.path.isfile(os.path.join(root, "README.md")):
        print(f"check_links.py: '{root}' has no README.md: not the source tree", file=sys.stderr)
        return 2
    faults = check_tree(root)
    for fault in faults:
        print(fault, file=sys.stderr)
    checked = len(pages(root))
    if faults:
        print(f"check_links.py: {len(faults)} dead link(s) in {checked} pages", file=sys.stderr)
        return 1
    print(f"check_links.py: {checked} pages, every link and path resolves")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
