#!/usr/bin/env bash
# Run the atheris fuzz targets for a bounded time each (not part of the test suite).
#
#   fuzz/run.sh [SECONDS_PER_TARGET] [TARGET...]      default: 120 s, targets "parser check reports"
#
# Needs atheris (pip install "gclint[fuzz]" or pip install atheris).  The working corpus and any crash
# files go to $GCLINT_FUZZ_DIR (default: $TMPDIR/gclint-fuzz); the shared corpus (../shared/corpus, or
# $GCLINT_CORPUS) is read in place as extra seeds, never copied or written.  Exit status is non-zero
# when a target finds a crash; the last lines of each log give the number of inputs tried.
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(dirname "$here")"
seconds="${1:-120}"
shift || true
targets=("${@:-parser check reports}")
read -r -a targets <<< "${targets[*]}"
python="${PYTHON:-python3}"
work="${GCLINT_FUZZ_DIR:-${TMPDIR:-/tmp}/gclint-fuzz}"
shared="${GCLINT_CORPUS:-$root/../shared/corpus}"

status=0
for target in "${targets[@]}"; do
    corpus="$work/corpus_$target"
    log="$work/$target.log"
    mkdir -p "$corpus"
    "$python" "$here/_common.py" "$corpus"
    extra=()
    [ -d "$shared" ] && extra+=("$shared")
    echo "== fuzz_$target for ${seconds}s (corpus $corpus, log $log)"
    set +e
    "$python" "$here/fuzz_$target.py" \
        -max_total_time="$seconds" -timeout=20 -rss_limit_mb=3072 -max_len=8192 \
        -artifact_prefix="$work/crash-$target-" -print_final_stats=1 \
        "$corpus" "${extra[@]}" > "$log" 2>&1
    code=$?
    set -e
    grep -E "^Done [0-9]+ runs|stat::number_of_executed_units|ERROR|Uncaught|Traceback" "$log" | head -20 || true
    if [ "$code" -ne 0 ]; then
        echo "fuzz_$target: exit $code; see $log and $work/crash-$target-*"
        status=1
    fi
done
exit "$status"
