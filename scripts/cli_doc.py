#!/usr/bin/env python3
"""Writes the generated line under each option's heading in docs/user/cli.md.

    python3 scripts/cli_doc.py [--octrace build/app/octrace] [--check]

Every option of the options table (app/model) that has a CLI flag is documented under a heading
`### --FLAG ...` in the section `## octrace COMMAND` of its command (render when it takes it).
The line right under that heading is generated from the table (`octrace options --markdown`):
default, range or choices, the renderers that read it, its session member and studio control.
This script writes those lines; the prose around them is the writers'. A heading that is missing
is reported (exit 1): write it, then run the script again. With --check nothing is written and
the exit status says whether the file is current (the test OptionTable.CliDocShowsTheTable
checks the same).
"""
import argparse
import os
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DOC = os.path.join(ROOT, "docs", "user", "cli.md")
MARK = "*Options table:"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--octrace", default=os.path.join(ROOT, "build", "app", "octrace"))
    ap.add_argument("--check", action="store_true")
    args = ap.parse_args()
    rows = subprocess.run([args.octrace, "options", "--markdown"], check=True, capture_output=True, text=True).stdout
    with open(DOC, encoding="utf-8") as f:
        lines = f.read().split("\n")
    missing, stale = [], 0
    for row in rows.splitlines():
        command, heading, generated = row.split("\t")
        section = next((i for i, l in enumerate(lines) if l.startswith("## octrace " + command)), None)
        end = next((i for i in range(section + 1, len(lines)) if lines[i].startswith("## ")), len(lines)) if section is not None else None
        at = None
        if section is not None:
            for i in range(section + 1, end):
                l = lines[i]
                if l.startswith(heading) and (len(l) == len(heading) or l[len(heading)] in " ,"):
                    at = i
                    break
        if at is None:
            missing.append("%s (section '## octrace %s')" % (heading, command))
            continue
        if at + 1 < len(lines) and lines[at + 1].startswith(MARK):
            if lines[at + 1] != generated:
                lines[at + 1] = generated
                stale += 1
        else:
            lines.insert(at + 1, generated)
            stale += 1
    for m in missing:
        print("cli_doc: no heading %s in docs/user/cli.md" % m, file=sys.stderr)
    if args.check:
        print("cli_doc: %d generated lines out of date, %d headings missing" % (stale, len(missing)))
        return 1 if stale or missing else 0
    if stale:
        with open(DOC, "w", encoding="utf-8") as f:
            f.write("\n".join(lines))
    print("cli_doc: %d lines written, %d headings missing" % (stale, len(missing)))
    return 1 if missing else 0


if __name__ == "__main__":
    sys.exit(main())
