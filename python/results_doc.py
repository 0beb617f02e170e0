#!/usr/bin/python3
"""Writes one measurement script's section of docs/results.md.

Each script owns the text between `<!-- NAME begin -->` and `<!-- NAME end -->` and replaces
only that, so running one script leaves the other sections as they are. A section that is not
there yet is appended at the end under a heading. Every section starts with the command, the
commit it measured (`git rev-parse --short HEAD`), the date and the wall time.

From the shell (for scripts/bench-offline):
  python/results_doc.py NAME FILE.md --command "scripts/bench-offline 1" [--title TITLE] [--seconds S]
"""
import argparse
import datetime
import subprocess
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
RESULTS = ROOT / "docs" / "results.md"


def commit():
    """The short commit, with a note when the code differs from it; "unknown" outside git."""
    try:
        head = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT, capture_output=True, text=True,
                              check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return "unknown"
    dirty = subprocess.run(["git", "status", "--porcelain", "--", "src", "include", "Makefile", "scripts", "python", "inputs"],
                           cwd=ROOT, capture_output=True, text=True).stdout.strip()
    return head + (" (with uncommitted changes)" if dirty else "")


def provenance(command, seconds=None):
    """One line: the command, the commit, the date and the wall time."""
    took = ""
    if seconds is not None:
        m, s = divmod(int(round(seconds)), 60)
        took = f", {m} min {s} s" if m else f", {s} s"
    return f"Measured by `{command}` on commit {commit()}, {datetime.date.today().isoformat()}{took}."


def replace_section(text, name, body, title=None, after=None, level=2):
    """text with the section NAME's content replaced by body. If absent, it is appended at the end,
    or, with after (the text of a level-2 heading, or its start), put before the level-2 heading
    that follows that section (at the end if none follows, or if that heading is not found), under
    a heading of the given level (3: a subsection of the section headed after)."""
    begin, end = f"<!-- {name} begin -->", f"<!-- {name} end -->"
    block = f"{begin}\n{body.strip()}\n{end}"
    i, j = text.find(begin), text.find(end)
    if i >= 0 and j > i:
        return text[:i] + block + text[j + len(end):]
    if i >= 0 or j >= 0:
        raise ValueError(f"section {name}: its begin and end markers are not a pair")
    head = f"{'#' * level} {title or name}\n\n" if title is not False else ""
    if after is not None:
        lines = text.splitlines(keepends=True)
        at = next((k for k, line in enumerate(lines) if line.startswith("## " + after)), None)
        if at is not None:
            nxt = next((k for k in range(at + 1, len(lines)) if lines[k].startswith("## ")), None)
            if nxt is not None:
                return "".join(lines[:nxt]) + head + block + "\n\n" + "".join(lines[nxt:])
    return text.rstrip("\n") + "\n\n" + head + block + "\n"


def write_section(name, body, title=None, path=RESULTS, after=None, level=2):
    """Replaces the section NAME of docs/results.md (or path) with body, atomically (a new section
    goes after the section headed after, see replace_section, or at the end)."""
    path = Path(path)
    text = path.read_text() if path.exists() else "# Measured results\n"
    new = replace_section(text, name, body, title, after, level)
    tmp = path.with_name(path.name + ".tmp")
    tmp.write_text(new)
    tmp.replace(path)
    print(f"wrote the section {name} of {path}")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("name")
    ap.add_argument("file", help="markdown to put in the section")
    ap.add_argument("--command", required=True, help="the command that measured it")
    ap.add_argument("--title", default=None, help="heading if the section is new")
    ap.add_argument("--seconds", type=float, default=None, help="wall time of the measurement")
    ap.add_argument("--results", default=str(RESULTS))
    a = ap.parse_args()
    body = provenance(a.command, a.seconds) + "\n\n" + Path(a.file).read_text()
    write_section(a.name, body, a.title, a.results)


if __name__ == "__main__":
    main()
