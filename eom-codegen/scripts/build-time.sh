#!/bin/sh
# Release (and debug) build time of a scratch crate holding only the generated module of one
# model — what `cargo build --release` costs a consumer for the generated code itself.
#
#   eom-codegen/scripts/build-time.sh [model] [emit options, e.g. --f32]
#
# Dependencies (libm) are built first and not timed; the timed build recompiles the scratch
# crate alone. Needs the libm crate in the local cargo cache (it is a workspace dependency).
set -eu
model=${1:-bicycle}
[ $# -gt 0 ] && shift
root=$(cd "$(dirname "$0")/../.." && pwd)
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
cd "$root"
start=$(date +%s.%N)
cargo run -q --release -p eom-codegen --example emit -- "$model" "$@" > "$dir/generated.rs"
end=$(date +%s.%N)
echo "generation (cargo run, mostly process start): $(echo "$end - $start" | bc) s, $(wc -c < "$dir/generated.rs") bytes"
mkdir -p "$dir/src"
cat > "$dir/Cargo.toml" <<TOML
[package]
name = "generated-scratch"
version = "0.0.0"
edition = "2024"
publish = false

[dependencies]
libm = "0.2"

[workspace]
TOML
printf '#![no_std]\ninclude!("../generated.rs");\n' > "$dir/src/lib.rs"
cd "$dir"
cargo build --release --offline -q --target-dir "$dir/target"
cargo build --offline -q --target-dir "$dir/target"
for profile in release dev; do
    touch src/lib.rs
    start=$(date +%s.%N)
    if [ "$profile" = release ]; then cargo build --release --offline -q --target-dir "$dir/target"; else cargo build --offline -q --target-dir "$dir/target"; fi
    end=$(date +%s.%N)
    echo "$model: cargo build ($profile) of the generated crate: $(echo "$end - $start" | bc) s"
done
