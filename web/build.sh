#!/usr/bin/env bash
# Builds the browser app into web/dist/ (index.html, dmpscope.js,
# dmpscope_bg.wasm). Installs what it needs on a fresh Debian machine: the
# wasm32 target, wasm-bindgen-cli at Cargo.lock's wasm-bindgen version (from
# crates.io), and clang (zstd's C code for wasm32). No wasm-opt: Debian's
# binaryen 108 breaks the module at start-up.
#
# `web/build.sh --testing` builds with the `testing` feature: the browser
# tests' hook `window.dmpscope_state()`. The plain build has no test code.
# `web/build.sh --install-only` installs the tools and stops (CI runs it in
# the background, at low priority, while the Rust checks run).
set -euo pipefail
cd "$(dirname "$0")/.."

features=()
install_only=false
for arg in "$@"; do
  case "$arg" in
    --testing) features=(--features testing) ;;
    --install-only) install_only=true ;;
    *) echo "usage: web/build.sh [--testing | --install-only]" >&2; exit 2 ;;
  esac
done

version=$(awk '/^name = "wasm-bindgen"$/ { getline; gsub(/[^0-9.]/, ""); print; exit }' Cargo.lock)
[ -n "$version" ] || { echo "no wasm-bindgen in Cargo.lock" >&2; exit 1; }

rustup target add wasm32-unknown-unknown >/dev/null
if ! command -v clang >/dev/null; then
  apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq clang >/dev/null
fi
if [ "$(wasm-bindgen --version 2>/dev/null | awk '{print $2}')" != "$version" ]; then
  echo "installing wasm-bindgen-cli $version (a few minutes)" >&2
  # Without --locked: the registry here lacks one of its locked dependencies.
  # A tool, not ours: never under CI's clippy wrapper.
  install=(env -u RUSTC_WORKSPACE_WRAPPER -u CLIPPY_ARGS cargo install wasm-bindgen-cli --version "$version")
  if $install_only; then
    nice -n 15 "${install[@]}"
  else
    "${install[@]}"
  fi
fi
$install_only && exit 0

# The `web` profile: built for size, the core for speed, from the small
# entry crate web/entry (Cargo.toml says why).
cargo build --profile web -p dmpscope-web --target wasm32-unknown-unknown "${features[@]}"
out=web/dist
rm -rf "$out"
mkdir -p "$out"
wasm-bindgen --target web --no-typescript --out-dir "$out" --out-name dmpscope \
  target/wasm32-unknown-unknown/web/dmpscope-web.wasm
cp web/index.html web/worker.js "$out/"
ls -l "$out" >&2
echo "built $out; serve it with: python3 -m http.server -d $out 8080" >&2
