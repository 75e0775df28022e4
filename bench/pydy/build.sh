#!/bin/sh
# Emit eom's modules, compile each PyDy C file alone (gcc -O2 -c, as the peers' C-driver
# measurements did), the Rust static library, and the driver.
#
# MARCH=x86-64-v3 ./build.sh (or MARCH=native) compiles both sides for that CPU: gcc -march
# and rustc -C target-cpu, the same level for the C and the Rust. Default: neither flag, the
# compilers' baseline (x86-64, SSE2), as the notes measured PyDy.
set -e
cd "$(dirname "$0")"
CFLAGS="-O2${MARCH:+ -march=$MARCH}"
RSFLAGS="${MARCH:+-C target-cpu=$MARCH}"
unset RUSTFLAGS   # the emitter runs with the workspace's flags; only rslib gets RSFLAGS
EOM=${EOM:-../..}
(cd "$EOM" && cargo run -q --release -p eom-codegen --example emit -- bicycle) > bicycle_f64.rs
(cd "$EOM" && cargo run -q --release -p eom-codegen --example emit -- shimmy) > shimmy_f64.rs
# The same, simplified: `--simplify` uses it for the shimmy; the bicycle needs
# `--simplify-always` (its estimate says slower, which this driver confirms).
(cd "$EOM" && cargo run -q --release -p eom-codegen --example emit -- bicycle \
    --simplify-always --module bicycle_simplified) > bicycle_simplified_f64.rs
(cd "$EOM" && cargo run -q --release -p eom-codegen --example emit -- shimmy \
    --simplify --module shimmy_simplified) > shimmy_simplified_f64.rs
mkdir -p build
for f in shimmy bicycle4 bicycle6; do gcc $CFLAGS -c pydy_$f.c -o build/pydy_$f.o; done
(cd rslib && RUSTFLAGS="$RSFLAGS" cargo build --release)
echo "built with ${MARCH:-the baseline target}" > build/target.txt
gcc $CFLAGS -c driver.c -o build/driver.o
gcc -o build/driver build/driver.o build/pydy_bicycle4.o build/pydy_bicycle6.o build/pydy_shimmy.o \
    rslib/target/release/libeom_peer_rslib.a -lm -lpthread -ldl
