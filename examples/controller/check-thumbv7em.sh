#!/bin/sh
# Cross-compile the no_std controller (with every built-in model's generated module) for a
# Cortex-M4F. Manual: needs `rustup target add thumbv7em-none-eabihf`, which CI does not do.
set -e
cd "$(dirname "$0")/../.."
cargo build -p controller --lib --release --target thumbv7em-none-eabihf
