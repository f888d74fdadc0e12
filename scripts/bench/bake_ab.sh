#!/usr/bin/env bash
# Whole-process A/B of two facet-bake builds on a shared machine:
#   scripts/bench/bake_ab.sh PAIRS ENV OLD_BAKE NEW_BAKE
# Each pair (OLD then NEW, `/usr/bin/time facet-bake ENV --out DIR --force`) runs only after a
# second in which the CPUs were under 15% busy. Prints per run "old|new wall user sys GPU
# bake-wall", then medians and the median of the paired differences (wall, and wall less the
# passes' GPU time, which shows changes outside the passes through the host's noise).
set -euo pipefail
if [ $# -ne 4 ]; then sed -n '2,7p' "$0"; exit 2; fi
pairs=$1 env=$2 old=$3 new=$4
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
busy() {
    read -r _ a b c d e f g _ < /proc/stat; local t1=$((a + b + c + d + e + f + g)) i1=$d
    sleep 1
    read -r _ a b c d e f g _ < /proc/stat; local t2=$((a + b + c + d + e + f + g)) i2=$d
    echo $((100 - 100 * (i2 - i1) / (t2 - t1)))
}
for b in "$old" "$new"; do "$b" "$env" --out "$dir/warm" --force > /dev/null 2>&1; done
n=0 tries=0
while [ $n -lt "$pairs" ] && [ $tries -lt 300 ]; do
    tries=$((tries + 1))
    [ "$(busy)" -gt 15 ] && continue
    for b in "$old" "$new"; do
        /usr/bin/time -o "$dir/time" -f "%e %U %S" "$b" "$env" --out "$dir/out" --force 2> "$dir/err" > /dev/null
        gpu=$(grep -o "wrote .*" "$dir/err" | sed 's/.*(\(.*\) ms GPU, \(.*\) ms wall)/\1 \2/')
        echo "$([ "$b" = "$old" ] && echo old || echo new) $(cat "$dir/time") $gpu"
    done
    n=$((n + 1))
done | tee "$dir/runs"
python3 - "$dir/runs" <<'PY'
import statistics as st, sys
rows = [l.split() for l in open(sys.argv[1]) if l.strip()]
pairs = [(list(map(float, rows[i][1:])), list(map(float, rows[i + 1][1:])))
         for i in range(0, len(rows) - 1, 2) if rows[i][0] == "old" and rows[i + 1][0] == "new"]
if not pairs: sys.exit("no quiet pairs")
for tag, k in (("old", 0), ("new", 1)):
    cols = list(zip(*[p[k] for p in pairs]))
    print(tag, " ".join(f"{n} {st.median(c):.3g} ({min(c):.3g}-{max(c):.3g})"
                        for n, c in zip(("wall s", "user s", "sys s", "GPU ms", "bake wall ms"), cols)))
print(f"{len(pairs)} pairs, new - old: wall {st.median(n[0] - o[0] for o, n in pairs) * 1000:+.0f} ms,",
      f"wall less GPU {st.median((n[0] - n[3] / 1000) - (o[0] - o[3] / 1000) for o, n in pairs) * 1000:+.0f} ms")
PY
