#!/usr/bin/env bash
# Fuzzes the input-script reader and the data-file parser of gendpde-io with
# cargo-fuzz (libFuzzer + AddressSanitizer, debug assertions on).
#
#   scripts/fuzz.sh [SECONDS] [TARGET...]
#
# SECONDS per target, default 600; TARGETs default to "script data" (run one
# after the other: each uses one core). Installs cargo-fuzz if it is missing.
# The stable toolchain is enough: RUSTC_BOOTSTRAP=1 lets it accept the nightly
# flags cargo-fuzz passes. FUZZ_SANITIZER=none builds without ASan (faster, or
# where the sanitizer runtime is unavailable).
#
# Corpora grow in fuzz/corpus/TARGET (seeded from fuzz/seeds/TARGET, with
# dictionaries fuzz/dict.TARGET); crashes and timeouts land in
# fuzz/artifacts/TARGET. Reproduce one with
#   (cd fuzz && RUSTC_BOOTSTRAP=1 cargo fuzz run -a TARGET artifacts/TARGET/crash-...)
# and minimise it with
#   (cd fuzz && RUSTC_BOOTSTRAP=1 cargo fuzz tmin -a TARGET artifacts/TARGET/crash-...)
set -euo pipefail

seconds=${1:-600}
shift || true
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
    targets=(script data)
fi

if ! cargo fuzz --version >/dev/null 2>&1; then
    cargo install cargo-fuzz
fi

cd "$(dirname "$0")/../fuzz"
export RUSTC_BOOTSTRAP=1
sanitizer=${FUZZ_SANITIZER:-address}

status=0
for target in "${targets[@]}"; do
    mkdir -p "corpus/$target"
    echo "== fuzzing '$target' for ${seconds}s (sanitizer: $sanitizer)"
    # -timeout: an input taking over 10 s counts as a hang (a finding).
    if ! cargo fuzz run -a -s "$sanitizer" "$target" "corpus/$target" "seeds/$target" -- \
        -dict="dict.$target" \
        -max_total_time="$seconds" \
        -timeout=10 \
        -max_len=8192 \
        -print_final_stats=1; then
        echo "== '$target' found a crash or a hang: see fuzz/artifacts/$target" >&2
        status=1
    fi
done
exit $status
