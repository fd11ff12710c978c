#!/usr/bin/env bash
# Runs the gendpde test suite (unit, integration and release-profile physics tests).
# Installs what it needs on a fresh Debian machine; idempotent.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

if ! command -v cargo >/dev/null; then
  echo "cargo is missing: install the Rust toolchain (https://rustup.rs)" >&2
  exit 1
fi
# C toolchain for crates that build C code.
if ! command -v cc >/dev/null; then
  sudo_cmd=""; [ "$(id -u)" = 0 ] || sudo_cmd="sudo"
  $sudo_cmd apt-get update -qq && $sudo_cmd env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq build-essential
fi

# Statistical physics tests need optimised code: the whole suite runs in release.
cargo test --release --workspace "$@"
