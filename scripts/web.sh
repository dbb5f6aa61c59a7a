#!/usr/bin/env bash
# The browser's build of shadowmap: the same renderer, scenes and steps on WebGL2.
#
#   scripts/web.sh build    builds web/dist/ (index.html, shadowmap.js, shadowmap_bg.wasm)
#   scripts/web.sh serve    serves web/dist/ on http://127.0.0.1:PORT/ (PORT: 8000, or $PORT)
#
# The build uses Debian's rustc-web toolchain, which builds std for wasm32 from its source
# (rustup's wasm32 target need not be installed), and wasm-bindgen-cli at the version of
# the wasm-bindgen crate in Cargo.lock; both are installed when missing (apt-get, cargo
# install: about 12 minutes the first time).
set -euo pipefail
cd "$(dirname "$0")/.."

. scripts/need-packages.sh

usage() { sed -n '2,10p' "$0" | sed 's/^# \{0,1\}//'; }

build() {
  need_packages rustc-web cargo-web rust-web-src lld-22
  local version
  version=$(awk '/^name = "wasm-bindgen"$/ { getline; gsub(/version = |"/, ""); print; exit }' Cargo.lock)
  local bindgen="${CARGO_HOME:-$HOME/.cargo}/bin/wasm-bindgen"
  if ! "$bindgen" --version 2>/dev/null | grep -qx "wasm-bindgen $version"; then
    echo "== installing wasm-bindgen-cli $version" >&2
    cargo install wasm-bindgen-cli --version "$version"
  fi
  echo "== cargo build --target wasm32-unknown-unknown (release)" >&2
  env PATH=/usr/bin:/bin RUSTC=/usr/bin/rustc RUSTC_BOOTSTRAP=1 \
    CARGO_TARGET_DIR="$PWD/target/web" \
    /usr/bin/cargo build -Zbuild-std=std,panic_abort --release \
    --target wasm32-unknown-unknown --no-default-features --bin shadowmap
  rm -rf web/dist
  mkdir -p web/dist
  "$bindgen" --target web --no-typescript --out-dir web/dist \
    target/web/wasm32-unknown-unknown/release/shadowmap.wasm
  cp web/index.html web/dist/
  local size
  size=$(gzip -9 -c web/dist/shadowmap_bg.wasm | wc -c)
  echo "== web/dist: shadowmap_bg.wasm $(( $(stat -c %s web/dist/shadowmap_bg.wasm) / 1024 )) KiB, $(( size / 1024 )) KiB gzipped" >&2
}

serve() {
  [ -f web/dist/index.html ] || { echo "web/dist is not built: run scripts/web.sh build" >&2; exit 1; }
  local port="${PORT:-8000}"
  echo "serving web/dist on http://127.0.0.1:$port/ (Ctrl-C stops)"
  exec python3 -m http.server "$port" --bind 127.0.0.1 --directory web/dist
}

case "${1:-}" in
  build) build ;;
  serve) serve ;;
  -h|--help|help) usage ;;
  *) usage >&2; exit 2 ;;
esac
