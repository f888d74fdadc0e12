#!/usr/bin/env bash
# Per-pass GPU times of two facet-bake builds taking turns:
#   scripts/bench/pass_ab.sh RUNS ENV BAKE_A BAKE_B
# Sums each pass over its faces and mips (facet-bake's "NAME  T ms GPU" lines) and prints
# the medians of RUNS runs of each, the passes over 1.5 ms, and the sums of the medians.
set -euo pipefail
if [ $# -ne 4 ]; then sed -n '2,5p' "$0"; exit 2; fi
runs=$1 env=$2 a=$3 b=$4
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
for i in $(seq "$runs"); do
    for bin in "$a" "$b"; do
        "$bin" "$env" --out "$dir/out" --force 2>&1 | grep ' ms GPU$' | grep -v ': wrote ' |
            sed "s/^[^:]*: *//; s/ face [0-9]//; s/ mip [0-9]//; s/ \+/ /g; s|^|$bin\t$i\t|"
    done
done | python3 -c '
import collections, statistics as st, sys
runs = collections.defaultdict(float)  # (pass, binary, run) -> ms
for line in sys.stdin:
    binary, run, rest = line.rstrip("\n").split("\t")
    words = rest.split(" ")
    runs[(" ".join(words[:-3]), binary, run)] += float(words[-3])
names, binaries = sorted({k[0] for k in runs}), [sys.argv[1], sys.argv[2]]
median = {(n, b): st.median([v for k, v in runs.items() if k[0] == n and k[1] == b] or [0]) for n in names for b in binaries}
print("%-44s %8s %8s" % ("pass", "A", "B"))
for n in sorted(names, key=lambda n: -max(median[(n, b)] for b in binaries)):
    if max(median[(n, b)] for b in binaries) > 1.5:
        print(f"{n:44s} {median[(n, binaries[0])]:8.2f} {median[(n, binaries[1])]:8.2f}")
print("%-44s " % "sum of the medians" + " ".join("%8.1f" % sum(median[(n, b)] for n in names) for b in binaries))
' "$a" "$b"
