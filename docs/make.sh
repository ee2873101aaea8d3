#!/bin/sh
# Regenerates the documents made from the code: docs/reference.md (every command and
# flag), docs/man/*.1 (man pages), docs/keys.md (the terminal application's keys) and
# docs/screenshot.png (the README's picture of the application, from a scripted run of
# its real jobs). A test compares the checked-in copies with what the build makes.
set -eu
cd "$(dirname "$0")/.."
cargo build --release --locked
target/release/bouncemap generate-docs docs
