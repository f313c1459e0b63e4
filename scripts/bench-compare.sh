#!/usr/bin/env bash
# A speed claim as a ratio measured on one machine in the same minutes (docs/benchmarks.md):
#   bash scripts/bench-compare.sh REV [ROUNDS]
# builds REV in a git worktree (under .bench/, kept between calls), builds this checkout, and runs
# both builds' benchmarks interleaved ROUNDS times (default 3): bench_simulation, bench_classifier
# and a seeds throughput (seeds of experiments/paper.json per core-second, user + system time of
# `seeds --from 1 --to 20 --jobs 1`). Each figure is the median over the rounds; the ratio is how
# many times faster (or higher, for a throughput) this checkout is than REV. A figure only one
# build prints shows a dash for the other.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
top="$(dirname "$here")"
rev="${1:?usage: bench-compare.sh REV [ROUNDS]}"
rounds="${2:-3}"
commit="$(git -C "$top" rev-parse --verify "$rev^{commit}")"
base="$top/.bench/${commit:0:12}"
build="${ACTIVETOUCH_BUILD_DIR:-$top/build}"

if [ ! -d "$base/src" ]; then
    mkdir -p "$base"
    git -C "$top" worktree add --detach "$base/src" "$commit" >/dev/null
fi
targets=(bench_simulation bench_classifier activetouch-cli)
cmake -S "$base/src" -B "$base/build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$base/build" --target "${targets[@]}" >/dev/null
cmake -S "$top" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build" --target "${targets[@]}" >/dev/null

out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
# Seeds of paper.json per core-second: 20 seeds on one thread, user + system CPU time.
seeds_per_core_second() {
    local cli=$1 folder="$out/seeds"
    rm -rf "$folder"
    python3 - "$cli" "$top/experiments/paper.json" "$folder" <<'PY'
import os, subprocess, sys
cli, experiment, folder = sys.argv[1:4]
# The seeds run's own CPU time (its threads included), from wait4: the interpreter's other
# children, if its start-up made any, are not the run's.
run = subprocess.Popen([cli, "seeds", experiment, "--from", "1", "--to", "20", "--jobs", "1",
                        "--out", folder, "--no-figures"], stdout=subprocess.DEVNULL,
                       stderr=subprocess.DEVNULL)
_, status, used = os.wait4(run.pid, 0)
if os.waitstatus_to_exitcode(status) != 0:
    sys.exit(f"{cli} seeds failed")
print(f"{'seeds of paper.json per core-second':52} {20 / (used.ru_utime + used.ru_stime):10.3f} seeds/s")
PY
}
# One round of one build: every figure as "label<TAB>value<TAB>unit".
round() {
    local dir=$1
    {
        "$dir/tests/bench_simulation"
        "$dir/tests/bench_classifier"
        seeds_per_core_second "$dir/app/activetouch-cli"
    } | grep -v "clock" |
        sed -E 's/^(.{52}) +([0-9.]+) +([a-zA-Z/]+).*$/\1\t\2\t\3/' |
        sed -E 's/^(.*[^ ]) *\t/\1\t/'
}
for r in $(seq 1 "$rounds"); do
    echo "round $r of $rounds" >&2
    round "$base/build" >"$out/base.$r"
    round "$build" >"$out/this.$r"
done

python3 - "$out" "$rounds" "$rev" <<'PY'
import sys, statistics, collections
out, rounds, rev = sys.argv[1], int(sys.argv[2]), sys.argv[3]
def read(who):
    figures, order = collections.defaultdict(list), []
    for r in range(1, rounds + 1):
        for line in open(f"{out}/{who}.{r}"):
            parts = line.rstrip("\n").split("\t")
            if len(parts) != 3:
                continue
            label, value, unit = parts
            if label not in figures:
                order.append(label)
            figures[label].append((float(value), unit))
    return figures, order
base, base_order = read("base")
this, this_order = read("this")
order = base_order + [l for l in this_order if l not in base_order]
print(f"{'figure (median of ' + str(rounds) + ' interleaved rounds)':52} {rev[:12]:>12} {'this':>12}  ratio")
for label in order:
    b = statistics.median(v for v, _ in base[label]) if label in base else None
    t = statistics.median(v for v, _ in this[label]) if label in this else None
    unit = (base.get(label) or this.get(label))[0][1]
    cell = lambda v: f"{v:12.3f}" if v is not None else f"{'-':>12}"
    ratio = "-"
    if b and t:
        faster = (t / b) if unit.endswith("/s") else (b / t)
        ratio = f"{faster:.2f}x {'higher' if unit.endswith('/s') else 'faster'}"
    print(f"{label:52} {cell(b)} {cell(t)}  {ratio}  ({unit})")
PY
