#!/bin/sh
# The bicycle of this checkout against a baseline checkout's (e.g. main's) and PyDy's, in one
# process: BASE=/path/to/other/eom EOM=/path/to/this/eom ./baseline.sh [rounds]
# (after derive_bicycle.py and gen_bicycle.py, which write pydy_bicycle6.c). Prints the
# largest relative difference of an entry between the two eom kernels, then ns per call.
set -e
cd "$(dirname "$0")"
: "${BASE:?BASE=/path/to/the baseline checkout of eom}"
EOM=${EOM:-../..}
unset RUSTFLAGS
(cd "$EOM" && cargo run -q --release -p eom-codegen --example emit -- bicycle) > bicycle_f64.rs
(cd "$BASE" && cargo run -q --release -p eom-codegen --example emit -- bicycle \
    --module bicycle_base) > bicycle_base_f64.rs
mkdir -p build
gcc -O2 -c pydy_bicycle6.c -o build/pydy_bicycle6.o
(cd baseline && cargo build -q --release)
gcc -O2 -c baseline.c -o build/baseline.o
gcc -o build/baseline build/baseline.o build/pydy_bicycle6.o \
    baseline/target/release/libeom_peer_baseline.a -lm -lpthread -ldl
for i in $(seq 1 "${1:-3}"); do ./build/baseline 3; done | tee results_baseline.txt
