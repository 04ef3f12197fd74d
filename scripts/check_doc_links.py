#!/usr/bin/env python3
"""Checks that every relative link in README.md and docs/*.md points to an
existing file and, with a #fragment, to a heading (GitHub's slug) or an
<a id> in it. Exit 1 and one line per broken link otherwise."""
import pathlib, re, sys

ROOT = pathlib.Path(__file__).resolve().parent.parent
LINK = re.compile(r"!?\[(?:[^\]\[]|\[[^\]]*\])*\]\(([^)\s]+)\)")


def slug(heading):
    # GitHub: lower case, drop punctuation but '-' and '_', spaces become '-'.
    s = heading.strip().lower()
    s = re.sub(r"[^\w\- ]", "", s)
    return s.replace(" ", "-")


def anchors(path):
    text = path.read_text(encoding="utf-8")
    text = re.sub(r"```.*?```", "", text, flags=re.S)  # no headings inside code
    seen, out = {}, set(re.findall(r'<a id="([^"]+)"', text))
    for m in re.finditer(r"^#{1,6}\s+(.*)$", text, flags=re.M):
        s = slug(m.group(1))
        n = seen.get(s, 0)
        seen[s] = n + 1
        out.add(s if n == 0 else "%s-%d" % (s, n))
    return out


def main():
    files = [ROOT / "README.md"] + sorted((ROOT / "docs").glob("*.md"))
    bad = 0
    for f in files:
        text = re.sub(r"```.*?```", "", f.read_text(encoding="utf-8"), flags=re.S)
        for target in LINK.findall(text):
            if re.match(r"[a-z]+:", target):
                continue  # http(s), mailto: not checked offline
            path, _, frag = target.partition("#")
            dest = (f.parent / path).resolve() if path else f
            if not dest.exists():
                print("%s: missing file %s" % (f.relative_to(ROOT), target)); bad += 1
            elif frag and dest.suffix == ".md" and frag not in anchors(dest):
                print("%s: missing anchor %s" % (f.relative_to(ROOT), target)); bad += 1
    print("%d files, %s" % (len(files), "ok" if not bad else "%d broken links" % bad))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
