#!/usr/bin/env python3
"""Every relative link in docs/**/*.md, README.md and CHANGELOG.md points at an existing
file, and every #anchor at a heading of that file (GitHub's slug rules).
Usage: check_doc_links.py [REPOSITORY_ROOT]; exit 1 when a link is broken."""
import pathlib, re, sys
root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else '.')
files = sorted(root.glob('docs/**/*.md')) + [p for p in (root/'README.md', root/'CHANGELOG.md') if p.exists()]
link = re.compile(r'!?\[[^\]]*\]\(([^)\s]+)\)')
def slugs(p):
    out = set(); seen = {}
    for line in p.read_text().split('\n'):
        m = re.match(r'#+\s+(.*)', line)
        if not m: continue
        s = m.group(1).strip().lower()
        s = re.sub(r'[^\w\- ]', '', s).replace(' ', '-')
        n = seen.get(s, 0); seen[s] = n + 1
        out.add(s if n == 0 else f'{s}-{n}')
    return out
bad = 0; count = 0
for f in files:
    text = re.sub(r'```.*?```', '', f.read_text(), flags=re.S)
    for target in link.findall(text):
        if re.match(r'[a-z]+:', target): continue
        count += 1
        path, _, anchor = target.partition('#')
        dest = (f.parent / path).resolve() if path else f
        if not dest.exists():
            print(f'{f.relative_to(root)}: missing file {target}'); bad += 1; continue
        if anchor and dest.suffix == '.md' and anchor not in slugs(dest):
            print(f'{f.relative_to(root)}: missing anchor {target}'); bad += 1
print(f'{count} relative links in {len(files)} files, {bad} broken')
sys.exit(1 if bad else 0)
