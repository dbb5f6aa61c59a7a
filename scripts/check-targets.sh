#!/usr/bin/env bash
# Lints the crate, every target (tests, benches, examples) included, for the desktops it
# opens on: Windows (MSVC and GNU), macOS (Apple silicon), and Linux with Wayland only
# (no X11); and the library and program for the browser (wasm32: what scripts/web.sh
# builds). `clippy -D warnings` must be clean on each.
#
# rustup's targets cannot be downloaded everywhere, so the cross targets use Debian's
# rustc-web toolchain (Rust 1.96 and std's source), which builds std for any target with
# -Zbuild-std. Missing packages are installed (apt-get, as root or through sudo).
#
#   scripts/check-targets.sh            every target
#   scripts/check-targets.sh TARGET...  only those (the names below, or linux-wayland)
set -euo pipefail
cd "$(dirname "$0")/.."

all_targets="x86_64-pc-windows-msvc x86_64-pc-windows-gnu aarch64-apple-darwin linux-wayland wasm32-unknown-unknown"
targets="${*:-$all_targets}"

. scripts/need-packages.sh
packages="rustc-web cargo-web rust-web-src rust-web-clippy lld-22"
# std for windows-gnu builds its import libraries with MinGW's dlltool.
case " $targets " in
  *" x86_64-pc-windows-gnu "*) packages="$packages binutils-mingw-w64-x86-64" ;;
esac
# shellcheck disable=SC2086
need_packages $packages

# Debian's cargo, rustc and clippy, called by path: rustup's come first on PATH, and cargo
# looks for `cargo-clippy` in ~/.cargo/bin (rustup's proxy) before PATH. A target folder of
# their own leaves the host's build alone.
cross() {
  env PATH=/usr/bin:/bin RUSTC=/usr/bin/rustc RUSTC_BOOTSTRAP=1 CARGO=/usr/bin/cargo \
    CARGO_TARGET_DIR="$PWD/target/cross" /usr/bin/cargo-clippy clippy "$@"
}

# Clippy 0.1.96 under RUSTC_BOOTSTRAP misreads std's `thread_local!` expansion and asks
# for the `const { }` initialiser every one of them already has; the host's clippy (run by
# .ci/run) checks that lint.
lints="-D warnings -A clippy::missing_const_for_thread_local"

for t in $targets; do
  start=$(date +%s)
  case "$t" in
    linux-wayland)
      # The host's own toolchain: it reuses the host build's crates (only the window
      # crates change features).
      echo "== clippy: x86_64-unknown-linux-gnu, Wayland only (no X11)"
      cargo clippy --all-targets \
        --no-default-features --features wayland -- -D warnings
      ;;
    wasm32-unknown-unknown)
      # The tests and benches run on the desktop (they need EGL); the page is the program.
      echo "== clippy: $t (the library and the program, as scripts/web.sh builds them)"
      cross -Zbuild-std=std,panic_abort --target "$t" --lib --bins \
        --no-default-features -- $lints
      ;;
    *)
      echo "== clippy: $t"
      cross -Zbuild-std --target "$t" --all-targets -- $lints
      ;;
  esac
  echo "== $t: clean ($(( $(date +%s) - start )) s)"
done
