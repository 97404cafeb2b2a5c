#!/usr/bin/env python3
"""Prints the markdown table of a long fuzz run from the JSON lines tests/fuzz/run.sh appends
when OCTRACE_FUZZ_JSON is set (docs/dev/fuzzing.md, "Record of a long run").

Usage: tests/fuzz/record.py FILE.jsonl
"""
import json
import sys


def main():
    if len(sys.argv) != 2:
        print(__doc__, file=sys.stderr)
        return 2
    rows = []
    with open(sys.argv[1]) as f:
        for line in f:
            line = line.strip()
            if line:
                rows.append(json.loads(line))
    print("| target | seconds | executions | exec/s | new inputs | corpus kept (found + seeds) | peak RSS | result | goal of 10 million |")
    print("|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        print("| `%s` | %d | %s | %s | %s | %s + %d (%.0f KB) | %d MB | %s | %s |" % (
            r["target"], r["seconds"], format(r["executions"], ","), format(r["exec_per_sec"], ","),
            format(r["new_units"], ","), format(r["corpus_found"], ","), r["seeds"], r["corpus_bytes"] / 1000.0,
            r["peak_rss_mb"], r["result"], "reached" if r["executions"] >= 10_000_000 else
            "%.1f %%" % (100.0 * r["executions"] / 10_000_000)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
